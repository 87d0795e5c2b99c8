// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMetaballRayCaster.h"

//------------------------------------------------------------------------------
void vtkMetaballRayCaster::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CountsOnHost: " << this->CountsOnHost() << "\n";
}
