// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkMetaballGPUCounters.h"

#include "vtkObjectFactory.h"
#include "vtkShaderStorageBuffer.h"

vtkStandardNewMacro(vtkMetaballGPUCounters);

//------------------------------------------------------------------------------
vtkMetaballGPUCounters::vtkMetaballGPUCounters() = default;

//------------------------------------------------------------------------------
vtkMetaballGPUCounters::~vtkMetaballGPUCounters() = default;

//------------------------------------------------------------------------------
bool vtkMetaballGPUCounters::ReadSlot(int slot, bool wait, unsigned int* out)
{
  GLsync fence = static_cast<GLsync>(this->Fences[slot]);
  if (!fence)
  {
    return false;
  }
  const GLenum status =
    glClientWaitSync(fence, wait ? GL_SYNC_FLUSH_COMMANDS_BIT : 0, wait ? 10000000000ull : 0);
  if (status != GL_ALREADY_SIGNALED && status != GL_CONDITION_SATISFIED)
  {
    return false;
  }
  glDeleteSync(fence);
  this->Fences[slot] = nullptr;
  return this->Buffers[slot]->Download(out, this->Size * sizeof(unsigned int));
}

//------------------------------------------------------------------------------
void vtkMetaballGPUCounters::BeginFrame(const Report& report, const unsigned int* initial)
{
  unsigned int counters[MaxSize] = {};
  for (int k = 0; k < Ring; ++k)
  {
    const int slot = (this->Next + k) % Ring; // oldest first: the one to reuse
    GLsync fence = static_cast<GLsync>(this->Fences[slot]);
    if (k == 0 && fence && glClientWaitSync(fence, 0, 0) == GL_TIMEOUT_EXPIRED)
    {
      ++this->Waits; // the GPU is a whole ring behind: this one waits
    }
    if (this->ReadSlot(slot, k == 0, counters))
    {
      report(counters);
    }
  }
  const unsigned int zeros[MaxSize] = {};
  this->Buffers[this->Next]->Upload(initial ? initial : zeros, this->Size * sizeof(unsigned int));
}

//------------------------------------------------------------------------------
void vtkMetaballGPUCounters::Poll(const Report& report)
{
  unsigned int counters[MaxSize] = {};
  for (int k = 0; k < Ring; ++k)
  {
    if (this->ReadSlot((this->Next + k) % Ring, false, counters))
    {
      report(counters);
    }
  }
}

//------------------------------------------------------------------------------
vtkShaderStorageBuffer* vtkMetaballGPUCounters::GetFrameBuffer()
{
  return this->Buffers[this->Next];
}

//------------------------------------------------------------------------------
void vtkMetaballGPUCounters::EndFrame(const Report& report, bool wait)
{
  // glGetBufferSubData reads what the shaders wrote once this barrier passed.
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  if (this->Fences[this->Next])
  {
    // Its wait timed out: that frame's counters are lost.
    glDeleteSync(static_cast<GLsync>(this->Fences[this->Next]));
  }
  this->Fences[this->Next] = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  unsigned int counters[MaxSize] = {};
  if (wait && this->ReadSlot(this->Next, true, counters))
  {
    report(counters);
  }
  this->Next = (this->Next + 1) % Ring;
}

//------------------------------------------------------------------------------
void vtkMetaballGPUCounters::ReleaseGraphicsResources(vtkWindow* win)
{
  for (int k = 0; k < Ring; ++k)
  {
    this->Buffers[k]->ReleaseGraphicsResources(win);
    if (this->Fences[k])
    {
      glDeleteSync(static_cast<GLsync>(this->Fences[k]));
      this->Fences[k] = nullptr;
    }
  }
}

//------------------------------------------------------------------------------
void vtkMetaballGPUCounters::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Ring: " << Ring << " buffers, next " << this->Next << "\n";
}
