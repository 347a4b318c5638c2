# cmake -DMODULE_DIR=<shaders/module> -DOUTPUT_DIR=<dir> -P emcv_module_hlsl.cmake
# The HLSL versions of the GPU modules: every MODULE_DIR/*.glsl but emcv_adaptive_language.glsl is written into
# OUTPUT_DIR as <name>.hlsl, beside a copy of MODULE_DIR/hlsl/emcv_adaptive_language.hlsl (the language file's HLSL
# side, which replaces its GLSL one). The modules are one implementation in the subset of GLSL that HLSL shares;
# emcv_adaptive_language.hlsl gives HLSL the GLSL names they use. So a module's HLSL file is its GLSL file with
# only its #include lines rewritten, one line for one line:
#   #include "emcv/port/<name>.h"    -> a comment: the engine includes emcv_port.hlsl first (the translated port)
#   #include "module/<name>.glsl"    -> #include "<name>.hlsl" (<name> one of the modules or the language file)
# and a generated-file header in place of the SPDX line. Everything else is copied as it is, after checks that
# fail the build on what the subset excludes (each names its rule: docs/porting.md, "HLSL modules"): another
# #include or a #version / #extension / #pragma; a resource (layout, uniform, buffer); a GLSL built-in variable
# other than gl_LocalInvocationID / gl_LocalInvocationIndex; a one-argument (splat) vector constructor of a
# literal or a macro; a struct or array constructor; == or != on a vector constructor; .length(); a block
# comment; a global neither `shared` nor EMCV_STATIC, a global `const`, or a global initialised by a call.
# glslang's HLSL front end accepts several of these (a splat, a struct constructor, a bool vector where a bool is
# wanted); DXC does not, or reads them otherwise. tests/hlsl/check_hlsl.py (hlsl.gpu_modules) runs this script on
# modules with each of them and expects the failure.
cmake_minimum_required(VERSION 3.21)
include("${CMAKE_CURRENT_LIST_DIR}/EmcvTextLines.cmake")
foreach(var MODULE_DIR OUTPUT_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "emcv_module_hlsl.cmake: -D${var}=... is required")
  endif()
endforeach()
set(language_name emcv_adaptive_language)
set(LANGUAGE "${MODULE_DIR}/hlsl/${language_name}.hlsl")
file(GLOB MODULES "${MODULE_DIR}/*.glsl")
list(FILTER MODULES EXCLUDE REGEX "/${language_name}\\.glsl$")
list(SORT MODULES)
if(MODULES STREQUAL "" OR NOT EXISTS "${LANGUAGE}" OR NOT EXISTS "${MODULE_DIR}/${language_name}.glsl")
  message(FATAL_ERROR "emcv_module_hlsl.cmake: no modules, or no ${language_name}.glsl and hlsl/${language_name}.hlsl, "
                      "in ${MODULE_DIR}")
endif()
file(MAKE_DIRECTORY "${OUTPUT_DIR}")
set(known_names "${language_name}")
foreach(path IN LISTS MODULES)
  get_filename_component(name "${path}" NAME_WE)
  list(APPEND known_names "${name}")
endforeach()

function(refuse path rule what)
  message(FATAL_ERROR "emcv_module_hlsl.cmake: ${path}: ${what}: ${rule} (the modules are GLSL in the subset HLSL "
                      "shares, docs/porting.md, \"HLSL modules\")")
endfunction()

# Fails where `code` (the module being read, at `path`) matches `pattern`, naming `rule`.
function(check pattern rule)
  string(REGEX MATCHALL "${pattern}" found "${code}")
  list(FILTER found EXCLUDE REGEX "gl_LocalInvocation(ID|Index)$")  # the two the language file maps
  if(NOT found STREQUAL "")
    list(GET found 0 found)
    refuse("${path}" "${rule}" "'${found}'")
  endif()
endfunction()

