// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSplatFileDelegatingMapper.h"

#include "vtkBoundingBox.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkFieldData.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSplatFileReader.h"
#include "vtkStreamingSplatMapper.h"
#include "vtkStringArray.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <set>

vtkStandardNewMacro(vtkSplatFileDelegatingMapper);

namespace
{
// The mappers of this process, for PollLoading (ParaView calls both on its
// main thread), and whether a GUI polls it.
std::set<vtkSplatFileDelegatingMapper*>& Mappers()
{
  static std::set<vtkSplatFileDelegatingMapper*> mappers;
  return mappers;
}
bool PolledByGUI = false;

// What the reader's field arrays say of `data` (of its first leaf that has
// each), and what `data` is (all its leaves): its points, their bounds and
// the names of its point arrays; found in one walk.
struct SplatFileFields
{
  vtkStringArray* Name = nullptr;
  vtkDataArray* Loaded = nullptr;
  vtkDataArray* Bounds = nullptr;
  vtkDataArray* LoadedBounds = nullptr;
  vtkStringArray* Arrays = nullptr;
  vtkIdType Points = 0;
  vtkBoundingBox DataBounds;
  std::set<std::string> DataArrays;

  explicit SplatFileFields(vtkDataObject* data)
  {
    auto visit = [this](vtkDataObject* object)
    {
      if (auto* set = vtkDataSet::SafeDownCast(object))
      {
        this->Points += set->GetNumberOfPoints();
        if (set->GetNumberOfPoints() > 0)
        {
          this->DataBounds.AddBounds(set->GetBounds());
        }
        vtkPointData* pd = set->GetPointData();
        for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
        {
          const char* name = pd->GetArrayName(a);
          this->DataArrays.insert(name ? name : "");
        }
      }
      vtkFieldData* fields = object ? object->GetFieldData() : nullptr;
      if (!fields)
      {
        return;
      }
      if (!this->Name)
      {
        this->Name = vtkStringArray::SafeDownCast(
          fields->GetAbstractArray(vtkSplatFileReader::FileNameArrayName()));
      }
      if (!this->Loaded)
      {
        this->Loaded = fields->GetArray("SplatFileLoadedSplats");
      }
      if (!this->Bounds)
      {
        this->Bounds = fields->GetArray(vtkSplatFileReader::FileBoundsArrayName());
      }
      if (!this->LoadedBounds)
      {
        this->LoadedBounds = fields->GetArray(vtkSplatFileReader::LoadedBoundsArrayName());
      }
      if (!this->Arrays)
      {
        this->Arrays = vtkStringArray::SafeDownCast(
          fields->GetAbstractArray(vtkSplatFileReader::ArraysArrayName()));
      }
    };
    if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
    {
      vtkSmartPointer<vtkCompositeDataIterator> it;
      it.TakeReference(composite->NewIterator());
      for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
      {
        visit(it->GetCurrentDataObject());
      }
    }
    else
    {
      visit(data);
    }
  }

  // The file's name when the data is the reader's output unfiltered, else
  // empty: as many points as it loaded, at the same bounds (a Transform
  // keeps the count) and no point array it did not have (a Calculator
  // keeps the points; the file has no such array to colour by).
  std::string File() const
  {
    if (!this->Name || this->Name->GetNumberOfValues() < 1 || !this->Loaded ||
      this->Loaded->GetNumberOfTuples() < 1 ||
      static_cast<vtkIdType>(this->Loaded->GetComponent(0, 0)) != this->Points ||
      !this->LoadedBounds || this->LoadedBounds->GetNumberOfComponents() != 6 ||
      this->LoadedBounds->GetNumberOfTuples() < 1 || !this->Arrays)
    {
      return std::string();
    }
    if (this->Points > 0)
    {
      double loaded[6], bounds[6];
      this->LoadedBounds->GetTuple(0, loaded);
      this->DataBounds.GetBounds(bounds);
      if (!std::equal(loaded, loaded + 6, bounds))
      {
        return std::string();
      }
    }
    for (const std::string& name : this->DataArrays)
    {
      // VTK's and ParaView's own bookkeeping (vtkOriginalPointIds, which
      // ParaView's delivery adds for selection; vtkGhostType) does not count.
      if (name.compare(0, 3, "vtk") != 0 && this->Arrays->LookupValue(name) < 0)
      {
        return std::string();
      }
    }
    return this->Name->GetValue(0);
  }
};
} // namespace

//------------------------------------------------------------------------------
std::string vtkSplatFileDelegatingMapper::SplatFileOf(vtkDataObject* data)
{
  return SplatFileFields(data).File();
}

