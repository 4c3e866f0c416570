// What the render session's two source files share (private to OpalGpu):
// the budgets of work per submit, small conversions, and the state the
// session keeps between frames (docs/design.md §5). OpalRenderSession.cxx
// holds the frame's set-up and buffers, OpalRenderPasses.cxx the passes.
#pragma once

#include "OpalComputePipeline.h"
#include "OpalRenderCamera.h"
#include "OpalRenderSession.h"
#include "OpalScatteredLight.h"
#include "OpalSpectralSampling.h"
#include "OpalVulkanBuffer.h"
#include "opal_render_contract.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace opal
{

namespace sessiondetail
{
constexpr std::uint32_t PushConstantBytes = 48;   // the largest push-constant struct of the contract (MarchWork)
// Voxels a submit of the light pass's walks takes when forwarded (docs/design.md
// §8.1): their kept walks, LightStateWords each, 8 MB.
constexpr std::int64_t ForwardedLightVoxels = std::int64_t(1) << 16;
// The sweeps through the pieces that take every forwarded ray of the march,
// and every walk to the light to its end and its store at its own voxel
// (RenderSession::recordPiecePasses, docs/design.md §8.1).
constexpr int MarchSweeps = 4;
constexpr int LightWalkSweeps = 5;
// The rows z beyond its own the light's sweep from above reads (docs/design.md
// §8.1): lightAboveGrid bounds a path's sideways move per layer below half a
// voxel, so the node nearest to where a voxel's path crosses the layer above
// is in the voxel's own row z, and its 3 x 3 read spans rows z - 1 to z + 1;
// a second row keeps a margin for the shader's rounding. The ranks' shared
// sweep exchanges them after each layer.
constexpr int SweepHaloRows = 2;
// The rows beside a piece its light fields and every-order field hold
// (RenderSession::holdPiece): the sweep's reads (and the march's trilinear
// read, one layer, within them). The shares holding their pieces exchange
// only the rows the pieces beside hold of theirs.
constexpr int HeldPieceHalo = SweepHaloRows;
// The layers beside a piece the medium (its cells, absorption cells and
// SurfaceDistance) holds where uploaded by piece (RenderSession::holdPiece
// before setVolume): the march's and the walks' traces read SurfaceDistance
// within TraceStepLayers + 2 layers of their piece (their steps, the
// bisection and the normal), a walk to the light the cells of
// TraceStepLayers + 1 behind its piece where it starts behind it
// (walkLayerHeld, docs/design.md §8.1), the march the cells of one, the
// sweep SweepHaloRows. The highlight reads SurfaceDistance's tiles (§3.4).
constexpr int MediumHaloLayers = gpu::TraceStepLayers + 2;
constexpr int MarchTileSize = 64; // pixels per side of a band's tiles: the fewest rows a march submit takes
// The works of a march shared by processes (docs/design.md §8.1) are alike on
// every share, so its bands and refined pixels per dispatch are fixed (the
// pacers follow each device's own time): a band of 2^14 pixels (its states,
// held on the device, in Held, the posts and the exchange's buffers, are
// what a shared march holds beyond the render: 2^17 held ~0.37 GB more per
// rank at 320 x 240 and was no faster), and the second stage's 2^12; a
// band's pixels fewer where their states would pass 2^27 bytes, the
// storage-buffer range every Vulkan device offers (maxStorageBufferRange's
// required least), alike on every share. Its bands are whole rows of
// workgroups (8 rows at least: wider than ~11 000 pixels at 41 bins, a band
// passes that range, which the frame refuses).
constexpr std::int64_t SharedBandPixels = 1 << 14;
// The walks to the light a share of a light pass shared by processes starts
// in each work of its rounds (RenderSession::marchLightShared): their kept
// states, LightStateWords each, 1 MB a share.
constexpr std::int64_t SharedLightWalks = 1 << 13;
constexpr std::int64_t SharedRefinePixels = 1 << 12;
constexpr std::uint64_t EveryDeviceStorageRange = std::uint64_t(1) << 27;
inline std::int64_t sharedBandPixels(std::uint64_t stateWords)
{
  const auto fit = static_cast<std::int64_t>(EveryDeviceStorageRange / (stateWords * sizeof(std::uint32_t)));
  return std::min(SharedBandPixels, fit);
}
// On the device per voxel: its VoxelCell (8), SurfaceDistance and the light
// field, as pairs (8 and 16) or one value each (4 and 8, PairedFields); with
// absorption also its two coefficients (8) and their light field (16 or 8).
// (Besides: the light pass's entry queue, 4 bytes per voxel of one layer.)
inline std::uint64_t lightBytesPerVoxel(bool absorbs, bool pairedFields)
{
  const std::uint64_t lightField = pairedFields ? sizeof(gpu::LightFieldPair) : sizeof(gpu::vec2);
  return lightField * (absorbs ? 2 : 1);
}
// The medium's cells, absorption cells and SurfaceDistance, which a piece may hold alone.
inline std::uint64_t mediumBytesPerVoxel(bool absorbs, bool pairedFields)
{
  const std::uint64_t surfaceDistance = pairedFields ? sizeof(gpu::vec2) : sizeof(float);
  return sizeof(gpu::VoxelCell) + (absorbs ? sizeof(gpu::vec2) : 0) + surfaceDistance;
}
inline std::uint64_t deviceBytesPerVoxel(bool absorbs, bool pairedFields)
{
  return mediumBytesPerVoxel(absorbs, pairedFields) + lightBytesPerVoxel(absorbs, pairedFields);
}
// A frame's progress before its march: the light pass and the every-order
// solve (renderFrame), then the exposure's thumbnail up to 0.25.
constexpr double FrameLightShare = 0.2;
// The image buffers' bytes per pixel on the device (prepareFrameBuffers):
// XYZ, Bragg and mirror images, highlight and edge queues, the edge pixels'
// sums, Radiance and RGB.
constexpr std::uint64_t ImageBytesPerPixel = sizeof(gpu::PixelColour) + sizeof(gpu::PixelBragg) +
  sizeof(gpu::PixelMirror) + 4 + 8 + sizeof(gpu::PixelSum) + 3 * sizeof(float) + 4;
// The every-order tally grid's bytes on the device for a volume of
// `dimensions` (its shape scatteredLightGrid's, §3.10).
inline std::uint64_t scatteredLightGridBytes(const std::array<int, 3>& dimensions)
{
  return scatteredLightGrid(glm::ivec3(dimensions[0], dimensions[1], dimensions[2])).size() *
    sizeof(gpu::ScatteredLightNode);
}
// The device fields of a volume of `dimensions` for frames with `p`: the
// volume's own, the Bragg shadows with energy conservation (§7.2) and the
// every-order tally grid (scatteredLightGridBytes), with its field per
// voxel where `fieldPerVoxel` (else the march evaluates the grid, §3.10),
// its fields paired where `pairedFields` (§3.7); the light fields, the
// Bragg shadows and the every-order field for `heldVoxels` of them (all, or
// a piece: RenderSession::holdPiece), the medium (cells, SurfaceDistance)
// for `mediumVoxels`.
inline std::uint64_t volumeDeviceBytes(const std::array<int, 3>& dimensions, std::uint64_t heldVoxels,
  std::uint64_t mediumVoxels, bool absorbs, const RenderParameters& p, bool fieldPerVoxel, bool pairedFields)
{
  const bool everyOrder = scattersEveryOrder(p);
  const std::uint64_t gridBytes = everyOrder ? scatteredLightGridBytes(dimensions) : 0;
  const std::uint64_t light = lightBytesPerVoxel(absorbs, pairedFields);
  const std::uint64_t medium = mediumBytesPerVoxel(absorbs, pairedFields);
  return mediumVoxels * medium +
    heldVoxels * (light + (conservesEnergy(p) ? sizeof(gpu::LightShadow) : 0) +
                   (everyOrder && fieldPerVoxel ? sizeof(gpu::vec4) : 0)) +
    gridBytes;
}
// What the every-order field's binding holds where no field per voxel is:
// one vec4 (docs/design.md §3.10).
inline std::unique_ptr<VulkanBuffer> scatteredLightPlaceholder(VulkanContext& context, BufferPlacement placement)
{
  return std::make_unique<VulkanBuffer>(context, sizeof(gpu::vec4), "scattered light placeholder", placement);
}
static_assert(sizeof(gpu::LightPassWork) <= PushConstantBytes && sizeof(gpu::MarchWork) <= PushConstantBytes &&
  sizeof(gpu::HighlightWork) <= PushConstantBytes);

using Clock = std::chrono::steady_clock;
inline double secondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

inline gpu::vec3 toVec3(const glm::dvec3& v)
{
  return gpu::vec3(v);
}

inline gpu::vec3 toVec3(const std::array<double, 3>& a)
{
  return gpu::vec3(static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2]));
}

