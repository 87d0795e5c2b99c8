# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
# The installed CMake package: find_package(PointSurfaces) gives the targets
# PointSurfaces::Filters, PointSurfaces::FiltersParallel, PointSurfaces::Rendering and
# PointSurfaces::IO, and those of the optional libraries that were found
# (PointSurfaces::IOHDF5, IOOpenMesh, IOOpenVDB, IOPCL, FiltersOpenVDB: test
# with if (TARGET ...)).
include(CMakePackageConfigHelpers)
set(_ps_cmake_dest "${CMAKE_INSTALL_LIBDIR}/cmake/PointSurfaces")

vtk_module_export_find_packages(
  CMAKE_DESTINATION "${_ps_cmake_dest}"
  FILE_NAME "PointSurfaces-vtk-module-find-packages.cmake"
  MODULES ${_ps_modules})

install(EXPORT PointSurfaces
  NAMESPACE PointSurfaces::
  FILE PointSurfaces-targets.cmake
  DESTINATION "${_ps_cmake_dest}"
  COMPONENT development)

configure_package_config_file(
  "${CMAKE_CURRENT_SOURCE_DIR}/CMake/PointSurfacesConfig.cmake.in"
  "${CMAKE_CURRENT_BINARY_DIR}/PointSurfacesConfig.cmake"
  INSTALL_DESTINATION "${_ps_cmake_dest}")
write_basic_package_version_file(
  "${CMAKE_CURRENT_BINARY_DIR}/PointSurfacesConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}"
  COMPATIBILITY SameMinorVersion)
install(FILES
  "${CMAKE_CURRENT_BINARY_DIR}/PointSurfacesConfig.cmake"
  "${CMAKE_CURRENT_BINARY_DIR}/PointSurfacesConfigVersion.cmake"
  DESTINATION "${_ps_cmake_dest}"
  COMPONENT development)
