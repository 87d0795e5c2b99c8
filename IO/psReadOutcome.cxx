// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psReadOutcome.h"

#include "psChildProcess.h"

#include "vtkAbstractArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkStringArray.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace pointsurfaces
{
namespace
{
const char Magic[8] = { 'P', 'S', 'R', 'O', '2', 0, 0, 0 };
// The point data attributes whose active array travels with the arrays.
const int Attributes[] = { vtkDataSetAttributes::SCALARS,
  vtkDataSetAttributes::VECTORS,
  vtkDataSetAttributes::NORMALS,
  vtkDataSetAttributes::TCOORDS };
enum : uint8_t
{
  NumericArray = 0,
  StringArray = 1
};

// Buffered writes to a file descriptor; large blocks go out as they are.
class Sink
{
public:
  explicit Sink(int fd)
    : Fd(fd)
  {
  }
  template<typename T>
  void Put(T value)
  {
    this->Bytes(&value, sizeof(value));
  }
  void Text(const std::string& text)
  {
    this->Put<uint64_t>(text.size());
    this->Bytes(text.data(), text.size());
  }
  void Bytes(const void* data, size_t size)
  {
    if (this->Buffer.size() + size > Capacity)
    {
      this->Flush();
    }
    if (size >= Capacity)
    {
      this->Raw(static_cast<const char*>(data), size);
    }
    else
    {
      this->Buffer.append(static_cast<const char*>(data), size);
    }
  }
  void Flush()
  {
    this->Raw(this->Buffer.data(), this->Buffer.size());
    this->Buffer.clear();
  }

private:
  static constexpr size_t Capacity = 1 << 20;
  void Raw(const char* data, size_t size)
  {
#if defined(__unix__) || defined(__APPLE__)
    while (size > 0)
    {
      const ssize_t written = ::write(this->Fd, data, size);
      if (written < 0 && errno == EINTR)
      {
        continue;
      }
      if (written <= 0)
      {
        throw std::runtime_error(std::string("write failed: ") + std::strerror(errno));
      }
      data += written;
      size -= static_cast<size_t>(written);
    }
#else
    (void)data;
    (void)size;
    throw std::runtime_error("no file descriptors on this platform");
#endif
  }
  int Fd;
  std::string Buffer;
};

// Reads from the bytes, throwing when a read would pass their end.
class Source
{
public:
  Source(const char* bytes, size_t size)
    : At(bytes)
    , Left(size)
  {
  }
  const char* Take(size_t size)
  {
    if (size > this->Left)
    {
      throw std::runtime_error("the bytes end early");
    }
    const char* at = this->At;
    this->At += size;
    this->Left -= size;
    return at;
  }
  template<typename T>
  T Get()
  {
    T value;
    std::memcpy(&value, this->Take(sizeof(T)), sizeof(T));
    return value;
  }
  std::string Text()
  {
    const uint64_t size = this->Get<uint64_t>();
    if (size > this->Left)
    {
      throw std::runtime_error("a text is longer than the bytes left");
    }
    return std::string(this->Take(static_cast<size_t>(size)), static_cast<size_t>(size));
  }
  size_t Remaining() const { return this->Left; }

private:
  const char* At;
  size_t Left;
};

void PutArray(Sink& sink, vtkAbstractArray* array)
{
  auto* strings = vtkStringArray::SafeDownCast(array);
  auto* data = vtkDataArray::SafeDownCast(array);
  if (!strings && !data)
  {
    throw std::runtime_error("an array that is neither numeric nor of strings");
  }
  sink.Put<uint8_t>(strings ? StringArray : NumericArray);
  sink.Text(array->GetName() ? array->GetName() : "");
  sink.Put<int32_t>(array->GetDataType());
  sink.Put<int32_t>(array->GetNumberOfComponents());
  sink.Put<int64_t>(array->GetNumberOfTuples());
  if (strings)
  {
    for (vtkIdType i = 0; i < strings->GetNumberOfValues(); ++i)
    {
      sink.Text(strings->GetValue(i));
    }
    return;
  }
  const size_t bytes =
    static_cast<size_t>(data->GetNumberOfValues()) * static_cast<size_t>(data->GetDataTypeSize());
  if (bytes > 0)
  {
    sink.Bytes(data->GetVoidPointer(0), bytes);
  }
}

vtkSmartPointer<vtkAbstractArray> GetArray(Source& source)
{
  const uint8_t kind = source.Get<uint8_t>();
  const std::string name = source.Text();
  const int32_t type = source.Get<int32_t>();
  const int32_t components = source.Get<int32_t>();
  const int64_t tuples = source.Get<int64_t>();
  if ((kind != NumericArray && kind != StringArray) || components < 1 || tuples < 0 ||
    static_cast<uint64_t>(tuples) > source.Remaining() / static_cast<uint64_t>(components))
  {
    throw std::runtime_error("an array header is damaged");
  }
  const vtkIdType values = static_cast<vtkIdType>(tuples) * components;
  vtkSmartPointer<vtkAbstractArray> array;
  if (kind == StringArray)
  {
    auto strings = vtkSmartPointer<vtkStringArray>::New();
    strings->SetNumberOfComponents(components);
    strings->SetNumberOfValues(values);
    for (vtkIdType i = 0; i < values; ++i)
    {
      strings->SetValue(i, source.Text());
    }
    array = strings;
  }
  else
  {
    auto data = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(type));
    if (!data)
    {
      throw std::runtime_error("an array of unknown type " + std::to_string(type));
    }
    data->SetNumberOfComponents(components);
    const size_t bytes = static_cast<size_t>(values) * static_cast<size_t>(data->GetDataTypeSize());
    const char* from = source.Take(bytes);
    data->SetNumberOfTuples(static_cast<vtkIdType>(tuples));
    if (bytes > 0)
    {
      std::memcpy(data->GetVoidPointer(0), from, bytes);
    }
    array = data;
  }
  array->SetName(name.c_str());
  return array;
}
} // namespace

