// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psTestHitMapper.h
 * @brief vtkMetaballMapper with its hit buffer readable, for the accuracy tests.
 */
#ifndef psTestHitMapper_h
#define psTestHitMapper_h

#include "vtkMetaballMapper.h"
#include "vtkObjectFactory.h"

namespace
{
// The mapper with ReadHitBuffer public: per pixel the view-space normal and
// the view distance of the last render's hit, zeros on a miss.
class HitMapper : public vtkMetaballMapper
{
public:
  static HitMapper* New() { VTK_STANDARD_NEW_BODY(HitMapper); }
  vtkTypeMacro(HitMapper, vtkMetaballMapper);
  using vtkMetaballMapper::ReadHitBuffer;
};
} // namespace

#endif
