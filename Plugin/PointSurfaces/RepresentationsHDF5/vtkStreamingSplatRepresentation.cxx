// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkStreamingSplatRepresentation.h"

#include "vtkInformation.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPVRenderView.h"
#include "vtkPointSurfacesDelegatingMapper.h"
#include "vtkSplatFileDelegatingMapper.h"
#include "vtkStreamingSplatMapper.h"

vtkStandardNewMacro(vtkStreamingSplatRepresentation);

//------------------------------------------------------------------------------
vtkStreamingSplatRepresentation::vtkStreamingSplatRepresentation()
  : FileMapper(vtkSplatFileDelegatingMapper::New())
{
  this->SetMainMapper(this->FileMapper);
  this->FileMapper->Delete(); // the representation's Mapper holds it
  this->Splats.push_back(this->FileMapper->GetStream());
}

vtkStreamingSplatRepresentation::~vtkStreamingSplatRepresentation() = default;

//------------------------------------------------------------------------------
void vtkStreamingSplatRepresentation::SetSplatStreamingBudget(double megabytes)
{
  this->FileMapper->GetStream()->SetMemoryBudget(megabytes);
  this->Modified();
}

void vtkStreamingSplatRepresentation::SetSplatStreamingAsynchronous(bool on)
{
  this->FileMapper->GetStream()->SetAsynchronous(on);
  this->Modified();
}

void vtkStreamingSplatRepresentation::SetSplatStreamingBatchWait(double seconds)
{
  this->FileMapper->SetBatchWait(seconds);
  this->Modified();
}

//------------------------------------------------------------------------------
bool vtkStreamingSplatRepresentation::DrawsFile()
{
  // A rank that leaves the file to rank 0 reports nothing of it: its stream
  // may have opened the file for its bounds but never draws, nor loads.
  return !this->FileMapper->GetFileDrawn().empty() && this->FileMapper->GetDrawsFile();
}

vtkIdType vtkStreamingSplatRepresentation::GetSplatStreamingFileSplats()
{
  return !this->DrawsFile() ? 0 : this->FileMapper->GetStream()->GetNumberOfSplats();
}

vtkIdType vtkStreamingSplatRepresentation::GetSplatStreamingResidentSplats()
{
  return !this->DrawsFile() ? 0 : this->FileMapper->GetStream()->GetNumberOfResidentSplats();
}

vtkIdType vtkStreamingSplatRepresentation::GetSplatStreamingWantedSplats()
{
  return !this->DrawsFile() ? 0 : this->FileMapper->GetStream()->GetNumberOfWantedSplats();
}

int vtkStreamingSplatRepresentation::GetSplatStreamingLoading()
{
  return this->DrawsFile() && this->FileMapper->GetStream()->GetLoading();
}

//------------------------------------------------------------------------------
int vtkStreamingSplatRepresentation::ProcessViewRequest(vtkInformationRequestKey* request_type,
  vtkInformation* inInfo,
  vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request_type, inInfo, outInfo))
  {
    return 0;
  }
  if (request_type == vtkPVView::REQUEST_UPDATE())
  {
    // The view frames and clips the file, not the pages the reader loaded;
    // and the processes that read it render it (a client would draw them).
    double bounds[6];
    if (vtkSplatFileDelegatingMapper::SplatFileBoundsOf(this->GetInputDataObject(0, 0), bounds))
    {
      vtkPVRenderView::SetGeometryBounds(inInfo, this, bounds);
      vtkPVRenderView::SetRequiresDistributedRendering(inInfo, this, true);
    }
  }
  else if (request_type == vtkPVView::REQUEST_RENDER())
  {
    // Composited by depth, piece by piece: one rank draws the whole file.
    vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
    const int rank = controller ? controller->GetLocalProcessId() : 0;
    this->FileMapper->SetDrawsFile(
      !vtkPointSurfacesDelegatingMapper::RendersPiecewise(inInfo) || rank == 0);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkStreamingSplatRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  this->FileMapper->PrintSelf(os, indent.GetNextIndent());
}
