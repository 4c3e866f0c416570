#include "vtkOpalVolumePieces.h"

#include "OpalMemory.h"
#include "OpalParallel.h"
#include "OpalRenderSession.h"
#include "vtkOpalRankAgreement.h"
#include "vtkOpalRankWait.h"
#include "vtkOpalRenderInput.h"

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
#include <new>
#include <stdexcept>
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

// Copies bytes [first, first + count) of a rank's piece of one array (its
// extent `e`, rows x of `tupleBytes` each, y then z) into `target`, whose
// extent `t` spans the whole x and y, at the rows within `t`'s layers z (a
// rank of a shared march holds only some, docs/design.md §8.1).
void placeBytes(const int* e, const int* t, vtkIdType tupleBytes, vtkIdType first, vtkIdType count, const char* data,
  char* target)
{
  const vtkIdType row = (e[1] - e[0] + 1) * tupleBytes, rowsPerLayer = e[3] - e[2] + 1;
  const vtkIdType nx = t[1] - t[0] + 1, ny = t[3] - t[2] + 1;
  for (vtkIdType at = first; at < first + count;)
  {
    const vtkIdType q = at / row, within = at % row, n = std::min(row - within, first + count - at);
    const vtkIdType j = e[2] + q % rowsPerLayer, k = e[4] + q / rowsPerLayer;
    if (k >= t[4] && k <= t[5])
    {
      std::memcpy(target + (((k - t[4]) * ny + (j - t[2])) * nx + (e[0] - t[0])) * tupleBytes + within,
        data + (at - first), static_cast<std::size_t>(n));
    }
    at += n;
  }
}

