# cmake -DGLSLANG=<glslangValidator> -DSPIRV_CROSS=<spirv-cross> -DPORT_GLSL=<emcv_port.glsl>
#       -DKERNEL=<shaders/reference/port_reference.glsl> -DWORK=<dir> -DOUTPUT=<emcv_port_reference.hlsl>
#       [-DMODULE=<emcv_port.hlsl>] [-DSHADER_MODEL=51] [-DTUNABLES=NAME=VALUE;...] -P emcv_port_hlsl.cmake
# Installed with its helper and kernel as <prefix>/share/emcv/hlsl-port/ (PORT_GLSL: <prefix>/share/emcv/emcv_port.glsl,
# KERNEL: hlsl-port/port_reference.glsl), so that an engine makes emcv_port.hlsl again with its own TUNABLES.
# The HLSL deliverables, from one translation: `#version 450 core` + the flattened port + the reference kernel,
# compiled to Vulkan SPIR-V by glslang and translated by spirv-cross for shader model 5.1.
#  OUTPUT  the reference kernel as spirv-cross writes it, with an entry point `main` and its resources: each
#          descriptor set becomes a register space (set 0 -> space0, set 1 -> space1), so the port's buffers and
#          images, whose binding numbers overlap between the sets, never share a register.
#  MODULE  the library an engine #includes: the port's structs and every emcv_* function (same names as in
#          GLSL), the port's numeric constants as #defines, include-guarded; no entry point, no resource, no
#          cbuffer, no register, no global. Anything of the translation that is neither a port struct, a port
#          function, spirv-cross's own helper nor one of the kernel's (entry point, resources, built-ins) fails
#          the build, as does a kept function that names one of the kernel's resources.
# TUNABLES: NAME=VALUE pairs #defined before the port (its #ifndef tunables, history.h, resolve.h): the HLSL is
# translated code, so the tunables are baked at these values (the defaults otherwise) and the module's header says
# which; an engine that #defines one of them before the #include gets an #error instead of a silent mismatch.
cmake_minimum_required(VERSION 3.21)
include("${CMAKE_CURRENT_LIST_DIR}/EmcvTextLines.cmake")
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
set(overrides "")
set(override_names "")
foreach(pair IN LISTS TUNABLES)
  if(NOT pair MATCHES "^(EMCV_[A-Z0-9_]+)=(.+)$")
    message(FATAL_ERROR "emcv_port_hlsl.cmake: TUNABLES takes NAME=VALUE items, not '${pair}'")
  endif()
  string(APPEND overrides "#define ${CMAKE_MATCH_1} ${CMAKE_MATCH_2}\n")
  list(APPEND override_names "${CMAKE_MATCH_1}")
  set("override_${CMAKE_MATCH_1}" "${CMAKE_MATCH_2}")
endforeach()
set(glsl "${WORK}/emcv_port_reference.comp.glsl")
file(WRITE "${glsl}" "#version 450 core\n${overrides}${port}\n${kernel}")

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
// Do not edit. What it is: an example of binding the port, not a file to #include (that is emcv_port.hlsl):
// the port's structs and functions (as in emcv_port.hlsl) and an entry point `main` that shows the bindings:
// Vulkan set 0 (buffers, the uniform block, the texture) in space0 and set 1 (images) in space1, binding b ->
// register (u|t|b|s)b. Storage buffers are (RW)ByteAddressBuffers, as spirv-cross writes them, read at the
// std430 offsets of emcv/port/host.hpp. docs/integration.md, section 4.
${hlsl}")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
if(NOT DEFINED MODULE)
  return()
endif()

# ---- the module: the translation's top-level items, sorted into kept and dropped ----
# one list item per line: park the characters that CMake lists treat specially
emcv_text_lines("${hlsl}" lines)
set(kept "")
set(dropped_names "")
set(item "")
set(depth 0)
set(struct_count 0)
set(function_count 0)
foreach(line IN LISTS lines)
  if(item STREQUAL "" AND line MATCHES "^[ \t]*$")
    continue()
  endif()
  string(APPEND item "${line}\n")
  string(REGEX MATCHALL "{" opens "${line}")
  string(REGEX MATCHALL "}" closes "${line}")
  list(LENGTH opens n_open)
  list(LENGTH closes n_close)
  math(EXPR depth "${depth} + ${n_open} - ${n_close}")
  if(depth GREATER 0 OR NOT (line MATCHES "@EMCV_SEMICOLON@[ \t]*$" OR line MATCHES "^}"))
    continue()
  endif()
  # a complete top-level item: its first line says what it is
  string(REGEX MATCH "^[^\n]*" head "${item}")
  if(head MATCHES "^struct (Emcv[A-Za-z0-9_]*)$")
    string(APPEND kept "${item}\n")
    math(EXPR struct_count "${struct_count} + 1")
  elseif(head MATCHES "^struct SPIRV_Cross_(Input|Output)$")
    # the entry point's stage interface
  elseif(head MATCHES "^static (const )?[A-Za-z0-9_]+ (gl_[A-Za-z0-9_]+)")
    list(APPEND dropped_names "${CMAKE_MATCH_2}")  # built-ins of the kernel (gl_WorkGroupSize, gl_GlobalInvocationID)
  elseif(head MATCHES "^cbuffer ([A-Za-z0-9_]+)")
    list(APPEND dropped_names "${CMAKE_MATCH_1}")
    string(REGEX MATCHALL "[A-Za-z0-9_]+ : packoffset" members "${item}")
    foreach(m IN LISTS members)
      string(REGEX REPLACE " : packoffset$" "" m "${m}")
      list(APPEND dropped_names "${m}")
    endforeach()
  elseif(head MATCHES "([A-Za-z0-9_]+) : register\\(")
    list(APPEND dropped_names "${CMAKE_MATCH_1}")
  elseif(head MATCHES "^@EMCV_LBRACKET@numthreads\\(" OR head MATCHES "^void (comp_main|main)\\(")
    # the entry point
  elseif(head MATCHES "^[A-Za-z0-9_]+ (emcv_[a-z0-9_]+)\\(")
    string(APPEND kept "${item}\n")
    math(EXPR function_count "${function_count} + 1")
  elseif(head MATCHES "^[A-Za-z0-9_<>, ]+ (spv[A-Za-z0-9_]*|SPIRV_Cross_[A-Za-z0-9_]*)\\(" OR
         head MATCHES "^static const [A-Za-z0-9_]+ (spv|_)[A-Za-z0-9_]*")
    string(APPEND kept "${item}\n")  # spirv-cross's helper functions and the port's constant tables
  else()
    emcv_unpark_text("${item}" item)
    message(FATAL_ERROR "emcv_port_hlsl.cmake: spirv-cross wrote an item the module does not know how to sort "
                        "(keep it or drop it, cmake/emcv_port_hlsl.cmake):\n${item}")
  endif()
  set(item "")
