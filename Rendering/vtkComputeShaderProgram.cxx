// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkComputeShaderProgram.h"

#include "psShaderHooks.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"

#include <algorithm>
#include <cstring>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkComputeShaderProgram);

//------------------------------------------------------------------------------
vtkComputeShaderProgram::vtkComputeShaderProgram() = default;

//------------------------------------------------------------------------------
vtkComputeShaderProgram::~vtkComputeShaderProgram()
{
  if (this->Handle)
  {
    vtkWarningMacro(<< "Program '" << this->Name
                    << "' destroyed without ReleaseGraphicsResources(): its GL program leaks.");
  }
}

//------------------------------------------------------------------------------
void vtkComputeShaderProgram::SetSource(const std::string& source)
{
  if (source == this->Source)
  {
    return;
  }
  this->Source = source;
  this->SourceChanged = true; // the next Compile() replaces the program
  this->Modified();
}

//------------------------------------------------------------------------------
std::string vtkComputeShaderProgram::NumberedExcerpt(const std::string& log) const
{
  // Mesa writes "0:12(5): error", NVIDIA "0(12) : error": collect the line numbers.
  std::set<int> lines;
  const std::regex pattern(R"((?:^|\n)\s*\d+(?::(\d+)\(|\((\d+)\)))");
  for (std::sregex_iterator it(log.begin(), log.end(), pattern), end; it != end; ++it)
  {
    lines.insert(std::stoi((*it)[(*it)[1].matched ? 1 : 2].str()));
  }
  std::vector<std::string> source;
  std::istringstream in(this->Source);
  for (std::string line; std::getline(in, line);)
  {
    source.push_back(line);
  }
  std::ostringstream out;
  for (int n : lines)
  {
    for (int k = std::max(1, n - 1); k <= std::min<int>(static_cast<int>(source.size()), n + 1);
         ++k)
    {
      out << (k == n ? ">" : " ") << k << ": " << source[k - 1] << "\n";
    }
  }
  if (lines.empty())
  {
    // No line numbers in the log: number the whole source.
    for (size_t k = 0; k < source.size(); ++k)
    {
      out << " " << k + 1 << ": " << source[k] << "\n";
    }
  }
  return out.str();
}

//------------------------------------------------------------------------------
bool vtkComputeShaderProgram::Compile(vtkOpenGLRenderWindow* renWin)
{
  if (this->Handle && !this->SourceChanged)
  {
    return true;
  }
  if (renWin)
  {
    renWin->MakeCurrent();
  }
  if (!renWin || !pointsurfaces::HasOpenGLVersion(4, 3))
  {
    vtkErrorMacro(<< "Program '" << this->Name
                  << "': compute shaders need an OpenGL 4.3 context, and this one has "
                  << (renWin ? "an older version" : "no window"));
    return false;
  }
  this->ReleaseGraphicsResources(renWin);
  this->SourceChanged = false;
  // `//VTK::System::Dec` opens every .glsl file of the project: for compute
  // programs it becomes the version line, on the same line so numbers match.
  std::string source = this->Source;
  const std::string marker = "//VTK::System::Dec";
  const size_t at = source.find(marker);
  if (at != std::string::npos)
  {
    source.replace(at, marker.size(), "#version 430 core");
  }
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, &log[0]);
  log.resize(std::strlen(log.c_str()));
  this->LastLog = log;
  if (!ok)
  {
    glDeleteShader(shader);
    vtkErrorMacro(<< "Compute program '" << this->Name << "' does not compile:\n"
                  << log << "\n"
                  << this->NumberedExcerpt(log));
    return false;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDeleteShader(shader); // stays alive while attached
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok)
  {
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string linkLog(static_cast<size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, &linkLog[0]);
    linkLog.resize(std::strlen(linkLog.c_str()));
    this->LastLog += linkLog;
    glDeleteProgram(program);
    vtkErrorMacro(<< "Compute program '" << this->Name << "' does not link:\n" << linkLog);
    return false;
  }
  this->Handle = program;
  this->UniformLocations.clear();
  return true;
}

//------------------------------------------------------------------------------
void vtkComputeShaderProgram::Bind(vtkOpenGLRenderWindow* renWin)
{
  if (!this->Handle)
  {
    vtkErrorMacro(<< "Program '" << this->Name << "' is bound before it compiled.");
    return;
  }
  // VTK's cache skips glUseProgram when it thinks its program is still bound:
  // make it forget, so the next mapper rebinds its own.
  renWin->GetShaderCache()->ReleaseCurrentShader();
  glUseProgram(this->Handle);
}

//------------------------------------------------------------------------------
void vtkComputeShaderProgram::Unbind()
{
  glUseProgram(0);
}

