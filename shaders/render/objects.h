// SPDX-License-Identifier: MIT
// shaders/render/objects.h — per-object transforms, read by the rasterising passes (gbuffer, shadow).
#ifndef EMCV_RENDER_OBJECTS_H
#define EMCV_RENDER_OBJECTS_H

#include "render/frame.h"

layout(std430, EMCV_LAYOUT_BINDING(EMCV_RENDER_OBJECTS)) readonly buffer Objects {
    EmcvObject objects[];
};

// The object index arrives as an instanced attribute (divisor 1, base instance = object index): GL 4.5 has
// no gl_BaseInstance without ARB_shader_draw_parameters.
#define EMCV_RENDER_ATTRIB_POSITION 0
#define EMCV_RENDER_ATTRIB_NORMAL 1
#define EMCV_RENDER_ATTRIB_UV 2
#define EMCV_RENDER_ATTRIB_OBJECT 3

#endif  // #ifndef EMCV_RENDER_OBJECTS_H
