// The medium the every-order solve reads (docs/design.md §3.10), read back
// from the device: whole, or, where processes share the solve (§8.1), each
// share's slab of it read back alone and the slabs exchanged, so that every
// share holds the whole medium without reading its device beyond its slab.
#include "OpalRenderSession.h"

#include "OpalRenderSessionState.h"
#include "OpalShareSlabs.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace opal
{

using namespace sessiondetail;

namespace
{
// The medium's values the solve reads, one per voxel of the whole grid.
struct MediumValues
{
  std::vector<float> Scattering, SurfaceDistance;
  std::vector<glm::vec2> Absorption; // empty: nothing absorbs

  MediumValues(std::size_t voxels, bool absorbs)
    : Scattering(voxels)
    , SurfaceDistance(voxels)
    , Absorption(absorbs ? voxels : 0)
  {
  }
  // Each array's first byte and bytes per voxel, in the order a share's bytes carry them.
  std::vector<std::pair<char*, std::size_t>> columns()
  {
    std::vector<std::pair<char*, std::size_t>> columns{ { reinterpret_cast<char*>(this->Scattering.data()), sizeof(float) },
      { reinterpret_cast<char*>(this->SurfaceDistance.data()), sizeof(float) } };
    if (!this->Absorption.empty())
    {
      columns.emplace_back(reinterpret_cast<char*>(this->Absorption.data()), sizeof(glm::vec2));
    }
    return columns;
  }
};

// A value of each of a device field's records of `voxels`, read back round by
// round into `into` at the voxels' places; the field holds voxels from `held` on.
template <typename Record, typename Value>
void readEach(const VulkanBuffer& buffer, std::size_t held, VoxelRange voxels, float* into, Value&& value)
{
  buffer.readRange((voxels.first - held) * sizeof(Record), (voxels.second - voxels.first) * sizeof(Record),
    [into, voxels, &value](std::uint64_t first, std::uint64_t bytes, const void* from) {
      const auto* records = static_cast<const Record*>(from);
      float* to = into + voxels.first + first / sizeof(Record);
      for (std::size_t i = 0; i < bytes / sizeof(Record); ++i) to[i] = value(records[i]);
    });
}

// The device's medium of `voxels`: the cells' scattering coefficients, the
// absorption cells and SurfaceDistance (all held from voxel `held` on),
// each voxel's its pair's first value where `paired` (the second is its +x
// neighbour's).
void readMedium(const VulkanBuffer& cells, const VulkanBuffer& absorption, std::size_t held, const VulkanBuffer& surface,
  bool paired, VoxelRange voxels, MediumValues& into)
{
  readEach<gpu::VoxelCell>(
    cells, held, voxels, into.Scattering.data(), [](const gpu::VoxelCell& cell) { return cell.scattering; });
  if (paired)
  {
    readEach<gpu::vec2>(surface, held, voxels, into.SurfaceDistance.data(), [](const gpu::vec2& pair) { return pair.x; });
  }
  else
  {
    readEach<float>(surface, held, voxels, into.SurfaceDistance.data(), [](float value) { return value; });
  }
  if (!into.Absorption.empty())
  {
    absorption.readRange((voxels.first - held) * sizeof(glm::vec2), (voxels.second - voxels.first) * sizeof(glm::vec2),
      [&into, voxels](std::uint64_t first, std::uint64_t count, const void* from) {
        std::memcpy(reinterpret_cast<char*>(into.Absorption.data() + voxels.first) + first, from, count);
      });
  }
}

// The bytes of `voxels` of `values`: each array's, array after array.
std::vector<char> bytesOf(MediumValues& values, VoxelRange voxels)
{
  std::vector<char> bytes;
  for (const auto& [base, size] : values.columns())
  {
    bytes.insert(bytes.end(), base + voxels.first * size, base + voxels.second * size);
  }
  return bytes;
}

// The bytes bytesOf gives for `voxels`.
std::uint64_t bytesFor(MediumValues& values, VoxelRange voxels)
{
  std::uint64_t bytes = 0;
  for (const auto& column : values.columns())
  {
    bytes += (voxels.second - voxels.first) * column.second;
  }
  return bytes;
}

// Bytes [first, first + count) of those bytesOf gives for `voxels`, copied into `values`.
void place(MediumValues& values, VoxelRange voxels, std::uint64_t first, std::uint64_t count, const char* bytes)
{
  const std::size_t n = voxels.second - voxels.first;
  std::uint64_t start = 0; // an array's first byte among the chunk's
  for (const auto& [base, size] : values.columns())
  {
    const std::uint64_t end = start + n * size;
    const std::uint64_t from = std::max(first, start), to = std::min(first + count, end);
    if (from < to)
    {
      std::memcpy(base + voxels.first * size + (from - start), bytes + (from - first), to - from);
    }
    start = end;
  }
  if (first + count > start)
  {
    throw std::runtime_error("A share's chunk of the every-order solve's medium is longer than its voxels' values.");
  }
}

// Every share's slab of `values` to every other share, a chunk of each a
// round (as the light field's, ShareChunkBytes), each placed as it arrives.
// False where a share stopped (the round ended the exchange: `exchanging` false).
bool exchangeMedium(MediumValues& values, const std::array<int, 3>& dims, int share, int shares,
  const RenderSession::LayerExchange& round, bool& exchanging)
{
  const std::size_t voxels = ShareChunkBytes / bytesFor(values, { 0, 1 });
  const std::size_t rounds = slabChunks(dims, shares, voxels); // alike on every share
  for (std::size_t k = 0; k < rounds; ++k)
  {
    std::exception_ptr failure;
    std::vector<std::uint64_t> arrived(static_cast<std::size_t>(shares), 0);
    const RenderSession::ShareSink placed = [&](int from, std::uint64_t first, std::uint64_t count, const char* bytes) {
      try
      {
        place(values, slabChunk(shareSlab(dims, from, shares), voxels, k), first, count, bytes);
        arrived.at(static_cast<std::size_t>(from)) += count;
      }
      catch (...)
      {
        failure = std::current_exception(); // thrown once the round is over, not inside the exchange
      }
    };
    const std::vector<char> mine = bytesOf(values, slabChunk(shareSlab(dims, share, shares), voxels, k));
    exchanging = false; // a throw ends it too
    exchanging = round(mine, placed);
    if (failure)
    {
      std::rethrow_exception(failure);
    }
    if (!exchanging)
    {
      return false;
    }
    for (int from = 0; from < shares; ++from)
    {
      const std::uint64_t expected = bytesFor(values, slabChunk(shareSlab(dims, from, shares), voxels, k));
      if (from != share && arrived[static_cast<std::size_t>(from)] != expected)
      {
        throw std::runtime_error("Share " + std::to_string(from) + " sent " +
          std::to_string(arrived[static_cast<std::size_t>(from)]) + " bytes of its chunk of the every-order solve's "
          "medium, not its voxels' " + std::to_string(expected) + ".");
      }
    }
  }
  return true;
}
} // namespace

// The medium the every-order solve reads: its fields read back from the
// device's cells (and absorption cells) and SurfaceDistance for each solve
// and released after it (releaseScatteringMedium), so the host holds them (8
// bytes per voxel, 16 with absorption) only while a solve runs, not beside the
// frame's field; its tally nodes' volumes, a few MB, are kept for every later
// light (docs/design.md §3.10).
const ScatteringMedium& RenderSession::scatteringMedium()
{
  bool exchanging = true;
  return *this->shareScatteringMedium(0, 1, nullptr, exchanging);
}

// The same, of share `share` of `shares` sharing a solve: the device's medium
// of its slab read back, the other shares' slabs arriving through `round`.
// Null where a share stopped (the round ended the exchange).
const ScatteringMedium* RenderSession::shareScatteringMedium(
  int share, int shares, const LayerExchange& round, bool& exchanging)
{
  DeviceVolume& v = *this->Volume;
  const std::array<int, 3> dims = v.Shape.Dimensions;
  // Read whole before it is kept: a read that throws (its staging round
  // beyond the memory limit, say) leaves no half-read medium for a later solve.
  const VoxelRange slab = shareSlab(dims, share, shares);
  this->requireMediumOf(slab, "An every-order solve shared by other processes than the march's");
  MediumValues values(v.Shape.voxelCount(), v.Absorbs);
  readMedium(*v.Cells, *v.AbsorptionCells, v.mediumFirstVoxel(), *v.SurfaceDistance, v.PairedFields, slab, values);
  if (shares > 1 && !exchangeMedium(values, dims, share, shares, round, exchanging))
  {
    return nullptr;
  }
  // Refused where the values' signs disagree with the inside bits (a share's bytes misplaced, say).
  v.Medium.Geometry.setSurfaceDistance(std::move(values.SurfaceDistance));
  if (v.Medium.NodeVolumes.empty())
  {
    v.Medium.NodeVolumes = scatteredLightNodeVolumes(v.Medium.Geometry);
  }
  v.Medium.Scattering = std::move(values.Scattering);
  v.Medium.Absorption = std::move(values.Absorption);
  return &v.Medium;
}

void RenderSession::releaseScatteringMedium()
{
  if (!this->Volume)
  {
    return;
  }
  ScatteringMedium& medium = this->Volume->Medium;
  std::vector<float>().swap(medium.Scattering);
  std::vector<glm::vec2>().swap(medium.Absorption);
  medium.Geometry.releaseSurfaceDistance();
}

} // namespace opal
