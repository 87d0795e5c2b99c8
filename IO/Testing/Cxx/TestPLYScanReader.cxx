// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkPLYScanReader on PLY files written here:
// - one mesh (normals, colours, point arrays of four types, faces of 3 to 5
//   corners after a per-face flag) in ASCII and binary of both byte orders:
//   the same points, arrays and polygons from each;
// - a MeshLab-style range map (a camera element before the vertices, flags
//   and quality per vertex, colours with alpha, a range_grid of lists of 0 or
//   1 indices after the faces), in the three formats;
// - float colours (scaled, clipped, NaN as 0), double points, faces with
//   fewer than three corners and points with NaN or infinite coordinates
//   (left out, with their faces, and one warning each);
// - bad files: missing, empty, not PLY, no end_header, truncated (ASCII, and
//   the binary range map cut at every length), a huge count or list length
//   in a small file, face indices out of range or not integers, a vertex
//   without z, no points, a word that is no number: one error each, naming
//   the file, an empty output, no crash.
#include "psIOTestSupport.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPLYScanReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace pointsurfaces_test;

namespace
{
const char* const Formats[] = { "ascii", "binary_little_endian", "binary_big_endian" };

// A PLY body in one of the three formats, value by value.
class Body
{
public:
  explicit Body(const std::string& format)
    : Ascii(format == "ascii")
    , Swap(format == "binary_big_endian")
  {
  }
  template<typename T>
  Body& operator<<(T v)
  {
    if (this->Ascii)
    {
      std::ostringstream word;
      word.precision(17);
      word << +v << ' ';
      this->Text += word.str();
      return *this;
    }
    char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    for (size_t k = 0; k < sizeof(T); ++k)
    {
      this->Text += bytes[this->Swap ? sizeof(T) - 1 - k : k];
    }
    return *this;
  }
  void EndRecord()
  {
    if (this->Ascii)
    {
      this->Text += '\n';
    }
  }
  std::string Text;

private:
  bool Ascii, Swap;
};

// The test mesh: a unit square's corners and an apex.
const float Corners[5][3] = { { 0, 0, 0 },
  { 1, 0, 0 },
  { 1, 1, 0 },
  { 0, 1, 0 },
  { 0.5f, 0.5f, 1 } };
const std::vector<std::vector<int>> Faces = { { 0, 1, 2, 3 },
  { 0, 1, 4 },
  { 1, 2, 4 },
  { 0, 1, 2, 3, 4 } };
const std::int64_t BigId = 1000000000000000001LL; // not a double: exact only as an integer

// The test faces as records of a uchar `flags` property and the index list.
void WriteFaces(Body& body, std::uint8_t flags)
{
  for (const auto& face : Faces)
  {
    body << flags << std::uint8_t(face.size());
    for (int i : face)
    {
      body << std::int32_t(i);
    }
    body.EndRecord();
  }
}

std::string MeshFile(const std::string& format)
{
  std::string header = "ply\nformat " + format +
    " 1.0\ncomment the test mesh\nelement vertex 5\n"
    "property float x\nproperty float y\nproperty float z\n"
    "property float nx\nproperty float ny\nproperty float nz\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    "property double quality\nproperty short flags\nproperty int64 id\nproperty char tag\n"
    "element face 4\nproperty uchar flags\nproperty list uchar int vertex_indices\nend_header\n";
  Body body(format);
  for (int k = 0; k < 5; ++k)
  {
    body << Corners[k][0] << Corners[k][1] << Corners[k][2] << 0.0f << 0.0f << 1.0f
         << std::uint8_t(10 * k) << std::uint8_t(20 * k) << std::uint8_t(255 - k) << 0.25 * k
         << std::int16_t(-300 * k) << BigId + k << std::int8_t(-k);
    body.EndRecord();
  }
  WriteFaces(body, 7);
  return header + body.Text;
}

// MeshLab's range map: camera, vertices with flags, quality and RGBA, faces
// with flags, and a range grid (a list per grid cell: its vertex or none).
std::string RangeMapFile(const std::string& format)
{
  const char* camera[] = { "view_px",
    "view_py",
    "view_pz",
    "x_axisx",
    "x_axisy",
    "x_axisz",
    "y_axisx",
    "y_axisy",
    "y_axisz",
    "z_axisx",
    "z_axisy",
    "z_axisz",
    "focal",
    "scalex",
    "scaley",
    "centerx",
    "centery",
    "viewportx",
    "viewporty",
    "k1",
    "k2",
    "k3",
    "k4" };
  std::string header = "ply\nformat " + format + " 1.0\nelement camera 1\n";
  for (const char* name : camera)
  {
    header += std::string("property ") + (std::strncmp(name, "viewport", 8) ? "float " : "int ") +
      name + "\n";
  }
  header += "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
            "property uchar flags\nproperty float quality\nproperty uchar red\n"
            "property uchar green\nproperty uchar blue\nproperty uchar alpha\n"
            "element face 4\nproperty uchar flags\nproperty list uchar int vertex_indices\n"
            "element range_grid 10\nproperty list uchar int vertex_indices\nend_header\n";
  Body body(format);
  for (const char* name : camera)
  {
    if (std::strncmp(name, "viewport", 8) == 0)
    {
      body << std::int32_t(640);
    }
    else
    {
      body << 5.5f; // numbers that are no vertex's
    }
  }
  body.EndRecord();
  for (int k = 0; k < 5; ++k)
  {
    body << Corners[k][0] << Corners[k][1] << Corners[k][2] << std::uint8_t(0) << 0.1f * k
         << std::uint8_t(k) << std::uint8_t(2 * k) << std::uint8_t(3 * k) << std::uint8_t(255);
    body.EndRecord();
  }
  WriteFaces(body, 0);
  for (int cell = 0; cell < 10; ++cell)
  {
    if (cell % 2 == 0)
    {
      body << std::uint8_t(1) << std::int32_t(cell / 2);
    }
    else
    {
      body << std::uint8_t(0);
    }
    body.EndRecord();
  }
  return header + body.Text;
}

// Reads `path`; counts its errors and warnings, keeps the warnings' text.
struct Read
{
  vtkNew<vtkPLYScanReader> Reader;
  vtkNew<vtkTest::ErrorObserver> Messages;
  int ErrorCount = 0, WarningCount = 0;

