// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The multi-resolution splat file and the streaming fit that writes it:
// - a fitted sphere (three levels, a colour array) written and read back
//   whole: every splat, each value as the file stores it (origins in
//   double, the rest in float), and written again from what was read, the
//   same rows bit for bit; integer attributes (unsigned char, int) keep
//   their types and values, and values written to an integer attribute
//   are rounded and clamped to it;
// - lazy reads: a budget that holds the coarsest level of every page loads
//   all of it first; a camera loads only the pages in view, and with a
//   PixelError only the levels its pixels need; a budget smaller than one
//   page gives a warning and an empty output;
// - bad files (missing, empty, truncated, foreign HDF5, unfinished,
//   damaged octree, a column of a damaged number type): one error each,
//   naming the file, and an empty output; the number type check alone;
// - vtkStreamingSplatFitter on a binary PLY read in 7 pieces
//   (vtkPLYScanReader SplitPoints) across chunks: the in-memory fit's count
//   within 3 %, every splat in the file, the colours carried; on a source
//   that does not split (the whole input in piece 0) the same; no FileName
//   and FixedCount refused with one error.
#include "psHDF5.h"
#include "psIOTestSupport.h"
#include "psSplatFile.h"
#include "psSplatPages.h"

#include "vtkAlgebraicSplatFitter.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkPLYScanReader.h"
#include "vtkSplatDataModel.h"
#include "vtkSplatFileReader.h"
#include "vtkSplatFileWriter.h"
#include "vtkStreamingSplatFitter.h"
#include "vtkTrivialProducer.h"
#include "vtkUnsignedCharArray.h"
#include "vtk_hdf5.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <utility>
#include <vector>

using namespace pointsurfaces_test;

namespace
{
std::string Temp(const std::string& name)
{
  const char* dir = std::getenv("POINTSURFACES_TEMP_DIR");
  return std::string(dir ? dir : "/tmp") + "/" + name;
}

// n points on a sphere of radius 1 (a Fibonacci lattice), with a colour
// array "Colour" (3 floats: the point's x, y, z mapped to 0..1).
vtkSmartPointer<vtkPolyData> Sphere(long long n)
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkFloatArray> colour;
  colour->SetName("Colour");
  colour->SetNumberOfComponents(3);
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (long long i = 0; i < n; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / n;
    const double s = std::sqrt(1.0 - z * z);
    const double p[3] = { s * std::cos(golden * i), s * std::sin(golden * i), z };
    points->InsertNextPoint(p);
    const float c[3] = { static_cast<float>(0.5 + 0.5 * p[0]),
      static_cast<float>(0.5 + 0.5 * p[1]),
      static_cast<float>(0.5 + 0.5 * p[2]) };
    colour->InsertNextTypedTuple(c);
  }
  pd->SetPoints(points);
  pd->GetPointData()->AddArray(colour);
  return pd;
}

// The binary PLY of `pd`'s points (float x y z) and colours (uchar).
void WritePLY(vtkPolyData* pd, const std::string& path)
{
  const vtkIdType n = pd->GetNumberOfPoints();
  std::string bytes = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(n) +
    "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
    "property uchar green\nproperty uchar blue\nend_header\n";
  vtkDataArray* colour = pd->GetPointData()->GetArray("Colour");
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    pd->GetPoint(i, p);
    for (int c = 0; c < 3; ++c)
    {
      const float f = static_cast<float>(p[c]);
      bytes.append(reinterpret_cast<const char*>(&f), 4);
    }
    for (int c = 0; c < 3; ++c)
    {
      bytes += static_cast<char>(static_cast<unsigned char>(255.0 * colour->GetComponent(i, c)));
    }
  }
  Write(path, bytes);
}

vtkSmartPointer<vtkPolyData> Fit(vtkPolyData* points, int levels)
{
  vtkNew<vtkAlgebraicSplatFitter> fitter;
  fitter->SetInputData(points);
  fitter->SetNumberOfLevels(levels);
  fitter->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(fitter->GetOutput());
  return out;
}