// Collective: every rank's rows within the layers z of `target`, rank
// `to`'s extent (every rank's where `to` is -1), into that rank's `array` of
// `volume` (its extent `target`); a rank's rows in some layers are one run
// of its piece's bytes (z slowest).
bool sendLayers(vtkMultiProcessController* controller, const char* values, vtkIdType tupleBytes,
  const std::vector<int>& extents, const int* target, int to, vtkImageData* volume, vtkDataArray* array,
  vtkIdType roundBytes)
{
  const int ranks = controller->GetNumberOfProcesses(), me = controller->GetLocalProcessId();
  std::vector<std::array<int, 6>> runs(static_cast<std::size_t>(ranks));
  std::vector<vtkIdType> lengths(static_cast<std::size_t>(ranks));
  for (int r = 0; r < ranks; ++r)
  {
    std::array<int, 6>& run = runs[static_cast<std::size_t>(r)];
    std::copy_n(&extents[6 * r], 6, run.begin());
    run[4] = std::max(run[4], target[4]);
    run[5] = std::min(run[5], target[5]);
    lengths[static_cast<std::size_t>(r)] = pointsIn(run.data()) * tupleBytes;
  }
  const int* e = &extents[6 * me];
  const vtkIdType from = lengths[static_cast<std::size_t>(me)] > 0
    ? static_cast<vtkIdType>(runs[static_cast<std::size_t>(me)][4] - e[4]) * (e[3] - e[2] + 1) * (e[1] - e[0] + 1) * tupleBytes
    : 0;
  char* into = static_cast<char*>(array->GetVoidPointer(0));
  return vtkOpalRankAgreement::GatherBytesTo(
    controller, values ? values + from : nullptr, lengths,
    [&](int rank, vtkIdType first, vtkIdType count, const char* data) {
      placeBytes(runs[static_cast<std::size_t>(rank)].data(), volume->GetExtent(), tupleBytes, first, count, data, into);
    },
    roundBytes, to);
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

// One array of every rank's piece into `volume` at its extent (the whole, or
// the whole's x and y and some layers z): empty, or the reason it cannot be
// (alike on every rank). In exchange rounds of `roundBytes` per rank.
std::string gatherArray(vtkMultiProcessController* controller, vtkImageData* piece, const char* name,
  const std::vector<int>& extents, vtkImageData* volume, vtkIdType roundBytes)
{
  const int ranks = controller->GetNumberOfProcesses();
  // Its type and components (0: absent; -1: an empty piece takes the others').
  vtkSmartPointer<vtkDataArray> mine = contiguous(piece->GetPointData()->GetArray(name));
  const bool empty = pointsIn(piece->GetExtent()) == 0;
  const int kind[2] = { empty ? -1 : mine ? mine->GetDataType() : 0, empty ? -1 : mine ? mine->GetNumberOfComponents() : 0 };
  const std::vector<int> kinds = vtkOpalRankAgreement::GatherInts(controller, kind, 2, "their arrays' types");
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
  array->SetName(name);
  array->SetNumberOfTuples(pointsIn(volume->GetExtent()));
  // Each rank receives only the rows within its extent's layers z (all of
  // them, or a rank's piece and halo of the medium, docs/design.md §8.1):
  // to every rank at once where their extents are alike, else to each in turn.
  const std::vector<int> targets = vtkOpalRankAgreement::GatherInts(controller, volume->GetExtent(), 6, "the extents they gather");
  bool alike = true;
  for (int r = 1; r < ranks; ++r)
  {
    alike = alike && std::equal(targets.begin(), targets.begin() + 6, targets.begin() + 6 * r);
  }
  const char* values = mine && !empty ? static_cast<const char*>(mine->GetVoidPointer(0)) : nullptr;
  const auto sendTo = [&](int to) {
    return sendLayers(
      controller, values, tupleBytes, extents, &targets[6 * std::max(to, 0)], to, volume, array, roundBytes);
  };
  bool sent = !alike || sendTo(-1);
  for (int to = 0; to < ranks && !alike && sent; ++to)
  {
    sent = sendTo(to);
  }
  if (!sent)
  {
    return std::string("The ranks could not exchange the volume's ") + name + ".";
  }
  volume->GetPointData()->AddArray(array);
  return {};
}

// The layers z [first, end) of the medium's arrays a rank gathers for
// `heldPiece` (share, shares) of a volume of extent `whole`: those its device
// reads (opal::mediumLayersRead), all for one share.
std::pair<int, int> mediumLayers(const int whole[6], std::pair<int, int> heldPiece)
{
  return opal::mediumLayersRead(whole[5] - whole[4] + 1, heldPiece.first, heldPiece.second);
}

// Empty where the arrays the render reads fit in this machine's memory:
// SurfaceDistance of the whole volume `whole` (an extent) and the others,
// the absorption pair among them, of its `layers`, and the exchange's
// window of `ranks` ranks; else the sentence refusing them.
std::string MemoryError(const int whole[6], std::pair<int, int> layers, int ranks)
{
  const auto layer = static_cast<std::uint64_t>(whole[1] - whole[0] + 1) * static_cast<std::uint64_t>(whole[3] - whole[2] + 1);
  // A round of every rank, MPI's int counts bounding them together (GatherBytesTo).
  const std::uint64_t window =
    std::min<std::uint64_t>(static_cast<std::uint64_t>(ranks) * vtkOpalRankAgreement::RoundBytes, VTK_INT_MAX);
  const std::uint64_t needed = static_cast<std::uint64_t>(pointsIn(whole)) * 4 +
    layer * static_cast<std::uint64_t>(layers.second - layers.first) * (opal::RenderVolumeBytesPerVoxel - 4 + 8) + window;
  const std::uint64_t available = opal::physicalMemoryBytes();
  if (available == 0 || needed <= available)
  {
    return {};
  }
  return "The volume's arrays that the render reads need about " + opal::formatBytes(needed) +
    " on this rank, more than this machine's " + opal::formatBytes(available) + " of memory.";
}

// An empty image of `extent`, placed as `like`.
vtkSmartPointer<vtkImageData> imageOf(const int extent[6], vtkImageData* like)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetExtent(const_cast<int*>(extent));
  image->SetOrigin(like->GetOrigin());
  image->SetSpacing(like->GetSpacing());
  return image;
}