  explicit Read(const std::string& path)
  {
    vtkNew<vtkCallbackCommand> errors, warnings;
    errors->SetCallback(CountError);
    warnings->SetCallback(CountWarning);
    this->Reader->AddObserver(vtkCommand::ErrorEvent, errors);
    this->Reader->AddObserver(vtkCommand::WarningEvent, warnings);
    this->Reader->AddObserver(vtkCommand::ErrorEvent, this->Messages);
    this->Reader->AddObserver(vtkCommand::WarningEvent, this->Messages);
    this->Reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
    const int e = Errors, w = Warnings;
    this->Reader->SetFileName(path.c_str());
    this->Reader->Update();
    this->ErrorCount = Errors - e;
    this->WarningCount = Warnings - w;
  }
  vtkPolyData* Output() { return this->Reader->GetOutput(); }
};

std::vector<vtkIdType> Polygon(vtkPolyData* poly, vtkIdType k)
{
  vtkNew<vtkIdList> ids;
  poly->GetPolys()->GetCellAtId(k, ids);
  return std::vector<vtkIdType>(ids->begin(), ids->end());
}

void CheckPolygons(vtkPolyData* poly,
  const std::vector<std::vector<int>>& faces,
  const std::string& what)
{
  bool same = poly->GetNumberOfPolys() == static_cast<vtkIdType>(faces.size()) &&
    poly->GetNumberOfVerts() == 0 && poly->GetNumberOfLines() == 0;
  for (size_t k = 0; same && k < faces.size(); ++k)
  {
    same = Polygon(poly, static_cast<vtkIdType>(k)) ==
      std::vector<vtkIdType>(faces[k].begin(), faces[k].end());
  }
  Check(same, what + ": the polygons as written");
}

void CheckMesh(const std::string& path, const std::string& what)
{
  Read read(path);
  vtkPolyData* out = read.Output();
  Check(read.ErrorCount == 0 && read.WarningCount == 0, what + ": no error, no warning");
  Check(out->GetNumberOfPoints() == 5 && out->GetPoints()->GetDataType() == VTK_FLOAT,
    what + ": five float points");
  for (vtkIdType k = 0; k < out->GetNumberOfPoints(); ++k)
  {
    double p[3];
    out->GetPoint(k, p);
    Check(p[0] == Corners[k][0] && p[1] == Corners[k][1] && p[2] == Corners[k][2],
      what + ": point " + std::to_string(k));
  }
  vtkPointData* pd = out->GetPointData();
  vtkDataArray* normals = pd->GetNormals();
  Check(normals && std::string(normals->GetName()) == "Normals" &&
      normals->GetDataType() == VTK_FLOAT && normals->GetNumberOfComponents() == 3 &&
      normals->GetComponent(4, 2) == 1.0,
    what + ": Normals");
  vtkDataArray* rgb = pd->GetScalars();
  Check(rgb && std::string(rgb->GetName()) == "RGB" && rgb->GetDataType() == VTK_UNSIGNED_CHAR &&
      rgb->GetNumberOfComponents() == 3 && rgb->GetComponent(3, 0) == 30 &&
      rgb->GetComponent(3, 1) == 60 && rgb->GetComponent(3, 2) == 252,
    what + ": RGB");
  vtkDataArray* quality = pd->GetArray("quality");
  vtkDataArray* flags = pd->GetArray("flags");
  vtkDataArray* id = pd->GetArray("id");
  vtkDataArray* tag = pd->GetArray("tag");
  Check(quality && quality->GetDataType() == VTK_DOUBLE && quality->GetTuple1(3) == 0.75,
    what + ": quality, double");
  Check(flags && flags->GetDataType() == VTK_SHORT && flags->GetTuple1(2) == -600,
    what + ": flags, short");
  Check(tag && tag->GetDataType() == VTK_SIGNED_CHAR && tag->GetTuple1(4) == -4,
    what + ": tag, signed char");
  Check(id && id->GetDataType() == VTK_TYPE_INT64 &&
      static_cast<const std::int64_t*>(id->GetVoidPointer(0))[4] == BigId + 4,
    what + ": id, int64, exactly");
  Check(pd->GetNumberOfArrays() == 6 && !pd->GetArray("nx") && !pd->GetArray("red"),
    what + ": x y z, nx ny nz and red green blue are not arrays of their own");
  CheckPolygons(out, Faces, what);
}

void CheckRangeMap(const std::string& path, const std::string& what)
{
  Read read(path);
  vtkPolyData* out = read.Output();
  Check(read.ErrorCount == 0 && read.WarningCount == 0, what + ": no error, no warning");
  bool points = out->GetNumberOfPoints() == 5;
  for (vtkIdType k = 0; points && k < 5; ++k)
  {
    double p[3];
    out->GetPoint(k, p);
    points = p[0] == Corners[k][0] && p[1] == Corners[k][1] && p[2] == Corners[k][2];
  }
  Check(points, what + ": the vertices, not the camera's numbers");
  vtkDataArray* rgba = out->GetPointData()->GetScalars();
  Check(rgba && rgba->GetNumberOfComponents() == 4 && rgba->GetComponent(4, 2) == 12 &&
      rgba->GetComponent(4, 3) == 255,
    what + ": RGBA");
  vtkDataArray* quality = out->GetPointData()->GetArray("quality");
  Check(quality && quality->GetDataType() == VTK_FLOAT && out->GetPointData()->GetArray("flags") &&
      std::abs(quality->GetTuple1(2) - 0.2) < 1e-6,
    what + ": flags and quality");
  CheckPolygons(out, Faces, what);
}

const std::string Vertices3 =
  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";

// A bad file: one error that names it and says `expected`, no points.
void ExpectBad(const std::string& path, const std::string& expected)
{
  Read read(path);
  const std::string message = read.Messages->GetErrorMessage();
  Check(read.ErrorCount == 1 && message.find(path + ": " + expected) != std::string::npos,
    "one error '" + expected + "' naming " + path + " (got " + std::to_string(read.ErrorCount) +
      ": '" + message + "')");
  Check(read.Output()->GetNumberOfPoints() == 0 && read.Output()->GetNumberOfCells() == 0,
    "an empty output for " + path);
}
} // namespace

