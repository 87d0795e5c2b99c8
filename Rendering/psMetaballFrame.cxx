// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psMetaballFrame.h"

#include "vtkMath.h"
#include "vtkProperty.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"

#include "psMetaball.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace pointsurfaces
{
//------------------------------------------------------------------------------
vtkIdType MetaballBalls::Convert(const MetaballSet& set)
{
  const vtkIdType n = set.Count;
  const bool strengths = set.Strengths != nullptr;
  std::vector<float>& balls = this->HostBalls;
  std::vector<float>& q = this->HostStrengths;
  balls.resize(4 * n);
  q.assign(strengths ? n : 1, 1.0f);
  std::atomic<vtkIdType> invalidCount(0);
  struct Smallest
  {
    double Value = std::numeric_limits<double>::max();
  };
  vtkSMPThreadLocal<Smallest> smallest;
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      vtkIdType bad = 0;
      double& least = smallest.Local().Value;
      for (vtkIdType i = begin; i < end; ++i)
      {
        const double r = set.Radii[i];
        for (int k = 0; k < 3; ++k)
        {
          balls[4 * i + k] = static_cast<float>(set.Centers[3 * i + k] - this->Shift[k]);
        }
        balls[4 * i + 3] = static_cast<float>(r);
        if (strengths)
        {
          q[i] = static_cast<float>(set.Strengths[i]);
        }
        // Usable as psMetaball's ValidBall says, with a strength that
        // stays finite in float.
        if (!ValidBall(set, i) || (strengths && !std::isfinite(q[i])))
        {
          balls[4 * i + 3] = 0.0f;
          ++bad;
        }
        else
        {
          least = std::min(least, r);
        }
      }
      invalidCount += bad;
    });
  const vtkIdType invalid = invalidCount;
  double minRadius = std::numeric_limits<double>::max();
  for (const Smallest& s : smallest)
  {
    minRadius = std::min(minRadius, s.Value);
  }
  this->MinRadius = invalid < n ? minRadius : 1.0;
  return invalid;
}

//------------------------------------------------------------------------------
unsigned int PlainColor(vtkProperty* prop)
{
  double* diffuse = prop->GetDiffuseColor();
  return static_cast<unsigned int>(vtkMath::Round(255 * diffuse[0])) |
    (static_cast<unsigned int>(vtkMath::Round(255 * diffuse[1])) << 8) |
    (static_cast<unsigned int>(vtkMath::Round(255 * diffuse[2])) << 16) | (255u << 24);
}

//------------------------------------------------------------------------------
void MetaballBalls::ConvertColors(vtkUnsignedCharArray* mapped, vtkProperty* prop, vtkIdType n)
{
  std::vector<unsigned int>& colors = this->HostColors;
  colors.resize(std::max<vtkIdType>(n, 1));
  const unsigned char* rgba =
    mapped && mapped->GetNumberOfComponents() == 4 ? mapped->GetPointer(0) : nullptr;
  const unsigned int plain = PlainColor(prop);
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        const unsigned char* c = rgba ? rgba + 4 * i : nullptr;
        colors[i] =
          c ? c[0] | (c[1] << 8) | (c[2] << 16) | (static_cast<unsigned int>(c[3]) << 24) : plain;
      }
    });
}
} // namespace pointsurfaces
