# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
#[==[
Find LASzip's C API (Debian 13 and later: liblaszip-dev; Debian 12 has no
LAS library at all). LASzip reads and writes LAS and LAZ files.

Defines the imported target LASzip::LASzip.
#]==]
# laszip_api.h includes <laszip_common.h>: the include folder is laszip/ itself.
find_path(LASzip_INCLUDE_DIR laszip_api.h PATH_SUFFIXES laszip)
# liblaszip exports the C API itself; liblaszip_api is a shim that dlopens it.
find_library(LASzip_LIBRARY laszip)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(LASzip REQUIRED_VARS LASzip_INCLUDE_DIR LASzip_LIBRARY)

if (LASzip_FOUND AND NOT TARGET LASzip::LASzip)
  add_library(LASzip::LASzip UNKNOWN IMPORTED)
  set_target_properties(LASzip::LASzip PROPERTIES
    IMPORTED_LOCATION "${LASzip_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${LASzip_INCLUDE_DIR}")
endif ()
mark_as_advanced(LASzip_INCLUDE_DIR LASzip_LIBRARY)
