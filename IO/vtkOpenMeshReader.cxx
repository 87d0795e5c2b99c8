// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOpenMeshReader.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkOpenMeshReader);

namespace
{
using Mesh = OpenMesh::PolyMesh_ArrayKernelT<>;

std::string Extension(const std::string& name)
{
  const size_t dot = name.find_last_of('.');
  std::string ext = dot == std::string::npos ? std::string() : name.substr(dot + 1);
  std::transform(ext.begin(),
    ext.end(),
    ext.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// Binary STL: 80-byte header, a face count, 50 bytes a face. OpenMesh reads
// past the end of a truncated file; check the size first.
bool BinarySTLComplete(const std::string& name, std::string& why)
{
  std::ifstream in(name, std::ios::binary | std::ios::ate);
  const std::streamoff size = in.tellg();
  if (size < 84)
  {
    return true; // too short for binary: OpenMesh tries ASCII
  }
  char head[6] = { 0 };
  in.seekg(0);
  in.read(head, 5);
  if (std::string(head, 5) == "solid")
  {
    return true; // ASCII (or a binary file that says "solid": size decides below)
  }
  in.seekg(80);
  unsigned char count[4];
  in.read(reinterpret_cast<char*>(count), 4);
  const std::streamoff faces =
    count[0] | (count[1] << 8) | (count[2] << 16) | (static_cast<std::streamoff>(count[3]) << 24);
  if (84 + 50 * faces > size)
  {
    why = "the binary STL header announces " + std::to_string(faces) + " faces (" +
      std::to_string(84 + 50 * faces) + " bytes) but the file has " + std::to_string(size) +
      " bytes";
    return false;
  }
  return true;
}
// The vertex and face counts an ASCII OFF header announces (-1: not found).
void OFFCounts(const std::string& name, long long& vertices, long long& faces)
{
  vertices = faces = -1;
  std::ifstream in(name);
  std::string line;
  bool keyword = false;
  while (std::getline(in, line))
  {
    const size_t hash = line.find('#');
    if (hash != std::string::npos)
    {
      line.erase(hash);
    }
    std::istringstream words(line);
    std::string first;
    if (!(words >> first))
    {
      continue;
    }
    if (!keyword && first.find("OFF") != std::string::npos)
    {
      keyword = true;
      if (line.find("BINARY") != std::string::npos)
      {
        return; // binary OFF: OpenMesh checks its own sizes
      }
      std::string rest;
      std::getline(words, rest);
      std::istringstream counts(rest);
      if (counts >> vertices >> faces)
      {
        return;
      }
      continue;
    }
    std::istringstream counts(line);
    counts >> vertices >> faces;
    return;
  }
}
} // namespace

//------------------------------------------------------------------------------
vtkOpenMeshReader::vtkOpenMeshReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
bool vtkOpenMeshReader::CanReadFile(const char* fileName)
{
  const std::string ext = Extension(fileName ? fileName : "");
  return ext == "off" || ext == "obj" || ext == "om" || ext == "stl";
}

//------------------------------------------------------------------------------
int vtkOpenMeshReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No file name.");
    return 1;
  }
  if (!CanReadFile(this->FileName.c_str()))
  {
    vtkErrorMacro(<< "Cannot read " << this->FileName
                  << ": OpenMesh reads .off, .obj, .om and .stl files.");
    return 1;
  }
  {
    std::ifstream probe(this->FileName, std::ios::binary | std::ios::ate);
    if (!probe)
    {
      vtkErrorMacro(<< "Cannot open " << this->FileName << ".");
      return 1;
    }
    if (probe.tellg() <= 0)
    {
      vtkErrorMacro(<< this->FileName << " is empty.");
      return 1;
    }
  }
  std::string why;
  if (Extension(this->FileName) == "stl" && !BinarySTLComplete(this->FileName, why))
  {
    vtkErrorMacro(<< this->FileName << " is truncated: " << why << ".");
    return 1;
  }