endforeach()
if(NOT item STREQUAL "" OR NOT depth EQUAL 0)
  message(FATAL_ERROR "emcv_port_hlsl.cmake: unbalanced braces at the end of spirv-cross's output")
endif()
emcv_unpark_text("${kept}" kept)
foreach(name IN LISTS dropped_names ITEMS stage_input comp_main)
  if(kept MATCHES "[^A-Za-z0-9_.]${name}[^A-Za-z0-9_]")  # not a struct member of that name
    message(FATAL_ERROR "emcv_port_hlsl.cmake: a function kept for the module uses the kernel's '${name}'")
  endif()
endforeach()
if(struct_count EQUAL 0 OR function_count EQUAL 0)
  message(FATAL_ERROR "emcv_port_hlsl.cmake: no port struct or function in spirv-cross's output")
endif()

# The port's numeric constants (`#define EMCV_NAME <number>` in emcv_port.glsl) as #defines of the module, at
# the values the translation baked in: a tunable (an #ifndef-guarded one) overridden by TUNABLES takes its value.
string(REGEX MATCHALL "\n#define EMCV_[A-Z0-9_]+[ \t]+[-+(). 0-9eEuf]+[^\n]*" defines "\n${port}")
string(REGEX MATCHALL "\n#ifndef (EMCV_[A-Z0-9_]+)\n#define EMCV_[A-Z0-9_]+ " guarded "\n${port}")
set(constants "")
set(tunable_list "")
foreach(d IN LISTS defines)
  if(NOT d MATCHES "^\n#define (EMCV_[A-Z0-9_]+)[ \t]+([-+(). 0-9eEuf]*[0-9][-+(). 0-9eEuf]*)[ \t]*(///?.*)?$")
    continue()
  endif()
  set(name "${CMAKE_MATCH_1}")
  string(STRIP "${CMAKE_MATCH_2}" value)
  if(name MATCHES "_H$" OR constants MATCHES "#define ${name} ")
    continue()
  endif()
  if(DEFINED "override_${name}")
    set(value "${override_${name}}")
  endif()
  string(APPEND constants "#ifdef ${name}\n#error \"emcv_port.hlsl: ${name} is ${value} in its translated functions: "
                          "do not #define it before the #include\"\n#endif\n"
                          "#define ${name} ${value}\n")
  if(guarded MATCHES "#ifndef ${name}\n")
    string(APPEND tunable_list "//   ${name} ${value}\n")
  endif()
endforeach()
foreach(name IN LISTS override_names)
  if(NOT guarded MATCHES "#ifndef ${name}\n" OR NOT constants MATCHES "#define ${name} ")
    message(FATAL_ERROR "emcv_port_hlsl.cmake: TUNABLES names ${name}, which is not one of the port's numeric tunables")
  endif()
endforeach()
string(REGEX MATCH "GLSL side of emcv ([0-9.]+)'s" _ "${port}")
set(version "${CMAKE_MATCH_1}")
file(WRITE "${MODULE}.tmp" "// SPDX-License-Identifier: MIT
// emcv_port.hlsl: emcv ${version}'s shared C++/GLSL port as an HLSL library to #include: the port's structs and
// its ${function_count} emcv_* functions under their GLSL names, and its numeric constants as #defines. No entry
// point, resource, cbuffer, register or global: the including shader declares its own (docs/porting.md, \"HLSL\").
// Generated at emcv's build time (cmake/emcv_port_hlsl.cmake) from emcv_port.glsl and the reference kernel
// shaders/reference/port_reference.glsl, which calls every function: `#version 450 core` + both ->
// glslangValidator -V -> spirv-cross --hlsl --shader-model ${SHADER_MODEL}, the kernel's entry point and
// resources dropped. Do not edit.
// Translated code: the tunables are baked in at these values (#defining one before the #include is an #error;
// cmake -DTUNABLES=NAME=VALUE regenerates the module with others):
${tunable_list}// Layouts: a StructuredBuffer<EmcvEmcm2> on Direct3D is 32 bytes per element, not host.hpp's 48 (std430):
// docs/porting.md, \"HLSL\".
#ifndef EMCV_PORT_HLSL
#define EMCV_PORT_HLSL

${constants}
${kept}#endif  // EMCV_PORT_HLSL
")
file(COPY_FILE "${MODULE}.tmp" "${MODULE}" ONLY_IF_DIFFERENT)
file(REMOVE "${MODULE}.tmp")
