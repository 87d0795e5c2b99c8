// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSurfacesDelegatingMapper.h"

#include "psBallExtraction.h" // For the spacing array's name
#include "vtkAppendPolyData.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkMetaballGhostBalls.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPVRenderView.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPolyData.h"

#include <vector>

vtkStandardNewMacro(vtkPointSurfacesDelegatingMapper);

//------------------------------------------------------------------------------
vtkPointSurfacesDelegatingMapper::vtkPointSurfacesDelegatingMapper() = default;

//------------------------------------------------------------------------------
vtkPointSurfacesDelegatingMapper::~vtkPointSurfacesDelegatingMapper() = default;

//------------------------------------------------------------------------------
void vtkPointSurfacesDelegatingMapper::SetDelegate(vtkMapper* delegate)
{
  if (this->Delegate != delegate)
  {
    this->Delegate = delegate;
    this->FlatTime = vtkTimeStamp();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkPointSurfacesDelegatingMapper::SetSkipDuplicatePoints(bool skip)
{
  if (this->SkipDuplicatePoints != skip)
  {
    this->SkipDuplicatePoints = skip;
    this->FlatTime = vtkTimeStamp();
    this->Modified();
  }
}

namespace
{
// Does any point-set piece of `data` flag points as ghosts?
bool HasGhostPoints(vtkDataObject* data)
{
  const char* name = vtkDataSetAttributes::GhostArrayName();
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      auto* leaf = vtkPointSet::SafeDownCast(it->GetCurrentDataObject());
      if (leaf && leaf->GetPointData()->GetArray(name))
      {
        return true;
      }
    }
    return false;
  }
  auto* set = vtkPointSet::SafeDownCast(data);
  return set && set->GetPointData()->GetArray(name);
}
} // namespace

//------------------------------------------------------------------------------
int vtkPointSurfacesDelegatingMapper::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

//------------------------------------------------------------------------------
vtkDataObject* vtkPointSurfacesDelegatingMapper::Flatten()
{
  vtkDataObject* input = this->GetInputDataObject(0, 0);
  if (!input)
  {
    this->Flat = nullptr;
    return nullptr;
  }
  if (this->Flat && this->FlatTime > input->GetMTime())
  {
    return this->Flat;
  }
  if (this->SkipDuplicatePoints && HasGhostPoints(input))
  {
    if (!this->Skipper)
    {
      this->Skipper = vtkSmartPointer<vtkMetaballGhostBalls>::New();
      this->Skipper->SetController(nullptr); // alone: only drops the duplicates
    }
    this->Skipper->SetInputDataObject(input);
    this->Skipper->Update();
    input = this->Skipper->GetOutputDataObject(0);
  }
  std::vector<vtkPointSet*> leaves;
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      auto* leaf = vtkPointSet::SafeDownCast(it->GetCurrentDataObject());
      if (leaf && leaf->GetNumberOfPoints() > 0)
      {
        leaves.push_back(leaf);
      }
    }
  }
  else if (auto* pointSet = vtkPointSet::SafeDownCast(input))
  {
    leaves.push_back(pointSet);
  }
  if (leaves.empty())
  {
    this->Flat = nullptr;
  }
  else if (leaves.size() == 1)
  {
    this->Flat = leaves[0];
  }
  else
  {
    // Several pieces: one poly data with their points and point arrays.
    vtkNew<vtkAppendPolyData> append;
    for (vtkPointSet* leaf : leaves)
    {
      auto* poly = vtkPolyData::SafeDownCast(leaf);
      if (poly)
      {
        append->AddInputData(poly);
      }
      else
      {
        vtkNew<vtkPolyData> points;
        points->SetPoints(leaf->GetPoints());
        points->GetPointData()->ShallowCopy(leaf->GetPointData());
        append->AddInputData(points);
      }
    }
    append->Update();
    this->Flat = append->GetOutput();
    // The append drops field data. vtkMetaballGhostBalls's spacing over all
    // processes is the same in every piece: keep it (not the splats' octree,
    // which indexes one piece only).
    if (vtkAbstractArray* spacing =
          leaves[0]->GetFieldData()->GetAbstractArray(pointsurfaces::MeanSpacingArrayName))
    {
      this->Flat->GetFieldData()->AddArray(spacing);
    }
  }
  this->FlatTime.Modified();
  return this->Flat;
}

//------------------------------------------------------------------------------
bool vtkPointSurfacesDelegatingMapper::RendersPiecewise(vtkInformation* viewRequest)
{
  auto* view =
    viewRequest ? vtkPVRenderView::SafeDownCast(viewRequest->Get(vtkPVView::VIEW())) : nullptr;
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  return view ? view->GetUseDistributedRenderingForRender() && !view->InTileDisplayMode() &&
      !view->InCaveDisplayMode()
              : controller && controller->GetNumberOfProcesses() > 1;
}

//------------------------------------------------------------------------------
void vtkPointSurfacesDelegatingMapper::Render(vtkRenderer* ren, vtkActor* act)
{
  if (!this->Delegate)
  {
    return;
  }
  vtkDataObject* flat = this->Flatten();
  if (!flat)
  {
    return;
  }
  if (this->Delegate->GetInputDataObject(0, 0) != flat)
  {
    this->Delegate->SetInputDataObject(flat);
  }
  // The colouring settings ParaView sets on this mapper (scalar visibility,
  // mode, array, lookup table, range, clipping planes).
  this->Delegate->vtkMapper::ShallowCopy(this);
  this->Delegate->Render(ren, act);
}

//------------------------------------------------------------------------------
double* vtkPointSurfacesDelegatingMapper::GetBounds()
{
  vtkDataObject* flat = this->Flatten();
  if (!this->Delegate || !flat)
  {
    vtkMath::UninitializeBounds(this->Bounds);
    return this->Bounds;
  }
  if (this->Delegate->GetInputDataObject(0, 0) != flat)
  {
    this->Delegate->SetInputDataObject(flat);
  }
  this->Delegate->GetBounds(this->Bounds);
  return this->Bounds;
}

//------------------------------------------------------------------------------
void vtkPointSurfacesDelegatingMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->Delegate)
  {
    this->Delegate->ReleaseGraphicsResources(window);
  }
}

//------------------------------------------------------------------------------
bool vtkPointSurfacesDelegatingMapper::HasOpaqueGeometry()
{
  return this->Delegate ? this->Delegate->HasOpaqueGeometry() : false;
}

//------------------------------------------------------------------------------
bool vtkPointSurfacesDelegatingMapper::HasTranslucentPolygonalGeometry()
{
  return this->Delegate ? this->Delegate->HasTranslucentPolygonalGeometry() : false;
}

//------------------------------------------------------------------------------
bool vtkPointSurfacesDelegatingMapper::GetSupportsSelection()
{
  return this->Delegate ? this->Delegate->GetSupportsSelection() : false;
}

//------------------------------------------------------------------------------
void vtkPointSurfacesDelegatingMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Delegate: " << (this->Delegate ? this->Delegate->GetClassName() : "(none)")
     << "\n";
}