// Collective: the whole volume from every rank's piece (GatheredVolume::Update).
// Where `byLayers`, the medium's arrays go into `medium`, an image of the
// whole's x and y and its `layers` (all of them for a rank whose piece and
// halo span the grid); else all into `volume`. In exchange rounds of `roundBytes` per rank.
std::string Gather(vtkMultiProcessController* given, vtkImageData* piece, const int whole[6], bool byLayers,
  std::pair<int, int> layers, vtkSmartPointer<vtkImageData>& volume, vtkSmartPointer<vtkImageData>& medium,
  vtkIdType roundBytes)
{
  vtkMultiProcessController* controller = ranksController(given);
  if (!controller)
  {
    volume = vtkSmartPointer<vtkImageData>::New();
    volume->ShallowCopy(piece);
    return {};
  }
  const std::vector<int> extents = vtkOpalRankAgreement::GatherInts(controller, piece->GetExtent(), 6, "their pieces' extents");
  const std::string uncovered = coverageError(extents, whole);
  if (!uncovered.empty())
  {
    return uncovered;
  }
  volume = imageOf(whole, piece);
  volume->GetFieldData()->ShallowCopy(piece->GetFieldData());
  if (byLayers)
  {
    const int extent[6] = { whole[0], whole[1], whole[2], whole[3], whole[4] + layers.first, whole[4] + layers.second - 1 };
    medium = imageOf(extent, piece);
  }
  for (const char* name : RenderArrays)
  {
    vtkImageData* into = medium && std::strcmp(name, "SurfaceDistance") != 0 ? medium.Get() : volume.Get();
    const std::string error = gatherArray(controller, piece, name, extents, into, roundBytes);
    if (!error.empty())
    {
      return error;
    }
  }
  return {};
}

// The sums as sent: absorbs, the coloured exponent, then per domain its
// index sums and its count (whole numbers, exact in a double).
std::vector<double> packed(const opal::MediumSums& sums)
{
  std::vector<double> words{ sums.Absorbs ? 1.0 : 0.0, sums.ColouredAbsorptionExponent };
  for (std::size_t d = 0; d < sums.DomainVoxels.size(); ++d)
  {
    words.insert(words.end(), sums.DomainIndexSums[d].begin(), sums.DomainIndexSums[d].end());
    words.push_back(static_cast<double>(sums.DomainVoxels[d]));
  }
  return words;
}

opal::MediumSums unpacked(const double* words, std::size_t count)
{
  opal::MediumSums sums;
  sums.Absorbs = count >= 2 && words[0] != 0.0;
  sums.ColouredAbsorptionExponent = count >= 2 ? static_cast<float>(words[1]) : 0.0f;
  for (std::size_t at = 2; at + 4 <= count; at += 4)
  {
    sums.DomainIndexSums.push_back({ words[at], words[at + 1], words[at + 2] });
    sums.DomainVoxels.push_back(static_cast<std::uint64_t>(words[at + 3]));
  }
  return sums;
}

// This rank's sums of its share's layers (`heldPiece`'s, which cover the
// whole one after another in rank order) of the medium it gathered: none
// where the render cannot read its arrays (its upload says why); false
// where it could not sum them (memory), which fails every rank's gather.
bool sumShare(vtkImageData* volume, const vtkOpalRenderInput::MediumPiece& medium, std::pair<int, int> heldPiece,
  opal::MediumSums& mine)
{
  try
  {
    opal::RenderVolume read;
    vtkOpalRenderInput::Storage storage;
    if (vtkOpalRenderInput::Read(volume, read, storage, &medium).empty())
    {
      mine = opal::sumMedium(read, opal::evenShare(read.Dimensions[2], heldPiece.first, heldPiece.second));
    }
    return true;
  }
  catch (const std::bad_alloc&)
  {
    return false;
  }
}

