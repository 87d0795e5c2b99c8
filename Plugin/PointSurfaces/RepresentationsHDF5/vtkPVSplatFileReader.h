// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPVSplatFileReader
 * @brief   The splat file reader as ParaView's GUI polls it: a live source while Streaming Splats load.
 *
 * vtkSplatFileReader for ParaView's Splat File Reader proxy, whose
 * `LiveSource` hint makes the GUI call GetNeedsUpdate every 100 ms (and
 * render its views again when it says true). Streaming Splats read the
 * file's pages on a thread; in the GUI's own process its Qt interactor
 * renders again as they arrive, but on a server (client-server) no event
 * loop does. GetNeedsUpdate says whether pages arrived there since the
 * last render (vtkSplatFileDelegatingMapper::PollLoading), so the GUI's
 * picture sharpens as on a workstation; and once polled, the server's
 * renders stop waiting for pages (BatchWait), so interaction never waits on
 * the disk. pvpython and pvbatch never poll: their renders wait, and their
 * pictures are whole.
 */
#ifndef vtkPVSplatFileReader_h
#define vtkPVSplatFileReader_h

#include "PointSurfacesParaViewRepresentationsHDF5Module.h" // For export macro
#include "vtkSplatFileReader.h"

class POINTSURFACESPARAVIEWREPRESENTATIONSHDF5_EXPORT vtkPVSplatFileReader
  : public vtkSplatFileReader
{
public:
  static vtkPVSplatFileReader* New();
  vtkTypeMacro(vtkPVSplatFileReader, vtkSplatFileReader);

  /** For ParaView's live-source poll: vtkSplatFileDelegatingMapper::PollLoading(). */
  bool GetNeedsUpdate();

protected:
  vtkPVSplatFileReader() = default;
  ~vtkPVSplatFileReader() override = default;

private:
  vtkPVSplatFileReader(const vtkPVSplatFileReader&) = delete;
  void operator=(const vtkPVSplatFileReader&) = delete;
};

#endif
