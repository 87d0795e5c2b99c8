// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkLASReader on LAS and LAZ files written here with LASzip (exact values):
// - 5000 points of format 3 near (6e5, 4.2e6, 300) at millimetre scale:
//   coordinates, intensity, classification, returns, GPS time and 8-bit
//   colours read back exactly, from the LAS and from the LAZ file;
// - pieces: 7 pieces of either file hold every point once, in order;
// - 16-bit colours become bytes (the high byte);
// - bad input: a missing file, an empty file, a text file, a truncated
//   LAS and a truncated LAZ: one error each, naming the file, and an empty
//   output.
#include "psIOTestSupport.h"
#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkLASReader.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <laszip_api.h>

#include <cmath>
#include <cstdlib>

using namespace pointsurfaces_test;

namespace
{
std::string Temp(const std::string& name)
{
  const char* dir = std::getenv("POINTSURFACES_TEMP_DIR");
  return std::string(dir ? dir : "/tmp") + "/" + name;
}

// The exact values of point i.
void Expected(int i, double xyz[3], int& intensity, int& cls, double& time, int rgb[3], bool wide)
{
  xyz[0] = 600000.0 + 0.001 * (i * 37 % 100000);
  xyz[1] = 4200000.0 + 0.001 * (i * 91 % 100000);
  xyz[2] = 300.0 + 0.001 * (i % 5000);
  intensity = (i * 13) % 65536;
  cls = i % 20;
  time = 1000.0 + 0.25 * i;
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = (i * (c + 3)) % 256;
    rgb[c] = wide ? rgb[c] * 256 + 7 : rgb[c];
  }
}

void WriteFile(const std::string& path, int n, bool compress, bool wide)
{
  laszip_POINTER writer = nullptr;
  laszip_create(&writer);
  laszip_header* h = nullptr;
  laszip_get_header_pointer(writer, &h);
  h->version_major = 1;
  h->version_minor = 2;
  h->header_size = 227;
  h->offset_to_point_data = 227;
  h->point_data_format = 3;
  h->point_data_record_length = 34;
  h->number_of_point_records = static_cast<laszip_U32>(n);
  h->x_scale_factor = h->y_scale_factor = h->z_scale_factor = 0.001;
  h->x_offset = 600000.0;
  h->y_offset = 4200000.0;
  h->z_offset = 300.0;
  h->min_x = 600000.0;
  h->max_x = 600100.0;
  h->min_y = 4200000.0;
  h->max_y = 4200100.0;
  h->min_z = 300.0;
  h->max_z = 305.0;
  laszip_point* p = nullptr;
  laszip_get_point_pointer(writer, &p);
  if (laszip_open_writer(writer, path.c_str(), compress ? 1 : 0))
  {
    laszip_CHAR* text = nullptr;
    laszip_get_error(writer, &text);
    std::cerr << "cannot write " << path << ": " << (text ? text : "") << "\n";
  }
  for (int i = 0; i < n; ++i)
  {
    double xyz[3], time;
    int intensity, cls, rgb[3];
    Expected(i, xyz, intensity, cls, time, rgb, wide);
    laszip_set_coordinates(writer, xyz);
    p->intensity = static_cast<laszip_U16>(intensity);
    p->classification = static_cast<laszip_U8>(cls);
    p->return_number = 1 + i % 3;
    p->number_of_returns = 3;
    p->gps_time = time;
    for (int c = 0; c < 3; ++c)
    {
      p->rgb[c] = static_cast<laszip_U16>(rgb[c]);
    }
    laszip_write_point(writer);
    laszip_update_inventory(writer);
  }
  laszip_close_writer(writer);
  laszip_destroy(writer);
}

vtkSmartPointer<vtkPolyData> Read(const std::string& path, int piece = 0, int pieces = 1)
{
  vtkNew<vtkLASReader> reader;
  reader->SetFileName(path.c_str());
  reader->UpdatePiece(piece, pieces, 0);
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(reader->GetOutput());
  return out;
}

// Whether `pd` holds points first .. first + size - 1 exactly.
bool Holds(vtkPolyData* pd, int first, bool wide)
{
  vtkDataArray* intensity = pd->GetPointData()->GetArray("Intensity");
  vtkDataArray* cls = pd->GetPointData()->GetArray("Classification");
  vtkDataArray* ret = pd->GetPointData()->GetArray("ReturnNumber");
  vtkDataArray* time = pd->GetPointData()->GetArray("GPSTime");
  vtkDataArray* rgb = pd->GetPointData()->GetScalars();
  if (!intensity || !cls || !ret || !time || !rgb ||
    pd->GetNumberOfVerts() != pd->GetNumberOfPoints())
  {
    return false;
  }
  for (vtkIdType k = 0; k < pd->GetNumberOfPoints(); ++k)
  {
    const int i = first + static_cast<int>(k);
    double xyz[3], p[3], t;
    int in, c, colour[3];
    Expected(i, xyz, in, c, t, colour, wide);
    pd->GetPoint(k, p);
    bool ok = std::abs(p[0] - xyz[0]) < 1e-6 && std::abs(p[1] - xyz[1]) < 1e-6 &&
      std::abs(p[2] - xyz[2]) < 1e-6 && intensity->GetTuple1(k) == in && cls->GetTuple1(k) == c &&
      ret->GetTuple1(k) == 1 + i % 3 && time->GetTuple1(k) == t;
    for (int j = 0; j < 3; ++j)
    {
      ok = ok && rgb->GetComponent(k, j) == (wide ? colour[j] >> 8 : colour[j]);
    }
    if (!ok)
    {
      std::cerr << "point " << i << " differs\n";
      return false;
    }
  }
  return true;
}
} // namespace

int TestLASReader(int, char*[])
{
  const int n = 5000;
  for (const bool compress : { false, true })
  {
    const std::string path = Temp(compress ? "TestLASReader.laz" : "TestLASReader.las");
    WriteFile(path, n, compress, false);
    const auto whole = Read(path);
    const std::string name = compress ? "LAZ" : "LAS";
    Check(whole->GetNumberOfPoints() == n, name + ": every point");
    Check(Holds(whole, 0, false), name + ": every value exactly");
    int total = 0;
    bool inOrder = true;
    for (int piece = 0; piece < 7; ++piece)
    {
      const auto part = Read(path, piece, 7);
      inOrder = inOrder && Holds(part, total, false);
      total += static_cast<int>(part->GetNumberOfPoints());
    }
    Check(total == n && inOrder, name + ": 7 pieces hold every point once, in order");
    const std::string bytes = Slurp(path);
    ExpectReadError<vtkLASReader>(
      Write(Temp("TestLASReader-truncated." + name), bytes.substr(0, bytes.size() / 2)),
      "TestLASReader-truncated");
  }
  const std::string wide = Temp("TestLASReader-wide.las");
  WriteFile(wide, 300, false, true);
  Check(Holds(Read(wide), 0, true), "16-bit colours become their high bytes");

  ExpectReadError<vtkLASReader>(Temp("TestLASReader-missing.las"), "cannot be opened");
  ExpectEmptyFileError<vtkLASReader>(Temp("TestLASReader-empty.las"));
  ExpectReadError<vtkLASReader>(
    Write(Temp("TestLASReader-text.las"),
      "not a lidar file at all, but long enough to have a header? no.\n"),
    "TestLASReader-text.las");
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
