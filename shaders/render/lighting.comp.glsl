// SPDX-License-Identifier: MIT
// Lighting pass: per pixel, the diffuse irradiance / pi without albedo (what scattering blurs, post-scatter
// texturing as UE) and the specular GGX radiance, kept apart so the specular never scatters (docs/frame.md).
// On frames whose SSS passes follow (EMCV_RENDER_FLAG_SSS_TILES) its workgroups, one per 8x8 tile, also list the
// SSS tiles those passes dispatch over (render/tiles.h): the material is read here anyway.
#version 450 core

#include "emcv/port/port.h"
#include "render/gbuffer_read.h"
#include "render/tiles.h"

layout(local_size_x = EMCV_RENDER_TILE_SIZE, local_size_y = EMCV_RENDER_TILE_SIZE) in;

layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_SHADOWS)) uniform sampler2DArrayShadow shadow_maps;
layout(rgba16f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_DIFFUSE)) writeonly uniform image2D out_diffuse;
layout(rgba16f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_SPECULAR)) writeonly uniform image2D out_specular;

const float pi = float(EMCV_PI);

/// Fraction of light reaching `world` (1 outside the shadow map). light.cone.y: normal offset (world
/// units, about one shadow texel), light.cone.z: depth bias; a 2x2 hardware PCF tap.
float shadow_visibility(EmcvLight light, vec3 world, vec3 n) {
    vec4 clip = light.shadow_view_proj * vec4(world + n * light.cone.y, 1.0f);
    vec3 ndc = clip.xyz / clip.w;
    vec3 uvz = ndc * 0.5f + 0.5f;
    if (any(lessThan(uvz, vec3(0.0f))) || any(greaterThan(uvz, vec3(1.0f)))) return 1.0f;
    return texture(shadow_maps, vec4(uvz.xy, light.position.w, uvz.z - light.cone.z));
}

/// GGX normal distribution times the height-correlated Smith visibility (Heitz 2014), Fresnel folded into
/// the material's specular weight.
float ggx_specular(float ndl, float ndv, float ndh, float roughness) {
    float a = roughness * roughness;
    float a2 = a * a;
    float t = ndh * ndh * (a2 - 1.0f) + 1.0f;
    float distribution = a2 / (pi * t * t);
    float visibility = 0.5f / (ndl * sqrt(ndv * ndv * (1.0f - a2) + a2) + ndv * sqrt(ndl * ndl * (1.0f - a2) + a2));
    return distribution * visibility;
}

/// Lights pixel p (material `code`, not 0).
void shade(ivec2 p, uint code) {
    EmcvMaterial m = materials[code - 1u];
    vec3 world = emcv_render_world_position(p, emcv_render_depth(p));
    vec3 n = normalize(texelFetch(gbuffer_normal, p, 0).xyz);
    vec3 v = normalize(frame.camera_position.xyz - world);
    float ndv = max(dot(n, v), 1e-4f);
    vec3 irradiance = frame.ambient.xyz;
    vec3 specular = vec3(0.0f);
    for (uint i = 0u; i < frame.counters.z; ++i) {
        EmcvLight light = lights[i];
        int kind = int(light.radiance.w);
        vec3 e = light.radiance.xyz;
        if (max(e.x, max(e.y, e.z)) <= 0.0f) continue;  // a dark light: its shadow map was not rendered this frame
        vec3 l = -light.direction.xyz;
        if (kind != EMCV_RENDER_LIGHT_DIRECTIONAL) {
            vec3 to_light = light.position.xyz - world;
            float dist2 = max(dot(to_light, to_light), 1e-8f);
            l = to_light * inversesqrt(dist2);
            e /= dist2;  // intensity -> irradiance at normal incidence, 1 / d^2
            if (kind == EMCV_RENDER_LIGHT_SPOT) e *= smoothstep(light.direction.w, light.cone.x, dot(-l, light.direction.xyz));
        }
        float ndl = dot(n, l);
        if (ndl <= 0.0f) continue;
        if (light.position.w >= 0.0f) e *= shadow_visibility(light, world, n);
        irradiance += e * ndl;
        if (m.specular.x > 0.0f) {
            vec3 h = normalize(l + v);
            specular += e * ndl * m.specular.x * ggx_specular(ndl, ndv, max(dot(n, h), 0.0f), max(m.specular.y, 0.02f));
        }
    }
    imageStore(out_diffuse, p, vec4(irradiance / pi, 1.0f));
    imageStore(out_specular, p, vec4(specular, 1.0f));
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    bool on_screen = emcv_render_on_screen(p);
    uint code = on_screen ? emcv_render_material_code(p) : 0u;
    if (on_screen && code == 0u) {
        imageStore(out_diffuse, p, vec4(0.0f));
        imageStore(out_specular, p, vec4(0.0f));
    } else if (on_screen) {
        shade(p, code);
    }
    if ((frame.counters.w & EMCV_RENDER_FLAG_SSS_TILES) != 0u) emcv_render_classify_tile(emcv_render_scatters(code));
}
