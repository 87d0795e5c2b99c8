// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMultiResolutionSplatBuilder.h"

#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkMultiResolutionSplatBuilder);

//------------------------------------------------------------------------------
vtkMultiResolutionSplatBuilder::vtkMultiResolutionSplatBuilder()
{
  this->SelectionMode = Quality;
  this->NumberOfLevels = 25;
  this->CoarsestQualityFactor = 4.0;
  this->QualityFactor = 1.0;
  this->BuildOctree = true;
}

//------------------------------------------------------------------------------
void vtkMultiResolutionSplatBuilder::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
