# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
#[==[
Find PCL's io and common libraries without PCLConfig.cmake.

PCLConfig.cmake, asked for the io component, runs find_package(VTK) with
components that Debian's VTK cannot satisfy (Qt, JsonCpp) and breaks the
configure. The io library itself links fine, so it is found directly here.

Defines the imported target PCLIO::PCLIO (pcl_io, pcl_common, headers, Eigen).
#]==]
find_path(PCLIO_INCLUDE_DIR pcl/io/pcd_io.h PATH_SUFFIXES pcl-1.15 pcl-1.14 pcl-1.13 pcl-1.12)
find_library(PCLIO_IO_LIBRARY pcl_io)
find_library(PCLIO_COMMON_LIBRARY pcl_common)
# No version: Eigen 5's package refuses a request for 3.x (same-major rule).
if (NOT TARGET Eigen3::Eigen)
  find_package(Eigen3 QUIET NO_MODULE)
endif ()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(PCLIO
  REQUIRED_VARS PCLIO_INCLUDE_DIR PCLIO_IO_LIBRARY PCLIO_COMMON_LIBRARY Eigen3_FOUND)

if (PCLIO_FOUND AND NOT TARGET PCLIO::PCLIO)
  add_library(PCLIO::PCLIO INTERFACE IMPORTED)
  set_target_properties(PCLIO::PCLIO PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${PCLIO_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${PCLIO_IO_LIBRARY};${PCLIO_COMMON_LIBRARY};Eigen3::Eigen")
endif ()
mark_as_advanced(PCLIO_INCLUDE_DIR PCLIO_IO_LIBRARY PCLIO_COMMON_LIBRARY)
