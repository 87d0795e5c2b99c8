// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAlgebraicSplatRepresentation.h"

#include "vtkAlgebraicSplatMapper.h"
#include "vtkObjectFactory.h"
#include "vtkPointSurfacesDelegatingMapper.h"

vtkStandardNewMacro(vtkAlgebraicSplatRepresentation);

//------------------------------------------------------------------------------
vtkAlgebraicSplatRepresentation::vtkAlgebraicSplatRepresentation()
{
  // Replace the superclass's mappers, then let it wire them up again.
  this->Mapper->Delete();
  this->LODMapper->Delete();
  vtkMapper** slots[2] = { &this->Mapper, &this->LODMapper };
  for (int k = 0; k < 2; ++k)
  {
    this->Splats.push_back(vtkSmartPointer<vtkAlgebraicSplatMapper>::New());
    vtkPointSurfacesDelegatingMapper* mapper = vtkPointSurfacesDelegatingMapper::New();
    mapper->SetDelegate(this->Splats[k]);
    *slots[k] = mapper;
  }
  this->SetupDefaults();
  this->Superclass::SetSuppressLOD(true);
}

//------------------------------------------------------------------------------
vtkAlgebraicSplatRepresentation::~vtkAlgebraicSplatRepresentation() = default;

//------------------------------------------------------------------------------
void vtkAlgebraicSplatRepresentation::SetMainMapper(vtkPointSurfacesDelegatingMapper* mapper)
{
  mapper->SetDelegate(this->Splats[0]);
  mapper->Register(this);
  this->Mapper->Delete();
  this->Mapper = mapper;
  this->SetupDefaults();
  this->Superclass::SetSuppressLOD(true);
}

#define PS_FORWARD(name, type)                                                                     \
  void vtkAlgebraicSplatRepresentation::SetSplat##name(type value)                                 \
  {                                                                                                \
    for (vtkAlgebraicSplatMapper * splats : this->Splats)                                          \
    {                                                                                              \
      splats->Set##name(value);                                                                    \
    }                                                                                              \
    this->Modified();                                                                              \
  }
PS_FORWARD(Blending, bool)
PS_FORWARD(BlendDepthOffset, double)
PS_FORWARD(BlendSharpness, double)
PS_FORWARD(AntiAliasing, int)
PS_FORWARD(SilhouetteThreshold, double)
PS_FORWARD(Culling, bool)
PS_FORWARD(LODPixelError, double)
#undef PS_FORWARD

//------------------------------------------------------------------------------
void vtkAlgebraicSplatRepresentation::SetArrayIdNames(const char* pointArray, const char* cellArray)
{
  for (vtkAlgebraicSplatMapper* mapper : this->Splats)
  {
    mapper->SetPointIdArrayName(pointArray ? pointArray : "vtkOriginalPointIds");
    mapper->SetCellIdArrayName(cellArray ? cellArray : "vtkOriginalCellIds");
  }
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatRepresentation::SetOpacity(double opacity)
{
  if (opacity < 1.0)
  {
    vtkWarningMacro(<< "The Algebraic Splats representation draws an opaque surface: Opacity "
                    << opacity << " is drawn as 1.");
  }
  this->Superclass::SetOpacity(1.0);
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  this->Splats[0]->PrintSelf(os, indent.GetNextIndent());
}
