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
 * Each point is a ball with support radius R_i = RadiusScale times a radius
 * chosen by the first rule that applies (psBallExtraction.h):
 * 1. the first component of the point array RadiusArrayName, when it is
 *    named and the input has it;
 * 2. the constant Radius, when it is positive;
 * 3. the first point array the readers write radii in that the input has:
 *    "Radius", "radius" (vtkPDBReader, vtkAtomRadii, the GROMACS readers,
 *    LAMMPS dumps), "SmoothingLength" (Gadget), "SmoothingLengths" (SWIFT),
 *    "pscale" (OpenVDB points), or half of "diameter" (LAMMPS dumps);
 * 4. 1.5 times the mean nearest-neighbour spacing of the points
 *    (pointsurfaces::SpacingRadiusFactor, which says why 1.5), measured once
 *    for points that have not changed; split across processes,
 *    vtkMetaballGhostBalls measures it over all of them and passes it on in
 *    the field data, so that every process uses the same;
 * 5. 1, when there is nothing to measure (fewer than two distinct points).
 * The strength q_i comes from the StrengthArrayName point array (1 when
 * none is named). Balls with a NaN or infinite centre, radius or strength,
 * or a radius <= 0, are not part of the field. The kernels are Wyvill's
 * sixth-order polynomial, the quartic (1 - r^2/R^2)^2 and a Gaussian
 * truncated at R (psMetaball.h). pointsurfaces::ExtractBalls
 * (psBallExtraction.h) applies this rule.
 *
 * The automatic rules (3 to 5) are told once, as text (vtkOutputWindow's
 * DisplayText, not a warning), each time their outcome changes: another
 * array, another rule, or an automatic radius more than 10 % from the one
 * last told; a named array that the input lacks is warned about the same
 * way. GetRadiusRule, GetChosenRadiusArrayName, GetMeanSpacing and
 * GetRadiusRuleDescription tell the outcome for the last input read.
 */
#ifndef vtkMetaballField_h
#define vtkMetaballField_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // For Assign

#include <string> // For array names

#include "psMetaballKernels.h" // For MetaballKernel, the Kernels values

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

  /**
   * The kernels (SetKernel): metaball falloffs and SPH kernels. The values
   * are pointsurfaces::MetaballKernel's (psMetaballKernels.h, where each
   * kernel's formulas live); this enum gives them to the wrappers.
   */
  enum Kernels
  {
    Wyvill = pointsurfaces::MetaballKernel::Wyvill,
    Quartic = pointsurfaces::MetaballKernel::Quartic,
    Gaussian = pointsurfaces::MetaballKernel::Gaussian,
    /** SPH M4 spline, Gadget's convention (support radius = h) */
    CubicSpline = pointsurfaces::MetaballKernel::CubicSpline,
    WendlandC2 = pointsurfaces::MetaballKernel::WendlandC2, ///< SPH Wendland C2
    WendlandC4 = pointsurfaces::MetaballKernel::WendlandC4  ///< SPH Wendland C4
  };

  ///@{
  /**
   * A kernel (a Kernels value) and its d/dx at x = r^2 / R^2, with peak 1
   * (pointsurfaces::KernelValue; 0 from x = 1): for scripts that plot the
   * kernels or check a copy of them against this definition.
   */
  static double EvaluateKernel(int kernel, double x);
  static double EvaluateKernelDerivative(int kernel, double x);
  ///@}

  /** The kernel as the GL-free code's enum. */
  pointsurfaces::MetaballKernel GetKernelId() const
  {
    return static_cast<pointsurfaces::MetaballKernel>(this->Kernel);
  }

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
  /**
   * Point array of support radii (its first component); it wins over every
   * other rule when the input has it. Empty (the default): the rules after
   * it choose (Radius, then an array the readers write, then the spacing).
   */
  vtkSetStdStringFromCharMacro(RadiusArrayName);
  vtkGetCharFromStdStringMacro(RadiusArrayName);
  ///@}

  ///@{
  /**
   * The support radius of every ball when it is positive and RadiusArrayName
   * names no array the input has. 0 (the default): automatic, from an array
   * the readers write or else 1.5 times the mean nearest-neighbour spacing.
   */
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

  /** The rules of the radii, in the order they apply (see the class comment). */
  enum RadiusRules
  {
    NamedRadiusArray = 0, ///< RadiusArrayName
    ConstantRadius = 1,   ///< Radius
    FoundRadiusArray = 2, ///< the first array the readers write radii in
    SpacingRadius = 3,    ///< 1.5 times the mean nearest-neighbour spacing
    UnitRadius = 4        ///< 1: nothing to measure
  };

  ///@{
  /**
   * The outcome for the last input whose radii were read (ExtractBalls,
   * GetLargestRadius or vtkMetaballGhostBalls): the rule (a RadiusRules
   * value; -1 before any input), the array it reads ("" when none), the
   * mean nearest-neighbour spacing (SpacingRadius; 0 otherwise), and the
   * sentence that tells it (as the message does).
   */
  vtkGetMacro(RadiusRule, int);
  const char* GetChosenRadiusArrayName() { return this->ChosenRadiusArrayName.c_str(); }
  vtkGetMacro(MeanSpacing, double);
  const char* GetRadiusRuleDescription() { return this->RadiusRuleDescription.c_str(); }
  ///@}

  /** The automatic radius in mean nearest-neighbour spacings (1.5). */
  static double GetSpacingRadiusFactor();

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

  /**
   * How `input`'s radii are found (pointsurfaces::ChooseRadii), the spacing
   * measured when the rule needs it and the input carries none: once for
   * the same points (the same vtkPoints, unmodified), so that a mapper that
   * reads its balls on every upload does not measure them again. Reported
   * (ReportRadii) when the input has points.
   */
  pointsurfaces::RadiusSource ChooseRadii(vtkPointSet* input);

  /**
   * Keep `choice` for the getters, and tell it when it is automatic and
   * differs from the last one told (see the class comment); a named array
   * that is missing is a warning. For vtkMetaballGhostBalls, which chooses
   * radii over all processes.
   */
  void ReportRadii(const pointsurfaces::RadiusChoice& choice);

  /** The balls of `input` (radii times `scale` on top of the rule), by ChooseRadii. */
  pointsurfaces::BallArrays ExtractBalls(vtkPointSet* input, double scale = 1.0);
  /** The same into `out`, keeping its storage (for every frame of a series). */
  void ExtractBalls(vtkPointSet* input, double scale, pointsurfaces::BallArrays& out);
#endif

protected:
  vtkMetaballField() = default;
  ~vtkMetaballField() override = default;

  int Kernel = Wyvill;
  double Threshold = 0.5;
  std::string RadiusArrayName;
  double Radius = 0.0;
  double RadiusScale = 1.0;
  std::string StrengthArrayName;
  std::string DensityArrayName;

  // The outcome of the last choice of radii (not settings: no Modified()).
  int RadiusRule = -1;
  std::string ChosenRadiusArrayName;
  double MeanSpacing = 0.0;
  std::string RadiusRuleDescription;
  // The outcome last told: rule, array and missing array; and its radius.
  std::string ToldOutcome;
  double ToldRadius = 0.0;
  // The spacing last measured, and the points it was measured on: their
  // address (compared, never followed) and modification time. A vtkPoints
  // made later at the same address has a later time.
  const void* MeasuredPoints = nullptr;
  vtkMTimeType MeasuredTime = 0;
  double MeasuredSpacing = 0.0;

private:
  vtkMetaballField(const vtkMetaballField&) = delete;
  void operator=(const vtkMetaballField&) = delete;
};

#endif
