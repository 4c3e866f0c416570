// The light field computed by several processes together, each a share of
// the voxels, before their frames (docs/design.md §8.1).
#include "OpalRenderSession.h"

#include "OpalRenderSessionState.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <exception>
#include <functional>
#include <optional>
#include <stdexcept>
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
  const auto rowAt = [&](int s) { return static_cast<int>(static_cast<std::int64_t>(dims[2]) * s / shares); };
  return { rowAt(share), rowAt(share + 1) };
}

// Voxel ranges [first, end), in the order a share's bytes carry them.
using Runs = std::vector<std::pair<std::size_t, std::size_t>>;

// The voxels of rows z [rows.first, rows.second) of every layer: one range.
Runs slabOf(const std::array<int, 3>& dims, std::pair<int, int> rows)
{
  const std::size_t slab = static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]);
  return { { slab * static_cast<std::size_t>(rows.first), slab * static_cast<std::size_t>(rows.second) } };
}

// The sweep's halo (docs/design.md §8.1): lightAboveGrid bounds a path's
// sideways move per layer below half a voxel, so the node nearest to where a
// voxel's path crosses the layer above is in the voxel's own row z, and its
// 3 x 3 read spans rows z - 1 to z + 1; a second row keeps a margin for the
// shader's rounding.
constexpr int HaloRows = 2;

// Layer `layer`'s first and last HaloRows rows of `rows` (all of them where
// fewer), one range each: what the shares beside read of it.
Runs haloOf(const std::array<int, 3>& dims, std::pair<int, int> rows, int layer)
{
  const auto nx = static_cast<std::size_t>(dims[0]);
  Runs runs;
  for (int z = rows.first; z < rows.second; ++z)
  {
    if (z < rows.first + HaloRows || z >= rows.second - HaloRows)
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
  return (z >= rows.first - HaloRows && z < rows.first) || (z >= rows.second && z < rows.second + HaloRows);
}

using Fields = std::vector<std::pair<VulkanBuffer*, std::uint64_t>>;

// Bytes of `runs`: each field's records of each run, field after field.
std::vector<char> readShare(const Fields& fields, const Runs& runs)
{
  std::vector<char> bytes;
  for (const auto& [buffer, record] : fields)
  {
    for (const auto& [first, end] : runs)
    {
      const std::size_t at = bytes.size();
      bytes.resize(at + (end - first) * record);
      buffer->readRange(first * record, (end - first) * record,
        [&bytes, at](std::uint64_t from, std::uint64_t count, const void* data) {
          std::memcpy(bytes.data() + at + from, data, count);
        });
    }
  }
  return bytes;
}

// Whether a run (by its first voxel) is written where it arrives; none: all.
using Wanted = std::function<bool(std::size_t firstVoxel)>;

// Bytes [first, first + count) of `runs` (as readShare lays them out)
// written into the fields, a run's part at a time, the runs `wanted` only.
void writeShare(const Fields& fields, const Runs& runs, const Wanted& wanted, std::uint64_t first, std::uint64_t count,
  const char* bytes)
{
  std::uint64_t runStart = 0;
  for (const auto& [buffer, record] : fields)
  {
    for (const auto& [voxel, end] : runs)
    {
      const std::uint64_t runBytes = (end - voxel) * record;
      const std::uint64_t from = std::max(first, runStart), to = std::min(first + count, runStart + runBytes);
      if (from < to && (!wanted || wanted(voxel)))
      {
        buffer->write(voxel * record + (from - runStart), to - from, bytes + (from - first));
      }
      runStart += runBytes;
    }
  }
}

// A sink that writes the other shares' runs into the fields, keeping the
// first failure to rethrow once the exchange is over (a throw inside it
// would leave the processes' exchange midway).
struct SharePlacer
{
  const Fields& Into;
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
      writeShare(this->Into, this->RunsOf(share), this->Keeps, first, count, bytes);
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
} // namespace

bool RenderSession::needsLightPass(const ResolvedFrame& frame) const
{
  if (!this->Volume)
  {
    return false;
  }
  const FrameSetup setup = this->setUpFrame(frame);
  this->checkMemoryBudget(setup);
  return !(this->LightField && *this->LightField == lightFieldKey(setup));
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
  std::optional<std::vector<char>> mine;
  std::exception_ptr failure;
  Fields fields; // none until known: other shares' bytes then go nowhere
  bool exchanging = true; // false once a layer's exchange ended the exchange
  try
  {
    this->cancelFrame();
    this->LightField.reset();
    this->requireVolume();
    setup = this->setUpFrame(frame);
    this->checkMemoryBudget(*setup);
    this->prepareFrameBuffers(*setup); // the parameter block the pass reads
    const bool braggShadow = conservesEnergy(setup->Parameters);
    if (braggShadow)
    {
      this->prepareShadowField();
    }
    Progress progress(callback);
    progress.stage(0.0, FrameLightShare * (scattersEveryOrder(setup->Parameters) ? 0.5 : 1.0));
    const std::array<int, 3> dims = this->Volume->Shape.Dimensions;
    const std::pair<int, int> rows = shareRows(dims, share, shares);
    fields = this->lightPassFields(braggShadow);
    const auto exchangeLayer = [&](int swept) {
      std::vector<char> halo = readShare(fields, haloOf(dims, rows, swept));
      SharePlacer place{ fields, share, [&](int from) { return haloOf(dims, shareRows(dims, from, shares), swept); },
        [&](std::size_t voxel) { return readsRow(dims, rows, voxel); }, {} };
      exchanging = false; // a throw ends it too
      exchanging = layer(halo, std::ref(place));
      place.rethrow();
      return exchanging;
    };
    const Runs slab = slabOf(dims, rows);
    const bool computed = this->Volume->Medium.Geometry.lightAboveGrid(setup->Camera.Light)
      ? this->sweepLightLayers(braggShadow, progress, rows, exchangeLayer)
      : this->dispatchOverVoxels(this->lightPass(gpu::LightPassMarchTowardsLight, braggShadow), this->SlabPacer,
          progress.stageCallback(), slab.front().first, slab.front().second);
    if (computed)
    {
      mine = readShare(fields, slab);
    }
  }
  catch (...)
  {
    failure = std::current_exception();
    mine.reset();
    fields.clear();
  }
  SharePlacer place{ fields, share,
    [&](int from) { return slabOf(this->Volume->Shape.Dimensions, shareRows(this->Volume->Shape.Dimensions, from, shares)); },
    {}, {} };
  const bool whole = exchanging && exchange(mine, std::ref(place));
  if (!failure)
  {
    failure = place.Failure;
  }
  if (failure)
  {
    std::rethrow_exception(failure);
  }
  if (!mine || !whole)
  {
    return false;
  }
  this->LightField = lightFieldKey(*setup);
  this->PendingLightSeconds = secondsSince(start);
  return true;
}

} // namespace opal
