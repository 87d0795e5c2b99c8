// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkGromacsXtcReader on trajectories written by GROMACS itself
// (IO/Testing/Data/gromacs: SPC water, 4 frames, at precisions 10^3, 10^4
// and 10^8, the last coded one coordinate at a time, and 6 atoms stored
// uncompressed), each checked frame by frame against what GROMACS decodes
// from the same file (`gmx trjconv -o .g96`, 9 decimals); the structure
// file's names and radii; and missing, truncated, damaged and garbage files,
// with random damage inside the coded blocks (which must never crash).
#include "psGromacsXtc.h"
#include "psIOTestSupport.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkGromacsXtcReader.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTestErrorObserver.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace pointsurfaces_test;

namespace
{
// One frame of a GROMOS-96 file as `gmx trjconv` writes it.
struct G96Frame
{
  long long Step = -1;
  double Time = 0.0;
  std::vector<double> Positions;
};

std::vector<G96Frame> ReadG96(const std::string& path)
{
  std::vector<G96Frame> frames;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
  {
    if (line == "TIMESTEP")
    {
      frames.emplace_back();
      std::getline(in, line);
      std::istringstream(line) >> frames.back().Step >> frames.back().Time;
    }
    else if (line == "POSITIONRED" && !frames.empty())
    {
      while (std::getline(in, line) && line != "END")
      {
        double x, y, z;
        std::istringstream(line) >> x >> y >> z;
        frames.back().Positions.insert(frames.back().Positions.end(), { x, y, z });
      }
    }
  }
  return frames;
}

// Every frame of `xtc` against `g96`: times, steps and positions within `tolerance` nm.
void CompareWithGromacs(const std::string& xtc,
  const std::string& g96,
  double precision,
  double tolerance)
{
  const std::vector<G96Frame> expected = ReadG96(g96);
  vtkNew<vtkGromacsXtcReader> reader;
  reader->SetFileName(xtc.c_str());
  reader->UpdateInformation();
  vtkInformation* info = reader->GetOutputInformation(0);
  const int steps = info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const double* times = info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  Check(!expected.empty() && steps == static_cast<int>(expected.size()),
    xtc + ": as many frames as GROMACS decodes");
  for (int f = 0; f < steps && f < static_cast<int>(expected.size()); ++f)
  {
    Check(std::abs(times[f] - expected[f].Time) < 1e-6,
      xtc + ": the time of frame " + std::to_string(f));
    reader->UpdateTimeStep(times[f]);
    vtkPolyData* out = reader->GetOutput();
    vtkFieldData* fd = out->GetFieldData();
    Check(fd->GetArray("Step") && fd->GetArray("Step")->GetTuple1(0) == expected[f].Step,
      xtc + ": the step of frame " + std::to_string(f));
    Check(fd->GetArray("Precision") && fd->GetArray("Precision")->GetTuple1(0) == precision,
      xtc + ": precision " + std::to_string(precision));
    Check(fd->GetArray("Box") && std::abs(fd->GetArray("Box")->GetComponent(0, 0) - 1.5) < 1e-3 &&
        fd->GetArray("Box")->GetComponent(0, 3) == 0.0,
      xtc + ": a rectangular box of about 1.5 nm");
    const vtkIdType n = static_cast<vtkIdType>(expected[f].Positions.size() / 3);
    Check(out->GetNumberOfPoints() == n && out->GetNumberOfVerts() == n,
      xtc + ": " + std::to_string(n) + " atoms in frame " + std::to_string(f));
    double worst = 0.0;
    for (vtkIdType k = 0; k < n && out->GetNumberOfPoints() == n; ++k)
    {
      double p[3];
      out->GetPoint(k, p);
      for (int c = 0; c < 3; ++c)
      {
        worst = std::max(worst, std::abs(p[c] - expected[f].Positions[3 * k + c]));
      }
    }
    Check(worst <= tolerance,
      xtc + ": frame " + std::to_string(f) + " is GROMACS's to " + std::to_string(tolerance) +
        " nm (off by " + std::to_string(worst) + ")");
  }
}
} // namespace

