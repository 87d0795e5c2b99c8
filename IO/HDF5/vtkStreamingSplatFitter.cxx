// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkStreamingSplatFitter.h"

#include "psLocalFit.h"
#include "psSplatFile.h"
#include "psSplatStream.h"
#include "vtkSplatFileReader.h"

#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <atomic>

vtkStandardNewMacro(vtkStreamingSplatFitter);
vtkCxxSetObjectMacro(vtkStreamingSplatFitter, Controller, vtkMultiProcessController);

struct vtkStreamingSplatFitter::Impl
{
  std::unique_ptr<pointsurfaces::SplatStream> Stream;
  int Piece = 0;
  std::vector<std::string> Names; // the carried arrays, from the first piece with points
  std::vector<int> Components;
  std::vector<int> Types; // their VTK data types
  bool Normals = false;
  bool Failed = false;
  vtkIdType Points = 0;
  vtkIdType Received = 0; // on rank 0: points the other ranks sent
  // Over MPI ranks (ParaView's pvserver and pvbatch): rank 0 fits and
  // writes, the others update their inputs in step and read back their
  // piece of rank 0's file.
  int Rank = 0;
  int Ranks = 1;
};

//------------------------------------------------------------------------------
vtkStreamingSplatFitter::vtkStreamingSplatFitter()
  : P(new Impl)
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkStreamingSplatFitter::~vtkStreamingSplatFitter()
{
  this->SetController(nullptr);
}

//------------------------------------------------------------------------------
int vtkStreamingSplatFitter::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  vtkInformation* in = inputVector[0]->GetInformationObject(0);
  in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), P->Piece);
  in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), this->NumberOfPieces);
  in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  return 1;
}

//------------------------------------------------------------------------------
int vtkStreamingSplatFitter::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (P->Piece == 0)
  {
    this->NumberOfSplatsWritten = this->NumberOfChunks = this->NumberOfHaloPoints = 0;
    this->LargestChunk = 0;
    this->NumberOfInvalidPoints = this->NumberOfMergedPoints = 0;
    this->NumberOfDegenerateSplats = this->NumberOfReducedDegreeSplats = 0;
    P->Stream.reset();
    P->Names.clear();
    P->Components.clear();
    P->Types.clear();
    P->Points = P->Received = 0;
    P->Ranks = this->Controller ? std::max(1, this->Controller->GetNumberOfProcesses()) : 1;
    P->Rank = P->Ranks > 1 ? this->Controller->GetLocalProcessId() : 0;
    // Only rank 0's FileName counts over ranks.
    P->Failed = P->Rank == 0 && this->FileName.empty();
    if (P->Failed)
    {
      vtkErrorMacro(<< "No FileName: the splats would have nowhere to go.");
    }
  }
  if (P->Ranks > 1)
  {
    // Every rank's piece goes to rank 0, unless it holds the same points as
    // rank 0's or an earlier rank's (a reader or source that every rank
    // runs alike).
    std::vector<vtkSmartPointer<vtkPointSet>> parts;
    this->GatherPiece(input, parts);
    for (vtkPointSet* part : parts)
    {
      this->AddPiece(part);
    }
  }
  else
  {
    this->AddPiece(input);
  }
  this->UpdateProgress(0.2 * (P->Piece + 1) / this->NumberOfPieces);
  int more = ++P->Piece < this->NumberOfPieces && !P->Failed && !this->GetAbortExecute() ? 1 : 0;
  if (P->Ranks > 1)
  {
    // The ranks go on or stop together: a parallel filter upstream must
    // execute on all of them for every piece.
    int all = 0;
    this->Controller->AllReduce(&more, &all, 1, vtkCommunicator::MIN_OP);
    more = all;
  }
  if (more)
  {
    request->Set(vtkStreamingDemandDrivenPipeline::CONTINUE_EXECUTING(), 1);
    return 1;
  }
  request->Remove(vtkStreamingDemandDrivenPipeline::CONTINUE_EXECUTING());
  const bool everyPiece = P->Piece >= this->NumberOfPieces;
  P->Piece = 0;
  if (P->Ranks > 1)
  {
    this->FinishOverRanks(output, everyPiece);
  }
  else if (P->Failed || !this->Finish(output))
  {
    output->Initialize();
  }
  P->Stream.reset();
  return 1;
}