//------------------------------------------------------------------------------
bool WriteReadOutcome(int fd, const ReadOutcome& outcome)
{
  try
  {
    Sink sink(fd);
    sink.Bytes(Magic, sizeof(Magic));
    sink.Put<uint64_t>(outcome.Warnings.size());
    for (const std::string& warning : outcome.Warnings)
    {
      sink.Text(warning);
    }
    sink.Text(outcome.Error);
    sink.Put<uint64_t>(outcome.Counts.size());
    for (long long count : outcome.Counts)
    {
      sink.Put<int64_t>(count);
    }
    vtkPolyData* output = outcome.Output;
    sink.Put<uint8_t>(output ? 1 : 0);
    if (output)
    {
      vtkPoints* points = output->GetPoints();
      sink.Put<uint8_t>(points ? 1 : 0);
      if (points)
      {
        PutArray(sink, points->GetData());
      }
      for (vtkFieldData* arrays :
        { static_cast<vtkFieldData*>(output->GetPointData()), output->GetFieldData() })
      {
        sink.Put<uint64_t>(static_cast<uint64_t>(arrays->GetNumberOfArrays()));
        for (int a = 0; a < arrays->GetNumberOfArrays(); ++a)
        {
          PutArray(sink, arrays->GetAbstractArray(a));
        }
      }
      for (int attribute : Attributes)
      {
        int active = -1;
        for (int a = 0; a < output->GetPointData()->GetNumberOfArrays(); ++a)
        {
          active = output->GetPointData()->IsArrayAnAttribute(a) == attribute ? a : active;
        }
        sink.Put<int32_t>(active);
      }
    }
    sink.Flush();
    return true;
  }
  catch (const std::exception&)
  {
    return false;
  }
}