// sRGB-encoded [0, 1] to linear (IEC 61966-2-1).
inline float srgbToLinear(double encoded)
{
  return static_cast<float>(encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4));
}
} // namespace sessiondetail

// The volume on the device: its fields, its domain table and its light field.
struct RenderSession::DeviceVolume
{
  RenderVolume Shape; // dimensions, origin, spacing and domain count; no field pointers
  // The medium's geometry and, once an every-order solve needed them
  // (scatteringMedium), the host's copy of its fields (skin filled): the
  // solve runs on it (docs/design.md §3.10).
  ScatteringMedium Medium;
  std::unique_ptr<VulkanBuffer> Cells, SurfaceDistance, DomainTable;
  // SurfaceDistance's tiles (gpu::SurfaceTile) and their held values, which
  // the highlight pass reads (docs/design.md §3.4).
  std::unique_ptr<VulkanBuffer> SurfaceTileRecords, SurfaceTileValues;
  std::uint64_t SurfaceTileBytes = 0;
  std::unique_ptr<VulkanBuffer> LightField;
  std::unique_ptr<VulkanBuffer> EntryQueues, EntryVoxels; // the light pass's queued entry voxels
  // The absorption (docs/design.md §3.9): each voxel's (coloured, grey) mu_a
  // and their light field; 16-byte placeholders when nothing absorbs.
  std::unique_ptr<VulkanBuffer> AbsorptionCells, LightAbsorption;
  bool Absorbs = false;
  float AbsorptionExponent = 0.0f; // of the coloured part
  // The Bragg shadow of every voxel (energy conservation, docs/design.md
  // §7.2): made by the first light pass that needs it, a placeholder before.
  std::unique_ptr<VulkanBuffer> LightShadow;
  bool HasShadowField = false;
  // The light scattered more than once (docs/design.md §3.10): the solve's
  // tally grid (ScatteredLightGridBinding) once a frame with every order
  // solved it, and the field per voxel written from it (ScatteredLightBinding)
  // while the frames' memory budget holds it; placeholders otherwise.
  std::unique_ptr<VulkanBuffer> ScatteredLight, ScatteredLightGrid;
  bool HasScatteredField = false;     // ScatteredLight is the field per voxel, not its placeholder
  bool ScatteredFieldPending = false; // the field per voxel (where held) not yet written from the grid held
  // Where the per-voxel fields live: DeviceAddressed for a volume beyond one
  // storage buffer's range (the passes compiled with OPAL_VOLUME_ADDRESSES
  // read them through the address table), else DeviceLocal (docs/design.md §3.7).
  BufferPlacement FieldPlacement = BufferPlacement::DeviceLocal;
  // SurfaceDistance and the light fields as pairs (a voxel's and its +x
  // neighbour's) where bound, one value per voxel where addressed (rows of
  // one voxel always paired): PairedFields, docs/design.md §3.7.
  bool PairedFields = true;
  std::unique_ptr<VulkanBuffer> Addresses; // gpu::VolumeAddresses
  bool addressed() const { return this->FieldPlacement == BufferPlacement::DeviceAddressed; }
  // The layers z [first, second) that the light pass's fields (LightField,
  // LightAbsorption, the Bragg shadows) hold: all, or a piece of a march
  // shared by processes and its halo (RenderSession::holdPiece, docs/
  // design.md §8.1), read from the piece's first voxel (an address shifted
  // by it, or bound, an index less it: RenderSession::boundFirstVoxel).
  std::pair<int, int> LightLayers{ 0, 0 };
  // The layers z the medium (cells, absorption cells, SurfaceDistance) holds: all, or where
  // uploaded for a piece held (holdPiece before setVolume) the piece and
  // MediumHaloLayers beside it, read likewise from their first voxel
  // (RenderSession::boundMediumVoxel). What would read them beyond is refused
  // (RenderSession::requireWholeMedium).
  std::pair<int, int> MediumLayers{ 0, 0 };
  bool mediumWhole() const { return this->MediumLayers == std::make_pair(0, this->Shape.Dimensions[2]); }
  std::size_t mediumFirstVoxel() const { return this->layerVoxels() * static_cast<std::size_t>(this->MediumLayers.first); }
  std::size_t mediumVoxels() const
  {
    return this->layerVoxels() * static_cast<std::size_t>(this->MediumLayers.second - this->MediumLayers.first);
  }
  std::size_t layerVoxels() const
  {
    return static_cast<std::size_t>(this->Shape.Dimensions[0]) * static_cast<std::size_t>(this->Shape.Dimensions[1]);
  }
  std::size_t lightFirstVoxel() const { return this->layerVoxels() * static_cast<std::size_t>(this->LightLayers.first); }
  std::size_t lightVoxels() const
  {
    return this->layerVoxels() * static_cast<std::size_t>(this->LightLayers.second - this->LightLayers.first);
  }
  // A held field's bytes at `voxelBytes` a voxel: at least 16, a
  // placeholder's, where no layers are held (a refused allocation,
  // RenderSession::holdLightLayers).
  std::uint64_t heldFieldBytes(std::uint64_t voxelBytes) const
  {
    return std::max<std::uint64_t>(this->lightVoxels() * voxelBytes, 16);
  }
};

