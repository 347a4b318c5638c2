// SPDX-License-Identifier: MIT
/// \file
/// emcv/port/bindings.h — binding slots and workgroup sizes shared by the host (C++) and the shaders (GLSL),
/// FidelityFX `_resources.h` pattern: both sides read the same numbers from one place.
//
// ABOUT      Binding numbers are unique across resource types, so the same GLSL also validates for Vulkan,
//            where uniform and storage buffers share one binding space per descriptor set.
//            EMCV_LAYOUT_BINDING(b) expands to `binding = b` for OpenGL and to `set = 0, binding = b` under
//            Vulkan (glslang defines VULKAN for -V targets). Shaders use no loose (non-block) uniforms.
//            Image units are a separate and small space in OpenGL: GL_MAX_IMAGE_UNITS may be as low as 8 (the
//            GL 4.5 minimum, and NVIDIA's value), so image bindings are numbered 0..7 and declared with
//            EMCV_LAYOUT_IMAGE_BINDING(b): `binding = b` for OpenGL, `set = 1, binding = b` under Vulkan, which
//            keeps them apart from the buffers and textures of set 0.
#ifndef EMCV_PORT_BINDINGS_H
#define EMCV_PORT_BINDINGS_H

#define EMCV_WORKGROUP_SIZE_X 64  ///< local_size_x of the compute passes

/// Image units usable everywhere: GL_MAX_IMAGE_UNITS is at least 8 (OpenGL 4.5); every image binding is below.
#define EMCV_MAX_IMAGE_UNITS 8

#ifndef __cplusplus
#if defined(VULKAN)
#define EMCV_LAYOUT_BINDING(b) set = 0, binding = b
#define EMCV_LAYOUT_IMAGE_BINDING(b) set = 1, binding = b
#else
#define EMCV_LAYOUT_BINDING(b) binding = b
#define EMCV_LAYOUT_IMAGE_BINDING(b) binding = b
#endif
#endif  // #ifndef __cplusplus

#endif  // #ifndef EMCV_PORT_BINDINGS_H