  Mesh mesh;
  mesh.request_vertex_normals();
  mesh.request_vertex_colors();
  mesh.request_face_colors();
  OpenMesh::IO::Options options;
  options += OpenMesh::IO::Options::VertexNormal;
  options += OpenMesh::IO::Options::VertexColor;
  options += OpenMesh::IO::Options::FaceColor;
  bool ok = false;
  try
  {
    ok = OpenMesh::IO::read_mesh(mesh, this->FileName, options);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "OpenMesh failed on " << this->FileName << ": " << e.what());
    return 1;
  }
  if (!ok)
  {
    vtkErrorMacro(<< "OpenMesh could not read " << this->FileName
                  << " (a corrupt or truncated file, or not the format its extension names).");
    return 1;
  }
  // OpenMesh accepts an ASCII OFF file that ends early: compare with its header.
  if (Extension(this->FileName) == "off")
  {
    long long vertices = -1, faces = -1;
    OFFCounts(this->FileName, vertices, faces);
    if (vertices >= 0 &&
      (static_cast<long long>(mesh.n_vertices()) < vertices ||
        static_cast<long long>(mesh.n_faces()) < faces))
    {
      vtkErrorMacro(<< this->FileName << " is truncated or corrupt: its header announces "
                    << vertices << " vertices and " << faces << " faces, OpenMesh read "
                    << mesh.n_vertices() << " and " << mesh.n_faces() << ".");
      return 1;
    }
  }

  const vtkIdType n = static_cast<vtkIdType>(mesh.n_vertices());
  if (n == 0)
  {
    vtkWarningMacro(<< this->FileName << " holds no vertices.");
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(n);
  std::vector<char> used(n, 0);
  for (auto v : mesh.vertices())
  {
    const auto& p = mesh.point(v);
    points->SetPoint(v.idx(), p[0], p[1], p[2]);
  }
  vtkNew<vtkCellArray> polys;
  for (auto f : mesh.faces())
  {
    std::vector<vtkIdType> ids;
    for (auto v : mesh.fv_range(f))
    {
      ids.push_back(v.idx());
      used[v.idx()] = 1;
    }
    polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }
  output->SetPoints(points);
  output->SetPolys(polys);
  // Vertices that no face uses (a point cloud) are vertex cells.
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (!used[i])
    {
      verts->InsertNextCell(1, &i);
    }
  }
  if (verts->GetNumberOfCells() > 0)
  {
    output->SetVerts(verts);
  }

  if (options.check(OpenMesh::IO::Options::VertexNormal))
  {
    vtkNew<vtkFloatArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(n);
    for (auto v : mesh.vertices())
    {
      const auto& nv = mesh.normal(v);
      normals->SetTuple3(v.idx(), nv[0], nv[1], nv[2]);
    }
    output->GetPointData()->SetNormals(normals);
  }
  if (options.check(OpenMesh::IO::Options::VertexColor))
  {
    vtkNew<vtkUnsignedCharArray> colors;
    colors->SetName("Colors");
    colors->SetNumberOfComponents(3);
    colors->SetNumberOfTuples(n);
    for (auto v : mesh.vertices())
    {
      const auto& c = mesh.color(v);
      colors->SetTuple3(v.idx(), c[0], c[1], c[2]);
    }
    output->GetPointData()->SetScalars(colors);
  }
  if (options.check(OpenMesh::IO::Options::FaceColor) &&
    output->GetVerts()->GetNumberOfCells() == 0)
  {
    vtkNew<vtkUnsignedCharArray> colors;
    colors->SetName("Colors");
    colors->SetNumberOfComponents(3);
    colors->SetNumberOfTuples(static_cast<vtkIdType>(mesh.n_faces()));
    for (auto f : mesh.faces())
    {
      const auto& c = mesh.color(f);
      colors->SetTuple3(f.idx(), c[0], c[1], c[2]);
    }
    output->GetCellData()->SetScalars(colors);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkOpenMeshReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