int TestPLYScanReader(int, char*[])
{
  const std::string temp = std::getenv("POINTSURFACES_TEMP_DIR");
  auto file = [&](const std::string& name) { return temp + "/ply-" + name + ".ply"; };

  // The same mesh and range map in the three formats.
  for (const char* format : Formats)
  {
    const std::string mesh = Write(file(std::string("mesh-") + format), MeshFile(format));
    Check(vtkPLYScanReader::CanReadFile(mesh.c_str()), std::string("CanReadFile: ") + format);
    CheckMesh(mesh, std::string("the mesh in ") + format);
    CheckRangeMap(Write(file(std::string("rangemap-") + format), RangeMapFile(format)),
      std::string("the range map in ") + format);
  }
  const std::string crlf = Write(file("crlf"),
    "ply\r\nformat ascii 1.0\r\ncomment Windows\r\nelement vertex 3\r\nproperty double x\r\n"
    "property double y\r\nproperty double z\r\nend_header\r\n0.1 0 0\r\n1 0 0\r\n0 1 0\r\n");
  {
    Read read(crlf);
    Check(read.ErrorCount == 0 && read.Output()->GetNumberOfPoints() == 3 &&
        read.Output()->GetPoints()->GetDataType() == VTK_DOUBLE &&
        read.Output()->GetPoint(0)[0] == 0.1,
      "CRLF lines, double points: read as double");
  }

  // Float colours: 0..1 scaled to bytes, clipped, NaN as 0; diffuse_ colours.
  {
    Read read(Write(file("float-colours"),
      Vertices3 +
        "property float red\nproperty float green\nproperty float blue\nend_header\n"
        "0 0 0 0.5 1.5 -1\n1 0 0 nan 1 0.25\n0 1 0 0 0 0\n"));
    vtkDataArray* rgb = read.Output()->GetPointData()->GetScalars();
    Check(rgb && rgb->GetComponent(0, 0) == 128 && rgb->GetComponent(0, 1) == 255 &&
        rgb->GetComponent(0, 2) == 0 && rgb->GetComponent(1, 0) == 0 &&
        rgb->GetComponent(1, 2) == 64,
      "float colours scaled, clipped, NaN as 0");
    Read diffuse(Write(file("diffuse"),
      Vertices3 +
        "property uchar diffuse_red\nproperty uchar diffuse_green\n"
        "property uchar diffuse_blue\nend_header\n0 0 0 1 2 3\n1 0 0 4 5 6\n0 1 0 7 8 9\n"));
    rgb = diffuse.Output()->GetPointData()->GetScalars();
    Check(rgb && std::string(rgb->GetName()) == "RGB" && rgb->GetComponent(2, 1) == 8,
      "diffuse_ colours as RGB");
  }

  // Faces with fewer than three corners, and lists of several lengths.
  {
    Read read(Write(file("short-faces"),
      Vertices3 +
        "element face 4\nproperty list uchar uint vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n2 0 1\n0\n4 0 1 2 0\n"));
    Check(read.ErrorCount == 0 && read.WarningCount == 1 &&
        read.Messages->GetWarningMessage().find("fewer than three corners left out: 2") !=
          std::string::npos,
      "one warning for two faces with fewer than three corners");
    CheckPolygons(read.Output(), { { 0, 1, 2 }, { 0, 1, 2, 0 } }, "faces of 3 and 4 corners");
  }

  // Points with NaN or infinite coordinates go, with the faces that use them.
  {
    Read read(Write(file("non-finite"),
      "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
      "property float z\nproperty int id\nelement face 2\n"
      "property list uchar int vertex_indices\nend_header\n"
      "0 0 0 10\nnan 0 0 11\n1 1 0 12\n0 inf 0 13\n1 0 0 14\n3 0 2 4\n3 0 1 2\n"));
    vtkPolyData* out = read.Output();
    vtkDataArray* id = out->GetPointData()->GetArray("id");
    Check(read.ErrorCount == 0 && read.WarningCount == 1 &&
        read.Messages->GetWarningMessage().find(
          "2 of 5 points with NaN or infinite coordinates left out") != std::string::npos,
      "one warning for the non-finite points");
    Check(out->GetNumberOfPoints() == 3 && id && id->GetTuple1(0) == 10 && id->GetTuple1(1) == 12 &&
        id->GetTuple1(2) == 14,
      "the finite points and their arrays");
    CheckPolygons(out, { { 0, 1, 2 } }, "the face of finite points, renumbered");
  }

  // Bad files.
  ExpectBad(file("missing"), "cannot be opened");
  ExpectEmptyFileError<vtkPLYScanReader>(file("empty"));
  ExpectBad(Write(file("not-ply"), "solid ascii\nfacet normal 0 0 1\n"), "not a PLY file");
  Check(!vtkPLYScanReader::CanReadFile(file("not-ply").c_str()), "CanReadFile: not PLY");
  ExpectBad(Write(file("no-end"), Vertices3 + "0 0 0\n"), "the PLY header has no end_header line");
  ExpectBad(Write(file("no-z"),
              "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
              "property float y\nend_header\n" +
                std::string(8, '\0')),
    "the PLY header has no vertex element with x, y and z");
  ExpectBad(Write(file("bad-type"), Vertices3 + "property float128 w\nend_header\n"),
    "PLY header line 7: cannot parse 'property float128 w'");
  {
    std::string many = Vertices3;
    for (int k = 0; k < 5000; ++k)
    {
      many += "property float p" + std::to_string(k) + "\n";
    }
    ExpectBad(Write(file("too-many-properties"), many + "end_header\n"),
      "PLY header line 4100: more than 4096 properties in element vertex");
  }
  const std::string ascii = MeshFile("ascii");
  ExpectBad(Write(file("truncated-ascii"), ascii.substr(0, ascii.size() - 40)),
    "truncated: the file ends inside element face");
  ExpectBad(Write(file("huge-count-ascii"),
              "ply\nformat ascii 1.0\nelement vertex 99999999999999999999\nproperty float x\n"
              "property float y\nproperty float z\nend_header\n1 2 3\n"),
    "truncated: the file ends inside element vertex");
  ExpectBad(Write(file("huge-count-binary"),
              "ply\nformat binary_big_endian 1.0\nelement vertex 4000000000000\nproperty float x\n"
              "property float y\nproperty float z\nend_header\n" +
                std::string(12, '\0')),
    "truncated: element vertex needs 48000000000");
  ExpectBad(Write(file("huge-list-binary"),
              "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
              "property float y\nproperty float z\nelement face 1\n"
              "property list uint int vertex_indices\nend_header\n" +
                std::string(12, '\0') + std::string(4, '\xff') + std::string(12, '\0')),
    "truncated: element face needs");
  ExpectBad(Write(file("huge-list-ascii"),
              Vertices3 +
                "element face 1\nproperty list uint int vertex_indices\nend_header\n"
                "0 0 0 1 0 0 0 1 0\n4000000000 0 1 2\n"),
    "truncated: the file ends inside element face");
  ExpectBad(Write(file("face-out-of-range"),
              Vertices3 +
                "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
                "0 0 0 1 0 0 0 1 0\n3 0 1 2\n3 0 1 7\n"),
    "a face refers to vertex 7, but there are 3 vertices");
  ExpectBad(Write(file("face-negative"),
              Vertices3 +
                "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                "0 0 0 1 0 0 0 1 0\n3 0 -1 2\n"),
    "a face refers to vertex -1, but there are 3 vertices");
  ExpectBad(Write(file("face-float"),
              Vertices3 +
                "element face 1\nproperty list uchar float vertex_indices\nend_header\n"
                "0 0 0 1 0 0 0 1 0\n3 0 1 2\n"),
    "the face indices are not integers");
  ExpectBad(Write(file("not-a-number"), Vertices3 + "end_header\n0 0 0 1 zero 0 0 1 0\n"),
    "element vertex holds something that is not a number ('zero')");
  ExpectBad(Write(file("no-points"),
              "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
              "property float z\nend_header\n"),
    "no points");
  ExpectBad(
    Write(file("all-nan"), Vertices3 + "end_header\nnan 0 0 0 inf 0 0 0 -inf\n"), "no points");

  // The binary range map cut at every length: one error each, never a crash.
  const std::string whole = RangeMapFile("binary_little_endian");
  int clean = 0;
  for (size_t cut = 1; cut < whole.size(); ++cut)
  {
    Read read(Write(file("cut"), whole.substr(0, cut)));
    clean += read.ErrorCount == 1 && read.Output()->GetNumberOfPoints() == 0;
  }
  Check(clean == static_cast<int>(whole.size()) - 1,
    "every cut of the binary range map: one error and no points (" + std::to_string(clean) +
      " of " + std::to_string(whole.size() - 1) + ")");
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
