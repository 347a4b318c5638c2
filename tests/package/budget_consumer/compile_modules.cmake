# cmake -DGLSLANG=<glslangValidator> -DSPIRV_CROSS=<spirv-cross> -DSHARE_DIR=<prefix>/share/emcv
#       -DINCLUDE_ROOT=<prefix>/include -DSOURCE_MODULES=<emcv source>/shaders/module -DPASSES=<this folder>
#       [-DHLSL_PASSES=<emcv source>/tests/hlsl/modules] -DWORK=<dir> -P compile_modules.cmake
# The installed GPU modules as an engine on another API takes them:
#  1. the installed modules are the source tree's, file for file, and declare no resource (no `uniform`,
#     `buffer` or `layout(` outside comments: the application's bindings only);
#  2. budget_consumer's four passes, for each method (EMCV_ADAPTIVE_CV, _SPVG, _NOTEX) and grain
#     (EMCV_HISTORY_BLOCK 1, 2, 4), compile to OpenGL and Vulkan SPIR-V with glslang's include directive
#     (-I <prefix>/share/emcv -I <prefix>/include), and spirv-cross turns the Vulkan SPIR-V into HLSL (shader
#     model 5.1);
#  3. with HLSL_PASSES: the installed HLSL modules (share/emcv/module/hlsl, one per GLSL module and the language
#     file) take an HLSL engine's passes (tests/hlsl/modules) for each method, with the installed emcv_port.hlsl
#     and -I <prefix>/share/emcv/module/hlsl only, through glslang's HLSL front end.
cmake_minimum_required(VERSION 3.21)
include("${CMAKE_CURRENT_LIST_DIR}/../script_support.cmake")
emcv_require_vars(compile_modules.cmake GLSLANG SPIRV_CROSS SHARE_DIR INCLUDE_ROOT SOURCE_MODULES PASSES WORK)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

# 1. installed = source; no resources
emcv_require_same_files(modules "${SOURCE_MODULES}" "${SHARE_DIR}/module" "*.glsl" installed_modules)
foreach(m IN LISTS installed_modules)
  file(READ "${SHARE_DIR}/module/${m}" text)
  string(REGEX REPLACE "//[^\n]*" "" code "${text}")  # comments and #error messages out
  string(REGEX REPLACE "#error[^\n]*" "" code "${code}")
  foreach(pattern "(^|[^a-z_])(uniform|buffer)[ \t\n]" "layout[ \t]*\\(")
    if(code MATCHES "${pattern}")
      message(FATAL_ERROR "module/${m} declares a resource ('${CMAKE_MATCH_0}'): the application's bindings only")
    endif()
  endforeach()
endforeach()

# 2. every pass x method x grain: OpenGL and Vulkan SPIR-V, then HLSL
set(count 0)
foreach(method CV SPVG NOTEX)
  foreach(block 1 2 4)
    foreach(pass plan solve count update)
      set(name "${pass}_${method}_k${block}")
      set(wrapper "${WORK}/${name}.comp")
      file(WRITE "${wrapper}" "#version 450 core\n#extension GL_GOOGLE_include_directive : require\n"
                              "#define EMCV_ADAPTIVE_${method} 1\n#define EMCV_HISTORY_BLOCK ${block}\n"
                              "#define EMCV_HISTORY_SPP_BUDGET 8.0f\n#include \"${pass}.comp.glsl\"\n")
      set(includes "-I${PASSES}" "-I${SHARE_DIR}" "-I${INCLUDE_ROOT}")
      run("${name}, OpenGL SPIR-V" "${GLSLANG}" -G --target-env opengl ${includes} "${wrapper}" -o "${WORK}/${name}.gl.spv")
      run("${name}, Vulkan SPIR-V" "${GLSLANG}" -V --target-env vulkan1.0 ${includes} "${wrapper}" -o "${WORK}/${name}.vk.spv")
      run("${name}, HLSL" "${SPIRV_CROSS}" "${WORK}/${name}.vk.spv" --hlsl --shader-model 51 --output "${WORK}/${name}.hlsl")
      math(EXPR count "${count} + 1")
    endforeach()
  endforeach()
endforeach()
# 3. the HLSL modules, installed, as an HLSL engine includes them
set(hlsl_note "")
set(hlsl_count 0)
if(DEFINED HLSL_PASSES)
  set(hlsl_dir "${SHARE_DIR}/module/hlsl")
  file(GLOB hlsl_modules RELATIVE "${hlsl_dir}" "${hlsl_dir}/*.hlsl")
  list(SORT hlsl_modules)
  set(expected emcv_adaptive_language.hlsl)
  foreach(m IN LISTS installed_modules)  # = the source tree's (above)
    string(REGEX REPLACE "\\.glsl$" ".hlsl" m "${m}")
    list(APPEND expected "${m}")
  endforeach()
  list(REMOVE_DUPLICATES expected)
  list(SORT expected)
  if(NOT hlsl_modules STREQUAL expected)
    message(FATAL_ERROR "installed HLSL modules (${hlsl_modules}) are not the GLSL modules' (${expected})")
  endif()
  foreach(method CV SPVG NOTEX)
    foreach(pass plan solve count update quality)
      run("${pass}_${method}, HLSL" "${GLSLANG}" -D -V -e main -S comp "-DEMCV_ADAPTIVE_${method}=1" "-I${SHARE_DIR}"
          "-I${hlsl_dir}" "${HLSL_PASSES}/${pass}.comp.hlsl" -o "${WORK}/${pass}_${method}.hlsl.spv")
      math(EXPR hlsl_count "${hlsl_count} + 1")
    endforeach()
  endforeach()
  set(hlsl_note "; ${hlsl_count} HLSL passes compiled from the installed module/hlsl")
endif()
message(STATUS "gpu modules: OK (${installed_modules} without resources; ${count} passes compiled for OpenGL and Vulkan SPIR-V and translated to HLSL${hlsl_note})")
