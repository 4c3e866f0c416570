// A share's slab of the voxels and its chunks (docs/design.md §8.1): a step
// shared by processes computes share s's rows z of every layer (evenShare),
// one range of voxels, in chunks taken alike on every share.
#pragma once

#include "OpalParallel.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace opal
{
namespace sessiondetail
{
// A round of a slabs' exchange carries this much of each share's slab: the
// slab whole in one exchange was a copy of it held beside the fields (8 to
// 44 bytes per voxel of the share: 41 MB a rank on 4 ranks at 320 x 160 x
// 400 with the light field alone).
constexpr std::uint64_t ShareChunkBytes = std::uint64_t(4) << 20;

// Voxels [first, second).
using VoxelRange = std::pair<std::size_t, std::size_t>;

// Share `share` of `shares`: its rows z of every layer, one range of voxels.
inline VoxelRange shareSlab(const std::array<int, 3>& dims, int share, int shares)
{
  const std::pair<int, int> rows = evenShare(dims[2], share, shares);
  const std::size_t layer = static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]);
  return { layer * static_cast<std::size_t>(rows.first), layer * static_cast<std::size_t>(rows.second) };
}

// Chunk `k` of `voxels` voxels of `slab`: empty past its end.
inline VoxelRange slabChunk(VoxelRange slab, std::size_t voxels, std::size_t k)
{
  const std::size_t first = std::min(slab.first + k * voxels, slab.second);
  return { first, std::min(first + voxels, slab.second) };
}

// The chunks of `voxels` voxels of the largest share's slab (⌈nz / N⌉ rows):
// the count every share takes, so that their rounds stay alike.
inline std::size_t slabChunks(const std::array<int, 3>& dims, int shares, std::size_t voxels)
{
  const std::size_t layer = static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]);
  const auto rows = static_cast<std::size_t>(mostInShare(dims[2], shares));
  return (layer * rows + voxels - 1) / voxels;
}
} // namespace sessiondetail
} // namespace opal