// The per-frame buffers, kept while they are large enough.
struct RenderSession::FrameBuffers
{
  std::unique_ptr<VulkanBuffer> Parameters, WavelengthTable;
  std::unique_ptr<VulkanBuffer> PixelColour, PixelBragg, PixelMirror, PixelSpectrum, PixelRadiance, PixelRGB8;
  std::unique_ptr<VulkanBuffer> HighlightQueue, HighlightPixels; // the pixels queued for the highlight
  std::unique_ptr<VulkanBuffer> EdgeQueue, EdgePixels;           // the pixels an edge crosses
  std::unique_ptr<VulkanBuffer> PixelSums;                       // and their sub-rays' sums
  std::unique_ptr<VulkanBuffer> RayStates; // a forwarded pass's states: the march's rays, the light's walks (a placeholder without)
  std::unique_ptr<VulkanBuffer> ForwardedLeft; // the states a forwarded pass left unfinished (one uint)
  // What each domain passes of the light (the Bragg shadow table, docs/design.md
  // §7.2), device-local; one float where no frame conserved energy yet.
  std::unique_ptr<VulkanBuffer> ShadowTable;
  std::size_t PixelCapacity = 0;
  std::size_t SpectrumFloats = 0;
  std::size_t ShadowTableFloats = 0;
};

