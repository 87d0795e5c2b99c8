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
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkOpenMeshReader);

namespace
{
using Mesh = OpenMesh::PolyMesh_ArrayKernelT<>;

// OpenMesh's readers hand per-face (and other) attributes to the importer
// even when the element was rejected (an invalid or repeated vertex index, a
// non-manifold face): ImporterT then writes at index -1. Found by
// FuzzOpenMeshReader (an OFF face with a colour and a bad index). This
// importer drops every attribute and connectivity call whose handles are not
// valid elements of the mesh.
class GuardedImporter : public OpenMesh::IO::ImporterT<Mesh>
{
  using Base = OpenMesh::IO::ImporterT<Mesh>;
  using VH = OpenMesh::VertexHandle;
  using HH = OpenMesh::HalfedgeHandle;
  using EH = OpenMesh::EdgeHandle;
  using FH = OpenMesh::FaceHandle;
  using Status = OpenMesh::Attributes::StatusInfo;

public:
  explicit GuardedImporter(Mesh& mesh)
    : Base(mesh)
    , M(mesh)
  {
  }
  bool Ok(VH h) const { return h.is_valid() && static_cast<size_t>(h.idx()) < M.n_vertices(); }
  bool Ok(HH h) const { return h.is_valid() && static_cast<size_t>(h.idx()) < M.n_halfedges(); }
  bool Ok(EH h) const { return h.is_valid() && static_cast<size_t>(h.idx()) < M.n_edges(); }
  bool Ok(FH h) const { return h.is_valid() && static_cast<size_t>(h.idx()) < M.n_faces(); }

