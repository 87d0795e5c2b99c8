# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
#[==[
Find Debian's ParaView SDK (paraview-dev) for the `paraview` preset: 5.11
(bookworm), 5.13 (trixie) or 6.1 (forky), whichever is installed.

Where ParaView uses Debian's VTK (forky), python3-paraview is installed as
usual and ParaView's CMake package is used as it is.

Where ParaView bundles its own VTK (bookworm, trixie), its CMake package
imports targets whose files only python3-paraview ships (the Python modules
of that VTK, and pvpython), and python3-paraview can never be installed
beside python3-vtk9. `scripts/install-deps.sh --paraview` therefore unpacks
python3-paraview into POINTSURFACES_PARAVIEW_ROOT (default
build/paraview-sdk/root), and this file copies the CMake package into the
build tree with two edits:

- each targets file's install prefix (and VTK-m's package prefix, and the
  module properties' import prefix) is the original one (/usr), not the
  copy's location;
- the Python module, wrapping hierarchy and pvpython paths point into the
  unpacked package.

It then sets ParaView_DIR to the copy. Only the non-GUI components are
requested, so Qt is not needed. POINTSURFACES_PARAVIEW_PYTHONPATH is where
ParaView's Python package is (empty when it is installed system-wide).
#]==]
set(POINTSURFACES_PARAVIEW_ROOT "${CMAKE_SOURCE_DIR}/build/paraview-sdk/root"
  CACHE PATH "Where python3-paraview is unpacked (scripts/install-deps.sh --paraview)")
file(GLOB _ps_pv_candidates LIST_DIRECTORIES true
  "/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/paraview-*")
list(SORT _ps_pv_candidates COMPARE NATURAL ORDER DESCENDING)
set(_ps_pv_system "")
foreach (_ps_pv_candidate IN LISTS _ps_pv_candidates)
  if (EXISTS "${_ps_pv_candidate}/paraview-config.cmake")
    set(_ps_pv_system "${_ps_pv_candidate}")
    break ()
  endif ()
endforeach ()
if (NOT _ps_pv_system)
  message(FATAL_ERROR "No ParaView CMake package in /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake: "
    "run scripts/install-deps.sh --paraview (installs paraview-dev).")
endif ()
get_filename_component(_ps_pv_name "${_ps_pv_system}" NAME)
string(REGEX REPLACE "^paraview-" "" POINTSURFACES_PARAVIEW_SERIES "${_ps_pv_name}")
message(STATUS "PointSurfaces: ParaView ${POINTSURFACES_PARAVIEW_SERIES} SDK in ${_ps_pv_system}")

# paraview.simple: a module up to 5.13, a package from 6.0.
if (EXISTS "/usr/lib/python3/dist-packages/paraview/simple.py" OR
    EXISTS "/usr/lib/python3/dist-packages/paraview/simple/__init__.py")
  # Installed system-wide beside Debian's VTK (forky): the files are where
  # the package says, but for the Python modules' names (below).
  set(_ps_pv_pyroot "")
  set(POINTSURFACES_PARAVIEW_PYTHONPATH "")
else ()
  set(_ps_pv_pyroot "${POINTSURFACES_PARAVIEW_ROOT}")
  set(POINTSURFACES_PARAVIEW_PYTHONPATH "${_ps_pv_pyroot}/usr/lib/python3/dist-packages")
endif ()
set(_ps_pv_python "${_ps_pv_pyroot}/usr/lib/python3/dist-packages")
if (NOT EXISTS "${_ps_pv_python}/paraview/simple.py" AND
    NOT EXISTS "${_ps_pv_python}/paraview/simple/__init__.py")
  message(FATAL_ERROR "python3-paraview is not unpacked in ${POINTSURFACES_PARAVIEW_ROOT}: "
    "run scripts/install-deps.sh --paraview.")
endif ()

