// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPVSplatFileReader.h"

#include "vtkObjectFactory.h"
#include "vtkSplatFileDelegatingMapper.h"

vtkStandardNewMacro(vtkPVSplatFileReader);

//------------------------------------------------------------------------------
bool vtkPVSplatFileReader::GetNeedsUpdate()
{
  return vtkSplatFileDelegatingMapper::PollLoading();
}