  FH add_face(const VHandles& corners) override
  {
    ++this->FaceAttempts;
    const FH face = Base::add_face(corners);
    this->RejectedFaces += face.is_valid() ? 0 : 1;
    return face;
  }
  long long FaceAttempts = 0;  ///< faces the file gave, accepted or not
  long long RejectedFaces = 0; ///< faces OpenMesh refused to add
  HH add_edge(VH a, VH b) override { return Ok(a) && Ok(b) ? Base::add_edge(a, b) : HH(); }
  FH add_face(HH h) override { return Ok(h) ? Base::add_face(h) : FH(); }
  void set_point(VH h, const OpenMesh::Vec3f& p) override
  {
    Ok(h) ? Base::set_point(h, p) : void();
  }
  void set_halfedge(VH h, HH e) override { Ok(h) && Ok(e) ? Base::set_halfedge(h, e) : void(); }
  void set_normal(VH h, const OpenMesh::Vec3f& n) override
  {
    Ok(h) ? Base::set_normal(h, n) : void();
  }
  void set_normal(VH h, const OpenMesh::Vec3d& n) override
  {
    Ok(h) ? Base::set_normal(h, n) : void();
  }
  void set_color(VH h, const OpenMesh::Vec4uc& c) override
  {
    Ok(h) ? Base::set_color(h, c) : void();
  }
  void set_color(VH h, const OpenMesh::Vec3uc& c) override
  {
    Ok(h) ? Base::set_color(h, c) : void();
  }
  void set_color(VH h, const OpenMesh::Vec4f& c) override
  {
    Ok(h) ? Base::set_color(h, c) : void();
  }
  void set_color(VH h, const OpenMesh::Vec3f& c) override
  {
    Ok(h) ? Base::set_color(h, c) : void();
  }
  void set_texcoord(VH h, const OpenMesh::Vec2f& t) override
  {
    Ok(h) ? Base::set_texcoord(h, t) : void();
  }
  void set_texcoord(VH h, const OpenMesh::Vec3f& t) override
  {
    Ok(h) ? Base::set_texcoord(h, t) : void();
  }
  void set_status(VH h, const Status& s) override { Ok(h) ? Base::set_status(h, s) : void(); }
  void set_next(HH h, HH n) override { Ok(h) && Ok(n) ? Base::set_next(h, n) : void(); }
  void set_face(HH h, FH f) override { Ok(h) && Ok(f) ? Base::set_face(h, f) : void(); }
  void set_texcoord(HH h, const OpenMesh::Vec2f& t) override
  {
    Ok(h) ? Base::set_texcoord(h, t) : void();
  }
  void set_texcoord(HH h, const OpenMesh::Vec3f& t) override
  {
    Ok(h) ? Base::set_texcoord(h, t) : void();
  }
  void set_status(HH h, const Status& s) override { Ok(h) ? Base::set_status(h, s) : void(); }
  void set_color(EH h, const OpenMesh::Vec4uc& c) override
  {
    Ok(h) ? Base::set_color(h, c) : void();
  }
  void set_color(EH h, const OpenMesh::Vec3uc& c) override
  {
    Ok(h) ? Base::set_color(h, c) : void();
  }
  void set_color(EH h, const OpenMesh::Vec4f& c) override
  {
    Ok(h) ? Base::set_color(h, c) : void();
  }
  void set_color(EH h, const OpenMesh::Vec3f& c) override
  {
    Ok(h) ? Base::set_color(h, c) : void();
  }
  void set_status(EH h, const Status& s) override { Ok(h) ? Base::set_status(h, s) : void(); }
  void set_normal(FH h, const OpenMesh::Vec3f& n) override
  {
    Ok(h) ? Base::set_normal(h, n) : void();
  }
  void set_normal(FH h, const OpenMesh::Vec3d& n) override
  {
    Ok(h) ? Base::set_normal(h, n) : void();
  }
  void set_color(FH h, const OpenMesh::Vec3uc& c) override
  {
    Ok(h) ? Base::set_color(h, c) : void();
  }
  void set_color(FH h, const OpenMesh::Vec4uc& c) override
  {
    Ok(h) ? Base::set_color(h, c) : void();
  }
  void set_color(FH h, const OpenMesh::Vec3f& c) override
  {
    Ok(h) ? Base::set_color(h, c) : void();
  }
  void set_color(FH h, const OpenMesh::Vec4f& c) override
  {
    Ok(h) ? Base::set_color(h, c) : void();
  }
  void set_status(FH h, const Status& s) override { Ok(h) ? Base::set_status(h, s) : void(); }
  void add_face_texcoords(FH h, VH v, const std::vector<OpenMesh::Vec2f>& t) override
  {
    Ok(h) && Ok(v) ? Base::add_face_texcoords(h, v, t) : void();
  }
  void add_face_texcoords(FH h, VH v, const std::vector<OpenMesh::Vec3f>& t) override
  {
    Ok(h) && Ok(v) ? Base::add_face_texcoords(h, v, t) : void();
  }
  void set_face_texindex(FH h, int id) override { Ok(h) ? Base::set_face_texindex(h, id) : void(); }

private:
  Mesh& M;
};

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
void OFFCounts(const std::string& name,
  long long& vertices,
  long long& faces,
  long long* nextVertices = nullptr,
  long long* nextFaces = nullptr)
{
  // The keyword is [ST][C][N][4][n]OFF; the counts follow on its line or the
  // next non-comment line. Anything else leaves both at -1. The counts on
  // the line after the keyword line are also returned (next*), since
  // OpenMesh may read those even when the keyword line has some.
  vertices = faces = -1;
  long long ignored[2];
  long long& afterV = nextVertices ? *nextVertices : ignored[0];
  long long& afterF = nextFaces ? *nextFaces : ignored[1];
  afterV = afterF = -1;
  std::ifstream in(name);
  std::string line;
  bool keyword = false;
  static const std::regex offKeyword("^(ST)?C?N?4?n?OFF$");
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
    if (!keyword)
    {
      if (!std::regex_match(first, offKeyword))
      {
        return;
      }
      keyword = true;
      if (line.find("BINARY") != std::string::npos)
      {
        return; // binary OFF: OpenMesh checks its own sizes
      }
      long long v = -1, f = -1;
      if (words >> v >> f)
      {
        vertices = v;
        faces = f;
      }
      continue;
    }
    // A lone number counts too: OpenMesh reads it as the vertex count and
    // then the face count from whatever follows, on the next line as well
    // (found by FuzzOpenMeshReader: "OFF 0 0 1" over "666660" ran for
    // minutes; "COFF 0 0 255 0 0" over "1" over "66666 1 0" for 29 s).
    std::istringstream counts(line);
    long long v = -1, f = -1;
    if (counts >> v)
    {
      afterV = v;
      if (!(counts >> f) && counts.eof())
      {
        // The face count from the next line with anything on it.
        while (std::getline(in, line))
        {
          std::istringstream more(line);
          std::string word;
          if (more >> word)
          {
            std::istringstream number(word);
            if (!(number >> f))
            {
              f = -1;
            }
            break;
          }
        }
      }
      if (f >= 0 || counts)
      {
        afterF = f;
        if (vertices < 0 && f >= 0)
        {
          vertices = v;
          faces = f;
        }
      }
    }
    return;
  }
}