//------------------------------------------------------------------------------
bool ParseReadOutcome(const char* bytes, size_t size, ReadOutcome& outcome, std::string& why)
{
  outcome = ReadOutcome();
  try
  {
    Source source(bytes, size);
    if (std::memcmp(source.Take(sizeof(Magic)), Magic, sizeof(Magic)) != 0)
    {
      throw std::runtime_error("the bytes do not start as a read's outcome");
    }
    const uint64_t warnings = source.Get<uint64_t>();
    for (uint64_t w = 0; w < warnings; ++w)
    {
      outcome.Warnings.push_back(source.Text());
    }
    outcome.Error = source.Text();
    const uint64_t counts = source.Get<uint64_t>();
    for (uint64_t c = 0; c < counts; ++c)
    {
      outcome.Counts.push_back(source.Get<int64_t>());
    }
    if (source.Get<uint8_t>())
    {
      auto output = vtkSmartPointer<vtkPolyData>::New();
      if (source.Get<uint8_t>())
      {
        vtkNew<vtkPoints> points;
        vtkSmartPointer<vtkAbstractArray> data = GetArray(source);
        if (!vtkDataArray::SafeDownCast(data) || data->GetNumberOfComponents() != 3)
        {
          throw std::runtime_error("the points are not three numbers each");
        }
        points->SetData(vtkDataArray::SafeDownCast(data));
        output->SetPoints(points);
      }
      for (vtkFieldData* arrays :
        { static_cast<vtkFieldData*>(output->GetPointData()), output->GetFieldData() })
      {
        const uint64_t count = source.Get<uint64_t>();
        for (uint64_t a = 0; a < count; ++a)
        {
          arrays->AddArray(GetArray(source));
        }
      }
      for (int attribute : Attributes)
      {
        const int32_t active = source.Get<int32_t>();
        if (active >= output->GetPointData()->GetNumberOfArrays())
        {
          throw std::runtime_error("an active attribute names no array");
        }
        if (active >= 0)
        {
          output->GetPointData()->SetActiveAttribute(active, attribute);
        }
      }
      outcome.Output = output;
    }
    if (source.Remaining() != 0)
    {
      throw std::runtime_error("bytes are left over");
    }
    return true;
  }
  catch (const std::exception& e)
  {
    why = e.what();
    outcome = ReadOutcome();
    return false;
  }
}
//------------------------------------------------------------------------------
ReadOutcome GuardedRead(const std::function<ReadOutcome()>& read,
  bool inChild,
  const std::string& fileName,
  const std::string& library)
{
  if (!inChild || !ChildProcess::Supported())
  {
    return read();
  }
  ChildProcess child;
  const bool started = child.Run([&](int fd) { return WriteReadOutcome(fd, read()) ? 0 : 3; });
  if (!started)
  {
    ReadOutcome here = read();
    here.Warnings.insert(here.Warnings.begin(),
      "cannot start a child process to read it (" + child.Error() + "): read in this process.");
    return here;
  }
  ReadOutcome outcome;
  const std::string file = "\"" + fileName + "\"";
  std::string why;
  if (child.Signal() != 0)
  {
    outcome.Error = library + " ended the child process that read " + file + " with " +
      DescribeSignal(child.Signal()) + ": the file is damaged in a way that " + library +
      " does not check. This program goes on.";
  }
  else if (!child.Error().empty())
  {
    outcome.Error = "Cannot read " + file + " in a child process: " + child.Error();
  }
  else if (child.ExitStatus() != 0)
  {
    outcome.Error = "The child process that read " + file + " exited with status " +
      std::to_string(child.ExitStatus()) +
      (child.ExitStatus() == 3 ? " (it could not hand its result back)." : ".");
  }
  else if (!ParseReadOutcome(child.Data(), child.Size(), outcome, why))
  {
    outcome.Error = "Cannot take over what the child process read from " + file + ": " + why;
  }
  return outcome;
}
} // namespace pointsurfaces
