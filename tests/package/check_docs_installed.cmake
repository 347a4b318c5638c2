# The installed documentation (share/doc/emcv): the README and the docs the README links first.
# Usage: cmake -DDOC_DIR=<prefix>/share/doc/emcv -P check_docs_installed.cmake
foreach(f README.md integration.md porting.md frame.md renderer.md)
  if(NOT EXISTS "${DOC_DIR}/${f}")
    message(FATAL_ERROR "not installed: ${DOC_DIR}/${f}")
  endif()
endforeach()
message(STATUS "docs: OK")