// Collective: the whole medium's sums, every rank's share (sumShare) added
// up in rank order; empty, else (alike on every rank) why there are none.
std::string SumMedium(vtkMultiProcessController* controller, vtkImageData* volume,
  const vtkOpalRenderInput::MediumPiece& medium, std::pair<int, int> heldPiece, opal::MediumSums& whole)
{
  opal::MediumSums mine;
  const bool summed = sumShare(volume, medium, heldPiece, mine);
  const std::vector<double> words = packed(mine);
  const std::vector<vtkIdType> lengths = vtkOpalRankAgreement::GatherLengths(
    controller, static_cast<vtkIdType>(words.size() * sizeof(double)));
  std::vector<char> bytes;
  const bool exchanged =
    vtkOpalRankAgreement::GatherBytes(controller, reinterpret_cast<const char*>(words.data()), lengths, bytes);
  if (vtkOpalRankAgreement::AnyRank(controller, !summed || !exchanged))
  {
    return "The ranks could not sum the medium's absorption and domains over their layers (memory, or the exchange).";
  }
  const std::vector<vtkIdType> offsets = vtkOpalRankAgreement::RankOffsets(lengths);
  for (std::size_t r = 0; r < lengths.size(); ++r)
  {
    std::vector<double> theirs(static_cast<std::size_t>(lengths[r]) / sizeof(double));
    std::memcpy(theirs.data(), bytes.data() + offsets[r], theirs.size() * sizeof(double));
    whole.add(unpacked(theirs.data(), theirs.size()));
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

GatheredVolume::GatheredVolume()
  : RoundBytes(vtkOpalRankAgreement::RoundBytes)
{
}

void GatheredVolume::SetRoundBytes(vtkIdType bytes)
{
  if (bytes < 1)
  {
    throw std::invalid_argument("The gather's RoundBytes must be at least 1 byte, not " + std::to_string(bytes) + ".");
  }
  this->RoundBytes = bytes;
}

std::string GatheredVolume::Update(vtkMultiProcessController* controller, vtkImageData* piece,
  vtkInformation* pieceInformation, bool needsArrays, std::pair<int, int> heldPiece)
{
  if (vtkOpalRankAgreement::Ranks(controller) == 1)
  {
    this->Forget(); // a render that left its ranks reads its input: what they gathered serves it no more
    return {};
  }
  const bool changed = this->From != piece || this->Time != piece->GetMTime();
  const vtkOpalRankWait::Naming naming("the gather of the volume's pieces");
  if (!vtkOpalRankAgreement::AnyRank(controller, changed || (needsArrays && !this->Serves(heldPiece))))
  {
    return {};
  }
  this->Forget();
  int whole[6];
  pieceInformation->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  const std::pair<int, int> layers = mediumLayers(whole, heldPiece);
  // The gathered arrays must fit on every rank.
  const std::string memory = MemoryError(whole, layers, vtkOpalRankAgreement::Ranks(controller));
  if (vtkOpalRankAgreement::AnyRank(controller, !memory.empty()))
  {
    return memory.empty() ? "Another rank cannot hold the volume's arrays the render reads." : memory;
  }
  // Every rank alike (the sums below are collective), whatever its layers.
  const bool byLayers = heldPiece.second > 1;
  vtkSmartPointer<vtkImageData> mediumArrays;
  std::string error = Gather(controller, piece, whole, byLayers, layers, this->Volume, mediumArrays, this->RoundBytes);
  if (error.empty() && mediumArrays)
  {
    this->MediumLayers = std::make_shared<vtkOpalRenderInput::MediumPiece>(
      vtkOpalRenderInput::MediumPiece{ mediumArrays, { layers, {} } });
    error = SumMedium(controller, this->Volume, *this->MediumLayers, heldPiece, this->MediumLayers->Held.Whole);
  }
  if (!error.empty())
  {
    this->Forget();
    return error;
  }
  this->From = piece;
  this->Time = piece->GetMTime();
  return {};
}

void GatheredVolume::Forget()
{
  this->From = nullptr;
  this->Volume = nullptr;
  this->MediumLayers = nullptr;
  this->ArraysReleased = false;
}

void GatheredVolume::ReleaseArrays()
{
  if (this->From) // set by a gather only: nothing with one process
  {
    this->Volume->GetPointData()->Initialize();
    if (this->MediumLayers)
    {
      this->MediumLayers->Arrays->GetPointData()->Initialize();
    }
    this->ArraysReleased = true;
  }
}

bool GatheredVolume::Serves(std::pair<int, int> heldPiece) const
{
  if (!this->From)
  {
    return true; // one process reads its input; under MPI nothing was gathered to serve
  }
  const int* whole = this->Volume->GetExtent();
  const std::pair<int, int> read = mediumLayers(whole, heldPiece);
  const std::pair<int, int> held = this->MediumLayers ? this->MediumLayers->Held.Layers : std::make_pair(0, whole[5] - whole[4] + 1);
  return !this->ArraysReleased && held.first <= read.first && read.second <= held.second;
}

vtkImageData* GatheredVolume::Of(vtkMultiProcessController* controller, vtkImageData* piece) const
{
  if (vtkOpalRankAgreement::Ranks(controller) == 1)
  {
    return piece;
  }
  return piece && this->From == piece && this->Time == piece->GetMTime() ? this->Volume.Get() : nullptr;
}

const vtkOpalRenderInput::MediumPiece* GatheredVolume::Medium() const
{
  return this->From ? this->MediumLayers.get() : nullptr;
}
} // namespace vtkOpalVolumePieces
