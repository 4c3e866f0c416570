#include "vtkOpalVolumePieces.h"

#include "OpalMemory.h"
#include "vtkOpalRankAgreement.h"

#include "vtkDataArray.h"
#include "vtkExtentTranslator.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkType.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

namespace vtkOpalVolumePieces
{
namespace
{
// The point arrays the render reads (vtkOpalRenderInput).
constexpr std::array<const char*, 5> RenderArrays = { "ScatteringCoefficient", "DomainId", "SurfaceDistance",
  "AbsorptionCoefficient", "AbsorptionExponent" };

vtkMultiProcessController* ranksController(vtkMultiProcessController* controller)
{
  return controller && controller->GetNumberOfProcesses() > 1 ? controller : nullptr;
}

vtkIdType pointsIn(const int* e)
{
  vtkIdType points = 1;
  for (int a = 0; a < 3; ++a)
  {
    points *= std::max(e[2 * a + 1] - e[2 * a] + 1, 0);
  }
  return points;
}

void pieceOf(int rank, int ranks, const int whole[6], int extent[6])
{
  std::copy(whole, whole + 6, extent);
  if (ranks > 1 && pointsIn(whole) > 0)
  {
    vtkNew<vtkExtentTranslator> translator;
    translator->PieceToExtentThreadSafe(
      rank, ranks, 0, const_cast<int*>(whole), extent, vtkExtentTranslator::BLOCK_MODE, 0);
  }
}

// Empty where every rank's piece lies within the whole and holds the piece
// it was asked for (so together they cover it); else the reason.
std::string coverageError(const std::vector<int>& extents, const int whole[6])
{
  const int ranks = static_cast<int>(extents.size() / 6);
  for (int r = 0; r < ranks; ++r)
  {
    const int* e = &extents[6 * r];
    int asked[6];
    pieceOf(r, ranks, whole, asked);
    for (int a = 0; a < 3 && pointsIn(asked) > 0; ++a)
    {
      const bool within = e[2 * a] >= whole[2 * a] && e[2 * a + 1] <= whole[2 * a + 1];
      const bool holds = e[2 * a] <= asked[2 * a] && e[2 * a + 1] >= asked[2 * a + 1];
      if (!within || !holds)
      {
        return "Rank " + std::to_string(r) + "'s piece of the volume is not the extent it asked for " +
          "(an upstream filter made less or more): the ranks cannot gather the whole volume.";
      }
    }
  }
  return {};
}

// Copies each rank's rows of one array (`bytes`, the ranks' pieces one after
// another) into `whole` at their extents.
void placeRows(const std::vector<char>& bytes, const std::vector<int>& extents, const int* w, vtkDataArray* whole)
{
  const vtkIdType tupleBytes = whole->GetNumberOfComponents() * whole->GetDataTypeSize();
  char* target = static_cast<char*>(whole->GetVoidPointer(0));
  const vtkIdType nx = w[1] - w[0] + 1, ny = w[3] - w[2] + 1;
  std::size_t at = 0;
  for (std::size_t r = 0; r < extents.size() / 6; ++r)
  {
    const int* e = &extents[6 * r];
    const vtkIdType row = std::max(e[1] - e[0] + 1, 0) * tupleBytes;
    for (int k = e[4]; k <= e[5] && row > 0; ++k)
    {
      for (int j = e[2]; j <= e[3]; ++j, at += row)
      {
        std::memcpy(target + (((k - w[4]) * ny + (j - w[2])) * nx + (e[0] - w[0])) * tupleBytes, &bytes[at], row);
      }
    }
  }
}

// The array as sent: itself where its values lie in one block, else an
// ordinary copy (a numpy or implicit array).
vtkSmartPointer<vtkDataArray> contiguous(vtkDataArray* array)
{
  if (!array || array->HasStandardMemoryLayout())
  {
    return array;
  }
  auto copy = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(array->GetDataType()));
  copy->DeepCopy(array);
  return copy;
}

// One array of every rank's piece into `volume`: empty, or the reason it
// cannot be (alike on every rank).
std::string gatherArray(vtkMultiProcessController* controller, vtkImageData* piece, const char* name,
  const std::vector<int>& extents, const int whole[6], vtkImageData* volume)
{
  const int ranks = controller->GetNumberOfProcesses();
  // Its type and components (0: absent; -1: an empty piece takes the others').
  vtkSmartPointer<vtkDataArray> mine = contiguous(piece->GetPointData()->GetArray(name));
  const bool empty = pointsIn(piece->GetExtent()) == 0;
  const int kind[2] = { empty ? -1 : mine ? mine->GetDataType() : 0, empty ? -1 : mine ? mine->GetNumberOfComponents() : 0 };
  std::vector<int> kinds(2 * ranks);
  controller->AllGather(kind, kinds.data(), 2);
  std::array<int, 2> agreed{ -1, -1 };
  for (int r = 0; r < ranks; ++r)
  {
    const std::array<int, 2> other{ kinds[2 * r], kinds[2 * r + 1] };
    if (other[0] != -1 && agreed[0] != -1 && other != agreed)
    {
      return std::string("The ranks' pieces of the volume differ in the point array ") + name +
        " (present, type or components): every rank must read the same volume.";
    }
    agreed = other[0] != -1 ? other : agreed;
  }
  if (agreed[0] <= 0)
  {
    return {}; // absent everywhere: the render's reading names it where it needs it
  }
  auto array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(agreed[0]));
  array->SetNumberOfComponents(agreed[1]);
  const vtkIdType tupleBytes = agreed[1] * array->GetDataTypeSize();
  const std::vector<vtkIdType> lengths = vtkOpalRankAgreement::GatherLengths(
    controller, mine && !empty ? mine->GetNumberOfValues() * mine->GetDataTypeSize() : 0);
  for (int r = 0; r < ranks; ++r)
  {
    if (lengths[r] != pointsIn(&extents[6 * r]) * tupleBytes)
    {
      return "Rank " + std::to_string(r) + "'s " + name + " does not hold one value per point of its piece.";
    }
  }
  std::vector<char> bytes;
  if (!vtkOpalRankAgreement::GatherBytes(controller, mine && !empty ? static_cast<const char*>(mine->GetVoidPointer(0)) : nullptr,
        lengths, bytes))
  {
    return std::string("The ranks could not exchange the volume's ") + name + ".";
  }
  array->SetName(name);
  array->SetNumberOfTuples(pointsIn(whole));
  placeRows(bytes, extents, whole, array);
  volume->GetPointData()->AddArray(array);
  return {};
}

