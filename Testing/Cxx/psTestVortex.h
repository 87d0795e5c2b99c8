// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psTestVortex.h
 * @brief The particle vortex the metaball time-series tests step (test support).
 *
 * Particles start spread over the cylinder r <= 1, |z| <= 1; each step swirls
 * them around the z axis, pulls them in and lets them fall, and a particle
 * that falls below z = -1 comes back at the top (z = 1) at a random radius.
 * New positions every frame, a steady state after a few dozen steps: the
 * load of a dynamic particle simulation, the same from any test that draws
 * from the same generator. Examples/Python/particle_animation.py steps the
 * same vortex in numpy.
 */
#ifndef psTestVortex_h
#define psTestVortex_h

#include <cmath>  // For cos, sin, sqrt
#include <random> // For the uniform distribution
#include <vector> // For the positions

namespace pointsurfaces
{
template<class Generator>
class TestVortex
{
public:
  /** `n` particles seeded from `gen`, which the vortex keeps drawing from. */
  TestVortex(int n, Generator& gen)
    : Gen(gen)
    , Xyz(3 * static_cast<std::size_t>(n))
  {
    for (int i = 0; i < n; ++i)
    {
      this->Seed(i, false);
    }
  }

  /** One step of 0.04 time units: swirl, pull in, fall; re-seed at the top. */
  void Step()
  {
    for (int i = 0; i < this->Size(); ++i)
    {
      double* p = &this->Xyz[3 * static_cast<std::size_t>(i)];
      const double r2 = p[0] * p[0] + p[1] * p[1] + 0.05;
      const double v[3] = { -p[1] / r2 - 0.3 * p[0], p[0] / r2 - 0.3 * p[1], -1.2 };
      for (int k = 0; k < 3; ++k)
      {
        p[k] += 0.04 * v[k];
      }
      if (p[2] < -1.0)
      {
        this->Seed(i, true);
      }
    }
  }

  int Size() const { return static_cast<int>(this->Xyz.size() / 3); }
  /** x y z of particle `i`. */
  const double* Position(int i) const { return &this->Xyz[3 * static_cast<std::size_t>(i)]; }

private:
  void Seed(int i, bool top)
  {
    const double r = std::sqrt(0.04 + 0.96 * this->Unit(this->Gen));
    const double a = 6.283185307179586 * this->Unit(this->Gen);
    double* p = &this->Xyz[3 * static_cast<std::size_t>(i)];
    p[0] = r * std::cos(a);
    p[1] = r * std::sin(a);
    p[2] = top ? 1.0 : 2.0 * this->Unit(this->Gen) - 1.0;
  }

  Generator& Gen;
  std::uniform_real_distribution<double> Unit{ 0.0, 1.0 };
  std::vector<double> Xyz;
};
} // namespace pointsurfaces

#endif
