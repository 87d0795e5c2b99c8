// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// The metaball kernels of vtkMetaballMapper's ray casting and shadow shaders,
// inserted into each after its defines (KERNEL is pointsurfaces::MetaballKernel;
// psMetaballKernels.h is the table these formulas copy, in the same order of
// operations, and TestMetaballKernelGLSL checks them against it):
//
// 0 Wyvill's sixth-order polynomial, 1 the quartic (1 - x)^2, 2 a truncated
// Gaussian, 3 the SPH cubic spline (M4), 4 Wendland C2, 5 Wendland C4; the
// SPH kernels' normalisation N / R^3 is in the balls' strengths.

// Kernel K(x), x = r^2 / R^2 (peak 1 at x = 0, 0 from x = 1), and dK/dx.
float psKernel(float x, out float slope)
{
  slope = 0.0;
  if (x >= 1.0)
  {
    return 0.0;
  }
  x = max(x, 0.0);
#if KERNEL == 1
  slope = -2.0 * (1.0 - x);
  return (1.0 - x) * (1.0 - x);
#elif KERNEL == 2
  const float floorValue = 0.018315639; // exp(-4)
  float e = exp(-4.0 * x);
  slope = -4.0 * e / (1.0 - floorValue);
  return (e - floorValue) / (1.0 - floorValue);
#elif KERNEL == 3
  float q = sqrt(x);
  if (q < 0.5)
  {
    slope = -6.0 + 9.0 * q;
    return 1.0 - 6.0 * x + 6.0 * x * q;
  }
  float u = 1.0 - q;
  slope = -3.0 * u * u / q;
  return 2.0 * u * u * u;
#elif KERNEL == 4
  float q = sqrt(x);
  float u = 1.0 - q;
  slope = -10.0 * u * u * u;
  return u * u * u * u * (1.0 + 4.0 * q);
#elif KERNEL == 5
  float q = sqrt(x);
  float u = 1.0 - q;
  float u5 = u * u * u * u * u;
  slope = -28.0 / 3.0 * (1.0 + 5.0 * q) * u5;
  return u5 * u * (1.0 + 6.0 * q + 35.0 / 3.0 * x);
#else
  slope = (-4.0 / 3.0 * x + 34.0 / 9.0) * x - 22.0 / 9.0;
  return ((-4.0 / 9.0 * x + 17.0 / 9.0) * x - 22.0 / 9.0) * x + 1.0;
#endif
}

// The largest |dK/dq| of a kernel of unit support, q = r / R: bounds
// |grad f| by sum |q_i| times this over R_i. KERNEL_SLOPE_BOUND is the kernel
// table's (psMetaballKernels.h), defined with KERNEL by psMetaballShaderKernel.h.
float psKernelSlopeBound()
{
  return KERNEL_SLOPE_BOUND;
}
