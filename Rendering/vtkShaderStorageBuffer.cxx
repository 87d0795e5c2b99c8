// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkShaderStorageBuffer.h"

#include "vtkObjectFactory.h"

#include <algorithm>
#include <atomic>

vtkStandardNewMacro(vtkShaderStorageBuffer);

//------------------------------------------------------------------------------
vtkShaderStorageBuffer::vtkShaderStorageBuffer() = default;

//------------------------------------------------------------------------------
vtkShaderStorageBuffer::~vtkShaderStorageBuffer()
{
  if (this->Handle)
  {
    vtkWarningMacro(<< "Storage buffer destroyed without ReleaseGraphicsResources(): " << this->Size
                    << " bytes of GPU memory leak.");
  }
}

//------------------------------------------------------------------------------
namespace
{
std::atomic<size_t> SizeLimit{ 0 };
}

size_t vtkShaderStorageBuffer::GetMaximumSize()
{
  GLint64 size = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &size);
  const size_t limit = SizeLimit.load();
  return limit > 0 ? std::min(limit, static_cast<size_t>(size)) : static_cast<size_t>(size);
}

//------------------------------------------------------------------------------
void vtkShaderStorageBuffer::SetMaximumSizeLimit(size_t bytes)
{
  SizeLimit.store(bytes);
}

//------------------------------------------------------------------------------
size_t vtkShaderStorageBuffer::GetMaximumSizeLimit()
{
  return SizeLimit.load();
}

//------------------------------------------------------------------------------
bool vtkShaderStorageBuffer::Allocate(size_t bytes)
{
  if (this->Handle && bytes <= this->Size)
  {
    return true;
  }
  const size_t limit = GetMaximumSize();
  if (bytes > limit)
  {
    vtkErrorMacro(<< "A storage buffer of " << bytes << " bytes exceeds this context's limit of "
                  << limit << " bytes (GL_MAX_SHADER_STORAGE_BLOCK_SIZE): process in chunks.");
    return false;
  }
  if (!this->Handle)
  {
    glGenBuffers(1, &this->Handle);
  }
  while (glGetError() != GL_NO_ERROR)
  {
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, this->Handle);
  glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_DRAW);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  if (glGetError() == GL_OUT_OF_MEMORY)
  {
    vtkErrorMacro(<< "Out of GPU memory for a storage buffer of " << bytes << " bytes.");
    this->Size = 0;
    return false;
  }
  this->Size = bytes;
  return true;
}

//------------------------------------------------------------------------------
bool vtkShaderStorageBuffer::Upload(const void* data, size_t bytes)
{
  if (!this->Allocate(bytes))
  {
    return false;
  }
  if (bytes)
  {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, this->Handle);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(bytes), data);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  }
  return true;
}

//------------------------------------------------------------------------------
void* vtkShaderStorageBuffer::MapForWrite(size_t bytes)
{
  if (!this->Allocate(std::max<size_t>(bytes, 4)))
  {
    return nullptr;
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, this->Handle);
  void* data = glMapBufferRange(GL_SHADER_STORAGE_BUFFER,
    0,
    static_cast<GLsizeiptr>(std::max<size_t>(bytes, 4)),
    GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  if (!data)
  {
    vtkErrorMacro(<< "Cannot map " << bytes << " bytes of a storage buffer for writing.");
  }
  return data;
}

//------------------------------------------------------------------------------
bool vtkShaderStorageBuffer::Unmap()
{
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, this->Handle);
  const GLboolean intact = glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  if (!intact)
  {
    vtkErrorMacro(<< "A mapped storage buffer was lost (the display changed): upload it again.");
  }
  return intact == GL_TRUE;
}

//------------------------------------------------------------------------------
bool vtkShaderStorageBuffer::Download(void* data, size_t bytes, size_t offset) const
{
  if (!this->Handle || offset + bytes > this->Size)
  {
    vtkErrorMacro(<< "Cannot read " << bytes << " bytes at offset " << offset
                  << " from a storage buffer of " << this->Size << " bytes.");
    return false;
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, this->Handle);
  glGetBufferSubData(
    GL_SHADER_STORAGE_BUFFER, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  return true;
}

//------------------------------------------------------------------------------
void vtkShaderStorageBuffer::Fill(unsigned int value, size_t bytes)
{
  if (!this->Handle)
  {
    return;
  }
  const size_t n = (bytes == 0 || bytes > this->Size) ? this->Size : bytes;
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, this->Handle);
  glClearBufferSubData(GL_SHADER_STORAGE_BUFFER,
    GL_R32UI,
    0,
    static_cast<GLsizeiptr>(n & ~size_t(3)),
    GL_RED_INTEGER,
    GL_UNSIGNED_INT,
    &value);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
}

//------------------------------------------------------------------------------
void vtkShaderStorageBuffer::BindBase(unsigned int index) const
{
  BindHandle(this->Handle, index);
}

//------------------------------------------------------------------------------
void vtkShaderStorageBuffer::BindHandle(unsigned int handle, unsigned int index)
{
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, index, handle);
}

//------------------------------------------------------------------------------
void vtkShaderStorageBuffer::ReleaseGraphicsResources(vtkWindow*)
{
  if (this->Handle)
  {
    glDeleteBuffers(1, &this->Handle);
    this->Handle = 0;
    this->Size = 0;
  }
}

//------------------------------------------------------------------------------
void vtkShaderStorageBuffer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Size << "\n";
}
