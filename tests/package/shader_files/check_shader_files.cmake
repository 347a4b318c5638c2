# cmake -DSHADER_DIR=<prefix>/share/emcv -DSOURCE_DIR=<emcv source> -DGLSLANG=<glslangValidator>
#       -DSPIRV_CROSS=<spirv-cross> -DWORK=<dir> -P check_shader_files.cmake
# The installed share/emcv files, as an engine takes them:
#  1. emcv_port.glsl is the flattening of the source tree's port headers as they are now (a file generated
#     before a header changed fails), holds every header (its include guard) and no #include, #extension,
#     #line or #version;
#  2. `#version 450 core` + emcv_port.glsl + a main compiles as OpenGL GLSL, OpenGL SPIR-V and Vulkan SPIR-V;
#  3. emcv_port_reference.hlsl compiles with glslang's HLSL front end, gives every resource an explicit
#     register in a space, no two resources the same (register, space), and compiles back to the descriptor
#     sets and bindings of the GLSL it was translated from;
#  4. every function of emcv_port.glsl is a function of the HLSL, and the HLSL files (emcv_port_reference.hlsl
#     and the module emcv_port.hlsl, whose use tests/hlsl checks) are the translation of the source tree's port
#     and reference kernel (not stale);
#  5. the installed translation kit (share/emcv/hlsl-port) makes emcv_port.hlsl again from the installed
#     emcv_port.glsl with other tunables (a budget of 8 at K = 2): its header states them, each is #defined at
#     that value, and its reference kernel compiles with glslang's HLSL front end.
cmake_minimum_required(VERSION 3.21)
include("${CMAKE_CURRENT_LIST_DIR}/../script_support.cmake")
emcv_require_vars(check_shader_files.cmake SHADER_DIR SOURCE_DIR GLSLANG SPIRV_CROSS WORK)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(glsl_file "${SHADER_DIR}/emcv_port.glsl")
set(hlsl_file "${SHADER_DIR}/emcv_port_reference.hlsl")
set(module_file "${SHADER_DIR}/emcv_port.hlsl")
foreach(f "${glsl_file}" "${hlsl_file}" "${module_file}")
  if(NOT EXISTS "${f}")
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()

# 1. fresh, complete, self-contained
file(READ "${glsl_file}" installed)
string(REGEX MATCH "GLSL side of emcv ([0-9.]+)'s" _ "${installed}")
run("flattening the source tree's port" "${CMAKE_COMMAND}" "-DPORT_DIR=${SOURCE_DIR}/include/emcv/port"
    "-DOUTPUT=${WORK}/emcv_port.glsl" "-DVERSION=${CMAKE_MATCH_1}" -P "${SOURCE_DIR}/cmake/emcv_flatten_port.cmake")
file(READ "${WORK}/emcv_port.glsl" fresh)
if(NOT installed STREQUAL fresh)
  message(FATAL_ERROR "stale: ${glsl_file} is not the flattening of ${SOURCE_DIR}/include/emcv/port as it is now "
                      "(rebuild emcv, then install; compare with ${WORK}/emcv_port.glsl)")
endif()
file(GLOB headers "${SOURCE_DIR}/include/emcv/port/*.h")
foreach(h IN LISTS headers)
  file(STRINGS "${h}" guard REGEX "^#ifndef EMCV_[A-Z_]+_H$" LIMIT_COUNT 1)
  string(REPLACE "#ifndef " "" guard "${guard}")
  if(guard STREQUAL "" OR NOT installed MATCHES "#define ${guard}\n")
    message(FATAL_ERROR "${glsl_file} lacks ${h} (include guard '${guard}')")
  endif()
endforeach()
if(installed MATCHES "\n[ \t]*#[ \t]*(include|extension|line|version)")
  message(FATAL_ERROR "${glsl_file} holds a #${CMAKE_MATCH_1} line")
endif()

