// The piece of the volume's layers z that a process of a march shared by
// processes holds of its light fields and every-order field (docs/design.md
// §8.1): its march reads them only in its piece and one layer beside it, and
// the light's sweep, shared by the same shares, only SweepHaloRows rows
// beside it; and where the volume is set after the piece, of the medium's
// cells, absorption cells and SurfaceDistance, which the march and the walks
// to the light read only within MediumHaloLayers of it.
#include "OpalRenderSession.h"

#include "OpalParallel.h"
#include "OpalRenderSessionState.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace opal
{

using namespace sessiondetail;

namespace
{
// Share `share`'s layers of `layers` and `halo` beside them, within the grid.
std::pair<int, int> pieceWithHalo(int layers, int share, int shares, int halo)
{
  const std::pair<int, int> piece = evenShare(layers, share, shares);
  return { std::max(piece.first - halo, 0), std::min(piece.second + halo, layers) };
}

// The layers a field of `layers` holds for the piece `held` (share, shares)
// with `halo` beside it: all where one share is held.
std::pair<int, int> layersHeld(int layers, std::pair<int, int> held, int halo)
{
  return held.second > 1 ? pieceWithHalo(layers, held.first, held.second, halo) : std::make_pair(0, layers);
}

bool holds(std::pair<int, int> held, std::pair<int, int> layers)
{
  return held.first <= layers.first && layers.second <= held.second;
}
} // namespace

std::pair<int, int> mediumLayersRead(int layers, int share, int shares)
{
  return layersHeld(layers, { share, shares }, MediumHaloLayers + 1);
}

// Refuses a volume whose medium lacks layers the piece held reads.
void RenderSession::requireMediumArrays(const RenderVolume& volume) const
{
  const std::pair<int, int> read = mediumLayersRead(volume.Dimensions[2], this->HeldPiece.first, this->HeldPiece.second);
  const std::pair<int, int> given = volume.mediumLayers();
  if (!holds(given, read))
  {
    throw std::invalid_argument("The volume's medium arrays (ScatteringCoefficient, DomainId, absorption) hold layers z " +
      std::to_string(given.first) + " to " + std::to_string(given.second) + ", but the piece held (share " +
      std::to_string(this->HeldPiece.first) + " of " + std::to_string(this->HeldPiece.second) + ") reads layers " +
      std::to_string(read.first) + " to " + std::to_string(read.second) + ": set the volume with those layers.");
  }
}

void RenderSession::holdPiece(int share, int shares)
{
  if (shares < 1 || share < 0 || share >= shares)
  {
    throw std::invalid_argument("holdPiece: share " + std::to_string(share) + " is not one of the " +
      std::to_string(shares) + " shares.");
  }
  if (shares > 1 && this->MarchPieces > 1)
  {
    throw std::invalid_argument("holdPiece: a piece held for a march shared by processes cannot also be forwarded "
                                "through MarchPieces pieces in one process.");
  }
  if (this->HeldPiece == std::make_pair(share, shares))
  {
    return;
  }
  this->cancelFrame(); // a background frame reads the fields and the piece
  const bool served = this->mediumServes(share, shares);
  this->HeldPiece = { share, shares };
  if (this->Volume && !served)
  {
    // Its medium holds another piece: only the volume's arrays give the
    // layers this one needs (the VTK filter sets it again).
    this->dropVolume();
  }
  if (this->Volume)
  {
    this->holdLightLayers(this->lightLayersOf(*this->Volume));
  }
}

bool RenderSession::mediumServes(int share, int shares) const
{
  if (!this->Volume || this->Volume->mediumWhole())
  {
    return true; // none to serve, or whole
  }
  const int layers = this->Volume->Shape.Dimensions[2];
  return holds(this->Volume->MediumLayers, layersHeld(layers, { share, shares }, MediumHaloLayers));
}

std::pair<int, int> RenderSession::heldMediumLayers() const
{
  return this->Volume ? this->Volume->MediumLayers : std::pair<int, int>{ 0, 0 };
}

// The layers the medium of a volume set now holds: for a piece held
// (holdPiece) the piece and MediumHaloLayers beside it, else all.
std::pair<int, int> RenderSession::mediumLayersOf(const DeviceVolume& v) const
{
  return layersHeld(v.Shape.Dimensions[2], this->HeldPiece, MediumHaloLayers);
}

// The medium's fields held from DeviceVolume::MediumLayers, with their bytes
// per voxel: the cells, SurfaceDistance and, where the volume absorbs, the
// absorption cells.
std::vector<std::pair<VulkanBuffer*, std::uint64_t>> RenderSession::mediumFields() const
{
  const DeviceVolume& v = *this->Volume;
  std::vector<std::pair<VulkanBuffer*, std::uint64_t>> fields{ { v.Cells.get(), sizeof(gpu::VoxelCell) },
    { v.SurfaceDistance.get(), v.PairedFields ? sizeof(gpu::vec2) : sizeof(float) } };
  if (v.Absorbs)
  {
    fields.emplace_back(v.AbsorptionCells.get(), sizeof(gpu::vec2));
  }
  return fields;
}

// Refuses `reader`, which reads the medium of voxels [first, second) alone,
// where the medium held lacks them.
void RenderSession::requireMediumOf(std::pair<std::size_t, std::size_t> voxels, const std::string& reader) const
{
  const DeviceVolume& v = *this->Volume;
  if (voxels.first < v.mediumFirstVoxel() || voxels.second > v.mediumFirstVoxel() + v.mediumVoxels())
  {
    this->requireWholeMedium(reader);
  }
}

// Refuses `reader`, which reads the medium anywhere in the grid, where the
// medium is held by piece (docs/design.md §8.1): it would read beyond it.
void RenderSession::requireWholeMedium(const std::string& reader) const
{
  const DeviceVolume& v = *this->Volume;
  if (!v.mediumWhole())
  {
    throw std::runtime_error(reader + " reads the medium anywhere in the volume, but this process holds only layers " +
      std::to_string(v.MediumLayers.first) + " to " + std::to_string(v.MediumLayers.second) + " of its " +
      std::to_string(v.Shape.Dimensions[2]) + " (a march shared by processes, each holding its piece): no image is "
      "given; the processes compute it together, or render again with the march unshared.");
  }
}

std::pair<int, int> RenderSession::heldLightLayers() const
{
  return this->Volume ? this->Volume->LightLayers : std::pair<int, int>{ 0, 0 };
}

// The layers the light fields of `v` hold for HeldPiece: the piece and
// its halo, read at an index less its first voxel (bound: boundFirstVoxel)
// or from an address shifted by it (addressed: volumeAddresses); else all.
std::pair<int, int> RenderSession::lightLayersOf(const DeviceVolume& v) const
{
  return layersHeld(v.Shape.Dimensions[2], this->HeldPiece, HeldPieceHalo);
}

// The light fields made anew for `layers` where they hold others, the light
// field held dropped, and the every-order field, where read per voxel, made
// anew too, to be written from the grid held (ScatteredFieldPending).
void RenderSession::holdLightLayers(std::pair<int, int> layers)
{
  DeviceVolume& v = *this->Volume;
  if (v.LightLayers == layers)
  {
    return;
  }
  this->LightField.reset();
  v.LightField.reset(); // freed before the new ones are made
  v.LightAbsorption.reset();
  v.LightShadow.reset();
  const bool scatteredField = v.HasScatteredField;
  v.ScatteredLight = scatteredLightPlaceholder(*this->Context, v.FieldPlacement);
  v.HasScatteredField = false;
  try
  {
    v.LightLayers = layers;
    this->allocateLightFields(v);
    if (scatteredField)
    {
      this->makeScatteredField(true);
    }
  }
  catch (...)
  {
    // Refused (out of memory): no layers held, placeholders bound, so
    // that the next frame or step makes its fields anew, not one that
    // writes through a table of freed buffers.
    v.LightLayers = { 0, 0 };
    this->allocateLightFields(v);
    v.ScatteredLight = scatteredLightPlaceholder(*this->Context, v.FieldPlacement);
    this->bindBuffers();
    throw;
  }
  this->bindBuffers();
}

// The fields DeviceVolume::LightLayers holds, with their bytes per voxel:
// the light pass's (lightPassFields, the Bragg shadows where made) and the
// every-order field where read per voxel.
std::vector<std::pair<VulkanBuffer*, std::uint64_t>> RenderSession::pieceHeldFields() const
{
  const DeviceVolume& v = *this->Volume;
  std::vector<std::pair<VulkanBuffer*, std::uint64_t>> fields = this->lightPassFields(v.HasShadowField);
  if (v.HasScatteredField)
  {
    const auto scattered = this->scatteredFieldFields();
    fields.insert(fields.end(), scattered.begin(), scattered.end());
  }
  return fields;
}

// A share of a shared step computing share `share` of `shares`' rows and
// reading `halo` rows beside them (HeldPieceHalo at most). True where this
// session holds that share as its piece of the fields (holdsPieceOf): the
// piece's layers, made anew where it held others
// (a refused allocation left none); else the whole fields where the layers
// held lack the rows (the processes sharing the step are not those that
// share the march), and false.
bool RenderSession::holdShareRows(int share, int shares, int halo)
{
  if (this->holdsPieceOf(share, shares))
  {
    this->holdLightLayers(this->lightLayersOf(*this->Volume));
    return true;
  }
  const int layers = this->Volume->Shape.Dimensions[2];
  if (!holds(this->Volume->LightLayers, pieceWithHalo(layers, share, shares, halo)))
  {
    this->holdLightLayers({ 0, layers });
  }
  return false;
}

// The voxels whose light fields and every-order field a frame's memory is
// checked for: the piece held where one is asked for (the ranks' shared
// steps compute it; a frame computing the light alone makes the fields
// whole, and its allocation is then refused where they do not fit).
std::uint64_t RenderSession::framedVoxels() const
{
  const DeviceVolume& v = *this->Volume;
  return this->HeldPiece.second > 1 ? v.lightVoxels() : v.Shape.voxelCount();
}

// The light field held is the frame's light and holds the layers its march
// reads: all, or a shared march's piece and the layer beside it.
bool RenderSession::lightFieldServes(const FrameSetup& setup) const
{
  if (!this->LightField || !(*this->LightField == lightFieldKey(setup)))
  {
    return false;
  }
  const DeviceVolume& v = *this->Volume;
  const int layers = v.Shape.Dimensions[2];
  const std::pair<int, int> read = this->SharedMarch
    ? pieceWithHalo(layers, this->SharedMarch->Share, this->SharedMarch->Shares, 1)
    : std::make_pair(0, layers);
  return holds(v.LightLayers, read);
}

} // namespace opal
