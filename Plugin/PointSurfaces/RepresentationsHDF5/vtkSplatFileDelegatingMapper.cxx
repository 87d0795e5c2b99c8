// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSplatFileDelegatingMapper.h"

#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataSet.h"
#include "vtkFieldData.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkSmartPointer.h"
#include "vtkSplatFileReader.h"
#include "vtkStreamingSplatMapper.h"
#include "vtkStringArray.h"

#include <vtksys/SystemTools.hxx>

vtkStandardNewMacro(vtkSplatFileDelegatingMapper);

namespace
{
// The file name in the field data of `data` or of its first leaf that has one.
std::string FileNameOf(vtkDataObject* data)
{
  const char* name = vtkSplatFileReader::FileNameArrayName();
  auto fromField = [name](vtkDataObject* object) -> std::string
  {
    auto* array = object
      ? vtkStringArray::SafeDownCast(object->GetFieldData()->GetAbstractArray(name))
      : nullptr;
    return array && array->GetNumberOfValues() > 0 ? array->GetValue(0) : std::string();
  };
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      std::string file = fromField(it->GetCurrentDataObject());
      if (!file.empty())
      {
        return file;
      }
    }
    return std::string();
  }
  return fromField(data);
}
} // namespace

//------------------------------------------------------------------------------
vtkSplatFileDelegatingMapper::vtkSplatFileDelegatingMapper()
  : Stream(vtkStreamingSplatMapper::New())
{
}

vtkSplatFileDelegatingMapper::~vtkSplatFileDelegatingMapper()
{
  this->Stream->Delete();
}

//------------------------------------------------------------------------------
const std::string& vtkSplatFileDelegatingMapper::ChooseFile()
{
  this->FileDrawn.clear();
  if (this->StreamFile)
  {
    const std::string file = FileNameOf(this->GetInputDataObject(0, 0));
    if (!file.empty() && vtksys::SystemTools::FileExists(file, true))
    {
      this->FileDrawn = file;
      this->Stream->SetFileName(file.c_str());
    }
  }
  return this->FileDrawn;
}

//------------------------------------------------------------------------------
void vtkSplatFileDelegatingMapper::Render(vtkRenderer* ren, vtkActor* act)
{
  if (this->ChooseFile().empty())
  {
    this->Superclass::Render(ren, act);
    return;
  }
  if (!this->DrawsFile)
  {
    return;
  }
  this->Stream->vtkMapper::ShallowCopy(this);
  this->Stream->Render(ren, act);
}

//------------------------------------------------------------------------------
double* vtkSplatFileDelegatingMapper::GetBounds()
{
  if (this->ChooseFile().empty())
  {
    return this->Superclass::GetBounds();
  }
  this->Stream->GetBounds(this->Bounds);
  return this->Bounds;
}

//------------------------------------------------------------------------------
void vtkSplatFileDelegatingMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Stream->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
bool vtkSplatFileDelegatingMapper::HasOpaqueGeometry()
{
  return this->ChooseFile().empty() ? this->Superclass::HasOpaqueGeometry()
                                    : this->Stream->HasOpaqueGeometry();
}

bool vtkSplatFileDelegatingMapper::HasTranslucentPolygonalGeometry()
{
  return this->ChooseFile().empty() ? this->Superclass::HasTranslucentPolygonalGeometry()
                                    : this->Stream->HasTranslucentPolygonalGeometry();
}

bool vtkSplatFileDelegatingMapper::GetSupportsSelection()
{
  return this->FileDrawn.empty() && this->Superclass::GetSupportsSelection();
}

//------------------------------------------------------------------------------
void vtkSplatFileDelegatingMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "StreamFile: " << this->StreamFile << "\n";
  os << indent << "DrawsFile: " << this->DrawsFile << "\n";
  os << indent << "FileDrawn: " << (this->FileDrawn.empty() ? "(none)" : this->FileDrawn) << "\n";
  this->Stream->PrintSelf(os, indent.GetNextIndent());
}
