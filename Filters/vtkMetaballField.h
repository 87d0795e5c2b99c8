// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballField
 * @brief   The metaball field of a point set: kernel, iso-value, and how radii and strengths are read.
 *
 * One description of the field f(x) = sum_i q_i K(|x - p_i|^2 / R_i^2) = T
 * that vtkMetaballMapper draws, vtkMetaballLevelSetWriter writes,
 * vtkOpenVDBParticleMesher meshes and vtkMetaballGhostBalls exchanges
 * between processes. Each of them holds one (GetField), and they can share
 * one (SetField), as vtkPointInterpolator shares its kernel: a change to the
 * shared field reaches all of them, and they agree ball for ball.
 *
 * Each point is a ball with support radius R_i = RadiusScale times the first
 * component of the RadiusArrayName point array when the input has it, or
 * RadiusScale times the constant Radius otherwise, and strength q_i from
 * the StrengthArrayName point array (1 when none is named). Balls with a
 * NaN or infinite centre, radius or strength, or a radius <= 0, are not
 * part of the field. The kernels are Wyvill's sixth-order polynomial, the
 * quartic (1 - r^2/R^2)^2 and a Gaussian truncated at R (psMetaball.h).
 * pointsurfaces::ExtractBalls (psBallExtraction.h) applies this rule.
 */
#ifndef vtkMetaballField_h
#define vtkMetaballField_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // For Assign

#include <string> // For array names

#ifndef __VTK_WRAP__
#include "psBallExtraction.h" // For the rule
#endif

class vtkPointSet;

class POINTSURFACESFILTERS_EXPORT vtkMetaballField : public vtkObject
{
public:
  static vtkMetaballField* New();
  vtkTypeMacro(vtkMetaballField, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Kernels
  {
    Wyvill = 0,
    Quartic = 1,
    Gaussian = 2,
    CubicSpline = 3, ///< SPH M4 spline, Gadget's convention (support radius = h)
    WendlandC2 = 4,  ///< SPH Wendland C2
    WendlandC4 = 5   ///< SPH Wendland C4
  };

  ///@{
  /**
   * The field's kernel. Default Wyvill. The SPH kernels (CubicSpline,
   * WendlandC2, WendlandC4) are normalised by each ball's support radius
   * (pointsurfaces::KernelNormalization): with masses as strengths the field
   * is the SPH density, and the threshold is in density units; with
   * masses as strengths and densities as DensityArrayName, it is the SPH
   * interpolant of 1 (about 1 inside the fluid: T = 0.5 is its surface).
   * Gadget's smoothing length is the support radius (RadiusScale 1);
   * SWIFT's is not: set RadiusScale to
   * pointsurfaces::SWIFTSupportFactor(kernel) (1.825742 for the cubic spline).
   */
  vtkSetClampMacro(Kernel, int, Wyvill, WendlandC4);
  vtkGetMacro(Kernel, int);
  ///@}

  ///@{
  /** The iso-value T. Default 0.5. */
  vtkSetMacro(Threshold, double);
  vtkGetMacro(Threshold, double);
  ///@}

  ///@{
  /** Point array of support radii; when the input lacks it, Radius applies. Default "Radius". */
  vtkSetStdStringFromCharMacro(RadiusArrayName);
  vtkGetCharFromStdStringMacro(RadiusArrayName);
  ///@}

  ///@{
  /** The support radius of every ball when the input has no radius array. Default 1. */
  vtkSetMacro(Radius, double);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /**
   * Multiplies every radius, from the array or constant. With Wyvill's kernel
   * and T = 0.5 a lone ball's surface lies at half its support radius, so 2
   * turns van der Waals radii into spheres of those radii. Default 1.
   */
  vtkSetClampMacro(RadiusScale, double, 0.0, 1e30);
  vtkGetMacro(RadiusScale, double);
  ///@}

  ///@{
  /** Point array of strengths q_i; empty (the default): all 1. */
  vtkSetStdStringFromCharMacro(StrengthArrayName);
  vtkGetCharFromStdStringMacro(StrengthArrayName);
  ///@}

  ///@{
  /**
   * Point array that divides the strengths (SPH's rho_i, for weights
   * m_i / rho_i); empty (the default): none. A zero density makes the ball
   * invalid (skipped and counted).
   */
  vtkSetStdStringFromCharMacro(DensityArrayName);
  vtkGetCharFromStdStringMacro(DensityArrayName);
  ///@}

  /** Copy every setting of `other` (none when it is null). */
  void DeepCopy(vtkMetaballField* other);

  /**
   * The largest support radius of `input`'s balls (the radius array's
   * largest value, or the constant, times RadiusScale), for padding bounds;
   * 0 when it is not finite.
   */
  double GetLargestRadius(vtkPointSet* input);

#ifndef __VTK_WRAP__
  /**
   * For the classes that hold a field: put `field` in `slot` (a new default
   * field when null), and mark `owner` modified when it changed.
   */
  static void Assign(vtkSmartPointer<vtkMetaballField>& slot,
    vtkMetaballField* field,
    vtkObject* owner);

  /** The settings as the plain rule of psBallExtraction.h. */
  pointsurfaces::BallRule GetRule() const;

  /** The balls of `input` (radii times `scale` on top of the rule). */
  pointsurfaces::BallArrays ExtractBalls(vtkPointSet* input, double scale = 1.0) const;
  /** The same into `out`, keeping its storage (for every frame of a series). */
  void ExtractBalls(vtkPointSet* input, double scale, pointsurfaces::BallArrays& out) const;
#endif

protected:
  vtkMetaballField() = default;
  ~vtkMetaballField() override = default;

  int Kernel = Wyvill;
  double Threshold = 0.5;
  std::string RadiusArrayName = "Radius";
  double Radius = 1.0;
  double RadiusScale = 1.0;
  std::string StrengthArrayName;
  std::string DensityArrayName;

private:
  vtkMetaballField(const vtkMetaballField&) = delete;
  void operator=(const vtkMetaballField&) = delete;
};

#endif
