// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballMapper
 * @brief   Ray casts a metaball iso-surface of many dynamic particles on the GPU.
 *
 * After chapter 5 of N. K. R. Bolla, "High Quality Rendering of Large
 * Point-based Surfaces", M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
 *
 * The input is any vtkPointSet: each point is a ball with a support radius
 * R_i and an optional strength q_i, read by the rule of the mapper's
 * vtkMetaballField (GetField: the radius array or constant radius, the
 * radius scale, the strength array). The surface is
 * sum_i q_i f_i(|x - p_i| / R_i) = T for the field's kernel: Wyvill's
 * sixth-order polynomial ([Bolla 2010] eq. 1.4), the quartic
 * (1 - r^2/R^2)^2 (eq. 1.3), or a Gaussian truncated at R.
 *
 * Every frame, vtkMetaballGridBuilder rebuilds the perspective grid of the
 * balls in view on the GPU ([Bolla 2010] Algorithm 2); then a compute shader
 * casts the rays tile by tile (Algorithm 3, glsl/vtkMetaballRayCastCS.glsl): a work
 * group per tile walks its voxels front to back, skips empty ones, loads a
 * voxel's balls into shared memory, and marches with steps set by the field
 * value (never below StepScale times the voxel's smallest radius), then
 * bisects the crossing Bisections times. Normals are analytic; the colour is
 * the kernel-weighted mean of the balls' colours, which come from the usual
 * scalar colouring (lookup table, ScalarVisibility) or the actor's colour.
 * The hits are shaded with the renderer's lights (vtkOpenGLRenderer's
 * lighting uniforms: headlight, directional, positional and spot lights) and
 * the actor's material, and written into VTK's framebuffer with their true
 * depth.
 *
 * Only changed input is uploaded again (its modification time, the arrays
 * and the colouring are watched). Points with NaN or infinite values, or a
 * radius <= 0, are skipped and counted, with a warning.
 *
 * Selection (vtkHardwareSelector, and so ParaView's interactive selection)
 * picks balls: a hit pixel selects the ball that dominates the surface
 * there, the one whose term q_i K(|x - p_i|^2 / R_i^2) is the largest at the
 * pixel's surface point x (pointsurfaces::DominantBall). The ids are point
 * ids, with FIELD_ASSOCIATION_POINTS and FIELD_ASSOCIATION_CELLS alike: the
 * balls are the input's points, whatever cells it has. For a vtkPolyData
 * with one vertex cell per point, in point order (the usual point-cloud
 * layout), they are its cell ids too; for other cells they are not.
 *
 * Every pass of the selector draws the hits of one ray cast: the last
 * frame's when the view, the viewport, the balls and the settings have not
 * changed since (so its depths match the frame the point passes test
 * against), else a fresh one, without shadows. The dominant balls are found
 * on the CPU, once per cast and selection area, for the hit pixels of the
 * selector's area only: the balls that reach into the area's frustum are
 * binned into a perspective grid over the area (BuildPerspectiveGrid), and
 * each hit pixel's surface point (on its ray, at its view distance) is
 * tested against its voxel's balls. The pass's colour is written unlit,
 * unblended and exact, with the hit's depth, depth-tested against the other
 * props: the prop colour that the selector sets (GetPropColorValue: the prop
 * id in the actor pass, the ProcessID in the process pass, composite index
 * 1, as vtkOpenGLPolyDataMapper gives a plain data set, in the composite
 * pass, each plus one), and id + 1 split into its low and high 24 bits in
 * the id passes. A process id array (UseProcessIdFromData) is not read.
 * Normal rendering does no selection work.
 *
 * pointsurfaces::CastRay and BuildPerspectiveGrid (Filters/Core/Metaballs/psMetaball.h)
 * are the double-precision references the tests compare with.
 */
#ifndef vtkMetaballMapper_h
#define vtkMetaballMapper_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkMapper.h"
#include "vtkMetaballField.h" // For the field
#include "vtkSmartPointer.h"  // For the field

#include <memory> // For the implementation
#include <string> // For PointIdArrayName

class vtkFloatArray;
class vtkHardwareSelector;
class vtkMatrix4x4;
class vtkOpenGLRenderWindow;
class vtkPointSet;

namespace pointsurfaces
{
struct MetaballCastRequest;
struct MetaballCastStatistics;
}

class POINTSURFACESRENDERING_EXPORT vtkMetaballMapper : public vtkMapper
{
public:
  static vtkMetaballMapper* New();
  vtkTypeMacro(vtkMetaballMapper, vtkMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The metaball field: kernel, threshold T, radius array or constant
   * radius, radius scale and strength array (see vtkMetaballField). Set one
   * to share it with vtkMetaballGhostBalls, vtkMetaballLevelSetWriter or
   * vtkOpenVDBParticleMesher, so that they read the same balls; null
   * restores a field of its own. Default: a field of its own (Wyvill's
   * kernel, T = 0.5, radii by vtkMetaballField's rules: its radius array,
   * an array the readers write, or 1.5 times the mean point spacing).
   */
  void SetField(vtkMetaballField* field);
  vtkMetaballField* GetField() { return this->Field; }
  ///@}

  /** Also the field's and the lookup table's modification times. */
  vtkMTimeType GetMTime() override;

  ///@{
  /** Screen tile side of the grid, 8 or 16 pixels (one work group each). Default 16. */
  vtkSetClampMacro(TileSize, int, 8, 16);
  vtkGetMacro(TileSize, int);
  ///@}

  ///@{
  /** Depth slabs of the grid, placed over the balls in view. Default 16. */
  vtkSetClampMacro(Slabs, int, 1, 1024);
  vtkGetMacro(Slabs, int);
  ///@}

  ///@{
  /**
   * The smallest march step, as a fraction of the smallest radius in a voxel
   * ([Bolla 2010] uses 0.1). Smaller is slower and misses fewer thin features.
   */
  vtkSetClampMacro(StepScale, double, 1e-4, 10.0);
  vtkGetMacro(StepScale, double);
  ///@}

  ///@{
  /** Bisections of a crossing ([Bolla 2010]: 10). Default 10. */
  vtkSetClampMacro(Bisections, int, 0, 60);
  vtkGetMacro(Bisections, int);
  ///@}

  ///@{
  /**
   * Level of detail on the GPU ray caster: balls whose support radius covers
   * fewer than this many pixels on screen are merged, per frame, per cell of
   * that many pixels and the matching depth, into one ball each (their
   * centroid, second moments and kernel mass; vtkMetaballLevelOfDetail), so
   * that a cloud seen whole costs what its pixels cost. On a closed surface
   * the silhouette stays within a cell of the exact one and the depth within
   * a few cells' depth; 0 (the default) draws every ball exactly. The CPU ray
   * caster and the shadows draw every ball. Measured by
   * bench_metaball_lod.py.
   */
  vtkSetClampMacro(LevelOfDetailPixels, double, 0.0, 64.0);
  vtkGetMacro(LevelOfDetailPixels, double);
  ///@}

  ///@{
  /**
   * The last frame's merged balls and the balls they stand for (with
   * LevelOfDetailPixels; a frame or two late without CollectStatistics).
   */
  vtkGetMacro(NumberOfMergedBalls, vtkIdType);
  vtkGetMacro(NumberOfBallsMerged, vtkIdType);
  ///@}

  ///@{
  /**
   * The most memory the CPU ray caster may take for its copy of the balls
   * and its grid, in kibibytes; 0 (the default): the physical memory free
   * when the frame starts. A frame beyond it draws no balls and gives one
   * error naming both figures (the GPU caster is bounded by its buffers:
   * vtkShaderStorageBuffer::SetMaximumSizeLimit and the driver).
   */
  vtkSetClampMacro(MemoryLimit, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(MemoryLimit, vtkIdType);
  ///@}

  /** Where the rays are cast. */
  enum RayCasterType
  {
    AUTOMATIC = 0, ///< CPU on a software OpenGL (llvmpipe, softpipe, SWR), GPU otherwise
    GPU = 1,       ///< the compute shaders of [Bolla 2010] Algorithms 2 and 3
    CPU = 2,       ///< the native ray caster (pointsurfaces::CastMetaballs, vtkSMPTools)
  };

  ///@{
  /**
   * The ray caster: AUTOMATIC (the default) takes the CPU one where the
   * OpenGL renderer is a software one, where compute shaders are emulated
   * and run far slower than native code, and the GPU one elsewhere. Both
   * build the same perspective grid and march the same way, and write the
   * same images; shading, compositing and shadows are shared (shadows run
   * on the GPU path's shaders).
   */
  vtkSetClampMacro(RayCaster, int, AUTOMATIC, CPU);
  vtkGetMacro(RayCaster, int);
  void SetRayCasterToAutomatic() { this->SetRayCaster(AUTOMATIC); }
  void SetRayCasterToGPU() { this->SetRayCaster(GPU); }
  void SetRayCasterToCPU() { this->SetRayCaster(CPU); }
  ///@}

  /** The ray caster the last render used: GPU or CPU (AUTOMATIC before any). */
  vtkGetMacro(RayCasterInUse, int);

  ///@{
  /**
   * Where the ray caster's time went: rays cast, rays that hit, (ray, voxel)
   * visits and those with no ball's support on the ray (the GPU's: to voxels
   * with no ball), ray/support tests (CPU only), field samples of the march
   * and of the bisections, and kernel terms summed in them. The CPU ray
   * caster's are the last render's; the GPU's come with the other counters
   * (see CollectStatistics), in 32 bits, the kernel terms saturating.
   */
  vtkGetMacro(NumberOfRays, vtkIdType);
  vtkGetMacro(NumberOfHits, vtkIdType);
  vtkGetMacro(NumberOfVoxelVisits, vtkIdType);
  vtkGetMacro(NumberOfEmptyVoxelVisits, vtkIdType);
  vtkGetMacro(NumberOfSupportTests, vtkIdType);
  vtkGetMacro(NumberOfSamples, vtkIdType);
  vtkGetMacro(NumberOfBisectionSamples, vtkIdType);
  vtkGetMacro(NumberOfKernelTerms, vtkIdType);
  ///@}

  ///@{
  /**
   * Shadows from secondary rays toward the first four lights that are on,
   * tested against a perspective grid built from each light's point of view
   * every frame. Default off.
   */
  vtkSetMacro(Shadows, bool);
  vtkGetMacro(Shadows, bool);
  vtkBooleanMacro(Shadows, bool);
  ///@}

  ///@{
  /**
   * Wait for each frame's statistics and read them back as it is drawn:
   * the grid's culled balls and balls per voxel, and the ray casts'
   * counters (NumberOfPixelsStartingInside, NumberOfIncompleteRays). Off
   * (the default), nothing in a frame waits for the GPU to read them: the
   * grid statistics are not collected, and the counters are read a frame
   * or two late, once the GPU has passed them (their warnings come then).
   * Tests and benchmarks that check one frame's counters turn it on.
   */
  vtkSetMacro(CollectStatistics, bool);
  vtkGetMacro(CollectStatistics, bool);
  vtkBooleanMacro(CollectStatistics, bool);
  ///@}

  ///@{
  /**
   * Times in ms of the grid build, the primary rays, and the light grids
   * with the shadow rays. On the GPU ray caster, GPU times from timer
   * queries read without waiting: those of the last frame whose queries
   * have completed (usually the one before; 0 until one has). On the CPU
   * ray caster, the wall times of the last render's grid and rays.
   */
  vtkGetMacro(GridBuildTime, double);
  vtkGetMacro(RayCastTime, double);
  /** Wall time in ms of the last render's upload of the balls (0 when nothing changed). */
  vtkGetMacro(UploadTime, double);
  /**
   * Bytes the last upload wrote for the GPU: with the GPU ray caster the
   * input's arrays as they go (12 a ball for the positions, 4 for a radius
   * array, strength and colour each when there are some), with the CPU one
   * the host's float balls (16, 4 and 4).
   */
  vtkGetMacro(UploadedBytes, double);
  /**
   * Of UploadTime, the ms the GPU ray caster's upload spent writing the
   * arrays into GPU-visible memory (its one host copy); the rest is the
   * radius rule and the driver (the assembly pass's submission, which a
   * software renderer runs on the CPU). With the CPU ray caster, 0.
   */
  vtkGetMacro(UploadCopyTime, double);
  vtkGetMacro(ShadowTime, double);
  ///@}

  ///@{
  /**
   * The (voxel, ball) pairs the grid needed, the most balls in a voxel, the
   * culled and the invalid balls. With CollectStatistics, the last render's.
   * Without it, on the GPU ray caster, those of the latest grid build and
   * upload the GPU has finished (a frame or two late: nothing waits), and
   * the most balls in a voxel and the culled balls only with it on the CPU
   * one. Uploads: how often the balls went to the GPU.
   */
  vtkGetMacro(NumberOfPairs, vtkIdType);
  vtkGetMacro(MaximumBallsPerVoxel, vtkIdType);
  vtkGetMacro(NumberOfCulledBalls, vtkIdType);
  vtkGetMacro(NumberOfInvalidBalls, vtkIdType);
  vtkGetMacro(NumberOfUploads, int);
  ///@}

  /**
   * Read-backs that waited for the GPU in this mapper's frames so far: the
   * first build of each grid (the camera's and the light's), which sizes its
   * pair buffers, and with CollectStatistics every frame's grids and
   * counters. A frame at the defaults adds none: the slab range, the pair
   * count and the dispatch sizes stay on the GPU, and counters and
   * statistics arrive through fences a frame or two late.
   */
  vtkIdType GetNumberOfReadBacks();

  /**
   * Grid builds whose pairs outgrew the buffers sized from earlier frames
   * (a zoom far beyond the views so far): such a frame leaves some balls out
   * of the grid, and the buffers have room from the next frame on (see
   * vtkMetaballGridBuilder). With CollectStatistics a frame is built again
   * at once instead.
   */
  vtkIdType GetNumberOfGridOverflows();

  /**
   * Pixels whose rays start inside the surface, in the latest frame whose
   * counters were read (see CollectStatistics): the near clipping plane cuts
   * into it (the camera is inside a blob, or a ball crosses the near plane).
   * They show the surface from within; a warning says so when it first
   * happens.
   */
  vtkGetMacro(NumberOfPixelsStartingInside, vtkIdType);

  /**
   * Rays that stopped before finding the surface, in the latest frame whose
   * counters were read (see CollectStatistics), because
   * the GL driver's loop limit was near (llvmpipe ends the loops of a shader
   * invocation after 65535 iterations in all); a warning says so. Zero on
   * GPUs.
   */
  vtkGetMacro(NumberOfIncompleteRays, vtkIdType);

  ///@{
  /** The balls: any vtkPointSet (also through SetInputConnection). */
  void SetInputData(vtkPointSet* input);
  vtkPointSet* GetInput();
  ///@}

  /**
   * Draws the balls: uploads what changed, builds the grid, casts the rays
   * and shades the hits into the renderer's framebuffer.
   */
  void Render(vtkRenderer* ren, vtkActor* act) override;

  ///@{
  /** The balls' centres padded by the largest support radius (the input is updated first). */
  double* GetBounds() VTK_SIZEHINT(6) override;
  void GetBounds(double bounds[6]) override { this->Superclass::GetBounds(bounds); }
  ///@}

  void ReleaseGraphicsResources(vtkWindow* win) override;

  /**
   * Always 0: scalars are mapped to colours on the balls, one colour per
   * ball, whatever InterpolateScalarsBeforeMapping says (ParaView turns it
   * on for every display); the surface blends the mapped colours by the
   * balls' kernel weights.
   */
  int CanUseTextureMapForColoring(vtkDataObject* input) override;

  /** True: vtkHardwareSelector picks balls (point ids; see the class comment). */
  bool GetSupportsSelection() override { return true; }

  ///@{
  /**
   * Under a hardware selector, the id a ball reports: the value of this
   * integer point array of the input when it has it (ParaView's
   * "vtkOriginalPointIds", which maps the geometry it draws back to the
   * data set the user selects from), else the ball's point index. Default
   * empty: the point index.
   */
  vtkSetStdStringFromCharMacro(PointIdArrayName);
  vtkGetCharFromStdStringMacro(PointIdArrayName);
  ///@}

protected:
  vtkMetaballMapper();
  ~vtkMetaballMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void ComputeBounds();
  /** Brings the input up to date (unless Static). */
  void UpdateInput();
  /**
   * Takes one frame's counters: pixels starting inside, cut rays, cut shadow
   * rays, and the GPU ray caster's samples, bisection samples, voxel visits,
   * empty voxel visits, kernel terms and hits.
   */
  void ReportCounters(const unsigned int counters[9]);

  /**
   * The hits of the last render, one tuple per viewport pixel (rows from the
   * bottom): view-space unit normal and view distance, zeros on a miss. The
   * render window's context must be current. A hook for accuracy tests
   * (a subclass makes it public).
   */
  bool ReadHitBuffer(vtkFloatArray* hits);

  /** The balls to the GPU (and the host), when the input, the field or the colours changed. */
  bool Upload(vtkRenderer* ren, vtkActor* act, vtkPointSet* input);
  /** Is the context's OpenGL a software one (Mesa llvmpipe, softpipe, SWR)? */
  static bool IsSoftwareRenderer();
  /**
   * One pass of a hardware selection over the last cast's hits: each hit
   * pixel of the selector's area in the pass's colour, unlit, with its
   * depth. (x0, y0): the viewport's origin in the window.
   */
  void DrawSelection(vtkRenderer* ren,
    vtkActor* act,
    vtkHardwareSelector* selector,
    int x0,
    int y0);
  /**
   * The balls in double and in float on the host with colours `mapped` (the
   * CPU caster's and a selection's), warning about missing arrays and
   * invalid balls when `warn`.
   */
  void HostCopy(vtkActor* act, vtkPointSet* input, vtkUnsignedCharArray* mapped, bool warn);
  /** Takes an upload's count of invalid balls, with its warning. */
  void ReportInvalidBalls(vtkIdType invalid);
  /** Does this render use the CPU ray caster (RayCaster, or AUTOMATIC on a software renderer)? */
  bool UsesCPUCaster();
  /** The bounds of `input`'s finite points (uninitialised when it has none). */
  void FiniteBounds(vtkPointSet* input, double bounds[6]);
  /** The actor's largest axis scale, which the radii grow with. */
  static double ActorScale(vtkActor* act);

  vtkSmartPointer<vtkMetaballField> Field;
  int TileSize = 16;
  int Slabs = 16;
  double LevelOfDetailPixels = 0.0;
  vtkIdType NumberOfMergedBalls = 0;
  vtkIdType NumberOfBallsMerged = 0;
  double StepScale = 0.1;
  int Bisections = 10;
  vtkIdType MemoryLimit = 0;
  std::string LastCastError; // reported once while it lasts
  double GridBuildTime = 0.0;
  double RayCastTime = 0.0;
  double UploadTime = 0.0;
  vtkIdType NumberOfPairs = 0;
  vtkIdType MaximumBallsPerVoxel = 0;
  vtkIdType NumberOfCulledBalls = 0;
  vtkIdType NumberOfInvalidBalls = 0;
  int NumberOfUploads = 0;
  double UploadedBytes = 0.0;
  double UploadCopyTime = 0.0;
  vtkIdType NumberOfPixelsStartingInside = 0;
  vtkIdType NumberOfIncompleteRays = 0;
  bool Shadows = false;
  bool CollectStatistics = false;
  int RayCaster = AUTOMATIC;
  int RayCasterInUse = AUTOMATIC;
  vtkIdType NumberOfRays = 0;
  vtkIdType NumberOfHits = 0;
  vtkIdType NumberOfVoxelVisits = 0;
  vtkIdType NumberOfEmptyVoxelVisits = 0;
  vtkIdType NumberOfSupportTests = 0;
  vtkIdType NumberOfSamples = 0;
  vtkIdType NumberOfBisectionSamples = 0;
  vtkIdType NumberOfKernelTerms = 0;
  double ShadowTime = 0.0;

  std::string PointIdArrayName;

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;

  /** The view (into `model`: the float balls to world) and the settings of a cast. */
  void MakeRequest(vtkRenderer* ren,
    vtkActor* act,
    int width,
    int height,
    vtkMatrix4x4* model,
    pointsurfaces::MetaballCastRequest& request);
  /**
   * The primary rays on the chosen caster, then the shadows when `shadows`,
   * with the frame's counters around them. Returns the lights shadowed, -1
   * when nothing was cast.
   */
  int CastFrame(vtkRenderer* ren,
    vtkActor* act,
    vtkMatrix4x4* model,
    const pointsurfaces::MetaballCastRequest& request,
    bool shadows);
  /** A cast's host-side counts into the statistics; `march`: its march's too. */
  void TakeStatistics(const pointsurfaces::MetaballCastStatistics& stats, bool march);

  vtkMetaballMapper(const vtkMetaballMapper&) = delete;
  void operator=(const vtkMetaballMapper&) = delete;
};

#endif
