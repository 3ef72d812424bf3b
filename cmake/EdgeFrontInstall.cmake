# Install rules and the CMake package config.
#
# Included last by the top-level CMakeLists, when the targets edgefront, render, twist and gcs
# exist (static or INTERFACE: both are handled). Installs:
#   <prefix>/include/{edgefront,render,twist,gcs}/*.h     public headers
#   <prefix>/<libdir>/lib{edgefront,render,twist,gcs}.a   libraries (twist and gcs only once they have sources)
#   <prefix>/bin/<app>                               apps (their install() is in apps/CMakeLists.txt)
#   <prefix>/<libdir>/cmake/EdgeFront/               EdgeFrontConfig.cmake, version file, targets
#   <prefix>/<datadir>/doc/EdgeFront/LICENSE         the license (BSD-3-Clause)
#
# A consumer writes `find_package(EdgeFront REQUIRED)` and links `edgefront::edgefront`,
# `render::render`, `twist::twist` and `gcs::gcs`, the names used inside this build. Each library has its own export
# set, because an export set has a single NAMESPACE; CMake writes the cross-set references
# (render, twist -> edgefront::edgefront, gcs -> twist::twist) with the other set's namespace.

# On by default when EdgeFront is the top-level project, off when it is add_subdirectory()'d.
if(CMAKE_SOURCE_DIR STREQUAL PROJECT_SOURCE_DIR)
  set(_edgefront_install_default ON)
else()
  set(_edgefront_install_default OFF)
endif()
option(EDGEFRONT_INSTALL "Generate the install rules and the CMake package config" ${_edgefront_install_default})
if(NOT EDGEFRONT_INSTALL)
  return()
endif()

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(EDGEFRONT_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/EdgeFront"
    CACHE STRING "Where EdgeFrontConfig.cmake is installed, relative to the prefix")

foreach(lib IN ITEMS edgefront render twist shapes gcs)
  install(TARGETS ${lib}
    EXPORT ${lib}Targets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  # The include folder of a library without headers yet is absent from a fresh clone (git keeps
  # no empty folders).
  if(EXISTS "${PROJECT_SOURCE_DIR}/${lib}/include/${lib}")
    install(DIRECTORY "${PROJECT_SOURCE_DIR}/${lib}/include/${lib}"
      DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
      FILES_MATCHING PATTERN "*.h")
  endif()
  # Order matters: EdgeFrontConfig.cmake includes these files edgefront, render, twist, shapes, gcs, so that each
  # finds the targets it refers to.
  install(EXPORT ${lib}Targets
    NAMESPACE ${lib}::
    FILE ${lib}-targets.cmake
    DESTINATION ${EDGEFRONT_INSTALL_CMAKEDIR})
endforeach()

configure_package_config_file(
  "${CMAKE_CURRENT_LIST_DIR}/EdgeFrontConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/EdgeFrontConfig.cmake"
  INSTALL_DESTINATION ${EDGEFRONT_INSTALL_CMAKEDIR})
# 0.x: a minor version may break the API, so only the same major.minor is compatible.
write_basic_package_version_file(
  "${PROJECT_BINARY_DIR}/EdgeFrontConfigVersion.cmake"
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES
  "${PROJECT_BINARY_DIR}/EdgeFrontConfig.cmake"
  "${PROJECT_BINARY_DIR}/EdgeFrontConfigVersion.cmake"
  DESTINATION ${EDGEFRONT_INSTALL_CMAKEDIR})
install(FILES "${PROJECT_SOURCE_DIR}/LICENSE" DESTINATION ${CMAKE_INSTALL_DOCDIR})