// The rounds of a forwarded pass shared by processes (RenderSession::
// forwardShared, docs/design.md §8.1): a frame's shared march, a shared light
// pass's walks to the light. Each round every share's post goes to every
// share, its first word whether the share goes on; a state round's then
// carry each state the share took up, its slot and its words. Held, the
// states of the work being forwarded, has its layer words alike on every
// share after each round (a slot done on its share in the first round keeps
// there what its device wrote: nothing reads it), and Live its slots that go
// on. Once a share stopped, or the exchange ended, there is no round more.
class RenderSession::MarchRounds
{
public:
  explicit MarchRounds(const MarchShare& share);

  std::uint64_t Words = 0;         // per ray: RAY_STATE_WORDS of the frame
  std::vector<std::uint32_t> Held; // Words per slot; KeptDone where no ray is
  // The slots whose states in Held the device's ray states lack: those other
  // shares posted since they were last written (all where DeviceHolds is false).
  std::vector<std::uint32_t> Fresh;
  bool DeviceHolds = false;
  // The slots whose states go on in a piece (layer word below KeptUnwritten),
  // sorted: alike on every share after each round (live), so that a round
  // does not scan all of Held for the few that go on.
  std::vector<std::uint32_t> Live;
  double Seconds = 0; // in the exchanges and the states' copies (RenderTimings::MarchRounds)

  // Held for a dispatch's `slots` rays, none yet (each KeptDone).
  void begin(std::uint64_t slots);
  // What another share posted after its first word (`count` words): false
  // where it is not what this round's posts hold, for which exchange throws
  // once the round is over (the share then says it stops in its next round, stop).
  using Received = std::function<bool(int share, const std::uint32_t* words, std::uint64_t count)>;
  // Sends `post` (its words, the first whether this share goes on); hands
  // each other share's to `received`. Whether every share goes on. Each
  // share's Round must say alike whether all go on.
  bool exchange(const std::vector<std::uint32_t>& post, const Received& received = nullptr);
  bool exchangeBytes(const std::vector<char>& post, const Received& received);
  // A round of the rays each share took up (`post`, the words' bytes: a
  // band's states are sent without a copy), written into Held.
  bool exchangeRays(const std::vector<char>& post);
  // A round saying this share stops, unless the rounds are over.
  void stop();
  // Live again after a round: of the slots live before, `posted` (this
  // share's post) and those the other shares posted, those that go on.
  void live(const std::vector<std::uint32_t>& posted);
  // The live slots held in `layers` (the shader's resumeRay: a layer word
  // within them): those a round after the first takes up there.
  std::vector<std::uint32_t> liveIn(std::pair<int, int> layers) const;
  // Whether the last round's exchange itself ended (a share sent its last
  // instead), not a post saying a share stops.
  bool exchangeEnded() const { return this->ExchangeEnded; }
  int shares() const { return this->Share.Shares; }
  // The frame's last round is over: the rest of it is each share's alone.
  void finish() { this->Ended = true; }

private:
  bool takeRays(const std::uint32_t* rays, std::uint64_t count);

