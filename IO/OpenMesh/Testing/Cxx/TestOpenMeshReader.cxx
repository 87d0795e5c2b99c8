// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkOpenMeshReader on files written by the test: a coloured OFF
// tetrahedron, an OFF point cloud, an OBJ quad with vertex normals, an OM
// mesh with vertex colours (written by OpenMesh itself), a binary STL sphere
// (written by vtkSTLWriter); and on bad files: missing, empty, an unknown
// extension, a truncated OFF, a truncated binary STL, garbage. Bad files
// must give one error each and an empty output.
#include "psIOTestSupport.h"
#include "vtkCallbackCommand.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkOpenMeshReader.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSTLWriter.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

using namespace pointsurfaces_test;

namespace
{
std::string Write(const std::string& dir, const std::string& name, const std::string& text)
{
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}
} // namespace

int TestOpenMeshReader(int, char*[])
{
  const char* temp = std::getenv("POINTSURFACES_TEMP_DIR");
  const std::string dir = temp ? temp : ".";
  vtkNew<vtkOpenMeshReader> reader;
  vtkNew<vtkCallbackCommand> counter;
  counter->SetCallback(CountError);
  reader->AddObserver(vtkCommand::ErrorEvent, counter);
  auto read = [&](const std::string& path)
  {
    Errors = 0;
    reader->SetFileName(path.c_str());
    reader->Modified();
    reader->Update();
    return reader->GetOutput();
  };

  // A coloured OFF tetrahedron.
  vtkPolyData* out = read(Write(dir,
    "tetra.off",
    "COFF\n4 4 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n0 0 1 10 20 30 255\n"
    "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"));
  vtkDataArray* colors = out->GetPointData()->GetScalars();
  Check(Errors == 0 && out->GetNumberOfPoints() == 4 && out->GetNumberOfPolys() == 4, "OFF mesh");
  Check(colors && colors->GetNumberOfComponents() == 3 && colors->GetComponent(3, 0) == 10 &&
      colors->GetComponent(3, 2) == 30,
    "OFF vertex colours");

  // An OFF point cloud: vertex cells.
  out = read(Write(dir, "cloud.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1e3 0\n"));
  Check(Errors == 0 && out->GetNumberOfPoints() == 3 && out->GetNumberOfVerts() == 3 &&
      out->GetNumberOfPolys() == 0,
    "OFF point cloud");

  // An OBJ quad with vertex normals.
  out = read(Write(
    dir, "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n"));
  vtkDataArray* normals = out->GetPointData()->GetNormals();
  Check(Errors == 0 && out->GetNumberOfPoints() == 4 && out->GetNumberOfPolys() == 1 &&
      out->GetPolys()->GetMaxCellSize() == 4,
    "OBJ quad");
  Check(normals && std::abs(normals->GetComponent(2, 2) - 1.0) < 1e-6, "OBJ vertex normals");

  // An OM file with vertex colours, written by OpenMesh.
  {
    OpenMesh::PolyMesh_ArrayKernelT<> mesh;
    mesh.request_vertex_colors();
    auto a = mesh.add_vertex({ 0.f, 0.f, 0.f });
    auto b = mesh.add_vertex({ 2.f, 0.f, 0.f });
    auto c = mesh.add_vertex({ 0.f, 3.f, 0.f });
    mesh.add_face(a, b, c);
    mesh.set_color(c, { 7, 8, 9 });
    OpenMesh::IO::Options options(OpenMesh::IO::Options::VertexColor);
    Check(OpenMesh::IO::write_mesh(mesh, dir + "/tri.om", options), "writing the OM file");
  }
  out = read(dir + "/tri.om");
  colors = out->GetPointData()->GetScalars();
  double p[3] = { 0, 0, 0 };
  if (out->GetNumberOfPoints() == 3)
  {
    out->GetPoint(2, p);
  }
  Check(Errors == 0 && out->GetNumberOfPolys() == 1 && p[1] == 3.0, "OM mesh");
  Check(colors && colors->GetComponent(2, 1) == 8, "OM vertex colours");

  // A binary STL sphere written by VTK.
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(12);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(sphere->GetOutputPort());
  triangles->Update();
  vtkNew<vtkSTLWriter> stl;
  stl->SetInputConnection(triangles->GetOutputPort());
  stl->SetFileTypeToBinary();
  stl->SetFileName((dir + "/sphere.stl").c_str());
  stl->Write();
  out = read(dir + "/sphere.stl");
  Check(Errors == 0 && out->GetNumberOfPolys() == triangles->GetOutput()->GetNumberOfPolys() &&
      out->GetNumberOfPoints() == triangles->GetOutput()->GetNumberOfPoints(),
    "binary STL (vertices merged)");
  Check(!out->GetPointData()->GetNormals() && !out->GetPointData()->GetScalars() &&
      !out->GetCellData()->GetScalars(),
    "STL gives no normals or colours (it has none; OpenMesh leaves the options on)");

  // A coloured face that OpenMesh rejects (a repeated vertex): OpenMesh used
  // to write its colour at face -1 (ASan sees it in the asan preset). The
  // good face and its colour are read.
  out = read(Write(dir,
    "rejected-face.off",
    "COFF\n3 2 0\n0 0 0 9 9 9 255\n1 0 0 9 9 9 255\n0 1 0 9 9 9 255\n"
    "3 0 0 1 255 0 0\n3 0 1 2 0 0 255\n"));
  Check(out->GetNumberOfPolys() == 1 && out->GetCellData()->GetScalars() &&
      out->GetCellData()->GetScalars()->GetComponent(0, 2) == 255,
    "a rejected coloured face is dropped, the other keeps its colour");

  // Bad files: one error each and an empty output.
  std::string sphereBytes;
  {
    std::ifstream in(dir + "/sphere.stl", std::ios::binary);
    sphereBytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string bad[] = { dir + "/no-such-file.off",
    Write(dir, "empty.off", ""),
    Write(dir, "mesh.xyz", "0 0 0\n"),
    Write(dir, "short.off", "OFF\n3 1 0\n0 0 0\n1 0"),
    Write(dir, "short.stl", sphereBytes.substr(0, sphereBytes.size() / 2)),
    Write(dir, "garbage.obj", std::string(4096, '\x7f')),
    // Found by FuzzOpenMeshReader: each crashed or aborted inside OpenMesh.
    Write(dir, "empty-corner.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf //1 2 3\n"),
    Write(dir, "index-zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"),
    Write(dir, "huge-count.off", "OFF\n2 6606666666666666066 0\n0 0 0\n1 1 1\n"),
    Write(dir, "bad-keyword.off", std::string("OFF\b5 0 \0\0\0", 12)),
    Write(dir, "lone-count.off", "OFF 0 0 1\n666660\n"), // ran for minutes in OpenMesh
    // The face count on the line after a lone vertex count: 29 s in OpenMesh.
    Write(dir, "next-line-count.off", "COFF 0 0 255 0 0\n1\n66666 1 0\n3 0 0 255 0 0\n"),
    Write(dir, "huge.om", std::string("OMP\x02\xff\xff\xff\x7f\x01\0\0\0\x01\0\0\0", 16)) };
  for (const std::string& path : bad)
  {
    out = read(path);
    std::cout << path << ": " << Errors << " errors, " << out->GetNumberOfPoints() << " points\n";
    // OpenMesh reads garbage OBJ as an empty mesh: a warning and no points.
    const bool garbage = path.find("garbage") != std::string::npos;
    Check((Errors == 1 || (garbage && Errors == 0)) && out->GetNumberOfPoints() == 0 &&
        out->GetNumberOfCells() == 0,
      "bad file " + path);
  }
  ExpectEmptyFileError<vtkOpenMeshReader>(dir + "/empty.obj");
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