//------------------------------------------------------------------------------
int vtkComputeShaderProgram::GetUniformLocation(const char* name)
{
  auto it = this->UniformLocations.find(name);
  if (it != this->UniformLocations.end())
  {
    return it->second;
  }
  const int location = this->Handle ? glGetUniformLocation(this->Handle, name) : -1;
  this->UniformLocations[name] = location;
  return location;
}

void vtkComputeShaderProgram::SetUniformi(const char* name, int v)
{
  glUniform1i(this->GetUniformLocation(name), v);
}

void vtkComputeShaderProgram::SetUniformui(const char* name, unsigned int v)
{
  glUniform1ui(this->GetUniformLocation(name), v);
}

void vtkComputeShaderProgram::SetUniformf(const char* name, float v)
{
  glUniform1f(this->GetUniformLocation(name), v);
}

void vtkComputeShaderProgram::SetUniform2i(const char* name, int v0, int v1)
{
  glUniform2i(this->GetUniformLocation(name), v0, v1);
}

void vtkComputeShaderProgram::SetUniform2f(const char* name, float v0, float v1)
{
  glUniform2f(this->GetUniformLocation(name), v0, v1);
}

void vtkComputeShaderProgram::SetUniform3f(const char* name, const float v[3])
{
  glUniform3fv(this->GetUniformLocation(name), 1, v);
}

void vtkComputeShaderProgram::SetUniform4f(const char* name, const float v[4])
{
  glUniform4fv(this->GetUniformLocation(name), 1, v);
}

void vtkComputeShaderProgram::SetUniformMatrix4x4(const char* name, const float rowMajor[16])
{
  glUniformMatrix4fv(this->GetUniformLocation(name), 1, GL_TRUE, rowMajor);
}

//------------------------------------------------------------------------------
bool vtkComputeShaderProgram::Dispatch(unsigned int x, unsigned int y, unsigned int z)
{
  return this->Dispatch(
    x, y, z, GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

bool vtkComputeShaderProgram::Dispatch(unsigned int x,
  unsigned int y,
  unsigned int z,
  unsigned int barrierBits)
{
  GLint limits[3];
  for (GLuint axis = 0; axis < 3; ++axis)
  {
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, axis, &limits[axis]);
  }
  if (x > static_cast<unsigned int>(limits[0]) || y > static_cast<unsigned int>(limits[1]) ||
    z > static_cast<unsigned int>(limits[2]))
  {
    vtkErrorMacro(<< "Program '" << this->Name << "': " << x << "x" << y << "x" << z
                  << " work groups exceed the limit " << limits[0] << "x" << limits[1] << "x"
                  << limits[2] << "; split the dispatch.");
    return false;
  }
  if (x == 0 || y == 0 || z == 0)
  {
    return true; // nothing to do
  }
  glDispatchCompute(x, y, z);
  if (barrierBits)
  {
    glMemoryBarrier(barrierBits);
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkComputeShaderProgram::DispatchIndirect(unsigned int buffer,
  size_t offset,
  unsigned int barrierBits)
{
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, buffer);
  glDispatchComputeIndirect(static_cast<GLintptr>(offset));
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  if (barrierBits)
  {
    glMemoryBarrier(barrierBits);
  }
}

//------------------------------------------------------------------------------
bool vtkComputeShaderProgram::ReadyPass(vtkOpenGLRenderWindow* renWin,
  const char* name,
  const char* source,
  int pass)
{
  if (!this->IsCompiled())
  {
    std::string text = source;
    if (!pointsurfaces::ReplaceHook(
          text, "//VTK::Pass::Dec", "#define PASS " + std::to_string(pass)))
    {
      vtkErrorMacro(<< name << " lacks its //VTK::Pass::Dec hook: pass " << pass
                    << " cannot be compiled.");
      return false;
    }
    this->SetName((std::string(name) + " pass " + std::to_string(pass)).c_str());
    this->SetSource(text);
    if (!this->Compile(renWin))
    {
      return false;
    }
  }
  this->Bind(renWin);
  return true;
}

//------------------------------------------------------------------------------
unsigned int vtkComputeShaderProgram::GroupCount(size_t items, unsigned int groupSize)
{
  return groupSize ? static_cast<unsigned int>((items + groupSize - 1) / groupSize) : 0;
}

//------------------------------------------------------------------------------
int vtkComputeShaderProgram::GetMaxWorkGroupCount(vtkOpenGLRenderWindow* renWin)
{
  renWin->MakeCurrent();
  GLint limit = 0;
  glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &limit);
  return limit;
}

//------------------------------------------------------------------------------
void vtkComputeShaderProgram::ReleaseGraphicsResources(vtkWindow*)
{
  if (this->Handle)
  {
    glDeleteProgram(this->Handle);
    this->Handle = 0;
  }
  this->UniformLocations.clear();
}

//------------------------------------------------------------------------------
void vtkComputeShaderProgram::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Name: " << this->Name << "\n";
  os << indent << "Compiled: " << (this->Handle != 0) << "\n";
}
