// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMetaballRepresentation.h"

#include "vtkMetaballGhostBalls.h"
#include "vtkMetaballMapper.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPVRenderView.h"
#include "vtkPointSurfacesDelegatingMapper.h"

vtkStandardNewMacro(vtkMetaballRepresentation);

//------------------------------------------------------------------------------
vtkMetaballRepresentation::vtkMetaballRepresentation()
{
  // Replace the superclass's mappers, then let it wire them up again, with
  // the ghost exchange.
  this->Ghosts = vtkMetaballGhostBalls::New();
  for (vtkMetaballGhostBalls*& alone : this->Alone)
  {
    alone = vtkMetaballGhostBalls::New();
    alone->SetController(nullptr);
  }
  this->Mapper->Delete();
  this->LODMapper->Delete();
  vtkMapper** slots[2] = { &this->Mapper, &this->LODMapper };
  for (int k = 0; k < 2; ++k)
  {
    this->Balls[k] = vtkMetaballMapper::New();
    vtkPointSurfacesDelegatingMapper* mapper = vtkPointSurfacesDelegatingMapper::New();
    mapper->SetDelegate(this->Balls[k]);
    *slots[k] = mapper;
  }
  this->SetupDefaults();
  this->Superclass::SetSuppressLOD(true);
}

//------------------------------------------------------------------------------
vtkMetaballRepresentation::~vtkMetaballRepresentation()
{
  for (vtkMetaballMapper* balls : this->Balls)
  {
    balls->Delete();
  }
  this->Ghosts->Delete();
  for (vtkMetaballGhostBalls* alone : this->Alone)
  {
    alone->Delete();
  }
}

//------------------------------------------------------------------------------
void vtkMetaballRepresentation::SetupDefaults()
{
  this->Superclass::SetupDefaults();
  this->Ghosts->SetInputConnection(this->GeometryFilter->GetOutputPort());
  this->MultiBlockMaker->SetInputConnection(this->Ghosts->GetOutputPort());
}

//------------------------------------------------------------------------------
int vtkMetaballRepresentation::ProcessViewRequest(vtkInformationRequestKey* request_type,
  vtkInformation* inInfo,
  vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request_type, inInfo, outInfo))
  {
    return 0;
  }
  if (request_type == vtkPVView::REQUEST_UPDATE())
  {
    // Neither redistributable (the ghosts belong to this split) nor a
    // partition for others.
    vtkPVRenderView::SetOrderedCompositingConfiguration(inInfo, this, 0);
  }
  else if (request_type == vtkPVView::REQUEST_RENDER())
  {
    // Alone, this process renders every rank's balls, each rank's ghosts
    // among them: drop the ghosts (each ball is there once, from its owner).
    vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
    if (!controller || controller->GetNumberOfProcesses() <= 1)
    {
      vtkMapper* mappers[2] = { this->Mapper, this->LODMapper };
      for (int k = 0; k < 2; ++k)
      {
        vtkDataObject* delivered = mappers[k]->GetInputDataObject(0, 0);
        if (delivered && delivered != this->Alone[k]->GetOutputDataObject(0))
        {
          this->Alone[k]->SetInputDataObject(delivered);
          this->Alone[k]->Update();
          mappers[k]->SetInputDataObject(this->Alone[k]->GetOutputDataObject(0));
        }
      }
    }
  }
  return 1;
}

#define PS_FORWARD(name, setter, type)                                                             \
  void vtkMetaballRepresentation::SetMetaball##name(type value)                                    \
  {                                                                                                \
    for (vtkMetaballMapper * balls : this->Balls)                                                  \
    {                                                                                              \
      balls->Set##setter(value);                                                                   \
    }                                                                                              \
    this->Modified();                                                                              \
  }
// These also decide which balls reach other ranks.
#define PS_FORWARD_GHOSTS(name, setter, type)                                                      \
  void vtkMetaballRepresentation::SetMetaball##name(type value)                                    \
  {                                                                                                \
    for (vtkMetaballMapper * balls : this->Balls)                                                  \
    {                                                                                              \
      balls->Set##setter(value);                                                                   \
    }                                                                                              \
    this->Ghosts->Set##setter(value);                                                              \
    this->MarkModified();                                                                          \
  }
PS_FORWARD(Kernel, Kernel, int)
PS_FORWARD(Threshold, Threshold, double)
PS_FORWARD_GHOSTS(RadiusArray, RadiusArrayName, const char*)
PS_FORWARD_GHOSTS(Radius, Radius, double)
PS_FORWARD_GHOSTS(RadiusScale, RadiusScale, double)
PS_FORWARD_GHOSTS(StrengthArray, StrengthArrayName, const char*)
PS_FORWARD(StepScale, StepScale, double)
PS_FORWARD(Bisections, Bisections, int)
PS_FORWARD(TileSize, TileSize, int)
PS_FORWARD(Slabs, Slabs, int)
PS_FORWARD(Shadows, Shadows, bool)
#undef PS_FORWARD
#undef PS_FORWARD_GHOSTS

//------------------------------------------------------------------------------
void vtkMetaballRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  this->Balls[0]->PrintSelf(os, indent.GetNextIndent());
}