int TestGromacsXtcReader(int, char*[])
{
  const std::string data = std::string(std::getenv("POINTSURFACES_IO_DATA")) + "/gromacs";
  const std::string temp = std::getenv("POINTSURFACES_TEMP_DIR");
  const std::string p3 = data + "/water_p3.xtc";
  Check(vtkGromacsXtcReader::CanReadFile(p3.c_str()), "CanReadFile on an .xtc");
  Check(!vtkGromacsXtcReader::CanReadFile((data + "/water_traj.gro").c_str()),
    "CanReadFile refuses a .gro");

  // GROMACS's own numbers. Its decoder and ours round the same integers
  // to float; the .g96 prints them to 9 decimals. The 10^8 file codes the
  // 10^4 file's positions, one coordinate at a time.
  CompareWithGromacs(p3, data + "/water_p3.g96", 1000.0, 1e-7);
  CompareWithGromacs(data + "/water_p4.xtc", data + "/water_p4.g96", 10000.0, 1e-7);
  CompareWithGromacs(data + "/water_p8.xtc", data + "/water_p4.g96", 1e8, 2e-7);
  CompareWithGromacs(data + "/water6_p3.xtc", data + "/water6_p3.g96", 0.0, 1e-7);

  // Names and radii from a structure file of the same 327 atoms.
  {
    vtkNew<vtkGromacsXtcReader> reader;
    reader->SetFileName(p3.c_str());
    reader->SetStructureFileName((data + "/water_traj.gro").c_str());
    reader->UpdateTimeStep(0.04);
    vtkPolyData* out = reader->GetOutput();
    auto* name = vtkStringArray::SafeDownCast(out->GetPointData()->GetAbstractArray("name"));
    vtkDataArray* radius = out->GetPointData()->GetArray("radius");
    Check(out->GetNumberOfPoints() == 327 && name && radius && name->GetValue(0) == "OW" &&
        name->GetValue(1) == "HW1" && radius->GetTuple1(0) == 0.152 &&
        radius->GetTuple1(2) == 0.120,
      "names and radii from the structure file");
    Check(out->GetPointData()->GetArray("v") == nullptr, "no velocities from the structure file");
    Check(out->GetFieldData()->GetArray("Step")->GetTuple1(0) == 20, "t = 0.04 reads step 20");
  }
  {
    vtkNew<vtkGromacsXtcReader> reader;
    reader->SetFileName(p3.c_str());
    reader->UpdateTimeStep(0.0);
    vtkDataArray* atomid = reader->GetOutput()->GetPointData()->GetArray("atomid");
    Check(atomid && atomid->GetTuple1(326) == 327, "without a structure: atomid 1..n");
  }
  {
    vtkNew<vtkGromacsXtcReader> reader;
    vtkNew<vtkTest::ErrorObserver> errors;
    reader->AddObserver(vtkCommand::ErrorEvent, errors);
    reader->SetFileName((data + "/water6_p3.xtc").c_str());
    reader->SetStructureFileName((data + "/water_traj.gro").c_str());
    reader->Update();
    Check(errors->GetError() && errors->GetErrorMessage().find("has 327") != std::string::npos &&
        reader->GetOutput()->GetNumberOfPoints() == 0,
      "a structure file of other atoms: an error and an empty output");
  }

  {
    // A structure file that fails, then is mended on disk: read again.
    const std::string gro = Write(temp + "/structure.gro", "not a structure\n");
    vtkNew<vtkGromacsXtcReader> reader;
    vtkNew<vtkTest::ErrorObserver> errors;
    reader->AddObserver(vtkCommand::ErrorEvent, errors);
    reader->SetFileName(p3.c_str());
    reader->SetStructureFileName(gro.c_str());
    reader->Update();
    Check(errors->GetError() && reader->GetOutput()->GetNumberOfPoints() == 0,
      "a structure file that cannot be read: an error and an empty output");
    Write(gro, Slurp(data + "/water_traj.gro"));
    reader->Modified(); // what ParaView's Reload Files does
    reader->Update();
    Check(reader->GetOutput()->GetNumberOfPoints() == 327 &&
        reader->GetOutput()->GetPointData()->GetArray("radius") != nullptr,
      "the mended structure file is read again");
  }

  // Damage found while indexing.
  const std::string bytes = Slurp(p3);
  std::vector<pointsurfaces::XtcFrameInfo> frames;
  {
    std::ifstream in(p3, std::ios::binary);
    std::string error;
    frames = pointsurfaces::ScanXtc(in, error);
    Check(frames.size() == 4 && error.empty(), "ScanXtc finds four frames");
  }
  if (frames.size() != 4)
  {
    return EXIT_FAILURE;
  }
  {
    const std::string cut =
      Write(temp + "/cut.xtc", bytes.substr(0, static_cast<size_t>(frames[2].Offset + 70)));
    vtkNew<vtkGromacsXtcReader> r;
    vtkNew<vtkTest::ErrorObserver> errors;
    r->AddObserver(vtkCommand::ErrorEvent, errors);
    r->SetFileName(cut.c_str());
    r->UpdateInformation();
    Check(errors->GetError() &&
        errors->GetErrorMessage().find("is damaged after 2 frames") != std::string::npos &&
        errors->GetErrorMessage().find("truncated") != std::string::npos,
      "a truncated trajectory: an error naming what was kept (got '" + errors->GetErrorMessage() +
        "')");
    Check(r->GetNumberOfFrames() == 2, "the two whole frames stay readable");
    r->UpdateTimeStep(0.02);
    Check(r->GetOutput()->GetNumberOfPoints() == 327, "a frame before the damage reads");
  }
  auto patched = [&](const std::string& name, size_t at, const std::string& with)
  {
    std::string b = bytes;
    b.replace(at, with.size(), with);
    return Write(temp + "/" + name, b);
  };
  const size_t block = static_cast<size_t>(frames[0].Offset) + 56; // precision onwards
  ExpectReadError<vtkGromacsXtcReader>(temp + "/missing.xtc", "cannot be opened");
  ExpectEmptyFileError<vtkGromacsXtcReader>(temp + "/empty.xtc");
  ExpectReadError<vtkGromacsXtcReader>(Write(temp + "/garbage.xtc", "garbage, not XDR"), "magic");
  ExpectReadError<vtkGromacsXtcReader>(
    patched("count.xtc", 4, std::string("\x00\x01\x00\x00", 4)), "atom counts");
  ExpectReadError<vtkGromacsXtcReader>(
    patched("bytes.xtc", block + 32, std::string("\x7f\x00\x00\x00", 4)), "truncated");
  ExpectReadError<vtkGromacsXtcReader>(
    patched("time.xtc", 12, std::string("\x7f\xc0\x00\x00", 4)), "not a finite number");
  {
    // 2^31 - 1 atoms in both counts: refused before anything is allocated.
    std::string b = bytes.substr(0, static_cast<size_t>(frames[0].Size));
    b.replace(4, 4, std::string("\x7f\xff\xff\xff", 4));
    b.replace(52, 4, std::string("\x7f\xff\xff\xff", 4));
    ExpectReadError<vtkGromacsXtcReader>(Write(temp + "/giant.xtc", b), "coded bytes");
  }
  ExpectReadError<vtkGromacsXtcReader>(
    patched("tiny-precision.xtc", block, std::string("\x00\x00\x00\x01", 4)), "too small");
  // Damage found while decoding: the frame's output is empty.
  ExpectReadError<vtkGromacsXtcReader>(
    patched("smallidx.xtc", block + 28, std::string("\x00\x00\x00\x50", 4)), "size index");
  ExpectReadError<vtkGromacsXtcReader>(
    patched("precision.xtc", block, std::string("\x00\x00\x00\x00", 4)), "precision");
  ExpectReadError<vtkGromacsXtcReader>(
    patched("range.xtc", block + 16, std::string("\x80\x00\x00\x00", 4)), "range");

  // Random damage inside the coded bytes: decoded to some positions or
  // refused with an error, never a crash or a read past the block (ASan
  // checks this test).
  {
    const size_t begin = block + 36;
    const size_t end = static_cast<size_t>(frames[0].Offset + frames[0].Size);
    std::mt19937 random(7);
    int refused = 0;
    for (int trial = 0; trial < 3000; ++trial)
    {
      std::vector<unsigned char> coded(bytes.begin() + block, bytes.begin() + end);
      const int changes = 1 + trial % 6;
      for (int c = 0; c < changes; ++c)
      {
        coded[36 + random() % (end - begin)] = static_cast<unsigned char>(random() & 0xff);
      }
      std::vector<float> positions;
      std::string error;
      const bool ok =
        pointsurfaces::DecodeXtcCoordinates(coded.data(), coded.size(), 327, positions, error);
      Check(ok ? positions.size() == 3 * 327 : positions.empty() && !error.empty(),
        "damaged block " + std::to_string(trial) + ": all positions, or none and an error");
      refused += ok ? 0 : 1;
    }
    std::cout << refused << " of 3000 damaged blocks refused\n";
    std::vector<float> positions;
    std::string error;
    Check(
      !pointsurfaces::DecodeXtcCoordinates(
        reinterpret_cast<const unsigned char*>(bytes.data()) + block, 20, 327, positions, error),
      "a block shorter than its header is refused");
  }
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