// Empty where the arrays the render reads of the whole volume `whole` (an
// extent) fit in this machine's memory, else the sentence refusing them.
std::string MemoryError(const int whole[6])
{
  // The render's arrays with the absorption pair, and one array's exchange.
  const std::uint64_t needed = static_cast<std::uint64_t>(pointsIn(whole)) * (opal::RenderVolumeBytesPerVoxel + 8 + 4);
  const std::uint64_t available = opal::physicalMemoryBytes();
  if (available == 0 || needed <= available)
  {
    return {};
  }
  return "The whole volume's arrays that the render reads need about " + opal::formatBytes(needed) +
    " on every rank, more than this machine's " + opal::formatBytes(available) + " of memory.";
}

// Collective: the whole volume from every rank's piece (GatheredVolume::Update).
std::string Gather(
  vtkMultiProcessController* given, vtkImageData* piece, const int whole[6], vtkSmartPointer<vtkImageData>& volume)
{
  volume = vtkSmartPointer<vtkImageData>::New();
  vtkMultiProcessController* controller = ranksController(given);
  if (!controller)
  {
    volume->ShallowCopy(piece);
    return {};
  }
  std::vector<int> extents(6 * controller->GetNumberOfProcesses());
  controller->AllGather(piece->GetExtent(), extents.data(), 6);
  const std::string uncovered = coverageError(extents, whole);
  if (!uncovered.empty())
  {
    return uncovered;
  }
  volume->SetExtent(const_cast<int*>(whole));
  volume->SetOrigin(piece->GetOrigin());
  volume->SetSpacing(piece->GetSpacing());
  volume->GetFieldData()->ShallowCopy(piece->GetFieldData());
  for (const char* name : RenderArrays)
  {
    const std::string error = gatherArray(controller, piece, name, extents, whole, volume);
    if (!error.empty())
    {
      return error;
    }
  }
  return {};
}

} // namespace

void AskForPiece(vtkMultiProcessController* given, vtkInformation* inputInformation)
{
  vtkMultiProcessController* controller = ranksController(given);
  int whole[6], piece[6];
  inputInformation->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  pieceOf(controller ? controller->GetLocalProcessId() : 0, controller ? controller->GetNumberOfProcesses() : 1,
    whole, piece);
  // The extent alone says which: ParaView's executive would intersect it
  // with its own split of a piece number, which left holes.
  inputInformation->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  inputInformation->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  inputInformation->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  inputInformation->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), piece, 6);
}

std::string GatheredVolume::Update(
  vtkMultiProcessController* controller, vtkImageData* piece, vtkInformation* pieceInformation, bool needsArrays)
{
  const bool changed = this->From != piece || this->Time != piece->GetMTime();
  if (vtkOpalRankAgreement::Ranks(controller) == 1 ||
    !vtkOpalRankAgreement::AnyRank(controller, changed || (this->ArraysReleased && needsArrays)))
  {
    return {};
  }
  this->From = nullptr;
  this->Volume = nullptr;
  this->ArraysReleased = false;
  int whole[6];
  pieceInformation->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  // The gathered arrays (and one array's exchange) must fit on every rank.
  const std::string memory = MemoryError(whole);
  if (vtkOpalRankAgreement::AnyRank(controller, !memory.empty()))
  {
    return memory.empty() ? "Another rank cannot hold the whole volume the render reads." : memory;
  }
  const std::string error = Gather(controller, piece, whole, this->Volume);
  if (!error.empty())
  {
    this->Volume = nullptr;
    return error;
  }
  this->From = piece;
  this->Time = piece->GetMTime();
  return {};
}

void GatheredVolume::ReleaseArrays()
{
  if (this->From) // set by a gather only: nothing with one process
  {
    this->Volume->GetPointData()->Initialize();
    this->ArraysReleased = true;
  }
}

vtkImageData* GatheredVolume::Of(vtkMultiProcessController* controller, vtkImageData* piece) const
{
  if (vtkOpalRankAgreement::Ranks(controller) == 1)
  {
    return piece;
  }
  return piece && this->From == piece && this->Time == piece->GetMTime() ? this->Volume.Get() : nullptr;
}
} // namespace vtkOpalVolumePieces