# 2. pasted after #version 450, for OpenGL and Vulkan
set(shader "${WORK}/flat_consumer.comp")
file(WRITE "${shader}" "#version 450 core\n${installed}
layout(local_size_x = EMCV_WORKGROUP_SIZE_X) in;
layout(std430, EMCV_LAYOUT_BINDING(0)) buffer States { EmcvEmcm2 states[]; };
layout(r32f, EMCV_LAYOUT_IMAGE_BINDING(0)) uniform image2D alpha_image;
void main() {
    EmcvEmcm2 s = states[gl_GlobalInvocationID.x];
    emcv_emcm2_push(s, vec2(1.0f, 2.0f), EMCV_HISTORY_ETA_EMCM);
    states[gl_GlobalInvocationID.x] = s;
    imageStore(alpha_image, ivec2(gl_GlobalInvocationID.xy), vec4(emcv_cv_coefficient_emcm2(s)));
}
")
run("emcv_port.glsl, OpenGL GLSL" "${GLSLANG}" -l "${shader}")
run("emcv_port.glsl, OpenGL SPIR-V" "${GLSLANG}" -G --target-env opengl "${shader}" -o "${WORK}/flat.gl.spv")
run("emcv_port.glsl, Vulkan SPIR-V" "${GLSLANG}" -V --target-env vulkan1.0 "${shader}" -o "${WORK}/flat.vk.spv")

# 3. the HLSL: fresh, compiles, one register per resource, the GLSL's sets and bindings
run("translating the source tree's reference kernel" "${CMAKE_COMMAND}" "-DGLSLANG=${GLSLANG}"
    "-DSPIRV_CROSS=${SPIRV_CROSS}" "-DPORT_GLSL=${glsl_file}" "-DKERNEL=${SOURCE_DIR}/shaders/reference/port_reference.glsl"
    "-DWORK=${WORK}/hlsl" "-DOUTPUT=${WORK}/emcv_port_reference.hlsl" "-DMODULE=${WORK}/emcv_port.hlsl" -P "${SOURCE_DIR}/cmake/emcv_port_hlsl.cmake")
file(READ "${hlsl_file}" hlsl)
run("emcv_port_reference.hlsl, glslang HLSL front end" "${GLSLANG}" -D -e main -S comp -V "${hlsl_file}"
    -o "${WORK}/hlsl.spv")
string(REGEX MATCHALL "\n[^\n/]*: register\\([^)]*\\)" declarations "${hlsl}")
list(LENGTH declarations resource_count)
if(resource_count LESS 5)
  message(FATAL_ERROR "${hlsl_file}: only ${resource_count} resources with a register")
endif()
set(seen "")
foreach(d IN LISTS declarations)
  if(NOT d MATCHES "register\\(([btsu][0-9]+), (space[0-9]+)\\)")
    message(FATAL_ERROR "${hlsl_file}: a register without a space:${d}")
  endif()
  set(slot "${CMAKE_MATCH_1}/${CMAKE_MATCH_2}")
  if(slot IN_LIST seen)
    message(FATAL_ERROR "${hlsl_file}: two resources on register ${slot}:${d}")
  endif()
  list(APPEND seen "${slot}")
endforeach()

# (set, binding) of every resource in a SPIR-V module, sorted, from spirv-cross --reflect
function(descriptor_slots spv out_var)
  run("spirv-cross --reflect ${spv}" "${SPIRV_CROSS}" "${spv}" --reflect)
  set(slots "")
  foreach(kind ssbos ubos images textures separate_images separate_samplers)
    string(JSON count ERROR_VARIABLE missing LENGTH "${run_output}" ${kind})
    if(missing OR count EQUAL 0)
      continue()
    endif()
    math(EXPR last "${count} - 1")
    foreach(i RANGE ${last})
      string(JSON set GET "${run_output}" ${kind} ${i} set)
      string(JSON binding GET "${run_output}" ${kind} ${i} binding)
      list(APPEND slots "set ${set} binding ${binding}")
    endforeach()
  endforeach()
  list(SORT slots)
  set(${out_var} "${slots}" PARENT_SCOPE)
endfunction()
descriptor_slots("${WORK}/hlsl/emcv_port_reference.spv" glsl_slots)
descriptor_slots("${WORK}/hlsl.spv" hlsl_slots)
# the GLSL's combined image sampler is a texture and a sampler in HLSL: compare the distinct slots
list(REMOVE_DUPLICATES hlsl_slots)
if(NOT glsl_slots STREQUAL hlsl_slots)
  message(FATAL_ERROR "the HLSL's descriptors (${hlsl_slots}) are not the GLSL's (${glsl_slots})")
endif()
if(NOT glsl_slots MATCHES "set 1 binding 0" OR NOT glsl_slots MATCHES "set 0 binding 0")
  message(FATAL_ERROR "the reference kernel should bind set 0 and set 1 from binding 0 on: ${glsl_slots}")
endif()

# 4. every port function in the HLSL
string(REGEX MATCHALL "\n(EMCV_FN )?[A-Za-z0-9_]+ emcv_[a-z0-9_]+\\(" glsl_functions "${installed}")
list(LENGTH glsl_functions function_count)
foreach(f IN LISTS glsl_functions)
  string(REGEX MATCH "emcv_[a-z0-9_]+" name "${f}")
  if(NOT hlsl MATCHES "\n[A-Za-z0-9_]+ ${name}\\(")
    message(FATAL_ERROR "${hlsl_file} lacks the port function ${name} (call it in shaders/reference/port_reference.glsl)")
  endif()
endforeach()
# last, so that a broken file reports what is broken rather than only that it differs
foreach(name emcv_port_reference.hlsl emcv_port.hlsl)
  file(READ "${SHADER_DIR}/${name}" installed_hlsl)
  file(READ "${WORK}/${name}" fresh_hlsl)
  if(NOT installed_hlsl STREQUAL fresh_hlsl)
    message(FATAL_ERROR "stale: ${SHADER_DIR}/${name} is not the translation of the source tree's port and reference "
                        "kernel (rebuild emcv, then install; compare with ${WORK}/${name})")
  endif()
endforeach()

# 5. the installed kit, with other tunables (a quoted literal: execute_process keeps it one argument)
set(kit "${SHADER_DIR}/hlsl-port")
execute_process(COMMAND "${CMAKE_COMMAND}" "-DGLSLANG=${GLSLANG}" "-DSPIRV_CROSS=${SPIRV_CROSS}"
                        "-DPORT_GLSL=${glsl_file}" "-DKERNEL=${kit}/port_reference.glsl" "-DWORK=${WORK}/kit"
                        "-DOUTPUT=${WORK}/kit/emcv_port_reference.hlsl" "-DMODULE=${WORK}/kit/emcv_port.hlsl"
                        "-DTUNABLES=EMCV_HISTORY_SPP_BUDGET=8.0f;EMCV_HISTORY_BLOCK=2" -P "${kit}/emcv_port_hlsl.cmake"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed kit ${kit} failed (exit ${rc}):\n${out}${err}")
endif()
file(READ "${WORK}/kit/emcv_port.hlsl" kit_module)
foreach(pair "EMCV_HISTORY_SPP_BUDGET 8.0f" "EMCV_HISTORY_BLOCK 2")
  if(NOT kit_module MATCHES "\n//   ${pair}\n" OR NOT kit_module MATCHES "\n#define ${pair}\n")
    message(FATAL_ERROR "${WORK}/kit/emcv_port.hlsl does not state and #define ${pair}")
  endif()
endforeach()
run("the kit's emcv_port_reference.hlsl, glslang HLSL front end" "${GLSLANG}" -D -e main -S comp -V
    "${WORK}/kit/emcv_port_reference.hlsl" -o "${WORK}/kit.spv")
message(STATUS "shader files: OK (${function_count} functions, ${resource_count} registers: ${seen}; the kit)")