foreach(path IN LISTS MODULES)
  get_filename_component(name "${path}" NAME_WE)
  file(READ "${path}" text)
  # what the checks read: the code without comments and #error messages (which may name anything)
  if(text MATCHES "/\\*")
    refuse("${path}" "write // comments" "a block comment")
  endif()
  string(REGEX REPLACE "//[^\n]*" "" code "${text}")
  string(REGEX REPLACE "#[ \t]*error[^\n]*" "" code "${code}")
  set(v "[biu]?vec[234]")
  set(vector_equality "compare vectors with all(equal()) or any(notEqual()) (HLSL's == is componentwise)")
  # (one call per rule: a CMake list would split the patterns' brackets)
  check("#[ \t]*(version|extension|pragma)[^\n]*" "no #version, #extension or #pragma in a module")
  check("(^|[^A-Za-z0-9_])(layout[ \t]*\\(|uniform[ \t]|buffer[ \t])"
        "no resource in a module: the application binds its own")
  check("(^|[^A-Za-z0-9_])gl_[A-Za-z]+" "no GLSL built-in variable but gl_LocalInvocationID and gl_LocalInvocationIndex")
  check("(^|[^A-Za-z0-9_])${v}\\([ \t]*(-?[0-9][0-9.]*[uUfF]?|[A-Z][A-Z0-9_]*|true|false)[ \t]*\\)"
        "write every component of a vector constructor (HLSL has no splat)")
  check("(^|[^A-Za-z0-9_])Emcv[A-Z][A-Za-z0-9_]*[ \t]*\\(" "no struct constructor: set the members")
  check("[A-Za-z0-9_][ \t]*\\[[^]\n]*\\][ \t]*\\(" "no array constructor")
  check("(==|!=)[ \t]*${v}\\(" "${vector_equality}")
  check("(^|[^A-Za-z0-9_])${v}\\([^()\n]*\\)[ \t]*(==|!=)" "${vector_equality}")
  check("\\.length[ \t]*\\(" "no .length() (GLSL only)")

  # top-level declarations, line by line at brace depth 0 (CMake lists: park ; [ and ])
  emcv_text_lines("${code}" lines)
  set(depth 0)
  set(word "[A-Za-z_][A-Za-z0-9_]*")
  set(declaration "^(${word}[ \t]+)?${word}[ \t]+${word}[ \t]*(=|@EMCV_SEMICOLON@|@EMCV_LBRACKET@)")  # [qualifier] type name =|;|[
  foreach(line IN LISTS lines)
    if(depth EQUAL 0 AND line MATCHES "${declaration}")
      emcv_unpark_text("${line}" line)  # as the module wrote it, for the messages
      if(line MATCHES "^const[ \t]")
        refuse("${path}" "a global constant is a #define (HLSL's needs `static const`)" "'${line}'")
      elseif(NOT line MATCHES "^(shared|EMCV_STATIC)[ \t]")
        refuse("${path}" "a global is `shared` or EMCV_STATIC (HLSL's plain global is a constant)" "'${line}'")
      elseif(line MATCHES "=[^=]*[A-Za-z_][A-Za-z0-9_]*[ \t]*\\(")
        refuse("${path}" "no global initialised by a call (glslang's HLSL front end cannot)" "'${line}'")
      endif()
    endif()
    string(REGEX MATCHALL "{" opens "${line}")
    string(REGEX MATCHALL "}" closes "${line}")
    list(LENGTH opens n_open)
    list(LENGTH closes n_close)
    math(EXPR depth "${depth} + ${n_open} - ${n_close}")
  endforeach()

  # the #include lines, one for one
  emcv_text_lines("${text}" lines)
  set(out "")
  set(first TRUE)
  foreach(line IN LISTS lines)
    if(first)
      set(first FALSE)
      if(NOT line MATCHES "^// SPDX-License-Identifier: ")
        refuse("${path}" "a module starts with its SPDX line" "'${line}'")
      endif()
      # tests/hlsl/check_hlsl.py finds the header's end by its last sentence
      string(APPEND out "// SPDX-License-Identifier: MIT\n"
                        "// ${name}.hlsl: generated at emcv's build time from shaders/module/${name}.glsl by\n"
                        "// cmake/emcv_module_hlsl.cmake (do not edit): the same code with its #include lines\n"
                        "// pointed at the HLSL files; emcv_adaptive_language.hlsl gives HLSL the GLSL names it\n"
                        "// uses. #include it after emcv_port.hlsl (docs/porting.md, \"HLSL modules\").\n"
                        "// The GLSL file's header follows.\n")
      continue()
    endif()
    if(line MATCHES "^[ \t]*#[ \t]*include[ \t]*(.*)$")
      set(target "${CMAKE_MATCH_1}")
      if(target MATCHES "^\"emcv/port/[a-z_]+\\.h\"")
        string(APPEND out "// ${target}: emcv_port.hlsl, which the application includes first\n")
      elseif(target MATCHES "^\"module/([a-z0-9_]+)\\.glsl\"$" AND CMAKE_MATCH_1 IN_LIST known_names)
        string(APPEND out "#include \"${CMAKE_MATCH_1}.hlsl\"\n")
      else()
        refuse("${path}" "a module includes the port's headers and the modules only" "'#include ${target}'")
      endif()
      continue()
    endif()
    string(APPEND out "${line}\n")
  endforeach()
  string(REGEX REPLACE "\n$" "" out "${out}")  # the file's own last newline came back as an empty last line
  emcv_unpark_text("${out}" out)
  file(WRITE "${OUTPUT_DIR}/${name}.hlsl.tmp" "${out}")
  file(COPY_FILE "${OUTPUT_DIR}/${name}.hlsl.tmp" "${OUTPUT_DIR}/${name}.hlsl" ONLY_IF_DIFFERENT)
  file(REMOVE "${OUTPUT_DIR}/${name}.hlsl.tmp")
endforeach()
file(COPY_FILE "${LANGUAGE}" "${OUTPUT_DIR}/${language_name}.hlsl" ONLY_IF_DIFFERENT)
