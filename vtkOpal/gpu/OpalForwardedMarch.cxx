// The view march's rays and the light pass's walks to the light forwarded
// between pieces of the volume, slabs of layers z (docs/design.md §8.1): the
// host's side, in one process (VulkanOptions::MarchPieces), as the
// data-parallel render is to forward them between ranks.
#include "OpalRenderSession.h"

#include "OpalParallel.h"
#include "OpalRenderSessionState.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace opal
{

using namespace sessiondetail;

// Records the march's `work` over groupsX x groupsY workgroups: one
// dispatch, or, forwarded (MarchPieces above 1, docs/design.md §8.1), one
// per pass of recordPiecePasses. A ray's points move along z one way while
// it traces its entry, may step back (a piece or more) to where its walk
// begins, and move one way while it walks: four sweeps take every ray from
// the piece it starts in to the one it leaves from.
void RenderSession::recordMarch(VkCommandBuffer commands, const ComputePipeline& march, const gpu::MarchWork& work,
  std::uint32_t groupsX, std::uint32_t groupsY) const
{
  this->recordPiecePasses(commands, this->pieceFields(), this->Sweeps.March,
    [&](const PiecePass& pass) { march.dispatch(commands, pass.of(work), groupsX, groupsY); });
}

// The passes of a pass forwarded through MarchPieces pieces of layers z: the
// pieces in order, back, in order and so on, `sweeps` sweeps ((N - 1) sweeps
// + 1 passes; one over all layers unforwarded). With MarchPieceFieldsOnly
// each pass reads and writes its piece's `fields` alone (recordPieceFields,
// recordWrittenBack), the whole fields' addresses back after the last.
void RenderSession::recordPiecePasses(VkCommandBuffer commands, const std::vector<PieceField>& fields, int sweeps,
  const std::function<void(const PiecePass& pass)>& dispatch) const
{
  const int pieces = this->MarchPieces;
  const int period = 2 * pieces - 2;
  const int passes = sweeps * (pieces - 1) + 1;
  for (int pass = 0; pass < passes; ++pass)
  {
    const int at = period > 0 ? pass % period : 0;
    const int piece = at < pieces ? at : period - at;
    const std::pair<int, int> layers = evenShare(this->Volume->Shape.Dimensions[2], piece, pieces);
    this->recordPieceFields(commands, fields, layers);
    dispatch(PiecePass{ layers, pass > 0, pass + 1 == passes });
    this->recordWrittenBack(commands, fields, layers);
  }
  this->recordWholeFields(commands, fields);
}

// With MarchPieces, the count of states the forwarded passes' last
// dispatches leave unfinished set to 0, before a pass's first submit (its
// dispatches add to it: countUnfinished in opal_kept_state.glsl).
void RenderSession::resetForwardedLeft()
{
  if (this->MarchPieces > 1)
  {
    const std::uint32_t none = 0;
    this->Buffers->ForwardedLeft->write(0, sizeof(none), &none);
  }
}

// With MarchPieces, throws naming `pass` where its forwarded passes left a
// state unfinished since resetForwardedLeft: a path the sweeps' schedule does
// not bound, whose partial result no frame gives (docs/design.md §8.1).
void RenderSession::requireForwardedFinished(const std::string& pass) const
{
  if (this->MarchPieces <= 1)
  {
    return;
  }
  std::uint32_t left = 0;
  this->Buffers->ForwardedLeft->read(sizeof(left),
    [&](std::uint64_t, std::uint64_t count, const void* from) { std::memcpy(&left, from, count); });
  if (left > 0)
  {
    throw std::runtime_error("The " + pass + " forwarded through " + std::to_string(this->MarchPieces) +
      " pieces left " + std::to_string(left) + " of its states unfinished after its last pass; no image is given.");
  }
}

// Records the sweep from above of layer y = `layer`'s rows z `rows`: one
// dispatch per piece of them of `pieces` (one; MarchPieces; a shared light
// pass's shares, whose rows are this share's piece), each reading and
// writing its piece's `fields` alone (sweepPieceFields), as a rank holding
// its piece does (docs/design.md §8.1).
void RenderSession::recordSweepLayer(VkCommandBuffer commands, const ComputePipeline& sweep,
  const std::vector<PieceField>& fields, std::pair<int, int> rows, int layer, int pieces) const
{
  const std::array<int, 3>& dims = this->Volume->Shape.Dimensions;
  for (int piece = 0; piece < pieces; ++piece)
  {
    const std::pair<int, int> layers = evenShare(dims[2], piece, pieces);
    const int first = std::max(rows.first, layers.first), end = std::min(rows.second, layers.second);
    if (first >= end)
    {
      continue;
    }
    this->recordPieceFields(commands, fields, layers);
    const std::int64_t voxels = static_cast<std::int64_t>(dims[0]) * (end - first);
    sweep.dispatch(commands, gpu::LightPassWork{ static_cast<std::uint32_t>(first), end - first, layer, 0, gpu::ivec2(0, 0), 0, 0 },
      static_cast<std::uint32_t>((voxels + gpu::LightPassGroupSize - 1) / gpu::LightPassGroupSize));
    this->recordWrittenBack(commands, fields, layers);
  }
  this->recordWholeFields(commands, fields);
}

// Records the address table pointing at the whole fields again, after
// passes that read `fields`' pieces (none: nothing to restore).
void RenderSession::recordWholeFields(VkCommandBuffer commands, const std::vector<PieceField>& fields) const
{
  if (!fields.empty())
  {
    const gpu::VolumeAddresses whole = this->volumeAddresses({});
    this->Volume->Addresses->recordWrite(commands, &whole, sizeof(whole));
  }
}

// The fields the view march reads per voxel, with their bytes per voxel and
// the layers z beyond a piece its reads take (docs/design.md §8.1): the
// cells, the absorption's, the light pass's and the every-order field one
// (the light field's trilinear read); SurfaceDistance TraceStepLayers + 2
// (the view traces' steps, their bisection and the normal at the entry).
std::vector<RenderSession::PieceField> RenderSession::marchFields() const
{
  const DeviceVolume& v = *this->Volume;
  // Fields held by piece (holdPiece) hold no more than their piece already.
  const bool wholeHeld = v.LightLayers == std::make_pair(0, v.Shape.Dimensions[2]);
  std::vector<std::pair<VulkanBuffer*, std::uint64_t>> fields;
  if (wholeHeld)
  {
    fields = this->pieceHeldFields();
  }
  if (v.mediumWhole())
  {
    const auto medium = this->mediumFields();
    fields.insert(fields.end(), medium.begin(), medium.end());
  }
  std::vector<PieceField> pieceFields;
  for (const auto& [field, bytes] : fields)
  {
    pieceFields.push_back({ field, bytes, field == v.SurfaceDistance.get() ? gpu::TraceStepLayers + 2 : 1, nullptr, false });
  }
  return pieceFields;
}

// A piece's layers of a field and its halo, clamped to the grid, as bytes
// [first, second) of the whole field; the last layer's run goes to the
// field's end (a buffer holds at least 16 bytes).
std::pair<std::uint64_t, std::uint64_t> RenderSession::pieceBytes(const PieceField& field, std::pair<int, int> layers) const
{
  const std::array<int, 3>& dims = this->Volume->Shape.Dimensions;
  const int first = std::max(layers.first - field.Halo, 0), last = std::min(layers.second + field.Halo, dims[2]);
  const std::uint64_t layerBytes = static_cast<std::uint64_t>(dims[0]) * static_cast<std::uint64_t>(dims[1]) * field.VoxelBytes;
  return { first * layerBytes, last == dims[2] ? field.Whole->size() : std::max(first, last) * layerBytes };
}

// With MarchPieceFieldsOnly and `pieces` above 1 (MarchPieces, a shared
// march's or a shared light pass's shares), a buffer per field of the march
// (marchFields) for the largest piece's layers and halo (the march's or the
// walks to the light's, the larger), made for each march region and light
// pass (a test's option, so kept simple); none otherwise.
void RenderSession::preparePieceFields(int pieces)
{
  this->PieceFieldBuffers.clear();
  if (!this->MarchPieceFieldsOnly || pieces <= 1)
  {
    return;
  }
  const int layers = this->Volume->Shape.Dimensions[2];
  for (PieceField field : this->marchFields())
  {
    field.Halo = std::max(field.Halo, MediumHaloLayers); // the walks to the light's too (lightPieceFields)
    std::uint64_t bytes = 0;
    for (int piece = 0; piece < pieces; ++piece)
    {
      const auto [begin, end] = this->pieceBytes(field, evenShare(layers, piece, pieces));
      bytes = std::max(bytes, end - begin);
    }
    this->PieceFieldBuffers.push_back(
      std::make_unique<VulkanBuffer>(*this->Context, bytes, "piece field", BufferPlacement::DeviceAddressed));
  }
}

// The march's fields with their pieces' buffers (preparePieceFields).
std::vector<RenderSession::PieceField> RenderSession::pieceFields() const
{
  if (this->PieceFieldBuffers.empty())
  {
    return {};
  }
  std::vector<PieceField> fields = this->marchFields();
  for (std::size_t i = 0; i < fields.size(); ++i)
  {
    fields[i].Piece = this->PieceFieldBuffers.at(i).get();
  }
  return fields;
}

// The fields a piece's dispatch of a light pass reads and writes, with
// their pieces' buffers and the halos its reads take: the cells and the
// absorption's `cellsHalo`, SurfaceDistance `distanceHalo`, the light fields
// (and the absorption's, the Bragg shadows) `lightHalo`, which it writes
// at its voxels (copied back after each dispatch, recordWrittenBack). None
// where the pass splits into no `pieces` (MarchPieces in one process, a
// shared march's shares for the walks it shares, marchLightShared).
std::vector<RenderSession::PieceField> RenderSession::lightPassPieceFields(
  int pieces, int cellsHalo, int distanceHalo, int lightHalo) const
{
  const DeviceVolume& v = *this->Volume;
  std::vector<PieceField> fields;
  if (pieces <= 1)
  {
    return fields;
  }
  for (PieceField field : this->pieceFields())
  {
    const bool cells = field.Whole == v.Cells.get() || field.Whole == v.AbsorptionCells.get();
    field.Written = field.Whole == v.LightField.get() || field.Whole == v.LightAbsorption.get() ||
      field.Whole == v.LightShadow.get();
    field.Halo = cells ? cellsHalo : field.Written ? lightHalo : distanceHalo;
    if (cells || field.Written || field.Whole == v.SurfaceDistance.get())
    {
      fields.push_back(field);
    }
  }
  return fields;
}

// A forwarded walk to the light's (docs/design.md §8.1): the cells only
// where it walks, and those of TraceStepLayers + 1 layers beyond the piece
// where a walk starts behind it (walkLayerHeld); SurfaceDistance as the
// march reads it; its light at its own voxel, in its voxel's piece.
std::vector<RenderSession::PieceField> RenderSession::lightPieceFields(int pieces) const
{
  return this->lightPassPieceFields(pieces, MediumHaloLayers, gpu::TraceStepLayers + 2, 0);
}

// The sweep from above's through `pieces`: the halo of the ranks' shared
// sweep (SweepHaloRows) for the 3 x 3 read of the layer above, the rows
// about it and the segment to it.
std::vector<RenderSession::PieceField> RenderSession::sweepPieceFields(int pieces) const
{
  return this->lightPassPieceFields(pieces, SweepHaloRows, SweepHaloRows, SweepHaloRows);
}

// Records: each field's piece layers and halo copied into its piece buffer,
// and the address table pointing each field at its piece buffer less the
// bytes of the layers before (docs/design.md §8.1): the passes index the
// whole grid, and a read lands in the piece buffer for the layers it holds.
// A rank holding only its piece will address its fields so; a read beyond
// the halo lands outside the buffer, and the image differs (TestOpalForwardedMarch).
void RenderSession::recordPieceFields(
  VkCommandBuffer commands, const std::vector<PieceField>& fields, std::pair<int, int> layers) const
{
  std::map<const VulkanBuffer*, std::uint64_t> addresses;
  for (const PieceField& field : fields)
  {
    const auto [begin, end] = this->pieceBytes(field, layers);
    if (begin < end)
    {
      field.Piece->recordCopyFrom(commands, *field.Whole, begin, 0, end - begin);
    }
    // Unsigned and modulo 2^64, as the shaders add an index's bytes (voxelAddress).
    addresses[field.Whole] = field.Piece->address() - begin;
  }
  if (!fields.empty())
  {
    const gpu::VolumeAddresses table = this->volumeAddresses(addresses);
    this->Volume->Addresses->recordWrite(commands, &table, sizeof(table));
  }
}

// Records: each written field's piece layers (its halo left out) copied back
// from its piece buffer into the whole field, where the passes after read them.
void RenderSession::recordWrittenBack(
  VkCommandBuffer commands, const std::vector<PieceField>& fields, std::pair<int, int> layers) const
{
  for (const PieceField& field : fields)
  {
    PieceField own = field;
    own.Halo = 0;
    const auto [begin, end] = this->pieceBytes(own, layers);
    if (field.Written && begin < end)
    {
      field.Whole->recordCopyFrom(commands, *field.Piece, begin - this->pieceBytes(field, layers).first, begin, end - begin);
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
// pixels' (a shared march's first band's, the largest), its ring's or its
// queued pixels' (a shared march's SharedRefinePixels); none unforwarded.
std::uint64_t RenderSession::rayStateBytes(const FrameSetup& setup, const std::array<int, 4>& rect) const
{
  if (this->marchPieces() <= 1)
  {
    return 0;
  }
  const std::uint64_t words = rayStateWords(setup);
  const int rows = this->SharedMarch ? marchBandRows(rect, 0, sharedBandPixels(words), gpu::MarchGroupSide) : rect[3];
  const std::uint64_t queued = this->SharedMarch ? static_cast<std::uint64_t>(SharedRefinePixels)
                                                 : static_cast<std::uint64_t>(rect[2]) * static_cast<std::uint64_t>(rect[3]);
  constexpr std::uint64_t groupPixels = gpu::MarchGroupSide * gpu::MarchGroupSide;
  const auto roundUp = [&](std::uint64_t n) { return (n + groupPixels - 1) / groupPixels * groupPixels; };
  const std::uint64_t slots =
    std::max({ static_cast<std::uint64_t>(marchGroups(rect[2])) * static_cast<std::uint64_t>(marchGroups(rows)) * groupPixels,
      roundUp(static_cast<std::uint64_t>(MARCH_RING_PIXELS(rect[2], rect[3]))), roundUp(queued) });
  return slots * words * sizeof(std::uint32_t);
}

// The words a forwarded march keeps per ray for the frame's wavelengths and nodes.
std::uint64_t RenderSession::rayStateWords(const FrameSetup& setup)
{
  const int wavelengths = static_cast<int>(setup.Bins.size());
  const int nodes = marchNodes(setup) == 0 ? 4 : marchNodes(setup);
  return RAY_STATE_WORDS(wavelengths, nodes);
}

// The frame's largest march (over its region or the exposure's thumbnail).
std::uint64_t RenderSession::frameRayStateBytes(const FrameSetup& setup) const
{
  return std::max(
    this->rayStateBytes(setup, setup.Region), this->rayStateBytes(setup, { 0, 0, setup.Thumbnail[0], setup.Thumbnail[1] }));
}

// The frame's states of its forwarded passes, the largest of one buffer:
// its march's or its light pass's.
std::uint64_t RenderSession::frameStateBytes(const FrameSetup& setup) const
{
  return std::max(this->frameRayStateBytes(setup), this->frameLightStateBytes(setup));
}

// The voxels a submit of the forwarded light pass takes: ForwardedLightVoxels,
// fewer where their kept walks would pass the storage-buffer range.
std::int64_t RenderSession::forwardedLightVoxels() const
{
  const std::uint64_t walkBytes = gpu::LightStateWords * sizeof(std::uint32_t);
  return std::clamp<std::int64_t>(
    static_cast<std::int64_t>(this->Context->limits().maxStorageBufferRange / walkBytes), 1, ForwardedLightVoxels);
}

// The forwarded light pass's kept walks, LightStateWords per voxel of a
// submit of the per-voxel walks, or (`queued`) of a layer y's queue (all its
// voxels at most); none unforwarded.
std::uint64_t RenderSession::lightStateBytes(bool queued) const
{
  if (this->MarchPieces <= 1)
  {
    return 0;
  }
  const std::array<int, 3>& dims = this->Volume->Shape.Dimensions;
  const std::int64_t voxels = queued ? static_cast<std::int64_t>(dims[0]) * dims[2] : this->forwardedLightVoxels();
  return static_cast<std::uint64_t>(voxels) * gpu::LightStateWords * sizeof(std::uint32_t);
}

// The frame's light pass's kept walks: none where the light field it needs
// is held (no light pass runs), the queues' with the light above the grid.
std::uint64_t RenderSession::frameLightStateBytes(const FrameSetup& setup) const
{
  return this->lightFieldServes(setup) ? 0 : this->lightStateBytes(this->Volume->Medium.Geometry.lightAboveGrid(setup.Camera.Light));
}

// The buffer of a forwarded pass's states (the march's rays, the light's
// walks) grown to `bytes`, as the pixel buffers are (and bound again); a
// refused allocation keeps the buffer bound before.
void RenderSession::prepareRayStates(std::uint64_t bytes)
{
  if (this->Buffers->RayStates->size() < bytes)
  {
    auto grown = std::make_unique<VulkanBuffer>(*this->Context, bytes, "forwarded rays", BufferPlacement::DeviceLocal);
    this->Buffers->RayStates = std::move(grown);
    this->bindBuffers();
  }
}

} // namespace opal
