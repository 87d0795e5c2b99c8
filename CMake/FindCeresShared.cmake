# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
#[==[
Ceres through its shared library.

Debian's CeresConfig.cmake exports Ceres::ceres as the static libceres.a;
linked into several modules it would be duplicated in each. This finds the
shared libceres.so (with glog and Eigen) and defines CeresShared::CeresShared.
#]==]
find_path(CeresShared_INCLUDE_DIR ceres/ceres.h)
find_library(CeresShared_LIBRARY NAMES libceres.so.3 libceres.so ceres NAMES_PER_DIR)
find_library(CeresShared_GLOG_LIBRARY glog)
# No version: Eigen 5's package refuses a request for 3.x (same-major rule).
if (NOT TARGET Eigen3::Eigen)
  find_package(Eigen3 QUIET NO_MODULE)
endif ()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CeresShared
  REQUIRED_VARS CeresShared_INCLUDE_DIR CeresShared_LIBRARY CeresShared_GLOG_LIBRARY Eigen3_FOUND)
if (CeresShared_FOUND AND NOT TARGET CeresShared::CeresShared)
  add_library(CeresShared::CeresShared INTERFACE IMPORTED)
  set_target_properties(CeresShared::CeresShared PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${CeresShared_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${CeresShared_LIBRARY};${CeresShared_GLOG_LIBRARY};Eigen3::Eigen")
endif ()
mark_as_advanced(CeresShared_INCLUDE_DIR CeresShared_LIBRARY CeresShared_GLOG_LIBRARY)
