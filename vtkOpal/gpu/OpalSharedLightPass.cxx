// Per-voxel fields computed by several processes together, each a share of
// the voxels, before their frames (docs/design.md §8.1): the light field and
// the every-order field written from its tally grid.
#include "OpalRenderSession.h"

#include "OpalParallel.h"
#include "OpalRenderSessionState.h"
#include "OpalShareSlabs.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <exception>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace opal
{

using namespace sessiondetail;

namespace
{
// Rows z [first, second) of every layer: share `share` of `shares`, each a
// slab of whole rows, so that each row's pairs (a voxel's and its +x
// neighbour's, §3.7) are one share's writes and its voxels one range.
std::pair<int, int> shareRows(const std::array<int, 3>& dims, int share, int shares)
{
  return evenShare(dims[2], share, shares);
}

// Voxel ranges [first, end), in the order a share's bytes carry them.
using Runs = std::vector<std::pair<std::size_t, std::size_t>>;

// Layer `layer`'s first and last SweepHaloRows rows of `rows` (all of them where
// fewer), one range each: what the shares beside read of it.
Runs haloOf(const std::array<int, 3>& dims, std::pair<int, int> rows, int layer)
{
  const auto nx = static_cast<std::size_t>(dims[0]);
  Runs runs;
  for (int z = rows.first; z < rows.second; ++z)
  {
    if (z < rows.first + SweepHaloRows || z >= rows.second - SweepHaloRows)
    {
      const std::size_t first = nx * (static_cast<std::size_t>(layer) + static_cast<std::size_t>(dims[1]) * z);
      runs.emplace_back(first, first + nx);
    }
  }
  return runs;
}

// Whether the row of voxel `voxel` lies in the halo of `rows`, which their sweep reads.
bool readsRow(const std::array<int, 3>& dims, std::pair<int, int> rows, std::size_t voxel)
{
  const auto z = static_cast<int>(voxel / (static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1])));
  return (z >= rows.first - SweepHaloRows && z < rows.first) || (z >= rows.second && z < rows.second + SweepHaloRows);
}

using Fields = std::vector<std::pair<VulkanBuffer*, std::uint64_t>>;
// The voxels [first, end) a step's fields hold, from their buffers' start:
// all, or the piece of a light field held by piece (holdPiece).
using HeldVoxels = std::pair<std::size_t, std::size_t>;

// Bytes of `runs` (held): each field's records of each run, field after
// field, read together (readRuns: one submit on a device with dedicated memory).
std::vector<char> readShare(const Fields& fields, const HeldVoxels& held, const Runs& runs)
{
  std::vector<ReadRun> read;
  std::uint64_t bytes = 0;
  for (const auto& [buffer, record] : fields)
  {
    for (const auto& [first, end] : runs)
    {
      if (first < held.first || end > held.second)
      {
        throw std::logic_error("readShare: a share's voxels beyond the layers its light fields hold.");
      }
      read.push_back({ buffer, (first - held.first) * record, (end - first) * record });
      bytes += read.back().Bytes;
    }
  }
  std::vector<char> share(bytes);
  std::vector<char*> into;
  std::uint64_t at = 0;
  for (const ReadRun& run : read)
  {
    into.push_back(share.data() + at);
    at += run.Bytes;
  }
  readRuns(read, into);
  return share;
}

// Whether a run (by its first voxel) is written where it arrives; none: all.
using Wanted = std::function<bool(std::size_t firstVoxel)>;

// Bytes [first, first + count) of `runs` (as readShare lays them out)
// written into the fields together (writeRuns), the runs `wanted` only and
// their voxels `held` only.
void writeShare(const Fields& fields, const HeldVoxels& held, const Runs& runs, const Wanted& wanted,
  std::uint64_t first, std::uint64_t count, const char* bytes)
{
  std::vector<WrittenRun> written;
  std::vector<const char*> from;
  std::uint64_t runStart = 0;
  for (const auto& [buffer, record] : fields)
  {
    for (const auto& [voxel, end] : runs)
    {
      const std::uint64_t runBytes = (end - voxel) * record;
      // The run's bytes of held voxels, where this piece of the stream carries them.
      const std::uint64_t heldStart = runStart + (std::clamp(held.first, voxel, end) - voxel) * record;
      const std::uint64_t heldStop = runStart + (std::clamp(held.second, voxel, end) - voxel) * record;
      const std::uint64_t start = std::max(first, heldStart), stop = std::min(first + count, heldStop);
      if (start < stop && (!wanted || wanted(voxel)))
      {
        written.push_back({ buffer, (voxel - held.first) * record + (start - runStart), stop - start });
        from.push_back(bytes + (start - first));
      }
      runStart += runBytes;
    }
  }
  writeRuns(written, from);
}