// Debian's OpenMesh is built with assertions, and its OBJ reader asserts
// (aborting the program) on a face whose tokens yield no vertex ("f //1"),
// and indexes out of range with index 0 or one beyond the vertices read so
// far (found by FuzzOpenMeshReader). Check every face line first: each
// token is v, v/t, v//n or v/t/n with nonzero indices (negative: relative)
// that refer to elements already defined.
bool ValidOBJFaces(const std::string& name, std::string& why)
{
  std::ifstream in(name, std::ios::binary);
  std::string line;
  long long vertices = 0, texcoords = 0, normals = 0, number = 0;
  auto valid = [](const std::string& text, long long count)
  {
    if (text.empty())
    {
      return false;
    }
    char* end = nullptr;
    const long long index = std::strtoll(text.c_str(), &end, 10);
    return *end == '\0' && index != 0 && index <= count && -index <= count;
  };
  while (std::getline(in, line))
  {
    ++number;
    std::istringstream words(line);
    std::string keyword;
    if (!(words >> keyword))
    {
      continue;
    }
    if (keyword == "v")
    {
      ++vertices;
    }
    else if (keyword == "vt")
    {
      ++texcoords;
    }
    else if (keyword == "vn")
    {
      ++normals;
    }
    else if (keyword == "f")
    {
      std::string token;
      int corners = 0;
      while (words >> token)
      {
        const size_t slash = token.find('/');
        const size_t slash2 = slash == std::string::npos ? slash : token.find('/', slash + 1);
        const std::string v = token.substr(0, slash);
        const std::string t = slash == std::string::npos
          ? std::string()
          : token.substr(slash + 1, slash2 == std::string::npos ? slash2 : slash2 - slash - 1);
        const std::string n =
          slash2 == std::string::npos ? std::string() : token.substr(slash2 + 1);
        if (!valid(v, vertices) || (!t.empty() && !valid(t, texcoords)) ||
          (!n.empty() && !valid(n, normals)) ||
          (slash != std::string::npos && slash2 == std::string::npos && t.empty()))
        {
          why = "face line " + std::to_string(number) + " has the corner \"" + token +
            "\", which names no vertex defined before it";
          return false;
        }
        ++corners;
      }
      if (corners < 3)
      {
        why = "face line " + std::to_string(number) + " has fewer than three corners";
        return false;
      }
    }
  }
  return true;
}