//------------------------------------------------------------------------------
void vtkStreamingSplatFitter::AddPiece(vtkPointSet* input)
{
  const vtkIdType n = input ? input->GetNumberOfPoints() : 0;
  vtkPointData* pd = input ? input->GetPointData() : nullptr;
  if (!P->Failed && !P->Stream && n > 0)
  {
    // The arrays to carry: every numeric point array of the first piece.
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* array = pd->GetArray(a);
      if (array && array->GetName())
      {
        P->Names.emplace_back(array->GetName());
        P->Components.push_back(array->GetNumberOfComponents());
        P->Types.push_back(array->GetDataType());
      }
    }
    int total = 0;
    for (int c : P->Components)
    {
      total += c;
    }
    P->Normals = pd->GetNormals() != nullptr;
    pointsurfaces::StreamParameters params;
    params.Build = this->MakeParameters(total > 0);
    params.ChunkPoints = this->ChunkPoints;
    params.ScratchDirectory = this->ScratchDirectory;
    params.Orient = this->OrientNormals;
    params.MergeTolerance = this->MergeTolerance;
    P->Stream = std::make_unique<pointsurfaces::SplatStream>(params, total, P->Normals);
  }
  if (P->Failed || n == 0)
  {
    return;
  }
  // This piece, in blocks.
  const int total = P->Stream->Attributes();
  vtkDataArray* normals = P->Normals ? pd->GetNormals() : nullptr;
  std::vector<vtkDataArray*> arrays;
  for (const std::string& name : P->Names)
  {
    arrays.push_back(pd->GetArray(name.c_str()));
  }
  std::vector<double> xyz;
  std::vector<float> nrm, attr;
  const vtkIdType block = 65536;
  for (vtkIdType first = 0; first < n && !P->Failed; first += block)
  {
    const vtkIdType count = std::min(block, n - first);
    xyz.resize(3 * count);
    nrm.assign(normals ? 3 * count : 0, 0.0f);
    attr.assign(static_cast<size_t>(count) * total, 0.0f);
    for (vtkIdType i = 0; i < count; ++i)
    {
      input->GetPoint(first + i, &xyz[3 * i]);
      for (int c = 0; normals && c < 3; ++c)
      {
        nrm[3 * i + c] = static_cast<float>(normals->GetComponent(first + i, c));
      }
      int at = 0;
      for (size_t a = 0; a < arrays.size(); ++a)
      {
        for (int c = 0; c < P->Components[a]; ++c, ++at)
        {
          const bool has = arrays[a] && c < arrays[a]->GetNumberOfComponents();
          attr[static_cast<size_t>(i) * total + at] =
            has ? static_cast<float>(arrays[a]->GetComponent(first + i, c)) : 0.0f;
        }
      }
    }
    P->Failed = !P->Stream->AddPoints(
      xyz.data(), normals ? nrm.data() : nullptr, total ? attr.data() : nullptr, count);
  }
  P->Points += n;
  if (P->Failed)
  {
    vtkErrorMacro(<< P->Stream->Error());
  }
}

//------------------------------------------------------------------------------
void vtkStreamingSplatFitter::GatherPiece(vtkPointSet* input,
  std::vector<vtkSmartPointer<vtkPointSet>>& parts)
{
  // Collective: every rank, every piece. A signature of each rank's piece
  // (its count and coordinate sums) tells rank 0 which ranks hold points
  // of their own: those send them; a rank whose piece equals rank 0's or
  // an earlier sender's (every rank read the same piece) does not.
  vtkMultiProcessController* controller = this->Controller;
  const vtkIdType n = input ? input->GetNumberOfPoints() : 0;
  double signature[5] = { static_cast<double>(n), 0.0, 0.0, 0.0, 0.0 };
  for (vtkIdType i = 0; i < n; ++i)
  {
    double x[3];
    input->GetPoint(i, x);
    signature[1] += x[0];
    signature[2] += x[1];
    signature[3] += x[2];
    signature[4] += x[0] * (static_cast<double>(i % 7919) + 1.0);
  }
  std::vector<double> all(5 * static_cast<size_t>(P->Ranks));
  controller->Gather(signature, all.data(), 5, 0);
  std::vector<int> senders(static_cast<size_t>(P->Ranks), 0);
  if (P->Rank == 0)
  {
    for (int r = 1; r < P->Ranks; ++r)
    {
      const double* mine = &all[5 * static_cast<size_t>(r)];
      bool seen = !(mine[0] > 0.0);
      for (int q = 0; q < r && !seen; ++q)
      {
        seen =
          (q == 0 || senders[q]) && std::equal(mine, mine + 5, &all[5 * static_cast<size_t>(q)]);
      }
      senders[r] = seen ? 0 : 1;
    }
  }
  controller->Broadcast(senders.data(), P->Ranks, 0);
  const int tag = 871031;
  if (P->Rank == 0)
  {
    parts.emplace_back(input);
    for (int r = 1; r < P->Ranks; ++r)
    {
      if (senders[r])
      {
        vtkSmartPointer<vtkDataObject> received;
        received.TakeReference(controller->ReceiveDataObject(r, tag));
        vtkPointSet* points = vtkPointSet::SafeDownCast(received);
        if (points)
        {
          parts.emplace_back(points);
        }
        P->Received += points ? points->GetNumberOfPoints() : 0;
      }
    }
  }
  else
  {
    P->Points += n;
    if (senders[P->Rank])
    {
      // Points and point data only: the cells are not needed.
      vtkNew<vtkPolyData> piece;
      piece->SetPoints(input->GetPoints());
      piece->GetPointData()->ShallowCopy(input->GetPointData());
      controller->Send(piece, 0, tag);
    }
  }
}

