// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkComputeShaderProgram
 * @brief   A GL compute program that can be dispatched inside a VTK render.
 *
 * VTK 9.1's vtkShader has no compute type, so the metaball grid build and
 * other GPU passes compile their `.glsl` compute shaders (`#version 430` or
 * later) through this small helper instead:
 *
 * - Compile() builds the program in the current context of a
 *   vtkOpenGLRenderWindow. Compiler and linker messages are reported through
 *   vtkErrorMacro with the program's name and the offending source lines,
 *   numbered as the driver numbers them.
 * - Bind() tells VTK's shader cache to forget its current program
 *   (vtkOpenGLShaderCache::ReleaseCurrentShader) before glUseProgram, and
 *   Unbind() leaves no program bound, so VTK's cache never goes stale and the
 *   mappers drawn after a dispatch render as usual.
 * - Dispatch() runs the kernel and issues the memory barrier that the
 *   following reads need.
 *
 * The owner calls ReleaseGraphicsResources() from its own
 * ReleaseGraphicsResources(), as VTK's mappers do for vtkOpenGLHelper.
 * Storage buffers come from vtkShaderStorageBuffer.
 */
#ifndef vtkComputeShaderProgram_h
#define vtkComputeShaderProgram_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <cstddef> // For size_t
#include <map>     // For uniform locations
#include <string>  // For source and name

class vtkOpenGLRenderWindow;
class vtkWindow;

class POINTSURFACESRENDERING_EXPORT vtkComputeShaderProgram : public vtkObject
{
public:
  static vtkComputeShaderProgram* New();
  vtkTypeMacro(vtkComputeShaderProgram, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The GLSL source (usually a string encoded from a `.glsl` file at build
   * time) and a name used in messages. Changing the source forces a recompile.
   */
  void SetSource(const std::string& source);
  const std::string& GetSource() const { return this->Source; }
  vtkSetStdStringFromCharMacro(Name);
  vtkGetCharFromStdStringMacro(Name);
  ///@}

  /**
   * Compile and link in the current context of `renWin` (compiled once per
   * source and context). Returns false, after a vtkErrorMacro with numbered
   * source lines, when the driver rejects the program.
   */
  bool Compile(vtkOpenGLRenderWindow* renWin);

  /** True once Compile() succeeded. */
  bool IsCompiled() const { return this->Handle != 0; }

  /** The compiler and linker log of the last Compile(). */
  const std::string& GetLastLog() const { return this->LastLog; }

  /** Make the program current, after releasing VTK's cached shader. */
  void Bind(vtkOpenGLRenderWindow* renWin);

  /** Leave no program bound (VTK's cache already considers none bound). */
  void Unbind();

  ///@{
  /** Set uniforms of the bound program. Unknown names are ignored. */
  void SetUniformi(const char* name, int v);
  void SetUniformui(const char* name, unsigned int v);
  void SetUniformf(const char* name, float v);
  void SetUniform2i(const char* name, int v0, int v1);
  void SetUniform2f(const char* name, float v0, float v1);
  void SetUniform3f(const char* name, const float v[3]);
  void SetUniform4f(const char* name, const float v[4]);
  /** A 4x4 matrix given row-major, as vtkMatrix4x4 stores it. */
  void SetUniformMatrix4x4(const char* name, const float rowMajor[16]);
  ///@}

  ///@{
  /**
   * glDispatchCompute(x, y, z) on the bound program, then glMemoryBarrier with
   * `barrierBits` (default: shader storage, buffer update and command bits).
   * Returns false for group counts beyond GL_MAX_COMPUTE_WORK_GROUP_COUNT.
   */
  bool Dispatch(unsigned int x, unsigned int y = 1, unsigned int z = 1);
  bool Dispatch(unsigned int x, unsigned int y, unsigned int z, unsigned int barrierBits);
  ///@}

  /**
   * glDispatchComputeIndirect: the work group counts are three uints that
   * an earlier pass wrote into the GL buffer `buffer` at byte `offset` (a
   * multiple of 4), so no size is read back; the counts must respect
   * GL_MAX_COMPUTE_WORK_GROUP_COUNT. Then glMemoryBarrier(barrierBits).
   */
  void DispatchIndirect(unsigned int buffer,
    size_t offset,
    unsigned int barrierBits = 0x2000 | 0x200 | 0x40); // storage, buffer update, command

  /**
   * For a source of several passes: unless compiled already, compiles
   * `source` with its pass hook (the Pass::Dec line of the VTK hooks,
   * psShaderHooks.h) replaced by a definition of PASS as `pass`, named
   * after `name` and the pass; then binds the program. False, with an
   * error, when the hook is missing or the compile fails.
   */
  bool ReadyPass(vtkOpenGLRenderWindow* renWin, const char* name, const char* source, int pass);

  /** Number of groups needed to cover `items` with groups of `groupSize`. */
  static unsigned int GroupCount(size_t items, unsigned int groupSize);

  /** GL_MAX_COMPUTE_WORK_GROUP_COUNT in x of the current context. */
  static int GetMaxWorkGroupCount(vtkOpenGLRenderWindow* renWin);

  /** Delete the GL program. The context of `win` must be current. */
  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkComputeShaderProgram();
  ~vtkComputeShaderProgram() override;

  int GetUniformLocation(const char* name);
  std::string NumberedExcerpt(const std::string& log) const;

  std::string Source;
  std::string Name = "compute";
  std::string LastLog;
  unsigned int Handle = 0;
  bool SourceChanged = false;
  std::map<std::string, int> UniformLocations;

private:
  vtkComputeShaderProgram(const vtkComputeShaderProgram&) = delete;
  void operator=(const vtkComputeShaderProgram&) = delete;
};

#endif