bool vtkSplatFileDelegatingMapper::SplatFileBoundsOf(vtkDataObject* data, double bounds[6])
{
  const SplatFileFields fields(data);
  if (fields.File().empty() || !fields.Bounds || fields.Bounds->GetNumberOfTuples() < 1 ||
    fields.Bounds->GetNumberOfComponents() != 6)
  {
    return false;
  }
  fields.Bounds->GetTuple(0, bounds);
  return true;
}

//------------------------------------------------------------------------------
vtkSplatFileDelegatingMapper::vtkSplatFileDelegatingMapper()
  : Stream(vtkStreamingSplatMapper::New())
{
  Mappers().insert(this);
}

vtkSplatFileDelegatingMapper::~vtkSplatFileDelegatingMapper()
{
  Mappers().erase(this);
  this->Stream->Delete();
}

//------------------------------------------------------------------------------
bool vtkSplatFileDelegatingMapper::PollLoading()
{
  PolledByGUI = true;
  for (vtkSplatFileDelegatingMapper* mapper : Mappers())
  {
    if (mapper->DrawsFile && !mapper->FileDrawn.empty() && !mapper->RendersItself &&
      mapper->Stream->GetLoading())
    {
      return true;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
const std::string& vtkSplatFileDelegatingMapper::ChooseFile()
{
  // Once per input (and StreamFile) change: the file exists, or not, for as long.
  vtkDataObject* input = this->GetInputDataObject(0, 0);
  const vtkMTimeType stamp = input ? input->GetMTime() : 0;
  if (stamp == this->ChosenFor && this->StreamFile == this->ChosenStreaming && stamp != 0)
  {
    return this->FileDrawn;
  }
  this->ChosenFor = stamp;
  this->ChosenStreaming = this->StreamFile;
  this->FileDrawn.clear();
  if (this->StreamFile)
  {
    const std::string file = SplatFileOf(input);
    if (!file.empty() && vtksys::SystemTools::FileExists(file, true))
    {
      this->FileDrawn = file;
      this->Stream->SetFileName(file.c_str());
    }
  }
  return this->FileDrawn;
}

//------------------------------------------------------------------------------
void vtkSplatFileDelegatingMapper::Render(vtkRenderer* ren, vtkActor* act)
{
  if (this->ChooseFile().empty())
  {
    this->Superclass::Render(ren, act);
    return;
  }
  if (!this->DrawsFile)
  {
    return;
  }
  // The GUI's interactor (Qt's) renders again on the stream's timer; on a
  // server, the GUI renders again while PollLoading says so. Elsewhere an
  // interactor may exist (pvbatch) but no event loop runs it.
  vtkRenderWindow* window = ren->GetRenderWindow();
  vtkRenderWindowInteractor* interactor = window ? window->GetInteractor() : nullptr;
  this->RendersItself =
    interactor && interactor->GetInitialized() && interactor->IsA("QVTKInteractor");
  this->Stream->SetRenderWait(this->RendersItself || PolledByGUI ? 0.0 : this->BatchWait);
  this->Stream->vtkMapper::ShallowCopy(this);
  this->Stream->Render(ren, act);
}

//------------------------------------------------------------------------------
double* vtkSplatFileDelegatingMapper::GetBounds()
{
  if (this->ChooseFile().empty())
  {
    return this->Superclass::GetBounds();
  }
  this->Stream->GetBounds(this->Bounds);
  return this->Bounds;
}

//------------------------------------------------------------------------------
void vtkSplatFileDelegatingMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Stream->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
bool vtkSplatFileDelegatingMapper::HasOpaqueGeometry()
{
  return this->ChooseFile().empty() ? this->Superclass::HasOpaqueGeometry()
                                    : this->Stream->HasOpaqueGeometry();
}

bool vtkSplatFileDelegatingMapper::HasTranslucentPolygonalGeometry()
{
  return this->ChooseFile().empty() ? this->Superclass::HasTranslucentPolygonalGeometry()
                                    : this->Stream->HasTranslucentPolygonalGeometry();
}

bool vtkSplatFileDelegatingMapper::GetSupportsSelection()
{
  return this->FileDrawn.empty() && this->Superclass::GetSupportsSelection();
}

//------------------------------------------------------------------------------
void vtkSplatFileDelegatingMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "StreamFile: " << this->StreamFile << "\n";
  os << indent << "DrawsFile: " << this->DrawsFile << "\n";
  os << indent << "BatchWait: " << this->BatchWait << " s\n";
  os << indent << "FileDrawn: " << (this->FileDrawn.empty() ? "(none)" : this->FileDrawn) << "\n";
  this->Stream->PrintSelf(os, indent.GetNextIndent());
}
