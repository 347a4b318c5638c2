# cmake -DGLSLANG=<glslangValidator> -DSPIRV_CROSS=<spirv-cross> -DINCLUDE_ROOT=<prefix>/include
#       -DSOURCE_PORT=<emcv source>/include/emcv/port -DSHADER=consumer.comp.glsl -DWORK=<dir> -P compile_installed_port.cmake
# An engine taking the installed GLSL side: only <prefix>/include is on the include path.
#  1. every port header of the source tree is installed (the install rule takes the folder, not a list);
#  2. a shader including each installed header, twice, compiles for OpenGL (-G) and Vulkan (-V) SPIR-V;
#  3. SHADER validates as OpenGL GLSL, compiles to OpenGL and Vulkan SPIR-V, and spirv-cross turns the
#     Vulkan SPIR-V into HLSL (shader model 5.1) and MSL source: an engine on another API can take it.
cmake_minimum_required(VERSION 3.21)
include("${CMAKE_CURRENT_LIST_DIR}/../script_support.cmake")
emcv_require_vars(compile_installed_port.cmake GLSLANG SPIRV_CROSS INCLUDE_ROOT SOURCE_PORT SHADER WORK)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

# 1. the installed port is the source tree's port, header for header
emcv_require_same_files("port headers" "${SOURCE_PORT}" "${INCLUDE_ROOT}/emcv/port" "*.h" installed_headers)

# 2. every installed header, included twice (include guards), for both targets
set(all "${WORK}/all_port_headers.comp.glsl")
set(text "#version 450 core\n#extension GL_GOOGLE_include_directive : require\n")
foreach(h IN LISTS installed_headers)
  string(APPEND text "#include \"emcv/port/${h}\"\n#include \"emcv/port/${h}\"\n")
endforeach()
string(APPEND text "layout(local_size_x = 1) in;\nvoid main() {}\n")
file(WRITE "${all}" "${text}")
run("every installed header, OpenGL SPIR-V" "${GLSLANG}" -G --target-env opengl "-I${INCLUDE_ROOT}" "${all}" -o "${WORK}/all.gl.spv")
run("every installed header, Vulkan SPIR-V" "${GLSLANG}" -V --target-env vulkan1.0 "-I${INCLUDE_ROOT}" "${all}" -o "${WORK}/all.vk.spv")

# 3. the consumer shader through every target
run("consumer, OpenGL GLSL" "${GLSLANG}" -l "-I${INCLUDE_ROOT}" "${SHADER}")
run("consumer, OpenGL SPIR-V" "${GLSLANG}" -G --target-env opengl "-I${INCLUDE_ROOT}" "${SHADER}" -o "${WORK}/consumer.gl.spv")
run("consumer, Vulkan SPIR-V" "${GLSLANG}" -V --target-env vulkan1.0 "-I${INCLUDE_ROOT}" "${SHADER}" -o "${WORK}/consumer.vk.spv")
run("consumer, HLSL" "${SPIRV_CROSS}" "${WORK}/consumer.vk.spv" --hlsl --shader-model 51 --output "${WORK}/consumer.hlsl")
run("consumer, MSL" "${SPIRV_CROSS}" "${WORK}/consumer.vk.spv" --msl --output "${WORK}/consumer.metal")
# the translated sources hold the kernel with the port's workgroup size (EMCV_WORKGROUP_SIZE_X = 64)
file(READ "${WORK}/consumer.hlsl" hlsl)
file(READ "${WORK}/consumer.metal" msl)
if(NOT hlsl MATCHES "\\[numthreads\\(64, 1, 1\\)\\]")
  message(FATAL_ERROR "consumer.hlsl has no [numthreads(64, 1, 1)] entry point")
endif()
if(NOT msl MATCHES "kernel void main0\\(")
  message(FATAL_ERROR "consumer.metal has no kernel entry point")
endif()
message(STATUS "shader consumer: OK (${WORK})")
