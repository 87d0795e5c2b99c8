// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkShaderStorageBuffer
 * @brief   A GL shader storage buffer for compute passes: allocate, upload, clear, read back.
 *
 * vtkOpenGLBufferObject knows vertex, index and texture buffers but not
 * shader storage buffers, and it cannot read data back. The metaball grid
 * build keeps its counters, prefix sums and (voxel, ball) pairs in buffers of
 * this class, and tests read them back to compare with the CPU reference.
 * Existing VTK buffers (vtkOpenGLVertexBufferObject::GetHandle()) can be bound
 * to a storage binding point with BindHandle() without a copy.
 *
 * Every call needs the owning context to be current. The owner calls
 * ReleaseGraphicsResources() from its own ReleaseGraphicsResources().
 */
#ifndef vtkShaderStorageBuffer_h
#define vtkShaderStorageBuffer_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <cstddef> // For size_t

class vtkWindow;

class POINTSURFACESRENDERING_EXPORT vtkShaderStorageBuffer : public vtkObject
{
public:
  static vtkShaderStorageBuffer* New();
  vtkTypeMacro(vtkShaderStorageBuffer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Make the buffer at least `bytes` long. Contents are undefined after a
   * growth. Returns false (with an error) beyond GL_MAX_SHADER_STORAGE_BLOCK_SIZE
   * or when the driver is out of memory.
   */
  bool Allocate(size_t bytes);

  /** Allocate and copy `bytes` from `data`. */
  bool Upload(const void* data, size_t bytes);

  ///@{
  /**
   * Streaming: MapForWrite() makes the buffer at least `bytes` long and maps
   * its first `bytes` for writing with its old contents invalidated
   * (glMapBufferRange with GL_MAP_INVALIDATE_BUFFER_BIT), so that the writes
   * need not wait for the GPU to finish the commands that read the old
   * contents: the driver gives fresh storage (buffer orphaning). Any thread
   * may write into the pointer; Unmap() from the context's thread before
   * the buffer is used. Null (with an error) when it cannot be mapped.
   */
  void* MapForWrite(size_t bytes);
  bool Unmap();
  ///@}

  /** Copy `bytes` from the buffer at `offset` into `data`. */
  bool Download(void* data, size_t bytes, size_t offset = 0) const;

  /** Fill the first `bytes` (all when 0) with a 32-bit value. */
  void Fill(unsigned int value, size_t bytes = 0);

  /** Bind to a `layout(std430, binding = index)` block. */
  void BindBase(unsigned int index) const;

  /** Bind any GL buffer name (for example a VTK VBO) to a storage binding point. */
  static void BindHandle(unsigned int handle, unsigned int index);

  /**
   * The largest storage block allowed, in bytes: the current context's
   * GL_MAX_SHADER_STORAGE_BLOCK_SIZE, or the limit set below when smaller.
   */
  static size_t GetMaximumSize();

  ///@{
  /**
   * Caps every storage buffer at `bytes` (0, the default: no cap beyond the
   * driver's), process-wide. Tests use it to reach the size limits without
   * gigabytes of data; an application can use it to leave GPU memory to
   * others.
   */
  static void SetMaximumSizeLimit(size_t bytes);
  static size_t GetMaximumSizeLimit();
  ///@}

  /** The GL buffer name (0 before the first upload). */
  unsigned int GetHandle() const { return this->Handle; }
  /** The buffer's size in bytes. */
  size_t GetSize() const { return this->Size; }

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkShaderStorageBuffer();
  ~vtkShaderStorageBuffer() override;

  unsigned int Handle = 0;
  size_t Size = 0;

private:
  vtkShaderStorageBuffer(const vtkShaderStorageBuffer&) = delete;
  void operator=(const vtkShaderStorageBuffer&) = delete;
};

#endif