// A sink that writes the other shares' runs into the fields, keeping the
// first failure to rethrow once the exchange is over (a throw inside it
// would leave the processes' exchange midway).
struct SharePlacer
{
  const Fields& Into;
  HeldVoxels Held;
  int Own;
  std::function<Runs(int share)> RunsOf;
  Wanted Keeps; // the runs this share reads; none: all
  std::exception_ptr Failure;

  void operator()(int share, std::uint64_t first, std::uint64_t count, const char* bytes)
  {
    if (share == this->Own || this->Into.empty() || this->Failure)
    {
      return;
    }
    try
    {
      writeShare(this->Into, this->Held, this->RunsOf(share), this->Keeps, first, count, bytes);
    }
    catch (...)
    {
      this->Failure = std::current_exception();
    }
  }
  void rethrow() const
  {
    if (this->Failure)
    {
      std::rethrow_exception(this->Failure);
    }
  }
};

// What a shared step computed: the fields it wrote, in the order a share
// carries them, and the grid's shape (none where it failed first); whether
// the shares hold their pieces of the fields (holdsPieceOf), so that each
// sends only the rows the pieces beside it hold.
struct SlabShare
{
  Fields Written;
  std::array<int, 3> Dimensions{};
  HeldVoxels Held;
  bool PiecesHeld = false;
};

// The voxels share `s` sends of its slab: all of it, or where the shares hold
// their pieces its first and last HeldPieceHalo rows z, all that the pieces
// beside hold of it (a piece's halo rows lie within that many rows of the
// slabs' edges, however thin the slabs).
Runs sentOf(const SlabShare& step, int s, int shares)
{
  const VoxelRange slab = shareSlab(step.Dimensions, s, shares);
  const std::size_t edge = static_cast<std::size_t>(step.Dimensions[0]) * static_cast<std::size_t>(step.Dimensions[1]) *
    static_cast<std::size_t>(HeldPieceHalo);
  if (!step.PiecesHeld || slab.second - slab.first <= 2 * edge)
  {
    return { slab };
  }
  return { { slab.first, slab.first + edge }, { slab.second - edge, slab.second } };
}

// Chunk `k` of `voxels` voxels of `runs` taken end to end: none past their end.
Runs chunkOf(const Runs& runs, std::size_t voxels, std::size_t k)
{
  Runs chunk;
  std::size_t skip = k * voxels, left = voxels;
  for (const auto& [first, end] : runs)
  {
    if (left == 0)
    {
      break;
    }
    if (skip >= end - first)
    {
      skip -= end - first;
      continue;
    }
    const std::size_t from = first + skip, to = std::min(end, from + left);
    chunk.emplace_back(from, to);
    left -= to - from;
    skip = 0;
  }
  return chunk;
}

std::size_t voxelsOf(const Runs& runs)
{
  std::size_t voxels = 0;
  for (const auto& [first, end] : runs)
  {
    voxels += end - first;
  }
  return voxels;
}

// What every share sends of its slab of the fields (sentOf: all of it, or
// its edge rows where the shares hold their pieces) to every other share, a
// chunk of each a round, each written into the fields as it arrives. False where a share
// stopped (the round then ended the exchange: `exchanging` false).
bool exchangeSlabs(const SlabShare& step, int share, int shares, const RenderSession::LayerExchange& round,
  bool& exchanging)
{
  std::uint64_t voxelBytes = 0;
  for (const auto& field : step.Written)
  {
    voxelBytes += field.second;
  }
  const std::size_t voxels = std::max<std::size_t>(1, ShareChunkBytes / std::max<std::uint64_t>(voxelBytes, 1));
  std::vector<Runs> sent;
  std::size_t rounds = 0; // alike on every share: the most any sends
  for (int s = 0; s < shares; ++s)
  {
    sent.push_back(sentOf(step, s, shares));
    rounds = std::max(rounds, (voxelsOf(sent.back()) + voxels - 1) / voxels);
  }
  for (std::size_t k = 0; k < rounds; ++k)
  {
    const std::vector<char> chunk = readShare(step.Written, step.Held, chunkOf(sent[static_cast<std::size_t>(share)], voxels, k));
    SharePlacer place{ step.Written, step.Held, share,
      [&](int from) { return chunkOf(sent.at(static_cast<std::size_t>(from)), voxels, k); }, {}, {} };
    exchanging = false; // a throw ends it too
    exchanging = round(chunk, std::ref(place));
    place.rethrow();
    if (!exchanging)
    {
      return false;
    }
  }
  return true;
}