set(_ps_pv_copy "${CMAKE_BINARY_DIR}/paraview-cmake")
if (NOT EXISTS "${_ps_pv_copy}/paraview-config.cmake")
  file(COPY "${_ps_pv_system}/" DESTINATION "${_ps_pv_copy}")
  file(GLOB_RECURSE _ps_pv_files "${_ps_pv_copy}/*.cmake")
  foreach (_ps_pv_file IN LISTS _ps_pv_files)
    file(READ "${_ps_pv_file}" _ps_pv_text)
    set(_ps_pv_edited "${_ps_pv_text}")
    get_filename_component(_ps_pv_dir "${_ps_pv_file}" DIRECTORY)
    file(RELATIVE_PATH _ps_pv_sub "${_ps_pv_copy}" "${_ps_pv_dir}")
    set(_ps_pv_origin "${_ps_pv_system}")
    if (_ps_pv_sub)
      string(APPEND _ps_pv_origin "/${_ps_pv_sub}")
    endif ()
    # Prefixes computed upward from the file: VTK-m's package init and the
    # module properties' import prefix (header and hierarchy paths).
    string(REPLACE "\${CMAKE_CURRENT_LIST_DIR}/.." "${_ps_pv_origin}/.."
      _ps_pv_edited "${_ps_pv_edited}")
    string(REPLACE "set(_vtk_module_import_prefix \"\${CMAKE_CURRENT_LIST_DIR}\")"
      "set(_vtk_module_import_prefix \"${_ps_pv_origin}\")" _ps_pv_edited "${_ps_pv_edited}")
    # The wrapping hierarchy files ship in python3-paraview too.
    string(REPLACE "\${_vtk_module_import_prefix}/lib/${CMAKE_LIBRARY_ARCHITECTURE}/vtk/hierarchy"
      "${_ps_pv_pyroot}/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/vtk/hierarchy"
      _ps_pv_edited "${_ps_pv_edited}")
    if (_ps_pv_text MATCHES "_IMPORT_PREFIX")
      string(REPLACE
        "get_filename_component(_IMPORT_PREFIX \"\${CMAKE_CURRENT_LIST_FILE}\" PATH)"
        "set(_IMPORT_PREFIX \"${_ps_pv_origin}\")"
        _ps_pv_edited "${_ps_pv_edited}")
      string(REPLACE "\${_IMPORT_PREFIX}/lib/python3/dist-packages" "${_ps_pv_python}"
        _ps_pv_edited "${_ps_pv_edited}")
      string(REPLACE "\${_IMPORT_PREFIX}/bin/pvpython" "${_ps_pv_pyroot}/usr/bin/pvpython"
        _ps_pv_edited "${_ps_pv_edited}")
    endif ()
    # Debian 13 and forky: the targets name paraview/.../X.so (and vtkmodules/X.so), the
    # package ships X.cpython-3XX-<arch>.so. Point at the file that exists.
    string(REGEX MATCHALL "${_ps_pv_python}/[A-Za-z0-9_/]+\\.so\""
      _ps_pv_modules "${_ps_pv_edited}")
    list(REMOVE_DUPLICATES _ps_pv_modules)
    foreach (_ps_pv_module IN LISTS _ps_pv_modules)
      string(REGEX REPLACE "\\.so\"$" "" _ps_pv_stem "${_ps_pv_module}")
      file(GLOB _ps_pv_tagged "${_ps_pv_stem}.cpython-*.so")
      if (NOT EXISTS "${_ps_pv_stem}.so" AND _ps_pv_tagged)
        list(GET _ps_pv_tagged 0 _ps_pv_tagged)
        string(REPLACE "${_ps_pv_module}" "${_ps_pv_tagged}\"" _ps_pv_edited "${_ps_pv_edited}")
      endif ()
    endforeach ()
    if (NOT _ps_pv_edited STREQUAL _ps_pv_text)
      file(WRITE "${_ps_pv_file}" "${_ps_pv_edited}")
    endif ()
  endforeach ()
endif ()
set(ParaView_DIR "${_ps_pv_copy}" CACHE PATH "The patched copy of Debian's ParaView package" FORCE)