vtkSmartPointer<vtkPolyData> Read(const std::string& path,
  double budget = 0.0,
  vtkCamera* camera = nullptr,
  double pixelError = 0.0,
  int* warnings = nullptr,
  bool rangeEnds = true)
{
  vtkNew<vtkSplatFileReader> reader;
  vtkNew<vtkTest::ErrorObserver> observer;
  reader->AddObserver(vtkCommand::WarningEvent, observer);
  reader->SetFileName(path.c_str());
  reader->SetLoadRangeEnds(rangeEnds);
  reader->SetMemoryBudget(budget);
  reader->SetCamera(camera);
  reader->SetViewportSize(400, 300);
  reader->SetPixelError(pixelError);
  reader->Update();
  if (warnings)
  {
    *warnings = observer->GetWarning() ? 1 : 0;
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(reader->GetOutput());
  return out;
}

// The splats of `pd` by origin: every array's tuple, as doubles.
std::map<std::array<double, 3>, std::vector<double>> ByOrigin(vtkPolyData* pd)
{
  std::map<std::array<double, 3>, std::vector<double>> out;
  vtkPointData* data = pd->GetPointData();
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
  {
    std::array<double, 3> key;
    pd->GetPoint(i, key.data());
    std::vector<double> values;
    for (int a = 0; a < data->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* array = data->GetArray(a);
      for (int c = 0; array && c < array->GetNumberOfComponents(); ++c)
      {
        values.push_back(array->GetComponent(i, c));
      }
    }
    out[key] = values;
  }
  return out;
}

// Every row of the file `path`, as the file holds it.
pointsurfaces::SplatColumns Rows(const std::string& path)
{
  pointsurfaces::SplatFileReader file;
  pointsurfaces::SplatColumns rows;
  std::string error;
  if (!file.Open(path, error) || !file.Read(0, file.Info().Splats, rows, error))
  {
    std::cerr << path << ": " << error << "\n";
  }
  return rows;
}

bool Same(const pointsurfaces::SplatColumns& a, const pointsurfaces::SplatColumns& b)
{
  auto bytes = [](const auto& x, const auto& y)
  { return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0; };
  bool same = a.Count == b.Count && bytes(a.Origin, b.Origin) && bytes(a.Normal, b.Normal) &&
    bytes(a.Tangent, b.Tangent) && bytes(a.FeatureSize, b.FeatureSize) &&
    bytes(a.Coefficients, b.Coefficients) && bytes(a.Radius, b.Radius) &&
    bytes(a.MaxDeviation, b.MaxDeviation) && bytes(a.NominalRadius, b.NominalRadius) &&
    bytes(a.Tolerance, b.Tolerance) && bytes(a.LOD, b.LOD) &&
    a.Attributes.size() == b.Attributes.size();
  for (size_t k = 0; same && k < a.Attributes.size(); ++k)
  {
    same = bytes(a.Attributes[k], b.Attributes[k]);
  }
  return same;
}

vtkIdType Level(vtkPolyData* pd, int level)
{
  vtkDataArray* lod = pd->GetPointData()->GetArray(vtkSplatDataModel::LODName());
  vtkIdType count = 0;
  for (vtkIdType i = 0; lod && i < lod->GetNumberOfTuples(); ++i)
  {
    count += static_cast<int>(lod->GetTuple1(i)) == level ? 1 : 0;
  }
  return count;
}

void WriteAndReadBack()
{
  const auto splats = Fit(Sphere(60000), 3);
  const vtkIdType n = splats->GetNumberOfPoints();
  // Integer attributes: a class (unsigned char) and a signed offset (int).
  vtkNew<vtkUnsignedCharArray> classes;
  classes->SetName("Class");
  vtkNew<vtkIntArray> offsets;
  offsets->SetName("Offset");
  for (vtkIdType i = 0; i < n; ++i)
  {
    classes->InsertNextValue(static_cast<unsigned char>(i % 256));
    offsets->InsertNextValue(static_cast<int>(i - n / 2) * 1000);
  }
  splats->GetPointData()->AddArray(classes);
  splats->GetPointData()->AddArray(offsets);
  const std::string path = Temp("TestSplatFile-sphere.psplat");
  vtkNew<vtkSplatFileWriter> writer;
  writer->SetInputData(splats);
  writer->SetFileName(path.c_str());
  writer->SetPageSize(256); // some 40 pages
  writer->Write();
  Check(writer->GetNumberOfSplats() == n, "the writer writes every splat");

  const auto whole = Read(path);
  std::cout << "sphere: " << n << " splats written, " << whole->GetNumberOfPoints() << " read\n";
  Check(whole->GetNumberOfPoints() == n, "the whole file reads every splat");
  Check(vtkSplatDataModel::GetSplatDegree(whole) == 3, "the degree survives");
  vtkDataArray* q = whole->GetFieldData()->GetArray(vtkSplatDataModel::LODQualityName());
  Check(q && q->GetNumberOfTuples() == 3 && q->GetTuple1(0) == 4.0, "the levels' s survive");
  {
    // Checked in process instead of in a child first: the same splats.
    vtkNew<vtkSplatFileReader> inProcess;
    inProcess->SetFileName(path.c_str());
    inProcess->CheckInChildProcessOff();
    inProcess->Update();
    Check(inProcess->GetOutput()->GetNumberOfPoints() == n,
      "without the child's check the file reads the same splats");
  }
  Check(whole->GetPointData()->GetArray("Colour") &&
      whole->GetPointData()->GetArray("Colour")->GetNumberOfComponents() == 3,
    "the carried colour is stored with its components");
  vtkDataArray* classesRead = whole->GetPointData()->GetArray("Class");
  vtkDataArray* offsetsRead = whole->GetPointData()->GetArray("Offset");
  Check(classesRead && classesRead->GetDataType() == VTK_UNSIGNED_CHAR && offsetsRead &&
      offsetsRead->GetDataType() == VTK_INT &&
      whole->GetPointData()->GetArray("Colour")->GetDataType() == VTK_FLOAT,
    "integer attributes read back in their types (unsigned char, int), the colour as float");

  pointsurfaces::Octree tree;
  std::vector<double> quality;
  Check(vtkSplatDataModel::GetOctree(whole, tree, quality) == vtkSplatDataModel::ValidOctree,
    "the output has an octree for the mapper's LOD");

  // Each splat as the file stores it: origins exact, the rest float.
  const auto before = ByOrigin(splats), after = ByOrigin(whole);
  long long matched = 0, exact = 0;
  std::vector<std::string> names;
  for (const auto& [origin, values] : before)
  {
    const auto it = after.find(origin);
    if (it == after.end())
    {
      continue;
    }
    ++matched;
    // The arrays may come in another order: compare the multisets of values.
    std::vector<double> a, b = it->second;
    for (double v : values)
    {
      a.push_back(static_cast<double>(static_cast<float>(v)));
    }
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    exact += a == b ? 1 : 0;
  }
  Check(matched == n, "every splat's origin comes back exactly");
  Check(exact == n, "every splat's values come back as the file's floats");

  // Written again from what was read: the same rows, bit for bit.
  const std::string again = Temp("TestSplatFile-again.psplat");
  vtkNew<vtkSplatFileWriter> writer2;
  writer2->SetInputData(whole);
  writer2->SetPageSize(256);
  writer2->SetFileName(again.c_str());
  writer2->Write();
  Check(Same(Rows(path), Rows(again)), "a file written from what was read holds the same rows");

  // A budget for a bit more than the coarsest levels: all of level 0 first
  // (the pages alone: the range ends come on top, WholeFileRanges).
  pointsurfaces::SplatFileReader file;
  std::string error;
  file.Open(path, error);
  const double perSplat = file.BytesPerSplat();
  const vtkIdType coarse = Level(splats, 0);
  int warned = 0;
  const auto partial = Read(path, 1.2 * coarse * perSplat / 1e6, nullptr, 0.0, &warned, false);
  std::cout << "budget for 1.2 x level 0 (" << coarse
            << " splats): " << partial->GetNumberOfPoints() << " loaded, " << Level(partial, 0)
            << " of level 0\n";
  Check(Level(partial, 0) == coarse, "a budget that holds level 0 loads all of it first");
  Check(partial->GetNumberOfPoints() < n && partial->GetNumberOfPoints() <= 1.2 * coarse + 1,
    "and stays within the budget");
  Check(!warned, "no warning when something fits");

  const auto none = Read(path, 1e-6, nullptr, 0.0, &warned);
  Check(none->GetNumberOfPoints() == 0 && warned,
    "a budget smaller than one page: a warning and an empty output");

  // A camera inside the sphere, looking along +x, sees only its +x cap.
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 0);
  camera->SetFocalPoint(1, 0, 0);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(30);
  camera->SetClippingRange(0.01, 10);
  const auto seen = Read(path, 0.0, camera);
  std::cout << "camera inside, looking along +x: " << seen->GetNumberOfPoints() << " splats\n";
  Check(seen->GetNumberOfPoints() > 0 && seen->GetNumberOfPoints() < 0.5 * n,
    "a camera loads only the pages in its frustum");
  // Far away (the sphere some 28 pixels tall): level 0's splats are 4
  // pixels across there, level 1's 2.5, level 2's 1.
  camera->SetPosition(40, 0, 0);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetClippingRange(30, 50);
  const auto far = Read(path, 0.0, camera, 5.0, nullptr, false);
  std::cout << "camera at x = 40, PixelError 5: " << far->GetNumberOfPoints() << " splats, "
            << Level(far, 2) << " of level 2\n";
  Check(far->GetNumberOfPoints() > 0 && Level(far, 2) == 0,
    "far away with a PixelError, only coarse levels are loaded");
}

