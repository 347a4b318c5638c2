# The port's shader files for engines, generated at build time from include/emcv/port/*.h (never kept by hand)
# into <build>/share/emcv/ and installed under <prefix>/${CMAKE_INSTALL_DATADIR}/emcv/:
#   emcv_port.glsl             every port header's GLSL side in one file (cmake/emcv_flatten_port.cmake;
#                              CMake only, always generated)
#   emcv_port.hlsl             the port as an HLSL library to #include: its structs and functions, no entry
#                              point or resource (cmake/emcv_port_hlsl.cmake; needs glslangValidator and
#                              spirv-cross, scripts/install-deps.sh: skipped with a STATUS message without them)
#   emcv_port_reference.hlsl   the same translation's reference kernel, with its resources in register spaces:
#                              an example of the bindings (same tools)
# Sets EMCV_PORT_GLSL_FILE, EMCV_PORT_HLSL_MODULE and EMCV_PORT_HLSL_FILE (both empty when skipped) for the tests.
set(EMCV_SHADER_FILES_DIR "${PROJECT_BINARY_DIR}/share/emcv")
file(GLOB _emcv_port_sources CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/include/emcv/port/*.h")
set(EMCV_PORT_GLSL_FILE "${EMCV_SHADER_FILES_DIR}/emcv_port.glsl")
add_custom_command(
  OUTPUT "${EMCV_PORT_GLSL_FILE}"
  COMMAND "${CMAKE_COMMAND}" "-DPORT_DIR=${PROJECT_SOURCE_DIR}/include/emcv/port" "-DOUTPUT=${EMCV_PORT_GLSL_FILE}"
          "-DVERSION=${PROJECT_VERSION}" -P "${PROJECT_SOURCE_DIR}/cmake/emcv_flatten_port.cmake"
  DEPENDS ${_emcv_port_sources} "${PROJECT_SOURCE_DIR}/cmake/emcv_flatten_port.cmake"
  COMMENT "Flattening include/emcv/port/*.h into share/emcv/emcv_port.glsl"
  VERBATIM)
set(_emcv_shader_outputs "${EMCV_PORT_GLSL_FILE}")

find_program(EMCV_GLSLANG_VALIDATOR glslangValidator)
find_program(EMCV_SPIRV_CROSS spirv-cross)
set(EMCV_PORT_HLSL_FILE "")
set(EMCV_PORT_HLSL_MODULE "")
if(EMCV_GLSLANG_VALIDATOR AND EMCV_SPIRV_CROSS)
  set(EMCV_PORT_HLSL_FILE "${EMCV_SHADER_FILES_DIR}/emcv_port_reference.hlsl")
  set(EMCV_PORT_HLSL_MODULE "${EMCV_SHADER_FILES_DIR}/emcv_port.hlsl")
  set(_kernel "${PROJECT_SOURCE_DIR}/shaders/reference/port_reference.glsl")
  add_custom_command(
    OUTPUT "${EMCV_PORT_HLSL_FILE}" "${EMCV_PORT_HLSL_MODULE}"
    COMMAND "${CMAKE_COMMAND}" "-DGLSLANG=${EMCV_GLSLANG_VALIDATOR}" "-DSPIRV_CROSS=${EMCV_SPIRV_CROSS}"
            "-DPORT_GLSL=${EMCV_PORT_GLSL_FILE}" "-DKERNEL=${_kernel}"
            "-DWORK=${PROJECT_BINARY_DIR}/shader_files" "-DOUTPUT=${EMCV_PORT_HLSL_FILE}"
            "-DMODULE=${EMCV_PORT_HLSL_MODULE}"
            -P "${PROJECT_SOURCE_DIR}/cmake/emcv_port_hlsl.cmake"
    DEPENDS "${EMCV_PORT_GLSL_FILE}" "${_kernel}" "${PROJECT_SOURCE_DIR}/cmake/emcv_port_hlsl.cmake"
    COMMENT "Translating the port into share/emcv/emcv_port.hlsl and emcv_port_reference.hlsl"
    VERBATIM)
  list(APPEND _emcv_shader_outputs "${EMCV_PORT_HLSL_FILE}" "${EMCV_PORT_HLSL_MODULE}")
else()
  message(STATUS "emcv: share/emcv/emcv_port.hlsl and emcv_port_reference.hlsl skipped: glslangValidator or spirv-cross not found "
                 "(Debian: glslang-tools spirv-cross, scripts/install-deps.sh); emcv_port.glsl is still generated")
endif()
add_custom_target(emcv_shader_files ALL DEPENDS ${_emcv_shader_outputs})
