# The port's shader files for engines, generated at build time from include/emcv/port/*.h (never kept by hand)
# into <build>/share/emcv/ and installed under <prefix>/${CMAKE_INSTALL_DATADIR}/emcv/:
#   emcv_port.glsl             every port header's GLSL side in one file (cmake/emcv_flatten_port.cmake;
#                              CMake only, always generated)
#   emcv_port.hlsl             the port as an HLSL library to #include: its structs and functions, no entry
#                              point or resource (cmake/emcv_port_hlsl.cmake; needs glslangValidator and
#                              spirv-cross, scripts/install-deps.sh: skipped with a STATUS message without them)
#   emcv_port_reference.hlsl   the same translation's reference kernel, with its resources in register spaces:
#                              an example of the bindings (same tools)
#   module/hlsl/*.hlsl         the GPU modules (shaders/module) for HLSL, included after emcv_port.hlsl: each
#                              module's GLSL with its #includes pointed at the HLSL files, and the language file
#                              that maps the GLSL names they use (cmake/emcv_module_hlsl.cmake; CMake only, but
#                              made with emcv_port.hlsl, without which they are of no use)
# Sets EMCV_PORT_GLSL_FILE, EMCV_PORT_HLSL_MODULE, EMCV_PORT_HLSL_FILE, EMCV_MODULE_HLSL_DIR and
# EMCV_MODULE_HLSL_FILES (the HLSL ones empty when skipped) for the tests and the install.
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
set(EMCV_MODULE_HLSL_DIR "")
set(EMCV_MODULE_HLSL_FILES "")
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
            "${PROJECT_SOURCE_DIR}/cmake/EmcvTextLines.cmake"
    COMMENT "Translating the port into share/emcv/emcv_port.hlsl and emcv_port_reference.hlsl"
    VERBATIM)
  list(APPEND _emcv_shader_outputs "${EMCV_PORT_HLSL_FILE}" "${EMCV_PORT_HLSL_MODULE}")

  set(EMCV_MODULE_HLSL_DIR "${EMCV_SHADER_FILES_DIR}/module/hlsl")
  set(_module_dir "${PROJECT_SOURCE_DIR}/shaders/module")
  file(GLOB _emcv_modules CONFIGURE_DEPENDS "${_module_dir}/*.glsl")
  list(FILTER _emcv_modules EXCLUDE REGEX "/emcv_adaptive_language\\.glsl$")  # HLSL has its own (below)
  set(_language "${_module_dir}/hlsl/emcv_adaptive_language.hlsl")
  set(EMCV_MODULE_HLSL_FILES "${EMCV_MODULE_HLSL_DIR}/emcv_adaptive_language.hlsl")
  foreach(_module IN LISTS _emcv_modules)
    get_filename_component(_name "${_module}" NAME_WE)
    list(APPEND EMCV_MODULE_HLSL_FILES "${EMCV_MODULE_HLSL_DIR}/${_name}.hlsl")
  endforeach()
  add_custom_command(
    OUTPUT ${EMCV_MODULE_HLSL_FILES}
    COMMAND "${CMAKE_COMMAND}" "-DMODULE_DIR=${_module_dir}" "-DOUTPUT_DIR=${EMCV_MODULE_HLSL_DIR}"
            -P "${PROJECT_SOURCE_DIR}/cmake/emcv_module_hlsl.cmake"
    DEPENDS ${_emcv_modules} "${_language}" "${PROJECT_SOURCE_DIR}/cmake/emcv_module_hlsl.cmake"
            "${PROJECT_SOURCE_DIR}/cmake/EmcvTextLines.cmake"
    COMMENT "Writing the GPU modules for HLSL into share/emcv/module/hlsl"
    VERBATIM)
  list(APPEND _emcv_shader_outputs ${EMCV_MODULE_HLSL_FILES})
else()
  message(STATUS "emcv: share/emcv/emcv_port.hlsl, emcv_port_reference.hlsl and module/hlsl skipped: glslangValidator or spirv-cross not found "
                 "(Debian: glslang-tools spirv-cross, scripts/install-deps.sh); emcv_port.glsl is still generated")
endif()
add_custom_target(emcv_shader_files ALL DEPENDS ${_emcv_shader_outputs})
