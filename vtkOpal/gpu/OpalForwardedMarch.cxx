// The view march with its rays forwarded between pieces of the volume, slabs
// of layers z (docs/design.md §8.1): the host's side, in one process
// (VulkanOptions::MarchPieces), as the data-parallel render is to forward
// rays between ranks.
#include "OpalRenderSession.h"

#include "OpalParallel.h"
#include "OpalRenderSessionState.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace opal
{

using namespace sessiondetail;

// Records the march's `work` over groupsX x groupsY workgroups: one
// dispatch, or, forwarded (MarchPieces above 1, docs/design.md §8.1), one
// per piece of layers z, the pieces in order, back, in order and back again
// (4N - 3 dispatches). A ray's points move along z one way while it traces
// its entry, may step back (a piece or more) to where its walk begins, and move one
// way while it walks: four sweeps take every ray from the piece it starts in
// to the one it leaves from. With MarchPieceFieldsOnly each dispatch finds
// only its piece's fields (recordPieceFields), the whole fields back after the last.
void RenderSession::recordMarch(VkCommandBuffer commands, const ComputePipeline& march, const gpu::MarchWork& work,
  std::uint32_t groupsX, std::uint32_t groupsY) const
{
  gpu::MarchWork pieceWork = work;
  const int pieces = this->MarchPieces;
  const std::vector<FieldCopy> copies = this->marchFieldCopies();
  for (const FieldCopy& copy : copies)
  {
    copy.Whole->recordCopyFrom(commands, *copy.Field, 0, copy.Field->size());
  }
  const int period = 2 * pieces - 2;
  for (int pass = 0; pass < std::max(2 * period + 1, 1); ++pass)
  {
    const int at = period > 0 ? pass % period : 0;
    const int piece = at < pieces ? at : period - at;
    const std::pair<int, int> layers = evenShare(this->Volume->Shape.Dimensions[2], piece, pieces);
    this->recordPieceFields(commands, copies, layers);
    pieceWork.piece = gpu::ivec2(layers.first, layers.second);
    pieceWork.resumed = pass > 0 ? 1 : 0;
    march.dispatch(commands, pieceWork, groupsX, groupsY);
  }
  for (const FieldCopy& copy : copies)
  {
    copy.Field->recordCopyFrom(commands, *copy.Whole, 0, copy.Field->size());
  }
}

// The fields the view march reads per voxel, with their bytes per voxel and
// the layers z beyond a piece its reads take (docs/design.md §8.1): the
// cells, the absorption's, the light pass's and the every-order field one
// (the light field's trilinear read); SurfaceDistance ViewTraceLayers + 2
// (the view traces' steps, their bisection and the normal at the entry).
std::vector<RenderSession::FieldCopy> RenderSession::marchFields() const
{
  const DeviceVolume& v = *this->Volume;
  std::vector<std::pair<VulkanBuffer*, std::uint64_t>> fields = this->lightPassFields(v.HasShadowField);
  fields.emplace_back(v.Cells.get(), sizeof(gpu::VoxelCell));
  if (v.Absorbs)
  {
    fields.emplace_back(v.AbsorptionCells.get(), sizeof(gpu::vec2));
  }
  if (v.HasScatteredField)
  {
    const auto scattered = this->scatteredFieldFields();
    fields.insert(fields.end(), scattered.begin(), scattered.end());
  }
  std::vector<FieldCopy> copies;
  for (const auto& [field, bytes] : fields)
  {
    copies.push_back({ field, bytes, 1, nullptr });
  }
  copies.push_back(
    { v.SurfaceDistance.get(), v.PairedFields ? sizeof(gpu::vec2) : sizeof(float), gpu::ViewTraceLayers + 2, nullptr });
  return copies;
}

// With MarchPieceFieldsOnly and MarchPieces above 1, a buffer for the whole
// of each of the march's fields (marchFields), made for each march region
// (a test's option, so kept simple); none otherwise.
void RenderSession::prepareMarchFieldCopies()
{
  this->WholeFields.clear();
  if (!this->MarchPieceFieldsOnly || this->MarchPieces <= 1)
  {
    return;
  }
  for (const FieldCopy& copy : this->marchFields())
  {
    this->WholeFields.push_back(
      std::make_unique<VulkanBuffer>(*this->Context, copy.Field->size(), "whole field", this->Volume->FieldPlacement));
  }
}

// The march's fields with their whole copies (prepareMarchFieldCopies).
std::vector<RenderSession::FieldCopy> RenderSession::marchFieldCopies() const
{
  if (this->WholeFields.empty())
  {
    return {};
  }
  std::vector<FieldCopy> copies = this->marchFields();
  for (std::size_t i = 0; i < copies.size(); ++i)
  {
    copies[i].Whole = this->WholeFields.at(i).get();
  }
  return copies;
}

// Records: each field zeroed but for the piece's layers and its halo on
// either side, which take the whole field's values: a rank that holds only
// its piece lacks the rest, so a march reading beyond would change the image
// (TestOpalForwardedMarch).
void RenderSession::recordPieceFields(
  VkCommandBuffer commands, const std::vector<FieldCopy>& copies, std::pair<int, int> layers) const
{
  const std::array<int, 3>& dims = this->Volume->Shape.Dimensions;
  for (const FieldCopy& copy : copies)
  {
    const int first = std::max(layers.first - copy.Halo, 0), last = std::min(layers.second + copy.Halo, dims[2]);
    const std::uint64_t layerBytes = static_cast<std::uint64_t>(dims[0]) * static_cast<std::uint64_t>(dims[1]) * copy.VoxelBytes;
    // The last layer's copy runs to the buffer's end: an unpaired field's
    // read of a voxel and the next one (the grid's last voxel has none) may pass it.
    const std::uint64_t begin = first * layerBytes;
    const std::uint64_t end = last == dims[2] ? copy.Field->size() : last * layerBytes;
    copy.Field->recordClear(commands);
    if (first < last)
    {
      copy.Field->recordCopyFrom(commands, *copy.Whole, begin, end - begin);
    }
  }
}

// The spectral nodes the march sums the body's scattering on: 0 where it
// takes every wavelength (SpectralNodes 0, or no fewer bins than nodes).
int RenderSession::marchNodes(const FrameSetup& setup)
{
  const int wavelengths = static_cast<int>(setup.Bins.size());
  const int nodes = setup.Parameters.SpectralNodes;
  return nodes == 0 || wavelengths <= nodes ? 0 : nodes;
}

// A forwarded march's ray states for the largest dispatch over `rect`: its
// bands' pixels, its ring's or its queued pixels'; none unforwarded.
std::uint64_t RenderSession::rayStateBytes(const FrameSetup& setup, const std::array<int, 4>& rect) const
{
  if (this->MarchPieces <= 1)
  {
    return 0;
  }
  constexpr std::uint64_t groupPixels = gpu::MarchGroupSide * gpu::MarchGroupSide;
  const auto roundUp = [&](std::uint64_t n) { return (n + groupPixels - 1) / groupPixels * groupPixels; };
  const std::uint64_t slots =
    std::max({ static_cast<std::uint64_t>(marchGroups(rect[2])) * static_cast<std::uint64_t>(marchGroups(rect[3])) * groupPixels,
      roundUp(static_cast<std::uint64_t>(MARCH_RING_PIXELS(rect[2], rect[3]))),
      roundUp(static_cast<std::uint64_t>(rect[2]) * static_cast<std::uint64_t>(rect[3])) });
  const int wavelengths = static_cast<int>(setup.Bins.size());
  const int nodes = marchNodes(setup) == 0 ? 4 : marchNodes(setup);
  return slots * RAY_STATE_WORDS(wavelengths, nodes) * sizeof(std::uint32_t);
}

// The frame's largest march: over its region or the exposure's thumbnail.
std::uint64_t RenderSession::frameRayStateBytes(const FrameSetup& setup) const
{
  return std::max(
    this->rayStateBytes(setup, setup.Region), this->rayStateBytes(setup, { 0, 0, setup.Thumbnail[0], setup.Thumbnail[1] }));
}

// The ray states of rayStateBytes, grown as the pixel buffers are (and bound
// again); a refused allocation keeps the buffer bound before.
void RenderSession::prepareRayStates(const FrameSetup& setup, const std::array<int, 4>& rect)
{
  const std::uint64_t bytes = this->rayStateBytes(setup, rect);
  if (this->Buffers->RayStates->size() < bytes)
  {
    auto grown = std::make_unique<VulkanBuffer>(*this->Context, bytes, "forwarded rays", BufferPlacement::DeviceLocal);
    this->Buffers->RayStates = std::move(grown);
    this->bindBuffers();
  }
}

} // namespace opal
