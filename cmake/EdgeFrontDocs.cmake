# The `docs` target: the API reference (Doxygen HTML) from the public headers, through
# scripts/docs.sh, which fails on any Doxygen warning. Defined only when Doxygen is found; not
# part of `all`. Output: <build>/docs/html/index.html.
find_package(Doxygen QUIET)
if(DOXYGEN_FOUND)
  add_custom_target(docs
    COMMAND ${CMAKE_COMMAND} -E env "EDGEFRONT_DOCS_DIR=${CMAKE_BINARY_DIR}/docs"
            "${CMAKE_CURRENT_SOURCE_DIR}/scripts/docs.sh"
    WORKING_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}"
    COMMENT "API reference (Doxygen, warnings as errors) into ${CMAKE_BINARY_DIR}/docs/html"
    VERBATIM)
endif()
