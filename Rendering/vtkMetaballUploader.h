// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballUploader
 * @brief   Sends a frame's balls to the GPU with one host copy: float arrays as they are.
 *
 * A time series changes every ball every frame, so the upload is on the
 * per-frame path. Extracting the balls in double and repacking them as
 * float vec4 on the host (what the CPU ray caster needs) costs two passes
 * over the data before the driver's copy; here the arrays go to the GPU as
 * the input holds them and a compute pass (glsl/vtkMetaballAssembleCS.glsl)
 * builds the vec4 balls:
 *
 * - positions: a vtkFloatArray is copied as it is (the shift is subtracted
 *   on the GPU, in float, as the host did); other types are converted to
 *   float relative to the shift, in parallel, in one pass;
 * - radii: one radius as a uniform, or the radius array's first component
 *   (copied as it is from a one-component vtkFloatArray, else converted);
 * - strengths (strength and density arrays, SPH normalisation): computed in
 *   parallel into float, only when the rule weights the balls;
 * - colours: the mapped rgba8 colours byte for byte, or one colour.
 *
 * Each array is written straight into a streamed storage buffer
 * (vtkShaderStorageBuffer::MapForWrite: mapped with its old contents
 * invalidated), by all threads, so that the copy does not wait for the GPU
 * to finish the previous frame that still reads the old storage. Invalid
 * balls are counted on the GPU and read back through a fence a frame or
 * two later (at once when asked to wait). Private to vtkMetaballMapper.
 */
#ifndef vtkMetaballUploader_h
#define vtkMetaballUploader_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkNew.h"                       // For the members
#include "vtkObject.h"

#include "psBallExtraction.h" // For the rule
#include "psMetaballFrame.h"  // For the balls

#include <functional> // For the report

class vtkComputeShaderProgram;
class vtkMetaballGPUCounters;
class vtkOpenGLRenderWindow;
class vtkPointSet;
class vtkShaderStorageBuffer;
class vtkUnsignedCharArray;
class vtkWindow;

class POINTSURFACESRENDERING_EXPORT vtkMetaballUploader : public vtkObject
{
public:
  static vtkMetaballUploader* New();
  vtkTypeMacro(vtkMetaballUploader, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** What takes an upload's count of invalid balls once it is read. */
  using Report = std::function<void(vtkIdType invalid)>;

  /**
   * Uploads the balls of `input` under `rule` and `source` (radii times
   * `scale`) relative to balls.Shift, with colours `mapped` (rgba8, one per
   * point) or `plain` for all, into balls.Balls, Colors and Strengths; sets
   * balls.Count, HasStrengths, ColorPerBall and MinRadius. The invalid balls
   * of finished uploads go to `report` (this one's too, at once, with
   * `wait`). The context of `renWin` must be current.
   */
  bool Upload(vtkOpenGLRenderWindow* renWin,
    vtkPointSet* input,
    const pointsurfaces::BallRule& rule,
    const pointsurfaces::RadiusSource& source,
    double scale,
    vtkUnsignedCharArray* mapped,
    unsigned int plain,
    bool wait,
    const Report& report,
    pointsurfaces::MetaballBalls& balls);

  /**
   * Reports the invalid balls of finished uploads without waiting and
   * without uploading: a mapper whose data does not change calls it each
   * render, so that the first upload's count and warning still arrive.
   */
  void Poll(const Report& report);

  /** Bytes the last Upload() wrote for the GPU (its one host copy). */
  vtkGetMacro(UploadedBytes, double);

  /**
   * Wall time in ms of the last Upload()'s writes into the mapped buffers
   * (the host's one copy), without the assembly pass's submission.
   */
  vtkGetMacro(CopyTime, double);

  /** Whether the last Upload() used the positions as the input holds them (float). */
  vtkGetMacro(PositionsAsIs, bool);

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkMetaballUploader();
  ~vtkMetaballUploader() override;

  double UploadedBytes = 0.0;
  double CopyTime = 0.0;
  bool PositionsAsIs = false;

private:
  vtkNew<vtkShaderStorageBuffer> Positions, Radii;
  vtkNew<vtkComputeShaderProgram> Assemble;
  vtkNew<vtkMetaballGPUCounters> Invalid;

  vtkMetaballUploader(const vtkMetaballUploader&) = delete;
  void operator=(const vtkMetaballUploader&) = delete;
};

#endif
