# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""The off-screen scene the rendering benchmarks share: one window and renderer
(no multisampling), actors swapped per run, images read back as numpy arrays and
frames timed to the end of the GPU's work. Each benchmark subclasses it for its
cameras."""
import statistics
import time

import numpy as np
import pointsurfaces  # noqa: F401  (the EGL window factory)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
from vtkmodules.vtkRenderingCore import vtkRenderer, vtkRenderWindow


def material(actor, colour, ambient=0.0, diffuse=1.0, specular=0.0):
    """Sets the actor's colour and lighting coefficients; returns the actor."""
    p = actor.GetProperty()
    p.SetColor(*colour)
    p.SetAmbient(ambient)
    p.SetDiffuse(diffuse)
    p.SetSpecular(specular)
    return actor


class OffscreenScene:
    """One off-screen window and renderer; actors are swapped, the size may change."""

    def __init__(self, size=(512, 512), background=(0.1, 0.1, 0.15)):
        self.size = tuple(size)
        self.window = vtkRenderWindow()
        self.window.SetMultiSamples(0)
        self.window.SetOffScreenRendering(1)
        self.window.SetSize(*self.size)
        self.renderer = vtkRenderer()
        self.renderer.SetBackground(*background)
        self.window.AddRenderer(self.renderer)

    def resize(self, size):
        if tuple(size) != self.size:
            self.size = tuple(size)
            self.window.SetSize(*self.size)

    def show(self, actor):
        self.renderer.RemoveAllViewProps()
        self.renderer.AddActor(actor)

    def pixels(self):
        """Renders; the RGB image as rows bottom-up, shape (height, width, 3), 0..1."""
        self.window.Render()
        w, h = self.size
        rgb = vtkUnsignedCharArray()
        self.window.GetPixelData(0, 0, w - 1, h - 1, 0, rgb, 0)
        return vtk_to_numpy(rgb).reshape(h, w, 3).astype(np.float64) / 255.0

    def timed_frames(self, frames, before=None):
        """Median wall-clock and process-CPU milliseconds of `frames` frames, each
        waited for (a depth read-back); `before` runs ahead of each frame (new data)."""
        wall, cpu = [], []
        for _ in range(frames):
            t0, c0 = time.perf_counter(), time.process_time()
            if before:
                before()
            self.window.Render()
            self.window.GetZbufferDataAtPoint(0, 0)
            wall.append(1000.0 * (time.perf_counter() - t0))
            cpu.append(1000.0 * (time.process_time() - c0))
        return statistics.median(wall), statistics.median(cpu)
