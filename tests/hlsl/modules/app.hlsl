// SPDX-License-Identifier: MIT
// tests/hlsl/modules/app.hlsl: an HLSL engine's side of emcv's GPU modules (share/emcv/module/hlsl), the Direct3D
// counterpart of tests/package/budget_consumer/app.glsl: the port's library first, then the engine's own
// resources, its budget block (EMCV_APP_BUDGET) and the emcv_app_* functions over its own textures. The compiler's
// command line defines the method (EMCV_ADAPTIVE_CV, _SPVG or _NOTEX); the pass defines EMCV_BUDGET_GROUP_THREADS
// or EMCV_ADAPTIVE_TILE_UPDATE before including this file. Each entry point calls emcv_hlsl_set_invocation first.
#include "emcv_port.hlsl"

// One EmcvBudgetBlock (3104 bytes, zeroed once): a structured buffer packs it as host.hpp's std430 struct, and it
// takes atomics (a cbuffer could not).
RWStructuredBuffer<EmcvBudgetBlock> app_budget : register(u0);
#define EMCV_APP_BUDGET app_budget[0]
cbuffer AppFrame : register(b0)
{
    uint4 app_frame;  // frame index, seed, width, height
};

#include "emcv_adaptive_plan.hlsl"

// This frame's history (read and written: typed UAV loads of the layout's formats) and last frame's (read).
globallycoherent RWTexture2D<float4> app_history_a : register(u1);
Texture2D<float4> app_previous_a : register(t0);
float4 emcv_app_history_load_a(int2 t) { return app_history_a[t]; }
void emcv_app_history_store_a(int2 t, float4 v) { app_history_a[t] = v; }
float4 emcv_app_history_previous_a(int2 t) { return app_previous_a.Load(int3(t, 0)); }
#if EMCV_ADAPTIVE_HISTORY_TEXELS == 2
globallycoherent RWTexture2D<float2> app_history_b : register(u2);  // rg32f: the means
Texture2D<float2> app_previous_b : register(t1);
float4 emcv_app_history_load_b(int2 t) { return float4(app_history_b[t], 0.0f, 0.0f); }
void emcv_app_history_store_b(int2 t, float4 v) { app_history_b[t] = v.xy; }
float4 emcv_app_history_previous_b(int2 t) { return float4(app_previous_b.Load(int3(t, 0)), 0.0f, 0.0f); }
#endif

// The plan (budget mode: each block's shrunk variance as float bits) and the samples each pixel took.
RWTexture2D<uint> app_plan : register(u3);
RWTexture2D<uint> app_taken : register(u4);
// The surface's material id (0: does not scatter), the same in every frame.
Texture2D<uint> app_material : register(t2);

int2 emcv_app_viewport_size() { return int2(app_frame.zw); }
float2 emcv_app_previous_position(int2 p) { return float2(p) + 0.5f; }  // a still camera
float emcv_app_expected_previous_depth(int2 p) { return 1.0f; }
float3 emcv_app_normal(int2 p) { return float3(0.0f, 0.0f, 1.0f); }
uint emcv_app_previous_material(int2 q) { return app_material.Load(int3(q, 0)); }
float emcv_app_previous_depth(int2 q) { return 1.0f; }
float3 emcv_app_previous_normal(int2 q) { return float3(0.0f, 0.0f, 1.0f); }
void emcv_app_store_plan(int2 t, uint v) { app_plan[t] = v; }
uint emcv_app_load_plan(int2 t) { return app_plan[t]; }

/// Whether pixel p's kernel is under a pixel (there cv takes no samples): the last column, in this test.
bool app_sub_pixel(int2 p) { return p.x == int(app_frame.z) - 1; }

/// Pixel p's material id, 0 off screen.
uint app_code(int2 p) { return emcv_adaptive_on_screen(p) ? app_material.Load(int3(p, 0)) : 0u; }

/// Shares pixel p's material code (returned) and sub-pixel test with its tile (emcv_adaptive_share_pixel), as the
/// planning passes do before emcv_adaptive_tile_sigma2 / emcv_adaptive_quality_count.
uint app_share_pixel(int2 p, uint group_index) {
    uint code = app_code(p);
    emcv_adaptive_share_pixel(group_index, code, code != 0u && app_sub_pixel(p));
    return code;
}
