// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMetaballRepresentation.h"

#include "vtkMetaballMapper.h"
#include "vtkObjectFactory.h"
#include "vtkPointSurfacesDelegatingMapper.h"

vtkStandardNewMacro(vtkMetaballRepresentation);

//------------------------------------------------------------------------------
vtkMetaballRepresentation::vtkMetaballRepresentation()
{
  // Replace the superclass's mappers, then let it wire them up again.
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
PS_FORWARD(Kernel, Kernel, int)
PS_FORWARD(Threshold, Threshold, double)
PS_FORWARD(RadiusArray, RadiusArrayName, const char*)
PS_FORWARD(Radius, Radius, double)
PS_FORWARD(RadiusScale, RadiusScale, double)
PS_FORWARD(StrengthArray, StrengthArrayName, const char*)
PS_FORWARD(StepScale, StepScale, double)
PS_FORWARD(Bisections, Bisections, int)
PS_FORWARD(TileSize, TileSize, int)
PS_FORWARD(Slabs, Slabs, int)
PS_FORWARD(Shadows, Shadows, bool)
#undef PS_FORWARD

//------------------------------------------------------------------------------
void vtkMetaballRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  this->Balls[0]->PrintSelf(os, indent.GetNextIndent());
}
