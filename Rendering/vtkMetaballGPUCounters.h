// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballGPUCounters
 * @brief   The metaball shaders' per-frame counters, read without stalling a frame.
 *
 * The ray casting and shadow shaders add to nine counters a frame (pixels
 * starting inside the surface, rays and shadow rays cut by the loop limit,
 * and the GPU ray caster's samples, bisection samples, voxel visits, empty
 * voxel visits, kernel terms and hits, as vtkMetaballRayCastCS.glsl lists
 * them). Reading a buffer right after the dispatch would wait for the GPU,
 * so the counters go round a ring of buffers: each frame adds into a fresh
 * one and fences it, and a later frame reads those whose fence the GPU has
 * passed. Read(wait = true) gives the current frame's at once, for
 * vtkMetaballMapper's CollectStatistics. vtkMetaballGridBuilder keeps its
 * per-build statistics (slab range, pair count, dispatch sizes) in a ring of
 * its own, of a larger size. Private to PointSurfaces::Rendering.
 */
#ifndef vtkMetaballGPUCounters_h
#define vtkMetaballGPUCounters_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkNew.h"                       // For the buffers
#include "vtkObject.h"

#include <functional> // For the report

class vtkShaderStorageBuffer;
class vtkWindow;

class POINTSURFACESRENDERING_EXPORT vtkMetaballGPUCounters : public vtkObject
{
public:
  static vtkMetaballGPUCounters* New();
  vtkTypeMacro(vtkMetaballGPUCounters, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** How many counters a frame has, by default. */
  static constexpr int Count = 9;
  /** What takes a frame's counters (GetSize() of them) once they are read. */
  using Report = std::function<void(const unsigned int* counters)>;

  ///@{
  /** How many counters a frame has (Count unless set; at most 64). Set before the first frame. */
  void SetSize(int size) { this->Size = size < 1 ? 1 : (size > MaxSize ? MaxSize : size); }
  int GetSize() const { return this->Size; }
  ///@}

  /**
   * Starts a frame: reports the counters of the earlier frames that the GPU
   * has finished (waiting only for the oldest when the GPU is a whole ring
   * behind), then clears this frame's buffer to `initial` (zeros when null).
   */
  void BeginFrame(const Report& report, const unsigned int* initial = nullptr);

  /** Reports the counters of the finished frames, never waiting. */
  void Poll(const Report& report);

  /**
   * How often BeginFrame() waited for the oldest frame because the GPU was
   * a whole ring behind (a read-back that stalls), since construction.
   */
  long long GetNumberOfWaits() const { return this->Waits; }

  /** This frame's buffer, for the shaders to add into (binding 5). */
  vtkShaderStorageBuffer* GetFrameBuffer();

  /**
   * Ends the frame: a barrier and a fence after the shaders that wrote it;
   * with `wait`, reports this frame's counters at once.
   */
  void EndFrame(const Report& report, bool wait);

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkMetaballGPUCounters();
  ~vtkMetaballGPUCounters() override;

private:
  // Frames in flight: the metaball mapper and a grid builder use one a
  // frame, a light's grid builder one per light (up to four a frame).
  static constexpr int Ring = 8;
  static constexpr int MaxSize = 64;
  bool ReadSlot(int slot, bool wait, unsigned int* out);

  int Size = Count;

  vtkNew<vtkShaderStorageBuffer> Buffers[Ring];
  void* Fences[Ring] = {}; // GLsync
  int Next = 0;
  long long Waits = 0;

  vtkMetaballGPUCounters(const vtkMetaballGPUCounters&) = delete;
  void operator=(const vtkMetaballGPUCounters&) = delete;
};

#endif
