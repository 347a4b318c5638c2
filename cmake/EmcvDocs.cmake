# The API reference: `cmake --build build --target docs` runs scripts/docs.sh into <build>/docs
# (Doxygen, docs/Doxyfile, warnings are errors). Absent when doxygen is not installed.
find_program(EMCV_DOXYGEN doxygen)
if(EMCV_DOXYGEN)
  add_custom_target(docs
    COMMAND bash "${PROJECT_SOURCE_DIR}/scripts/docs.sh" "${PROJECT_BINARY_DIR}/docs"
    WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}"
    COMMENT "Doxygen API reference in ${PROJECT_BINARY_DIR}/docs/html"
    VERBATIM)
endif()
