# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
#[==[
Test helpers on top of VTK's vtkModuleTesting.

pointsurfaces_add_render_tests(<exe> <varname> <TestX.cxx[,OPTIONS]>...)

  Declares each rendering test twice through vtk_add_test_cxx, with the same
  baseline in ../Data/Baseline/<TestX>.png (alternates <TestX>_1.png ...):

    <Module>Cxx-egl-<TestX>  POINTSURFACES_RENDER_WINDOW=egl, DISPLAY unset.  Labels: render egl
    <Module>Cxx-x11-<TestX>  POINTSURFACES_RENDER_WINDOW=x11 under xvfb-run.  Labels: render x11

  <varname> receives the test files, for vtk_test_cxx_executable.

pointsurfaces_add_unit_tests(<exe> <varname> <TestX.cxx>...)

  Declares tests that open no window (label: unit); the target
  pointsurfaces-unit-tests builds their executables.
#]==]

find_program(POINTSURFACES_XVFB_RUN xvfb-run)

function (_pointsurfaces_test_names out)
  set(names)
  foreach (arg IN LISTS ARGN)
    if (arg MATCHES "^([^.,]*)\\.cxx")
      list(APPEND names "${CMAKE_MATCH_1}")
    endif ()
  endforeach ()
  set("${out}" "${names}" PARENT_SCOPE)
endfunction ()

function (pointsurfaces_add_render_tests exe varname)
  _pointsurfaces_test_names(names ${ARGN})

  set(vtk_test_prefix "egl-")
  vtk_add_test_cxx("${exe}" egl_tests ${ARGN})
  foreach (name IN LISTS names)
    set(test "${_vtk_build_test}Cxx-egl-${name}")
    set_property(TEST "${test}" APPEND PROPERTY LABELS render egl)
    set_property(TEST "${test}" APPEND PROPERTY ENVIRONMENT "POINTSURFACES_RENDER_WINDOW=egl")
    set_property(TEST "${test}" APPEND PROPERTY ENVIRONMENT_MODIFICATION "DISPLAY=unset:")
  endforeach ()

  if (POINTSURFACES_XVFB_RUN)
    # vtk_add_test_cxx puts _vtk_test_cxx_pre_args in front of the test
    # command (VTK uses it for mpiexec); here it starts a private X server.
    set(_vtk_test_cxx_pre_args
      "${POINTSURFACES_XVFB_RUN}" -a -s "-screen 0 1280x1024x24 +extension GLX -noreset")
    set(vtk_test_prefix "x11-")
    # Both variants write <TestX>.png: keep the X images apart.
    set(_vtk_build_TEST_OUTPUT_DIRECTORY "${_vtk_build_TEST_OUTPUT_DIRECTORY}/x11")
    file(MAKE_DIRECTORY "${_vtk_build_TEST_OUTPUT_DIRECTORY}")
    vtk_add_test_cxx("${exe}" x11_tests ${ARGN})
    foreach (name IN LISTS names)
      set(test "${_vtk_build_test}Cxx-x11-${name}")
      set_property(TEST "${test}" APPEND PROPERTY LABELS render x11)
      set_property(TEST "${test}" APPEND PROPERTY ENVIRONMENT "POINTSURFACES_RENDER_WINDOW=x11")
      # xvfb-run -a races when two start at once.
      set_property(TEST "${test}" PROPERTY RESOURCE_LOCK xvfb)
    endforeach ()
  else ()
    message(WARNING "xvfb-run not found: the x11 variants of the rendering tests are not declared. "
      "Run scripts/install-deps.sh.")
  endif ()

  set("${varname}" ${${varname}} ${egl_tests} PARENT_SCOPE)
endfunction ()

function (pointsurfaces_add_unit_tests exe varname)
  _pointsurfaces_test_names(names ${ARGN})
  vtk_add_test_cxx("${exe}" unit_tests NO_DATA NO_VALID NO_OUTPUT ${ARGN})
  foreach (name IN LISTS names)
    set_property(TEST "${_vtk_build_test}Cxx-${name}" APPEND PROPERTY LABELS unit)
  endforeach ()
  # The executables that the unit tests need: the target
  # pointsurfaces-unit-tests builds them alone (the asan preset).
  set_property(GLOBAL APPEND PROPERTY POINTSURFACES_UNIT_TEST_EXECUTABLES "${exe}")
  set("${varname}" ${${varname}} ${unit_tests} PARENT_SCOPE)
endfunction ()

#[==[
pointsurfaces_add_io_tests(<exe> <TestX.cxx>...)

  Unit tests of a reader, writer or file filter, in their own executable <exe>
  (made here): each test finds the committed inputs in $POINTSURFACES_IO_DATA
  (IO/Testing/Data) and writes its scratch files in $POINTSURFACES_TEMP_DIR;
  Testing/Cxx/psIOTestSupport.h has the counters they share.
#]==]
function (pointsurfaces_add_io_tests exe)
  _pointsurfaces_test_names(names ${ARGN})
  pointsurfaces_add_unit_tests("${exe}" tests ${ARGN})
  foreach (name IN LISTS names)
    set_property(TEST "${_vtk_build_test}Cxx-${name}" APPEND PROPERTY
      ENVIRONMENT "POINTSURFACES_IO_DATA=${PROJECT_SOURCE_DIR}/IO/Testing/Data"
                  "POINTSURFACES_TEMP_DIR=${PROJECT_BINARY_DIR}/Testing/Temporary")
  endforeach ()
  vtk_test_cxx_executable("${exe}" tests)
  target_include_directories("${exe}" PRIVATE "${PROJECT_SOURCE_DIR}/Testing/Cxx")
endfunction ()