//------------------------------------------------------------------------------
void vtkStreamingSplatFitter::FinishOverRanks(vtkPolyData* output, bool everyPiece)
{
  // Every rank ran through the same pieces (a parallel filter upstream
  // executes on all of them together) and rank 0 fitted them all, its own
  // and those the others sent; two ranks writing one file would race
  // (HDF5 refuses the second, or the file is damaged).
  vtkMultiProcessController* controller = this->Controller;
  const bool fitted = P->Rank == 0 && everyPiece && !P->Failed;
  if (fitted)
  {
    vtkDebugMacro(<< P->Points << " points fitted, " << P->Received << " of them from other ranks");
  }
  const int written = fitted && this->Finish(nullptr) ? 1 : 0;
  // Rank 0's file (its absolute path: the ranks' working directories may
  // differ), read back in pieces: every rank its share.
  std::string path;
  if (P->Rank == 0 && written)
  {
    path = vtksys::SystemTools::CollapseFullPath(this->FileName);
  }
  int sent[2] = { written, static_cast<int>(path.size()) };
  controller->Broadcast(sent, 2, 0);
  std::vector<char> name(path.begin(), path.end());
  name.resize(static_cast<size_t>(std::max(0, sent[1])));
  if (sent[1] > 0)
  {
    controller->Broadcast(name.data(), sent[1], 0);
  }
  path.assign(name.begin(), name.end());
  output->Initialize();
  if (!sent[0] || path.empty())
  {
    return;
  }
  if (P->Rank != 0 && !vtksys::SystemTools::FileExists(path))
  {
    vtkWarningMacro(<< path << " (written by rank 0) is not visible on rank " << P->Rank
                    << ": its piece of the output is empty.");
    return;
  }
  this->ReadBack(path, output, P->Rank, P->Ranks);
}

//------------------------------------------------------------------------------
void vtkStreamingSplatFitter::ReadBack(const std::string& path,
  vtkPolyData* output,
  int piece,
  int pieces)
{
  vtkNew<vtkSplatFileReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetMemoryBudget(this->OutputMemoryBudget);
  // The file was just written here: no need to check it in a child process
  // (a fork after MPI_Init is best avoided).
  reader->SetCheckInChildProcess(pieces == 1);
  reader->UpdatePiece(piece, pieces, 0);
  output->ShallowCopy(reader->GetOutput());
}

