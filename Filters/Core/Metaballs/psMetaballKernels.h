// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psMetaballKernels.h
 * @brief The metaball and SPH kernels, each defined once.
 *
 * One struct per kernel, templated on the scalar, holds everything the code
 * knows about it: its value and d/dx as functions of x = r^2 / R^2 (R the
 * support radius; 1 at x = 0, 0 from x = 1), the largest |dK/dq| for q = r / R
 * (the Lipschitz bound of the sphere tracers), the SPH normalisation N (the
 * integral over space of N / R^3 K(|x|^2 / R^2) is 1; 0 for the metaball
 * falloffs, which are not normalised) and SWIFT's ratio of support radius to
 * smoothing length. It is the role VTK's vtkSPHKernel subclasses play for
 * vtkSPHInterpolator, without the virtual call in the innermost loop.
 *
 * The double instances are the reference (psMetaball's KernelValue and
 * friends dispatch to them); the float instances are the CPU ray caster's;
 * Rendering/glsl/vtkMetaballKernel.glsl writes the same formulas in GLSL, with
 * the slope bound injected from here, and TestMetaballKernelGLSL evaluates the
 * shader against the float instances at many radii for every kernel. The
 * numpy peer of the benchmarks is Testing/Benchmarks/metaball_kernels.py,
 * checked against these by TestMetaballKernels.
 *
 * Adding a kernel: a struct here, a line in VisitMetaballKernel, a branch in
 * the GLSL and the numpy module, and a name in vtkMetaballField::Kernels.
 *
 * Formulas, with q = sqrt(x), u = 1 - q (Dehnen and Aly 2012 for the SPH ones):
 * - Wyvill: -4/9 x^3 + 17/9 x^2 - 22/9 x + 1 (thesis eq. 1.4);
 * - Quartic: (1 - x)^2 (thesis eq. 1.3);
 * - Gaussian: (exp(-4 x) - exp(-4)) / (1 - exp(-4)), a Gaussian cut to 0 at R;
 * - CubicSpline (M4, Gadget's convention: support R = h): 1 - 6 q^2 + 6 q^3
 *   below q = 1/2, 2 u^3 above; N = 8 / pi;
 * - WendlandC2: u^4 (1 + 4 q); N = 21 / (2 pi);
 * - WendlandC4: u^6 (1 + 6 q + 35/3 q^2); N = 495 / (32 pi).
 *
 * The order of every floating-point operation is part of the definition: the
 * value-only and the value-and-slope forms give the same bits, which the
 * caster's branch-free sums rely on.
 */
#ifndef psMetaballKernels_h
#define psMetaballKernels_h

#include <cmath>

namespace pointsurfaces
{
/**
 * The kernels. MetaballKernel::Wyvill and so on, as a scoped enum would be
 * written; unscoped inside a struct so that vtkMetaballField::Kernels can take
 * its values by name (VTK's wrappers parse no casts in enum values), which
 * keeps the numbers in one place.
 */
struct MetaballKernelEnum
{
  enum Id : int
  {
    Wyvill = 0,      ///< -4/9 x^3 + 17/9 x^2 - 22/9 x + 1 (eq. 1.4)
    Quartic = 1,     ///< (1 - x)^2 (eq. 1.3)
    Gaussian = 2,    ///< (exp(-4 x) - exp(-4)) / (1 - exp(-4)): a Gaussian cut to zero at R
    CubicSpline = 3, ///< SPH M4 cubic spline (Gadget's convention: support R = h)
    WendlandC2 = 4,  ///< SPH Wendland C2
    WendlandC4 = 5,  ///< SPH Wendland C4
  };
};
using MetaballKernel = MetaballKernelEnum::Id;

/** Every kernel, in MetaballKernel's order. */
constexpr MetaballKernel AllMetaballKernels[] = { MetaballKernel::Wyvill,
  MetaballKernel::Quartic,
  MetaballKernel::Gaussian,
  MetaballKernel::CubicSpline,
  MetaballKernel::WendlandC2,
  MetaballKernel::WendlandC4 };

/** How many kernels MetaballKernel names. */
constexpr int NumberOfMetaballKernels = sizeof(AllMetaballKernels) / sizeof(MetaballKernel);

namespace kernels
{
/** Wyvill's sixth-order polynomial in r (thesis eq. 1.4). */
template<typename Real>
struct Wyvill
{
  static constexpr MetaballKernel Id = MetaballKernel::Wyvill;
  static constexpr const char* Name = "wyvill";
  static constexpr Real SlopeBound = Real(1.5835); // max of |2 q K'(q^2)|
  static constexpr double Normalization = 0.0;
  static constexpr double SWIFTSupport = 1.0;
  static Real Value(Real x)
  {
    return ((Real(-4) / Real(9) * x + Real(17) / Real(9)) * x - Real(22) / Real(9)) * x + Real(1);
  }
  static Real Value(Real x, Real& slope)
  {
    slope = (Real(-4) / Real(3) * x + Real(34) / Real(9)) * x - Real(22) / Real(9);
    return Value(x);
  }
};

/** (1 - x)^2 (thesis eq. 1.3). */
template<typename Real>
struct Quartic
{
  static constexpr MetaballKernel Id = MetaballKernel::Quartic;
  static constexpr const char* Name = "quartic";
  static constexpr Real SlopeBound = Real(1.5397); // max of 4 q (1 - q^2)
  static constexpr double Normalization = 0.0;
  static constexpr double SWIFTSupport = 1.0;
  static Real Value(Real x) { return (Real(1) - x) * (Real(1) - x); }
  static Real Value(Real x, Real& slope)
  {
    slope = Real(-2) * (Real(1) - x);
    return Value(x);
  }
};

/** A Gaussian of sharpness 4, shifted and scaled to 1 at x = 0 and 0 at x = 1. */
template<typename Real>
struct Gaussian
{
  static constexpr MetaballKernel Id = MetaballKernel::Gaussian;
  static constexpr const char* Name = "gaussian";
  static constexpr Real SlopeBound = Real(1.7476); // max of 8 q exp(-4 q^2) / (1 - exp(-4))
  static constexpr double Normalization = 0.0;
  static constexpr double SWIFTSupport = 1.0;
  static constexpr Real Sharpness = Real(4);
  static constexpr Real Floor = Real(0.018315638888734179); // exp(-4)
  static Real Value(Real x) { return (std::exp(-Sharpness * x) - Floor) / (Real(1) - Floor); }
  static Real Value(Real x, Real& slope)
  {
    const Real e = std::exp(-Sharpness * x);
    slope = -Sharpness * e / (Real(1) - Floor);
    return (e - Floor) / (Real(1) - Floor);
  }
};

/** The SPH M4 cubic spline, Gadget's convention (support radius = h). */
template<typename Real>
struct CubicSpline
{
  static constexpr MetaballKernel Id = MetaballKernel::CubicSpline;
  static constexpr const char* Name = "cubic_spline";
  static constexpr Real SlopeBound = Real(2); // at q = 1/3
  static constexpr double Normalization = 8.0 / 3.14159265358979323846;
  static constexpr double SWIFTSupport = 1.825742; // SWIFT's kernel_gamma
  static Real Value(Real x)
  {
    const Real q = std::sqrt(x), u = Real(1) - q;
    return q < Real(0.5) ? Real(1) - Real(6) * x + Real(6) * x * q : Real(2) * u * u * u;
  }
  static Real Value(Real x, Real& slope)
  {
    const Real q = std::sqrt(x);
    if (q < Real(0.5))
    {
      slope = Real(-6) + Real(9) * q; // d/dx of 1 - 6 x + 6 x^(3/2)
      return Real(1) - Real(6) * x + Real(6) * x * q;
    }
    const Real u = Real(1) - q;
    slope = Real(-3) * u * u / q; // d/dx of 2 (1 - q)^3
    return Real(2) * u * u * u;
  }
};

/** The SPH Wendland C2 kernel. */
template<typename Real>
struct WendlandC2
{
  static constexpr MetaballKernel Id = MetaballKernel::WendlandC2;
  static constexpr const char* Name = "wendland_c2";
  static constexpr Real SlopeBound = Real(2.109375); // at q = 1/4
  static constexpr double Normalization = 21.0 / (2.0 * 3.14159265358979323846);
  static constexpr double SWIFTSupport = 1.936492;
  static Real Value(Real x)
  {
    const Real q = std::sqrt(x), u = Real(1) - q;
    return u * u * u * u * (Real(1) + Real(4) * q);
  }
  static Real Value(Real x, Real& slope)
  {
    const Real q = std::sqrt(x), u = Real(1) - q;
    slope = Real(-10) * u * u * u; // dK/dq = -20 q u^3, dq/dx = 1 / (2 q)
    return u * u * u * u * (Real(1) + Real(4) * q);
  }
};

/** The SPH Wendland C4 kernel. */
template<typename Real>
struct WendlandC4
{
  static constexpr MetaballKernel Id = MetaballKernel::WendlandC4;
  static constexpr const char* Name = "wendland_c4";
  static constexpr Real SlopeBound = Real(2.5); // 2.49979 near q = 0.2356
  static constexpr double Normalization = 495.0 / (32.0 * 3.14159265358979323846);
  static constexpr double SWIFTSupport = 2.207940;
  static Real Value(Real x)
  {
    const Real q = std::sqrt(x), u = Real(1) - q, u5 = u * u * u * u * u;
    return u5 * u * (Real(1) + Real(6) * q + Real(35) / Real(3) * x);
  }
  static Real Value(Real x, Real& slope)
  {
    const Real q = std::sqrt(x), u = Real(1) - q, u5 = u * u * u * u * u;
    slope = Real(-28) / Real(3) * (Real(1) + Real(5) * q) * u5; // dK/dq = -56/3 q (1 + 5 q) u^5
    return u5 * u * (Real(1) + Real(6) * q + Real(35) / Real(3) * x);
  }
};
} // namespace kernels

/**
 * Calls `visit(K{})` with K the kernel's struct in scalar Real and returns
 * what it returns: one switch for every place that needs a kernel's formulas
 * inlined (an unknown value gives Wyvill, the default).
 */
template<typename Real, typename Visitor>
decltype(auto) VisitMetaballKernel(MetaballKernel kernel, Visitor&& visit)
{
  switch (kernel)
  {
    case MetaballKernel::Quartic:
      return visit(kernels::Quartic<Real>{});
    case MetaballKernel::Gaussian:
      return visit(kernels::Gaussian<Real>{});
    case MetaballKernel::CubicSpline:
      return visit(kernels::CubicSpline<Real>{});
    case MetaballKernel::WendlandC2:
      return visit(kernels::WendlandC2<Real>{});
    case MetaballKernel::WendlandC4:
      return visit(kernels::WendlandC4<Real>{});
    case MetaballKernel::Wyvill:
    default:
      return visit(kernels::Wyvill<Real>{});
  }
}

/**
 * The kernel's snake-case name ("wyvill", ..., "wendland_c4"): the name files
 * store (vtkMetaballLevelSetWriter's metadata) and messages print.
 */
inline const char* MetaballKernelName(MetaballKernel kernel)
{
  return VisitMetaballKernel<double>(kernel, [](auto k) { return k.Name; });
}
} // namespace pointsurfaces

#endif