// OpenMesh reserves memory for the element counts a header announces before
// it reads a single element; a damaged header can ask for gigabytes (found by
// FuzzOpenMeshReader). Check the counts against the file size first: an
// ASCII OFF vertex takes at least 6 bytes ("0 0 0\n") and a face 8, an OM
// vertex at least 12 (its position) and a face or edge at least one.
bool PlausibleCounts(const std::string& name, const std::string& ext, std::string& why)
{
  std::ifstream in(name, std::ios::binary | std::ios::ate);
  const long long size = static_cast<long long>(in.tellg());
  if (ext == "off")
  {
    std::string head(64, '\0');
    in.seekg(0);
    in.read(&head[0], 64);
    const size_t eol = head.find('\n');
    if (head.substr(0, eol).find("BINARY") != std::string::npos)
    {
      // Binary OFF: three int32 counts (vertices, faces, edges) after the
      // keyword line; a vertex takes 12 bytes, a face at least 4.
      unsigned char counts[8] = { 0 };
      in.clear();
      in.seekg(eol == std::string::npos ? 0 : static_cast<std::streamoff>(eol + 1));
      in.read(reinterpret_cast<char*>(counts), 8);
      auto count = [&](int at)
      {
        return static_cast<long long>(static_cast<int32_t>(static_cast<uint32_t>(counts[at]) |
          (static_cast<uint32_t>(counts[at + 1]) << 8) |
          (static_cast<uint32_t>(counts[at + 2]) << 16) |
          (static_cast<uint32_t>(counts[at + 3]) << 24)));
      };
      const long long vertices = count(0), faces = count(4);
      if (eol == std::string::npos || !in || vertices < 0 || faces < 0 || vertices > size / 12 ||
        faces > size / 4)
      {
        why = "its binary header announces " + std::to_string(vertices) + " vertices and " +
          std::to_string(faces) + " faces, which " + std::to_string(size) + " bytes cannot hold";
        return false;
      }
      return true;
    }
    long long vertices = -1, faces = -1, nextVertices = -1, nextFaces = -1;
    OFFCounts(name, vertices, faces, &nextVertices, &nextFaces);
    if (vertices < 0 || faces < 0)
    {
      why = "its header has no vertex and face counts";
      return false;
    }
    if (vertices > size / 6 || faces > size / 8 || nextVertices > size / 6 || nextFaces > size / 8)
    {
      why = "its header announces " + std::to_string(vertices) + " vertices and " +
        std::to_string(faces) + " faces, more than " + std::to_string(size) + " bytes can hold";
      return false;
    }
  }
  else if (ext == "om" && size >= 16)
  {
    unsigned char header[16];
    in.seekg(0);
    in.read(reinterpret_cast<char*>(header), 16);
    auto count = [&](int at)
    {
      return static_cast<long long>(header[at]) | (static_cast<long long>(header[at + 1]) << 8) |
        (static_cast<long long>(header[at + 2]) << 16) |
        (static_cast<long long>(header[at + 3]) << 24);
    };
    const long long vertices = count(4), faces = count(8), edges = count(12);
    if (vertices * 12 > size || faces > size || edges > size)
    {
      why = "its header announces " + std::to_string(vertices) + " vertices, " +
        std::to_string(faces) + " faces and " + std::to_string(edges) + " edges, more than " +
        std::to_string(size) + " bytes can hold";
      return false;
    }
  }
  return true;
}
// The mesh as polygons (with vertex cells for the vertices no face uses)
// and, as `options` says it has them, its vertex normals, vertex colours
// and (without vertex cells) face colours.
void MeshToPolyData(Mesh& mesh, const OpenMesh::IO::Options& options, vtkPolyData* output)
{
  const vtkIdType n = static_cast<vtkIdType>(mesh.n_vertices());
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
  if (!PlausibleCounts(this->FileName, Extension(this->FileName), why) ||
    (Extension(this->FileName) == "obj" && !ValidOBJFaces(this->FileName, why)))
  {
    vtkErrorMacro(<< this->FileName << " is damaged: " << why << ".");
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
  GuardedImporter importer(mesh);
  // OpenMesh writes a line to its error stream for every face it rejects
  // (millions for a damaged file); the reader counts them and warns once.
  struct QuietOpenMesh
  {
    bool Saved = ::omerr().is_enabled();
    QuietOpenMesh() { ::omerr().disable(); }
    ~QuietOpenMesh() { this->Saved ? ::omerr().enable() : ::omerr().disable(); }
  } quiet;
  try
  {
    ok = OpenMesh::IO::IOManager().read(this->FileName, importer, options);
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
  if (Extension(this->FileName) == "stl")
  {
    // STL has no vertex normals or colours, but OpenMesh 9's STL reader
    // leaves those options set: the properties would hold uninitialised memory.
    options -= OpenMesh::IO::Options::VertexNormal;
    options -= OpenMesh::IO::Options::VertexColor;
    options -= OpenMesh::IO::Options::FaceColor;
  }
  // OpenMesh accepts an ASCII OFF file that ends early: compare with its header.
  if (Extension(this->FileName) == "off")
  {
    long long vertices = -1, faces = -1;
    OFFCounts(this->FileName, vertices, faces);
    if (vertices >= 0 &&
      (static_cast<long long>(mesh.n_vertices()) < vertices || importer.FaceAttempts < faces))
    {
      vtkErrorMacro(<< this->FileName << " is truncated or corrupt: its header announces "
                    << vertices << " vertices and " << faces << " faces, OpenMesh read "
                    << mesh.n_vertices() << " and " << importer.FaceAttempts << ".");
      return 1;
    }
  }
  if (importer.RejectedFaces > 0)
  {
    vtkWarningMacro(<< this->FileName << ": OpenMesh rejected " << importer.RejectedFaces << " of "
                    << importer.FaceAttempts
                    << " faces (an invalid or repeated vertex, or a non-manifold edge); they are "
                       "left out.");
  }

  const vtkIdType n = static_cast<vtkIdType>(mesh.n_vertices());
  if (n == 0)
  {
    vtkWarningMacro(<< this->FileName << " holds no vertices.");
  }
  MeshToPolyData(mesh, options, output);
  return 1;
}

//------------------------------------------------------------------------------
void vtkOpenMeshReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
