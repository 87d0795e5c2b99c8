// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkGromacsGroReader.h"

#include "psGromacsGro.h"
#include "psReaderTime.h"

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSplatDataModel.h"
#include "vtkStringArray.h"

#include <fstream>
#include <set>

vtkStandardNewMacro(vtkGromacsGroReader);

struct vtkGromacsGroReader::Index : pointsurfaces::FrameIndex<pointsurfaces::GroFrameInfo>
{
};

namespace
{
// A radius for atoms whose element the table lacks, nm.
constexpr double DefaultRadius = 0.15;
} // namespace

//------------------------------------------------------------------------------
vtkGromacsGroReader::vtkGromacsGroReader()
  : Frames(new Index)
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
vtkGromacsGroReader::~vtkGromacsGroReader() = default;

//------------------------------------------------------------------------------
int vtkGromacsGroReader::GetNumberOfFrames()
{
  return static_cast<int>(this->Frames->Frames.size());
}

//------------------------------------------------------------------------------
bool vtkGromacsGroReader::CanReadFile(const char* fileName)
{
  std::ifstream in(fileName ? fileName : "");
  std::string title, count, atom;
  if (!std::getline(in, title) || !std::getline(in, count) || !std::getline(in, atom))
  {
    return false;
  }
  char* end = nullptr;
  const long long n = std::strtoll(count.c_str(), &end, 10);
  return end != count.c_str() && n > 0 && atom.size() >= 44 &&
    atom.find('.', 20) != std::string::npos;
}

//------------------------------------------------------------------------------
int vtkGromacsGroReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  this->Frames->Update(
    this, this->FileName, pointsurfaces::ScanGro, "frame", outputVector->GetInformationObject(0));
  return 1;
}

//------------------------------------------------------------------------------
int vtkGromacsGroReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  const Index& index = *this->Frames;
  if (index.Frames.empty() || pointsurfaces::LaterPiece(info))
  {
    return 1; // RequestInformation said why; or another piece than the first
  }
  const pointsurfaces::GroFrameInfo& where = index.Frames[index.Pick(info)];
  std::ifstream in(this->FileName, std::ios::binary);
  pointsurfaces::GroFrame frame;
  std::string error;
  if (!in || !pointsurfaces::ReadGroFrame(in, where, frame, error))
  {
    vtkErrorMacro(<< "Cannot read the frame at t = " << where.Time << " of " << this->FileName
                  << ": " << (error.empty() ? "cannot open it" : error) << ".");
    return 1;
  }
  const vtkIdType n = static_cast<vtkIdType>(where.NumberOfAtoms);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkIntArray> resid, atomid;
  resid->SetName("resid");
  atomid->SetName("atomid");
  vtkNew<vtkStringArray> resname, name, element;
  resname->SetName("resname");
  name->SetName("name");
  element->SetName("element");
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("radius");
  vtkAbstractArray* const arrays[] = { resid, atomid, resname, name, element, radius };
  for (vtkAbstractArray* a : arrays)
  {
    a->SetNumberOfValues(n);
  }
  std::set<std::string> unknown;
  for (vtkIdType k = 0; k < n; ++k)
  {
    points->SetPoint(k, &frame.Positions[3 * k]);
    resid->SetValue(k, frame.ResidueNumbers[k]);
    atomid->SetValue(k, frame.AtomNumbers[k]);
    resname->SetValue(k, frame.ResidueNames[k]);
    name->SetValue(k, frame.AtomNames[k]);
    if (pointsurfaces::IsVirtualSite(frame.AtomNames[k]))
    {
      element->SetValue(k, ""); // a massless site of a water model: no atom, radius 0
      radius->SetValue(k, 0.0);
      continue;
    }
    const std::string e =
      pointsurfaces::ElementFromAtomName(frame.AtomNames[k], frame.ResidueNames[k]);
    element->SetValue(k, e);
    const double r = pointsurfaces::VanDerWaalsRadius(e);
    if (r <= 0.0)
    {
      unknown.insert(frame.AtomNames[k] + " (" + frame.ResidueNames[k] + ")");
    }
    radius->SetValue(k, r > 0.0 ? r : DefaultRadius);
  }
  if (!unknown.empty())
  {
    vtkWarningMacro(<< this->FileName << ": no van der Waals radius for the element of "
                    << unknown.size() << " atom names, such as " << *unknown.begin()
                    << ": their radius is " << DefaultRadius << " nm.");
  }
  output->SetPoints(points);
  vtkSplatDataModel::AddVertexCells(output);
  vtkPointData* pd = output->GetPointData();
  for (vtkAbstractArray* a : arrays)
  {
    pd->AddArray(a);
  }
  if (!frame.Velocities.empty())
  {
    vtkNew<vtkDoubleArray> v;
    v->SetName("v");
    v->SetNumberOfComponents(3);
    v->SetNumberOfTuples(n);
    std::copy(frame.Velocities.begin(), frame.Velocities.end(), v->GetPointer(0));
    pd->AddArray(v);
  }
  pointsurfaces::StampFrame(output, where.Time, where.Step, frame.Box);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGromacsGroReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Frames: " << this->Frames->Frames.size() << "\n";
}