// A shared step's part in the exchange, whole (shareLightPass,
// shareScatteredField): `compute` computes the share's slab, taking any
// rounds it needs through `round` (`exchanging` false once one ended the
// exchange), and says what it wrote (false: it stopped, an abort); the slabs
// then go to every share, and the last exchange ends it however the share
// ended. A failure is rethrown once the exchange is over. True where every
// share's slab arrived.
bool shareSlabs(const std::function<bool(SlabShare& step, bool& exchanging)>& compute, int share, int shares,
  const RenderSession::LayerExchange& round, const RenderSession::FieldExchange& last)
{
  SlabShare step;
  std::exception_ptr failure;
  bool exchanging = true;
  bool sent = false;
  try
  {
    sent = compute(step, exchanging) && exchanging && exchangeSlabs(step, share, shares, round, exchanging);
  }
  catch (...)
  {
    failure = std::current_exception();
    sent = false;
  }
  const auto ignore = [](int, std::uint64_t, std::uint64_t, const char*) {};
  const bool whole =
    exchanging && last(sent ? std::optional<std::vector<char>>(std::vector<char>{}) : std::nullopt, ignore);
  if (failure)
  {
    std::rethrow_exception(failure);
  }
  return sent && whole;
}
} // namespace

bool RenderSession::needsLightPass(const ResolvedFrame& frame) const
{
  if (!this->Volume)
  {
    return false;
  }
  return !(this->LightField && *this->LightField == lightFieldKey(this->setUpFrame(frame)));
}

namespace
{
// A share's layout as the processes compare it: each field's bytes per
// voxel, and the pieces held (`pieces`), which decide whether the walks go
// between the shares (holdsPieceOf), and so the shares' rounds, and which
// rows they exchange (sentOf).
std::string layoutOf(const Fields& fields, int pieces)
{
  std::string layout;
  for (const auto& field : fields)
  {
    layout += std::to_string(field.second) + " bytes per voxel; ";
  }
  return layout + "pieces held: " + std::to_string(pieces);
}
} // namespace

std::string RenderSession::lightPassLayout(const ResolvedFrame& frame) const
{
  return layoutOf(this->Volume ? this->lightPassFields(conservesEnergy(frame.Parameters)) : Fields{}, this->HeldPiece.second);
}

std::string RenderSession::scatteredFieldLayout() const
{
  return layoutOf(this->Volume ? this->scatteredFieldFields() : Fields{}, this->HeldPiece.second);
}

// The every-order field, the one field its shares carry.
std::vector<std::pair<VulkanBuffer*, std::uint64_t>> RenderSession::scatteredFieldFields() const
{
  return { { this->Volume->ScatteredLight.get(), sizeof(gpu::vec4) } };
}

// The light pass's per-voxel fields, in the order a share carries them, with
// their bytes per voxel: the light field, its absorption's where the volume
// absorbs, the Bragg shadows with `braggShadow`.
std::vector<std::pair<VulkanBuffer*, std::uint64_t>> RenderSession::lightPassFields(bool braggShadow) const
{
  const DeviceVolume& v = *this->Volume;
  const std::uint64_t light = v.PairedFields ? sizeof(gpu::LightFieldPair) : sizeof(gpu::vec2);
  Fields fields{ { v.LightField.get(), light } };
  if (v.Absorbs)
  {
    fields.emplace_back(v.LightAbsorption.get(), light);
  }
  if (braggShadow)
  {
    fields.emplace_back(v.LightShadow.get(), sizeof(gpu::LightShadow));
  }
  return fields;
}