void BadFiles()
{
  const std::string good = Temp("TestSplatFile-sphere.psplat");
  ExpectReadError<vtkSplatFileReader>(Temp("TestSplatFile-missing.psplat"), "cannot be opened");
  ExpectEmptyFileError<vtkSplatFileReader>(Temp("TestSplatFile-empty.psplat"));
  const std::string bytes = Slurp(good);
  const std::string truncated =
    Write(Temp("TestSplatFile-truncated.psplat"), bytes.substr(0, bytes.size() / 2));
  ExpectReadError<vtkSplatFileReader>(truncated, "truncated");
  ExpectReadError<vtkSplatFileReader>(
    Write(Temp("TestSplatFile-text.psplat"), "not a splat file\n"), "not an HDF5 file");

  // A foreign HDF5 file, an unfinished one and a damaged octree.
  const std::string foreign = Temp("TestSplatFile-foreign.h5");
  H5Fclose(H5Fcreate(foreign.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
  ExpectReadError<vtkSplatFileReader>(foreign, "not a PointSurfaces splat file");
  const std::string unfinished = Write(Temp("TestSplatFile-unfinished.psplat"), bytes);
  {
    const hid_t f = H5Fopen(unfinished.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    H5Adelete(f, "Complete");
    H5Fclose(f);
  }
  ExpectReadError<vtkSplatFileReader>(unfinished, "unfinished");
  const std::string damaged = Write(Temp("TestSplatFile-damaged.psplat"), bytes);
  {
    const hid_t f = H5Fopen(damaged.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t d = H5Dopen2(f, "Octree/Range", H5P_DEFAULT);
    std::vector<long long> range(2 * 4);
    const hsize_t start[2] = { 0, 0 }, count[2] = { 4, 2 }; // the page octree has more nodes
    const hid_t space = H5Dget_space(d);
    H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr);
    const hid_t memory = H5Screate_simple(2, count, nullptr);
    H5Dread(d, H5T_NATIVE_LLONG, memory, space, H5P_DEFAULT, range.data());
    range[7] = 1LL << 40; // node 3 ends far past the splats
    H5Dwrite(d, H5T_NATIVE_LLONG, memory, space, H5P_DEFAULT, range.data());
    H5Sclose(memory);
    H5Sclose(space);
    H5Dclose(d);
    H5Fclose(f);
  }
  ExpectReadError<vtkSplatFileReader>(damaged, "damaged");

  // A column whose float type is damaged (36 bytes wide, as the fuzzer
  // made it): HDF5 1.10 reads past its conversion buffer on such a type,
  // so the reader refuses the column before it reads a value.
  const std::string badType = Write(Temp("TestSplatFile-bad-type.psplat"), bytes);
  {
    // HDF5 1.14.4 and later refuse to write such a type unless told to.
    const hid_t access = H5Pcreate(H5P_FILE_ACCESS);
#ifdef H5F_RFIC_UNUSUAL_NUM_UNUSED_NUMERIC_BITS
    H5Pset_relax_file_integrity_checks(access, H5F_RFIC_UNUSUAL_NUM_UNUSED_NUMERIC_BITS);
#endif
    const hid_t f = H5Fopen(badType.c_str(), H5F_ACC_RDWR, access);
    H5Pclose(access);
    const hid_t old = H5Dopen2(f, "Splats/Radius", H5P_DEFAULT);
    const hid_t space = H5Dget_space(old);
    H5Dclose(old);
    H5Ldelete(f, "Splats/Radius", H5P_DEFAULT);
    const hid_t wide = H5Tcopy(H5T_IEEE_F32LE);
    H5Tset_size(wide, 36);
    const hid_t d =
      H5Dcreate2(f, "Splats/Radius", wide, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    Check(d >= 0, "a dataset of a 36-byte float type written");
    H5Dclose(d);
    H5Tclose(wide);
    H5Sclose(space);
    H5Fclose(f);
  }
  ExpectReadError<vtkSplatFileReader>(badType, "Splats/Radius");
  // The type check itself: standard types pass, odd widths and bits do not.
  for (const hid_t t : { H5T_IEEE_F32LE, H5T_IEEE_F64BE, H5T_STD_I8LE, H5T_STD_U64BE })
  {
    Check(pointsurfaces::SaneNumberType(t), "a standard HDF5 number type is sane");
  }
  Check(!pointsurfaces::SaneNumberType(H5T_C_S1), "a string type is not a number type");
  const hid_t odd = H5Tcopy(H5T_IEEE_F64LE);
  H5Tset_size(odd, 36);
  Check(!pointsurfaces::SaneNumberType(odd), "a 36-byte float is refused");
  H5Tclose(odd);
  const hid_t shifted = H5Tcopy(H5T_STD_I32LE);
  H5Tset_precision(shifted, 16);
  H5Tset_offset(shifted, 16);
  Check(pointsurfaces::SaneNumberType(shifted), "16 bits at offset 16 of an int32 are sane");
  H5Tclose(shifted);
}

// Values written to integer attributes: rounded to the nearest and clamped
// to the type (NaN: 0), read back in the type; a float attribute as it was.
void RoundedIntegers()
{
  const std::vector<float> values = { -3.0f, 2.6f, 7.5f, 254.6f, 300.0f, NAN, -2.5f, 1e10f };
  const long long n = static_cast<long long>(values.size());
  pointsurfaces::SplatFileInfo info;
  info.Degree = 1;
  info.AttributeNames = { "Byte", "Short", "Float" };
  info.AttributeComponents = { 1, 1, 1 };
  info.AttributeTypes = { VTK_UNSIGNED_CHAR, VTK_SHORT, VTK_FLOAT };
  std::vector<double> origins(3 * n), radii(n, 0.1);
  std::vector<int> levels(n, 0);
  for (long long i = 0; i < n; ++i)
  {
    origins[3 * i] = static_cast<double>(i);
  }
  auto fetch = [&](const std::vector<long long>& ids, pointsurfaces::SplatColumns& block)
  {
    for (size_t k = 0; k < ids.size(); ++k)
    {
      for (auto& column : block.Attributes)
      {
        column[k] = values[ids[k]];
      }
      for (int c = 0; c < 3; ++c)
      {
        block.Origin[3 * k + c] = origins[3 * ids[k] + c];
      }
      block.Radius[k] = 0.1f;
    }
    return true;
  };
  const std::string path = Temp("TestSplatFile-integers.psplat");
  std::string error;
  Check(pointsurfaces::WriteSplatFile(
          path, info, origins.data(), radii.data(), levels.data(), n, { 1.0 }, fetch, error),
    "a file of integer attributes is written");
  const auto read = Read(path);
  vtkDataArray* byte = read->GetPointData()->GetArray("Byte");
  vtkDataArray* word = read->GetPointData()->GetArray("Short");
  vtkDataArray* real = read->GetPointData()->GetArray("Float");
  Check(byte && byte->GetDataType() == VTK_UNSIGNED_CHAR && word &&
      word->GetDataType() == VTK_SHORT && real && real->GetDataType() == VTK_FLOAT,
    "the attributes read back as unsigned char, short and float");
  const double wantByte[] = { 0, 3, 8, 255, 255, 0, 0, 255 };
  const double wantShort[] = { -3, 3, 8, 255, 300, 0, -3, 32767 };
  bool rounded = byte && word && real && read->GetNumberOfPoints() == n;
  for (vtkIdType i = 0; rounded && i < n; ++i)
  {
    double p[3];
    read->GetPoint(i, p);
    const long long k = static_cast<long long>(p[0]); // the file's order is its own
    const double f = real->GetComponent(i, 0);
    rounded = byte->GetComponent(i, 0) == wantByte[k] && word->GetComponent(i, 0) == wantShort[k] &&
      (std::isnan(values[k]) ? std::isnan(f) : f == static_cast<double>(values[k]));
  }
  Check(rounded, "integer attributes are rounded and clamped to their types, floats kept");
}

void Streaming()
{
  const auto points = Sphere(40000);
  const auto memory = Fit(points, 1);
  const std::string ply = Temp("TestSplatFile-sphere.ply");
  WritePLY(points, ply);

  vtkNew<vtkPLYScanReader> reader;
  reader->SetFileName(ply.c_str());
  reader->SplitPointsOn();
  vtkNew<vtkStreamingSplatFitter> fitter;
  fitter->SetInputConnection(reader->GetOutputPort());
  fitter->SetNumberOfPieces(7);
  fitter->SetChunkPoints(5000);
  const std::string path = Temp("TestSplatFile-streamed.psplat");
  fitter->SetFileName(path.c_str());
  fitter->SetOutputMemoryBudget(0);
  fitter->Update();
  const double ratio = static_cast<double>(fitter->GetNumberOfSplatsWritten()) /
    std::max<vtkIdType>(1, memory->GetNumberOfPoints());
  std::cout << "streamed from 7 PLY pieces: " << fitter->GetNumberOfSplatsWritten()
            << " splats over " << fitter->GetNumberOfChunks() << " chunks (in memory "
            << memory->GetNumberOfPoints() << ", " << ratio << "x)\n";
  Check(fitter->GetNumberOfChunks() > 4, "the sphere is cut across chunks");
  Check(std::abs(ratio - 1.0) < 0.03, "the streamed count is within 3 % of the in-memory one");
  vtkPolyData* out = fitter->GetOutput();
  Check(out->GetNumberOfPoints() == fitter->GetNumberOfSplatsWritten(),
    "with no budget the output is the whole file");
  vtkDataArray* colour = out->GetPointData()->GetArray("RGB");
  Check(
    colour && colour->GetNumberOfComponents() == 3 && colour->GetDataType() == VTK_UNSIGNED_CHAR,
    "the PLY's colours are carried, as unsigned char");
  double worst = 0.0;
  for (vtkIdType i = 0; colour && i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    worst = std::max(worst, std::abs(colour->GetComponent(i, 0) - 255.0 * (0.5 + 0.5 * p[0])));
  }
  std::cout << "colour: largest |red - 255 (0.5 + 0.5 x)| " << worst << "\n";
  Check(worst < 3.0, "a splat's colour is its points' colour");
  vtkDataArray* oriented = out->GetFieldData()->GetArray(vtkSplatDataModel::NormalsOrientedName());
  Check(oriented && oriented->GetTuple1(0) == 1, "the streamed normals are oriented");
  long long inward = 0;
  vtkDataArray* normals = out->GetPointData()->GetArray(vtkSplatDataModel::NormalName());
  for (vtkIdType i = 0; normals && i < out->GetNumberOfPoints(); ++i)
  {
    double p[3], m[3];
    out->GetPoint(i, p);
    normals->GetTuple(i, m);
    inward += p[0] * m[0] + p[1] * m[1] + p[2] * m[2] < 0.0 ? 1 : 0;
  }
  Check(inward == 0, "every streamed normal faces outward");

  // A source that does not split: the whole input arrives in piece 0.
  vtkNew<vtkStreamingSplatFitter> whole;
  whole->SetInputData(points);
  whole->SetNumberOfPieces(3);
  whole->SetChunkPoints(5000);
  whole->SetFileName(Temp("TestSplatFile-whole.psplat").c_str());
  whole->Update();
  Check(whole->GetNumberOfSplatsWritten() == fitter->GetNumberOfSplatsWritten() ||
      std::abs(static_cast<double>(whole->GetNumberOfSplatsWritten()) /
          fitter->GetNumberOfSplatsWritten() -
        1.0) < 0.01,
    "an input that does not split streams all the same");

  // Errors.
  vtkNew<vtkStreamingSplatFitter> nowhere;
  vtkNew<vtkTest::ErrorObserver> errors;
  nowhere->AddObserver(vtkCommand::ErrorEvent, errors);
  nowhere->SetInputData(points);
  nowhere->Update();
  Check(errors->GetError() && errors->GetErrorMessage().find("FileName") != std::string::npos &&
      nowhere->GetOutput()->GetNumberOfPoints() == 0,
    "no FileName: one error and an empty output");
  vtkNew<vtkStreamingSplatFitter> lop;
  vtkNew<vtkTest::ErrorObserver> lopErrors;
  lop->AddObserver(vtkCommand::ErrorEvent, lopErrors);
  lop->SetInputData(points);
  lop->SetFileName(Temp("TestSplatFile-lop.psplat").c_str());
  lop->SetSelectionMode(vtkAlgebraicSplatFitter::FixedCount);
  lop->Update();
  Check(lopErrors->GetError() &&
      lopErrors->GetErrorMessage().find("FixedCount") != std::string::npos &&
      lop->GetOutput()->GetNumberOfPoints() == 0,
    "FixedCount: one error and an empty output");
}
} // namespace

// The file read in `pieces` pieces (as ParaView's ranks ask), each with its warnings counted.
std::vector<vtkSmartPointer<vtkPolyData>> ReadPieces(const std::string& path,
  int pieces,
  double budget,
  int* warnings,
  bool rangeEnds = true)
{
  std::vector<vtkSmartPointer<vtkPolyData>> out;
  *warnings = 0;
  for (int p = 0; p < pieces; ++p)
  {
    vtkNew<vtkSplatFileReader> reader;
    vtkNew<vtkTest::ErrorObserver> observer;
    reader->AddObserver(vtkCommand::WarningEvent, observer);
    reader->AddObserver(vtkCommand::ErrorEvent, observer);
    reader->SetFileName(path.c_str());
    reader->SetLoadRangeEnds(rangeEnds);
    reader->SetMemoryBudget(budget);
    reader->UpdatePiece(p, pieces, 0);
    *warnings += observer->GetWarning() || observer->GetError() ? 1 : 0;
    auto piece = vtkSmartPointer<vtkPolyData>::New();
    piece->ShallowCopy(reader->GetOutput());
    out.push_back(piece);
  }
  return out;
}

vtkIdType FieldCount(vtkPolyData* pd, const char* name)
{
  vtkDataArray* a = pd->GetFieldData()->GetArray(name);
  return a && a->GetNumberOfTuples() == 1 ? static_cast<vtkIdType>(a->GetTuple1(0)) : -1;
}

std::vector<std::string> ArrayNames(vtkPolyData* pd)
{
  std::vector<std::string> names;
  for (int a = 0; a < pd->GetPointData()->GetNumberOfArrays(); ++a)
  {
    names.emplace_back(pd->GetPointData()->GetArrayName(a));
  }
  std::sort(names.begin(), names.end());
  return names;
}

void Pieces()
{
  // The share of a selection: contiguous in the file's order, cut inside ranges.
  pointsurfaces::PageSelection chosen;
  for (const auto& [begin, end] :
    { std::pair<long long, long long>{ 0, 5 }, { 10, 12 }, { 20, 27 } })
  {
    pointsurfaces::PageRange r;
    r.Begin = begin;
    r.End = end;
    chosen.Ranges.push_back(r);
  }
  chosen.Splats = 14;
  auto ranges = [&](int piece, int pieces)
  {
    std::vector<std::pair<long long, long long>> out;
    for (const auto& r : pointsurfaces::PieceOfSelection(chosen, piece, pieces, 1.0).Ranges)
    {
      out.emplace_back(r.Begin, r.End);
    }
    return out;
  };
  using Ranges = std::vector<std::pair<long long, long long>>;
  Check(ranges(0, 3) == Ranges{ { 0, 5 } } && ranges(1, 3) == Ranges{ { 10, 12 }, { 20, 23 } } &&
      ranges(2, 3) == Ranges{ { 23, 27 } },
    "14 chosen splats in 3 pieces: 5, 5 and 4, the ranges cut at the shares' ends");
  Check(pointsurfaces::PieceOfSelection(chosen, 1, 3, 2.0).Bytes == 10.0 &&
      ranges(0, 1) == Ranges{ { 0, 5 }, { 10, 12 }, { 20, 27 } } && ranges(3, 3).empty() &&
      ranges(-1, 3).empty() && ranges(13, 20) == Ranges{ { 26, 27 } } && ranges(19, 20).empty(),
    "a piece's bytes; one piece is the whole; a piece out of range or past the splats is empty");

  // The file in three pieces: each splat once, as one piece reads them.
  const std::string path = Temp("TestSplatFile-sphere.psplat");
  const auto whole = Read(path);
  const vtkIdType n = whole->GetNumberOfPoints();
  // With the range ends (LoadRangeEnds) they go to piece 0 on top of its
  // share; without, the shares differ by one at most.
  std::vector<vtkIdType> withoutEnds;
  for (const bool ends : { false, true })
  {
    for (const double budget : { 0.0, 0.05 })
    {
      const auto one =
        budget > 0.0 || !ends ? Read(path, budget, nullptr, 0.0, nullptr, ends) : whole;
      int warned = 0;
      const auto parts = ReadPieces(path, 3, budget, &warned, ends);
      std::map<std::array<double, 3>, std::vector<double>> joined;
      vtkIdType sum = 0, smallest = one->GetNumberOfPoints(), largest = 0;
      bool fields = true, arrays = true;
      for (const auto& part : parts)
      {
        const vtkIdType m = part->GetNumberOfPoints();
        sum += m;
        smallest = std::min(smallest, m);
        largest = std::max(largest, m);
        const auto byOrigin = ByOrigin(part);
        joined.insert(byOrigin.begin(), byOrigin.end());
        fields = fields && FieldCount(part, "SplatFileLoadedSplats") == m &&
          FieldCount(part, "SplatFileSplats") == n;
        arrays = arrays && ArrayNames(part) == ArrayNames(one);
        if (!ends)
        {
          withoutEnds.push_back(m);
        }
      }
      std::cout << "in 3 pieces, budget " << budget << " MB, range ends " << (ends ? "on" : "off")
                << ": " << parts[0]->GetNumberOfPoints() << " + " << parts[1]->GetNumberOfPoints()
                << " + " << parts[2]->GetNumberOfPoints() << " of " << one->GetNumberOfPoints()
                << " splats\n";
      const size_t at = budget > 0.0 ? 3 : 0; // this budget's pieces without the ends
      const bool shares = ends ? parts[1]->GetNumberOfPoints() == withoutEnds[at + 1] &&
          parts[2]->GetNumberOfPoints() == withoutEnds[at + 2] &&
          parts[0]->GetNumberOfPoints() >= withoutEnds[at]
                               : largest - smallest <= 1;
      Check(sum == one->GetNumberOfPoints() && joined == ByOrigin(one) && shares && smallest > 0 &&
          !warned,
        "three pieces hold the splats one piece reads, each once, in shares that differ by one "
        "(the range ends in piece 0)");
      Check(fields && arrays,
        "each piece has the same arrays and counts its own splats (SplatFileLoadedSplats)");
    }
  }
  // More pieces than chosen splats: the last ones empty, with the arrays.
  int warned = 0;
  const vtkIdType few = Read(path, 0.01)->GetNumberOfPoints();
  vtkNew<vtkSplatFileReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetMemoryBudget(0.01);
  reader->UpdatePiece(static_cast<int>(few) + 5, static_cast<int>(few) + 10, 0);
  const auto last = ReadPieces(path, 1, 0.01, &warned);
  Check(few > 0 && reader->GetOutput()->GetNumberOfPoints() == 0 &&
      ArrayNames(reader->GetOutput()) == ArrayNames(last[0]) && !warned,
    "a piece past the chosen splats is empty, with the same arrays, and no warning");
}

// Attribute `name` of `object`: `n` doubles (for damaging a file by hand).
void WriteDoubles(hid_t object, const char* name, const double* values, hsize_t n)
{
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t attribute = H5Acreate2(object, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attribute, H5T_NATIVE_DOUBLE, values);
  H5Aclose(attribute);
  H5Sclose(space);
}

// [min, max] of component c (-1: the magnitude, or the only component) of
// `a`'s finite values, computed here.
std::array<double, 2> Span(vtkDataArray* a, int c)
{
  std::array<double, 2> r = { std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity() };
  const int comps = a->GetNumberOfComponents();
  for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
  {
    double v = 0.0;
    if (c < 0 && comps > 1)
    {
      bool finite = true;
      for (int k = 0; k < comps; ++k)
      {
        const double x = a->GetComponent(t, k);
        finite = finite && std::isfinite(x);
        v += x * x;
      }
      if (!finite)
      {
        continue;
      }
      v = std::sqrt(v);
    }
    else
    {
      v = a->GetComponent(t, std::max(0, c));
    }
    if (std::isfinite(v))
    {
      r[0] = std::min(r[0], v);
      r[1] = std::max(r[1], v);
    }
  }
  return r;
}

void WholeFileRanges()
{
  // Some pages of the sphere's file: their arrays report the whole file's
  // ranges (GetRange, GetFiniteRange: what ParaView's colour maps fit).
  const std::string path = Temp("TestSplatFile-sphere.psplat");
  const auto whole = Read(path);
  const auto partial = Read(path, 0.05);
  const auto pages = Read(path, 0.05, nullptr, 0.0, nullptr, false);
  const char* names[] = { "Class",
    "Offset",
    "Colour",
    vtkSplatDataModel::RadiusName(),
    vtkSplatDataModel::NormalName(),
    vtkSplatDataModel::CoefficientsName(),
    vtkSplatDataModel::FeatureSizeName(),
    vtkSplatDataModel::LODName() };
  bool same = true, narrower = false, found = true, ends = true;
  for (const char* name : names)
  {
    vtkDataArray* part = partial->GetPointData()->GetArray(name);
    vtkDataArray* page = pages->GetPointData()->GetArray(name);
    vtkDataArray* all = whole->GetPointData()->GetArray(name);
    if (!part || !page || !all)
    {
      found = false;
      continue;
    }
    for (int c = -1; c < part->GetNumberOfComponents(); ++c)
    {
      const std::array<double, 2> expected = Span(all, c);
      // The cached ranges (the pages alone) and the values (with the range ends).
      std::array<double, 2> got, finite;
      page->GetRange(got.data(), c);
      page->GetFiniteRange(finite.data(), c);
      if (got != expected || finite != expected)
      {
        same = false;
        std::cout << name << " component " << c << ": [" << got[0] << ", " << got[1]
                  << "], finite [" << finite[0] << ", " << finite[1] << "], the file's ["
                  << expected[0] << ", " << expected[1] << "]\n";
      }
      narrower = narrower || Span(page, c) != expected;
      if (Span(part, c) != expected)
      {
        ends = false;
        std::cout << name << " component " << c << ": the values with the range ends span ["
                  << Span(part, c)[0] << ", " << Span(part, c)[1] << "], the file [" << expected[0]
                  << ", " << expected[1] << "]\n";
      }
    }
  }
  const vtkIdType added = partial->GetNumberOfPoints() - pages->GetNumberOfPoints();
  std::cout << "whole-file ranges: " << pages->GetNumberOfPoints() << " of "
            << whole->GetNumberOfPoints() << " splats read, and " << added << " range ends\n";
  Check(
    found && narrower, "the pages read alone span less than the file (the check means something)");
  Check(same, "arrays of some pages report the whole file's ranges, per component and magnitude");
  Check(ends && added > 0 && added <= 64,
    "with the splats that hold the range ends (a few), the values span the whole file");

  // Changed afterwards, an array computes its own range again.
  vtkDataArray* classes = pages->GetPointData()->GetArray("Class");
  for (vtkIdType t = 0; classes && t < classes->GetNumberOfTuples(); ++t)
  {
    classes->SetComponent(t, 0, 7.0);
  }
  if (classes)
  {
    classes->Modified();
  }
  Check(classes && classes->GetRange()[0] == 7.0 && classes->GetRange()[1] == 7.0,
    "an array changed after reading computes its own range");

  // A file without ranges (written before them), or with one that does not
  // fit its dataset: the pages' own ranges, and no error.
  const std::string old = Write(Temp("TestSplatFile-noranges.psplat"), Slurp(path));
  {
    const hid_t f = H5Fopen(old.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t classSet = H5Dopen2(f, "Attributes/Class", H5P_DEFAULT);
    H5Adelete(classSet, "Range");
    H5Dclose(classSet);
    const hid_t offsetSet = H5Dopen2(f, "Attributes/Offset", H5P_DEFAULT);
    H5Adelete(offsetSet, "Range");
    const double wrong[3] = { 5.0, 1.0, 2.0 };
    WriteDoubles(offsetSet, "Range", wrong, 3);
    H5Dclose(offsetSet);
    H5Fclose(f);
  }
  int warned = 0;
  const auto older = Read(old, 0.05, nullptr, 0.0, &warned);
  vtkDataArray* oldClasses = older->GetPointData()->GetArray("Class");
  vtkDataArray* oldOffsets = older->GetPointData()->GetArray("Offset");
  vtkDataArray* oldRadius = older->GetPointData()->GetArray(vtkSplatDataModel::RadiusName());
  Check(oldClasses && oldOffsets && oldRadius && !warned &&
      std::array<double, 2>{ oldClasses->GetRange()[0], oldClasses->GetRange()[1] } ==
        Span(oldClasses, 0) &&
      std::array<double, 2>{ oldOffsets->GetRange()[0], oldOffsets->GetRange()[1] } ==
        Span(oldOffsets, 0) &&
      std::array<double, 2>{ oldRadius->GetRange()[0], oldRadius->GetRange()[1] } ==
        Span(whole->GetPointData()->GetArray(vtkSplatDataModel::RadiusName()), 0),
    "without a Range, or with one of the wrong size, the pages' own range; the others stay");

  // A file without range rows (written before them), or with one outside
  // the file: the pages alone, and no warning.
  const std::string norows = Write(Temp("TestSplatFile-norows.psplat"), Slurp(path));
  {
    const hid_t f = H5Fopen(norows.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    for (const char* group : { "Splats", "Attributes" })
    {
      const hid_t g = H5Gopen2(f, group, H5P_DEFAULT);
      H5G_info_t content;
      H5Gget_info(g, &content);
      for (hsize_t k = 0; k < content.nlinks; ++k)
      {
        char name[256] = { 0 };
        H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof(name), H5P_DEFAULT);
        const hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
        if (H5Aexists(d, "RangeRows") > 0)
        {
          H5Adelete(d, "RangeRows");
        }
        if (std::string(name) == "Radius")
        {
          const double outside[2] = { 0.0, 1e12 };
          WriteDoubles(d, "RangeRows", outside, 2);
        }
        H5Dclose(d);
      }
      H5Gclose(g);
    }
    H5Fclose(f);
  }
  const auto noEnds = Read(norows, 0.05, nullptr, 0.0, &warned);
  Check(!warned && noEnds->GetNumberOfPoints() == pages->GetNumberOfPoints() &&
      Span(noEnds->GetPointData()->GetArray(vtkSplatDataModel::RadiusName()), 0) ==
        Span(pages->GetPointData()->GetArray(vtkSplatDataModel::RadiusName()), 0),
    "without range rows, or with rows outside the file, the pages alone and no warning");
}

int TestSplatFile(int, char*[])
{
  WriteAndReadBack();
  Pieces();
  WholeFileRanges();
  RoundedIntegers();
  BadFiles();
  Streaming();
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
