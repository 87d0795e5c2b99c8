// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMetaballRepresentation.h"

#include "vtkInformation.h"
#include "vtkMetaballField.h"
#include "vtkMetaballGhostBalls.h"
#include "vtkMetaballMapper.h"
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
  this->Ghosts->SetField(this->Field); // one field: the ghosts follow the mapper's radii
  this->Mapper->Delete();
  this->LODMapper->Delete();
  vtkMapper** slots[2] = { &this->Mapper, &this->LODMapper };
  for (int k = 0; k < 2; ++k)
  {
    this->Balls[k] = vtkMetaballMapper::New();
    this->Balls[k]->SetField(this->Field);
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
    // Ghosts belong where each rank renders its own piece; anywhere else
    // (data gathered to a client, tile and CAVE displays) they would count
    // beside their owners.
    const bool piecewise = vtkPointSurfacesDelegatingMapper::RendersPiecewise(inInfo);
    for (vtkMapper* mapper : { this->Mapper, this->LODMapper })
    {
      if (auto* delegating = vtkPointSurfacesDelegatingMapper::SafeDownCast(mapper))
      {
        delegating->SetSkipDuplicatePoints(!piecewise);
      }
    }
  }
  return 1;
}

#define PS_FORWARD_TO_MAPPERS(setter)                                                              \
  for (vtkMetaballMapper * balls : this->Balls)                                                    \
  {                                                                                                \
    balls->Set##setter(value);                                                                     \
  }
#define PS_FORWARD(name, setter, type)                                                             \
  void vtkMetaballRepresentation::SetMetaball##name(type value)                                    \
  {                                                                                                \
    PS_FORWARD_TO_MAPPERS(setter)                                                                  \
    this->Modified();                                                                              \
  }
// The field is shared by both mappers and the ghost exchange.
#define PS_FORWARD_FIELD(name, setter, type)                                                       \
  void vtkMetaballRepresentation::SetMetaball##name(type value)                                    \
  {                                                                                                \
    this->Field->Set##setter(value);                                                               \
    this->Modified();                                                                              \
  }
// These also decide which balls reach other ranks: the data must update.
#define PS_FORWARD_GHOSTS(name, setter, type)                                                      \
  void vtkMetaballRepresentation::SetMetaball##name(type value)                                    \
  {                                                                                                \
    this->Field->Set##setter(value);                                                               \
    this->MarkModified();                                                                          \
  }
PS_FORWARD_FIELD(Kernel, Kernel, int)
PS_FORWARD_FIELD(Threshold, Threshold, double)
PS_FORWARD_GHOSTS(RadiusArray, RadiusArrayName, const char*)
PS_FORWARD_GHOSTS(Radius, Radius, double)
PS_FORWARD_GHOSTS(RadiusScale, RadiusScale, double)
PS_FORWARD_GHOSTS(StrengthArray, StrengthArrayName, const char*)
PS_FORWARD_GHOSTS(DensityArray, DensityArrayName, const char*)
PS_FORWARD(RayCaster, RayCaster, int)
PS_FORWARD(StepScale, StepScale, double)
PS_FORWARD(Bisections, Bisections, int)
PS_FORWARD(TileSize, TileSize, int)
PS_FORWARD(Slabs, Slabs, int)
PS_FORWARD(Shadows, Shadows, bool)
PS_FORWARD(MemoryLimit, MemoryLimit, vtkIdType)
PS_FORWARD(LevelOfDetailPixels, LevelOfDetailPixels, double)
#undef PS_FORWARD
#undef PS_FORWARD_TO_MAPPERS
#undef PS_FORWARD_GHOSTS
#undef PS_FORWARD_FIELD

//------------------------------------------------------------------------------
void vtkMetaballRepresentation::SetArrayIdNames(const char* pointArray, const char* cellArray)
{
  for (vtkMetaballMapper* mapper : this->Balls)
  {
    mapper->SetPointIdArrayName(pointArray ? pointArray : "vtkOriginalPointIds");
    (void)cellArray; // a ball reports its point id for cells too
  }
}

//------------------------------------------------------------------------------
void vtkMetaballRepresentation::SetOpacity(double opacity)
{
  if (opacity < 1.0)
  {
    vtkWarningMacro(<< "The Metaballs representation draws an opaque surface: Opacity " << opacity
                    << " is drawn as 1.");
  }
  this->Superclass::SetOpacity(1.0);
}

//------------------------------------------------------------------------------
void vtkMetaballRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  this->Balls[0]->PrintSelf(os, indent.GetNextIndent());
}
