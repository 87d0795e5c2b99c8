// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballGridBuilder
 * @brief   Builds the metaball perspective grid on the GPU every frame ([Bolla 2010] Algorithm 2).
 *
 * Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
 * M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
 *
 * The view frustum is cut into screen tiles (TileSize pixels square) times
 * depth slabs (Slabs planes spaced uniformly in view distance, between the
 * nearest and farthest ball in view unless SlabRange fixes them). Each voxel
 * lists the balls whose support sphere reaches into it. The build runs in GL
 * compute shaders (glsl/vtkMetaballGridCS.glsl): frustum culling and a count
 * of voxels per ball, an exclusive scan (Blelloch, multi-level), a scatter
 * of (voxel, ball) pairs (each ball's voxels found again rather than stored:
 * 4 bytes a ball in all) with a histogram of pairs per voxel, a scan of the
 * histogram into voxel offsets, and a counting sort of the ball ids by voxel.
 * The ray caster reads VoxelOffsets and VoxelBalls; within a voxel the order
 * of the ids is not fixed.
 *
 * pointsurfaces::BuildPerspectiveGrid (Filters/Core/Metaballs/psMetaball.h) is the
 * double-precision CPU reference that the tests compare with.
 *
 * Balls come as one vec4 per ball (centre, support radius R) in an SSBO, in
 * the coordinates that WorldToView expects; balls with NaN or infinite
 * values, or R <= 0, are skipped and counted.
 *
 * Nothing is read back inside a build. The slab range, the pair count and
 * the work group counts of the pair pass stay on the GPU, in the
 * statistics buffer (GetGridStatistics(), which the ray casters bind to
 * read the slab range), and the pair pass is dispatched indirectly. The
 * pair buffers have a capacity that the builder sets from the pair counts
 * of earlier builds, read through fences once the GPU has passed them
 * (never waiting): it grows to 1.5 times the count whenever a count comes
 * within three quarters of it. A build that needs more pairs than the
 * capacity leaves the rest out and is counted in NumberOfOverflows when its
 * count arrives; the next builds have room. Only the first build, which has
 * no earlier count, reads its pair count back before it sorts, and
 * CollectStatistics reads every build's statistics back and builds again at
 * once after an overflow, so that a frame with statistics is always whole.
 * Pairs beyond one shader storage buffer are left out with a warning that
 * names the count.
 */
#ifndef vtkMetaballGridBuilder_h
#define vtkMetaballGridBuilder_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For the implementation
#include <vector> // For the slab planes

class vtkOpenGLRenderWindow;
class vtkShaderStorageBuffer;
class vtkWindow;