//------------------------------------------------------------------------------
bool vtkStreamingSplatFitter::Finish(vtkPolyData* output)
{
  if (!P->Stream)
  {
    vtkWarningMacro(<< "The input has no points: no splat file written.");
    return false;
  }
  pointsurfaces::SplatStream& stream = *P->Stream;
  std::atomic<bool> abort(false);
  if (!stream.Run(
        [&](double f)
        {
          this->UpdateProgress(0.2 + 0.7 * f);
          abort = this->GetAbortExecute() != 0;
        },
        &abort))
  {
    vtkErrorMacro(<< stream.Error());
    return false;
  }
  const pointsurfaces::StreamStatistics& stats = stream.Statistics();
  this->NumberOfInvalidPoints = static_cast<vtkIdType>(stats.Dropped);
  this->NumberOfMergedPoints = static_cast<vtkIdType>(stats.Merged);
  this->NumberOfDegenerateSplats = static_cast<vtkIdType>(stats.Degenerate);
  this->NumberOfReducedDegreeSplats = static_cast<vtkIdType>(stats.Reduced);
  this->NumberOfChunks = static_cast<vtkIdType>(stats.Chunks);
  this->NumberOfHaloPoints = static_cast<vtkIdType>(stats.HaloPoints);
  this->LargestChunk = static_cast<vtkIdType>(stats.LargestChunk);
  this->SetResolvedTolerance(stats.Tolerance, stats.Noise);
  if (stats.Dropped > 0)
  {
    vtkWarningMacro(<< "Dropped " << stats.Dropped << " of " << P->Points
                    << " input points with NaN or infinite coordinates.");
  }

  // The file: page octree, then the rows in its order.
  pointsurfaces::SplatFileInfo info;
  info.Degree = this->Degree;
  info.InputPoints = stats.Points;
  info.Oriented = stream.Oriented();
  info.AttributeNames = P->Names;
  info.AttributeComponents = P->Components;
  info.AttributeTypes = P->Types;
  const int m = pointsurfaces::MonomialCount(this->Degree);
  const int total = stream.Attributes();
  std::vector<pointsurfaces::StreamedSplat> splats;
  std::vector<float> attributes;
  auto fetch = [&](const std::vector<long long>& ids, pointsurfaces::SplatColumns& out)
  {
    if (!stream.ReadSplatsAt(ids, splats, attributes))
    {
      return false;
    }
    for (size_t k = 0; k < ids.size(); ++k)
    {
      const pointsurfaces::StreamedSplat& s = splats[k];
      const pointsurfaces::LocalFrame& f = s.Fitted.Frame;
      for (int c = 0; c < 3; ++c)
      {
        out.Origin[3 * k + c] = f.Origin[c];
        out.Normal[3 * k + c] = static_cast<float>(f.Normal[c]);
        out.Tangent[3 * k + c] = static_cast<float>(f.Tangent[c]);
      }
      out.FeatureSize[k] = static_cast<float>(f.Scale);
      for (int c = 0; c < m; ++c)
      {
        // Lower-degree fallbacks keep zeros in the higher coefficients.
        out.Coefficients[static_cast<size_t>(m) * k + c] = static_cast<float>(
          c < pointsurfaces::MonomialCount(s.Fitted.Fit.Degree) ? s.Fitted.Fit.Coefficients[c]
                                                                : 0.0);
      }
      out.Radius[k] = static_cast<float>(s.Radius);
      out.MaxDeviation[k] = static_cast<float>(s.MaxDeviation);
      out.NominalRadius[k] = static_cast<float>(s.NominalRadius);
      out.Tolerance[k] = static_cast<float>(s.Tolerance);
      out.LOD[k] = s.Level;
      int at = 0;
      for (size_t a = 0; a < P->Components.size(); ++a)
      {
        for (int c = 0; c < P->Components[a]; ++c, ++at)
        {
          out.Attributes[a][static_cast<size_t>(P->Components[a]) * k + c] =
            attributes[k * total + at];
        }
      }
    }
    return true;
  };
  std::string error;
  if (!pointsurfaces::WriteSplatFile(this->FileName,
        info,
        stream.Origins().data(),
        stream.Radii().data(),
        stream.Levels().data(),
        stream.NumberOfSplats(),
        stream.LevelQuality(),
        fetch,
        error,
        this->PageSize))
  {
    vtkErrorMacro(<< this->FileName << ": " << error);
    return false;
  }
  this->NumberOfSplatsWritten = static_cast<vtkIdType>(stream.NumberOfSplats());
  this->UpdateProgress(0.95);

  // The output: the file, coarsest levels first, within the budget.
  if (output)
  {
    this->ReadBack(this->FileName, output, 0, 1);
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkStreamingSplatFitter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "PageSize: " << this->PageSize << "\n";
  os << indent << "NumberOfPieces: " << this->NumberOfPieces << "\n";
  os << indent << "ChunkPoints: " << this->ChunkPoints << "\n";
  os << indent << "ScratchDirectory: " << this->ScratchDirectory << "\n";
  os << indent << "OutputMemoryBudget: " << this->OutputMemoryBudget << " MB\n";
  os << indent << "NumberOfSplatsWritten: " << this->NumberOfSplatsWritten << "\n";
  os << indent << "NumberOfChunks: " << this->NumberOfChunks << "\n";
}