bool RenderSession::shareLightPass(const ResolvedFrame& frame, int share, int shares, const FieldExchange& exchange,
  const LayerExchange& layer, const RenderProgress& callback)
{
  const auto start = Clock::now();
  std::optional<FrameSetup> setup;
  const bool shared = shareSlabs(
    [&](SlabShare& step, bool& exchanging) {
      setup = this->setUpSharedStep(frame);
      if (!this->holdsPieceOf(share, shares))
      {
        // Each walk to the light goes through the medium wherever it leads.
        this->requireWholeMedium("A light field shared by other processes than the march's");
      }
      this->LightField.reset();
      const bool piecesHeld = this->holdShareRows(share, shares, SweepHaloRows);
      this->prepareFrameBuffers(*setup); // the parameter block the pass reads
      this->resetForwardedLeft();
      const bool braggShadow = conservesEnergy(setup->Parameters);
      if (braggShadow)
      {
        this->prepareShadowField();
      }
      Progress progress(callback);
      progress.stage(0.0, FrameLightShare * (scattersEveryOrder(setup->Parameters) ? 0.5 : 1.0));
      const std::array<int, 3> dims = this->Volume->Shape.Dimensions;
      const std::pair<int, int> rows = shareRows(dims, share, shares);
      const DeviceVolume& v = *this->Volume;
      step = { this->lightPassFields(braggShadow), dims, { v.lightFirstVoxel(), v.lightFirstVoxel() + v.lightVoxels() },
        piecesHeld };
      const auto exchangeLayer = [&](int swept) {
        const std::vector<char> halo = readShare(step.Written, step.Held, haloOf(dims, rows, swept));
        SharePlacer place{ step.Written, step.Held, share,
          [&](int from) { return haloOf(dims, shareRows(dims, from, shares), swept); },
          [&](std::size_t voxel) { return readsRow(dims, rows, voxel); }, {} };
        exchanging = false; // a throw ends it too
        exchanging = layer(halo, std::ref(place));
        place.rethrow();
        return exchanging;
      };
      const VoxelRange slab = shareSlab(dims, share, shares);
      if (this->Volume->Medium.Geometry.lightAboveGrid(setup->Camera.Light))
      {
        return this->holdsPieceOf(share, shares)
          ? this->sweepLightShared(braggShadow, progress, rows, exchangeLayer, layer, exchanging)
          : this->sweepLightLayers(braggShadow, progress, rows, exchangeLayer);
      }
      return this->holdsPieceOf(share, shares)
        ? this->marchLightShared(braggShadow, progress, layer, exchanging)
        : this->dispatchOverVoxels(this->lightPass(gpu::LightPassMarchTowardsLight, braggShadow), this->SlabPacer,
            progress.stageCallback(), slab.first, slab.second);
    },
    share, shares, layer, exchange);
  if (!shared)
  {
    return false;
  }
  this->requireForwardedFinished("light pass");
  this->LightField = lightFieldKey(*setup);
  this->PendingLightSeconds = secondsSince(start);
  return true;
}

// Whether a shared light pass's shares are the pieces this session holds
// (holdPiece: a march shared by processes, the data-parallel render): its
// walks to the light then go between the shares (OpalSharedLightWalks.cxx).
bool RenderSession::holdsPieceOf(int share, int shares) const
{
  return shares > 1 && this->HeldPiece == std::make_pair(share, shares);
}

bool RenderSession::needsScatteredField(const ResolvedFrame& frame) const
{
  if (!this->Volume || !scattersEveryOrder(frame.Parameters))
  {
    return false;
  }
  const FrameSetup setup = this->setUpFrame(frame);
  const DeviceVolume& v = *this->Volume;
  return this->scatteredLightServes(setup) && !setup.ScatteredLightFromGrid &&
    (v.ScatteredFieldPending || !v.HasScatteredField);
}

bool RenderSession::shareScatteredField(const ResolvedFrame& frame, int share, int shares,
  const FieldExchange& exchange, const LayerExchange& round)
{
  const auto start = Clock::now();
  const bool shared = shareSlabs(
    [&](SlabShare& step, bool&) {
      const FrameSetup setup = this->setUpSharedStep(frame);
      const std::array<int, 3> dims = this->Volume->Shape.Dimensions;
      // Each voxel's field reads its own cell alone.
      this->requireMediumOf(shareSlab(dims, share, shares), "The every-order field's writing of a slab");
      const bool piecesHeld = this->holdShareRows(share, shares, 0);
      this->placeScatteredField(setup);
      this->prepareFrameBuffers(setup); // the parameter block the pass reads (the tally grid's shape)
      const DeviceVolume& v = *this->Volume;
      step = { this->scatteredFieldFields(), dims, { v.lightFirstVoxel(), v.lightFirstVoxel() + v.lightVoxels() },
        piecesHeld };
      const VoxelRange slab = shareSlab(dims, share, shares);
      return this->dispatchOverVoxels(this->lightPass(gpu::LightPassScatteredField, false), this->FieldPacer, nullptr,
        slab.first, slab.second);
    },
    share, shares, round, exchange);
  if (shared)
  {
    this->Volume->ScatteredFieldPending = false;
    this->PendingFieldSeconds = secondsSince(start);
  }
  return shared;
}

} // namespace opal
