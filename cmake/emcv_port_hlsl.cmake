# cmake -DGLSLANG=<glslangValidator> -DSPIRV_CROSS=<spirv-cross> -DPORT_GLSL=<emcv_port.glsl>
#       -DKERNEL=<shaders/reference/port_reference.glsl> -DWORK=<dir> -DOUTPUT=<emcv_port_reference.hlsl>
#       [-DSHADER_MODEL=51] -P emcv_port_hlsl.cmake
# The HLSL deliverable: `#version 450 core` + the flattened port + the reference kernel, compiled to Vulkan
# SPIR-V by glslang and translated by spirv-cross for shader model 5.1, where each descriptor set becomes a
# register space (set 0 -> space0, set 1 -> space1): the port's buffers and images, whose binding numbers
# overlap between the sets, never share a register. (Under shader model 5.0 there are no spaces and a storage
# buffer at binding 1 and an image at binding 1 both land on u1.)
cmake_minimum_required(VERSION 3.21)
foreach(var GLSLANG SPIRV_CROSS PORT_GLSL KERNEL WORK OUTPUT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "emcv_port_hlsl.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT DEFINED SHADER_MODEL)
  set(SHADER_MODEL 51)
endif()
file(MAKE_DIRECTORY "${WORK}")
file(READ "${PORT_GLSL}" port)
file(READ "${KERNEL}" kernel)
set(glsl "${WORK}/emcv_port_reference.comp.glsl")
file(WRITE "${glsl}" "#version 450 core\n${port}\n${kernel}")

function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "emcv_port_hlsl.cmake: ${step} failed (exit ${rc}):\n${out}${err}")
  endif()
endfunction()
run("glslangValidator (Vulkan SPIR-V)" "${GLSLANG}" -V --target-env vulkan1.0 "${glsl}" -o "${WORK}/emcv_port_reference.spv")
run("spirv-cross --hlsl" "${SPIRV_CROSS}" "${WORK}/emcv_port_reference.spv" --hlsl --shader-model ${SHADER_MODEL}
    --output "${WORK}/emcv_port_reference.hlsl")
file(READ "${WORK}/emcv_port_reference.hlsl" hlsl)
file(WRITE "${OUTPUT}.tmp" "// SPDX-License-Identifier: MIT
// emcv_port_reference.hlsl: HLSL (shader model ${SHADER_MODEL}) translation of emcv's reference compute kernel,
// generated at emcv's build time (cmake/emcv_port_hlsl.cmake): `#version 450 core` + emcv_port.glsl +
// shaders/reference/port_reference.glsl -> glslangValidator -V -> spirv-cross --hlsl --shader-model ${SHADER_MODEL}.
// Do not edit. What it is: every emcv_* port function as an HLSL function of the same name (the tunables at
// their defaults), the port's structs, and an entry point `main` that shows the bindings: Vulkan set 0
// (buffers, the uniform block, the texture) in space0 and set 1 (images) in space1, binding b -> register
// (u|t|b|s)b. Storage buffers are (RW)ByteAddressBuffers, as spirv-cross writes them. docs/integration.md,
// step 3.
${hlsl}")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
