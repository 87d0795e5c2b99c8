# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
# Install the build tree into a scratch prefix, build the standalone C++
# examples against the installed CMake package, run them headless, and import
# the installed Python package with /usr/bin/python3.
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DPREFIX=... -DPYTHON=... -DSITE=... -P InstallAndExample.cmake
function (run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  message("${out}")
  if (NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}")
  endif ()
endfunction ()

file(REMOVE_RECURSE "${PREFIX}" "${PREFIX}-example" "${PREFIX}-metaballs")
run("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}")
run("${CMAKE_COMMAND}" -S "${SOURCE_DIR}/Examples/Cxx/RenderScan" -B "${PREFIX}-example"
  -G Ninja -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${PREFIX}")
run("${CMAKE_COMMAND}" --build "${PREFIX}-example")
run("${PREFIX}-example/RenderScan" "${SOURCE_DIR}/Testing/Data/bunny.vtp" "${PREFIX}-example/bunny.png" 128)
if (NOT EXISTS "${PREFIX}-example/bunny.png")
  message(FATAL_ERROR "the example wrote no image")
endif ()
# The metaball example: PDB atoms to an image and an OpenVDB level set, when
# PointSurfaces::IOOpenVDB was built (OpenVDB found).
file(GLOB _ps_openvdb_module "${PREFIX}/lib*/libPointSurfacesIOOpenVDB*")
if (_ps_openvdb_module)
  run("${CMAKE_COMMAND}" -S "${SOURCE_DIR}/Examples/Cxx/ParticleMetaballs" -B "${PREFIX}-metaballs"
    -G Ninja -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${PREFIX}")
  run("${CMAKE_COMMAND}" --build "${PREFIX}-metaballs")
  run("${PREFIX}-metaballs/ParticleMetaballs" "${SOURCE_DIR}/Testing/Data/hemoglobin_chainA.pdb"
    "${PREFIX}-metaballs/molecule.png" 128 "${PREFIX}-metaballs/molecule.vdb")
  foreach (out IN ITEMS molecule.png molecule.vdb)
    if (NOT EXISTS "${PREFIX}-metaballs/${out}")
      message(FATAL_ERROR "the metaball example wrote no ${out}")
    endif ()
  endforeach ()
else ()
  message("No PointSurfaces::IOOpenVDB installed: the metaball example is not built.")
endif ()
set(ENV{PYTHONPATH} "${PREFIX}/${SITE}")
run("${PYTHON}" -c "import pointsurfaces, vtkmodules.vtkRenderingCore as rc; pointsurfaces.use_egl(); w = rc.vtkRenderWindow(); assert w.GetClassName() == 'vtkEGLHeadlessRenderWindow', w.GetClassName(); print('installed pointsurfaces from', pointsurfaces.__file__)")