class POINTSURFACESRENDERING_EXPORT vtkMetaballGridBuilder : public vtkObject
{
public:
  static vtkMetaballGridBuilder* New();
  vtkTypeMacro(vtkMetaballGridBuilder, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Tile side in pixels. Default 16. */
  vtkSetClampMacro(TileSize, int, 1, 1024);
  vtkGetMacro(TileSize, int);
  ///@}

  ///@{
  /** Depth slabs. Default 16. */
  vtkSetClampMacro(Slabs, int, 1, 4096);
  vtkGetMacro(Slabs, int);
  ///@}

  ///@{
  /**
   * The first and last slab plane, as view distances. When the second is not
   * larger than the first (the default), they follow the balls in view.
   */
  vtkSetVector2Macro(SlabRange, double);
  vtkGetVector2Macro(SlabRange, double);
  ///@}

  /**
   * Builds the grid for `count` balls of `balls` seen through `worldToView`
   * and `viewToClip` (row-major 4x4, column vectors, OpenGL clip space) in a
   * `width` x `height` viewport. The context of `renWin` must be current.
   */
  bool Build(vtkOpenGLRenderWindow* renWin,
    vtkShaderStorageBuffer* balls,
    vtkIdType count,
    const double worldToView[16],
    const double viewToClip[16],
    bool parallel,
    int width,
    int height);

  ///@{
  /**
   * The grid of the last Build(). GetSlabPlane() reads the slab range back
   * from the GPU the first time it is called after a build without
   * statistics (a read-back outside the frame, for tests and tools; the ray
   * casters read the range from GetGridStatistics() instead).
   */
  int GetTilesX() const { return this->TilesX; }
  int GetTilesY() const { return this->TilesY; }
  int GetNumberOfSlabPlanes() const { return this->Slabs + 1; }
  double GetSlabPlane(int k);
  vtkShaderStorageBuffer* GetVoxelOffsets(); // voxels + 1 uints
  vtkShaderStorageBuffer* GetVoxelBalls();   // pairs uints
  /**
   * The last build's statistics, 16 uints (vtkMetaballGridCS.glsl lists
   * them): [5] and [6] are the slab range as float bits.
   */
  vtkShaderStorageBuffer* GetGridStatistics();
  ///@}

  /**
   * An exclusive prefix sum of the first `n` uints of `values`, in place,
   * by the build's scan passes (saturating at 2^32 - 1); for other GPU
   * passes of the mapper (vtkMetaballLevelOfDetail). The context of
   * `renWin` must be current.
   */
  bool ExclusiveScan(vtkOpenGLRenderWindow* renWin, vtkShaderStorageBuffer* values, size_t n);

  ///@{
  /**
   * The pairs that the pair buffers hold (0 before the first build); the
   * builder sizes it as the class comment says. Set it before a build to
   * reserve room for a view that will need more (it never shrinks but with
   * ReleaseGraphicsResources()).
   */
  vtkIdType GetPairCapacity() const { return this->PairCapacity; }
  void ReservePairs(vtkIdType pairs);
  ///@}

  /**
   * Builds so far that needed more pairs than the capacity of their time,
   * known once their counts arrive (with CollectStatistics at once, and
   * built again).
   */
  vtkGetMacro(NumberOfOverflows, vtkIdType);

  /**
   * Read-backs that waited for the GPU since the builder was made: the
   * first build's pair count, each build's statistics with
   * CollectStatistics, and the slab range of GetSlabPlane(). A frame at
   * the defaults adds none after the first.
   */
  vtkGetMacro(NumberOfReadBacks, vtkIdType);

  ///@{
  /**
   * Read the grid's statistics back after each Build() (pairs, culled and
   * invalid balls, the most balls in a voxel), which waits for the GPU to
   * finish the build. Off (the default): nothing waits, and the statistics
   * are those of the latest build that the GPU has finished.
   */
  vtkSetMacro(CollectStatistics, bool);
  vtkGetMacro(CollectStatistics, bool);
  vtkBooleanMacro(CollectStatistics, bool);
  ///@}

  ///@{
  /** Statistics of the last Build() with CollectStatistics, else of the latest finished one. */
  vtkGetMacro(NumberOfPairs, vtkIdType);
  vtkGetMacro(MaximumBallsPerVoxel, vtkIdType);
  vtkGetMacro(NumberOfCulledBalls, vtkIdType);
  vtkGetMacro(NumberOfInvalidBalls, vtkIdType);
  ///@}

  /**
   * The GPU time of the last build whose timer queries have completed, in
   * ms (GL_TIMESTAMP queries, read without waiting: usually the previous
   * build's; 0 until one has completed).
   */
  double GetBuildTime();

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkMetaballGridBuilder();
  ~vtkMetaballGridBuilder() override;

  int TileSize = 16;
  int Slabs = 16;
  double SlabRange[2] = { 0.0, 0.0 };
  int TilesX = 0;
  int TilesY = 0;
  std::vector<double> SlabPlanes; // valid when SlabPlanesKnown
  bool SlabPlanesKnown = false;
  float TakenRange[2] = { 0.0f, 0.0f }; // the slab range of the latest statistics read
  vtkIdType PairCapacity = 0;
  vtkIdType NumberOfOverflows = 0;
  vtkIdType NumberOfReadBacks = 0;
  vtkIdType NumberOfPairs = 0;
  vtkIdType MaximumBallsPerVoxel = 0;
  vtkIdType NumberOfCulledBalls = 0;
  vtkIdType NumberOfInvalidBalls = 0;
  bool CollectStatistics = false;
  double BuildTime = 0.0;

private:
  void SetSlabPlanes(double nearD, double farD);
  void Take(const unsigned int* stats);

  struct Internals;
  std::unique_ptr<Internals> Impl;

  vtkMetaballGridBuilder(const vtkMetaballGridBuilder&) = delete;
  void operator=(const vtkMetaballGridBuilder&) = delete;
};

#endif