  const MarchShare& Share;
  bool Ended = false;
  bool ExchangeEnded = false;
  std::vector<std::uint32_t> Posted; // the slots the other shares posted in the last round
};

// A frame's shared march's rounds, held by the session (Rounds) while the
// frame runs: where the frame leaves before its last round (a failure or an
// abort anywhere, in the light pass, between the exposure's thumbnail and
// the image), a round saying it stopped ends the other shares' rounds.
class RenderSession::FrameRounds
{
public:
  explicit FrameRounds(RenderSession& session);
  ~FrameRounds();
  FrameRounds(const FrameRounds&) = delete;
  FrameRounds& operator=(const FrameRounds&) = delete;

private:
  RenderSession& Session;
};

// A forwarded pass's work shared by processes (RenderSession::forwardShared,
// docs/design.md §8.1): this share's piece of the layers z, the slots it
// starts in the first round (one run; none where another share starts
// them), the rounds that bound every path, what a refusal names, whether a
// failure posts a round saying this share stops (the march's rounds) or
// leaves them to its step's last exchange (a shared step's), and the
// dispatch of a round's slots (`started`: the first round's).
struct RenderSession::SharedForwarding
{
  std::pair<int, int> Layers;
  std::pair<std::uint64_t, std::uint64_t> Started;
  int MostRounds;
  std::string Pass, States;
  bool StopsInRound;
  std::function<void(bool started, const std::vector<std::uint32_t>& slots)> Dispatch;
};

// A pass of RenderSession::recordPiecePasses (docs/design.md §8.1): its
// piece's layers z, whether it takes up kept states (every pass but the
// first) and whether it is the last, whose dispatches count those still kept.
struct RenderSession::PiecePass
{
  std::pair<int, int> Layers;
  bool Resumed;
  bool Last;

  // `work` (a MarchWork or LightPassWork) for this pass.
  template <typename Work>
  Work of(Work work) const
  {
    work.piece = gpu::ivec2(this->Layers.first, this->Layers.second);
    work.resumed = this->Resumed ? 1 : 0;
    work.last = this->Last ? 1 : 0;
    return work;
  }
};

// Everything a frame derives from its parameters before touching the device.
struct RenderSession::FrameSetup
{
  RenderParameters Parameters;
  RenderCamera Camera;
  std::array<int, 4> Region{};
  std::array<int, 2> Thumbnail{}; // the automatic exposure's (0 x 0 where Exposure is set)
  std::size_t Pixels = 0;
  std::size_t PixelCapacity = 0; // the image rectangle or the exposure thumbnail, whichever is larger
  std::vector<WavelengthBin> Bins;
  gpu::RenderParameterBlock Block{};
  bool Preview = false; // the preview quality (Parameters hold what it implies): the march reads the light field per voxel
  // Every order, and the device's budget cannot hold the field per voxel:
  // the march evaluates the tally grid instead (docs/design.md §3.10).
  bool ScatteredLightFromGrid = false;
  // The spectrum image's bytes (WriteSpectrum), on the device and the host.
  // Whether the frame measures its exposure (Exposure 0) on its thumbnail.
  bool measuresExposure() const { return this->Thumbnail[0] > 0; }
  std::uint64_t spectrumBytes() const
  {
    return this->Parameters.WriteSpectrum ? std::uint64_t{ this->Pixels } * this->Bins.size() * 4 : 0;
  }
};

// A frame's progress: the frame's fraction done (report), or a stage's
// (stageDone) placed in the window the frame gave it (stage), so that the
// fraction the caller sees only rises, whichever stages run.
class RenderSession::Progress
{
public:
  explicit Progress(const RenderProgress& callback) : Callback(callback) {}
  bool report(double fraction) { return !this->Callback || this->Callback(fraction); }
  void stage(double from, double to)
  {
    this->From = from;
    this->To = to;
  }
  bool stageDone(double done) { return this->report(this->From + (this->To - this->From) * done); }
  // stageDone as the callback a pass or a solve takes (its fraction done).
  std::function<bool(double)> stageCallback()
  {
    return [this](double done) { return this->stageDone(done); };
  }

private:
  const RenderProgress& Callback;
  double From = 0.0, To = 1.0;
};

} // namespace opal
