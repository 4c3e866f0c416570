// The spectral render on Vulkan compute as a session (docs/design.md §5): it
// keeps the volume on the device (uploaded once per setVolume), the light
// field (recomputed only when the light in the model's frame, the refractive
// index, the fall-off rule or the volume changes), the pipelines, the
// wavelength table and the pixel buffers between frames, and renders a frame
// for a camera and an image rectangle in named stages: frame set-up, memory
// budget, buffers, light pass, exposure, march, colour, read-back.
// Plain C++ over OpalCore and Vulkan: the VTK filter and the programs wrap it.
#pragma once

#include "OpalFrameWorker.h"
#include "OpalRenderFrame.h"
#include "OpalRenderImage.h"
#include "OpalRenderParameters.h"
#include "OpalRenderVolume.h"
#include "OpalSubmitPacer.h"
#include "OpalVolumeGeometry.h"
#include "OpalVulkanContext.h"

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace opal
{

class ComputePipeline;
class StorageBufferBindings;
namespace gpu
{
struct MarchWork;
struct LightPassWork;
struct VolumeAddresses;
struct RenderParameterBlock;
}
class VulkanBuffer;
struct ScatteredLight;
struct SurfaceTiles;
struct ScatteredLightRequest;
struct ScatteringMedium;
struct WavelengthBin;

// Which stages a frame ran; the others reused what the session kept.
struct FrameStages
{
  bool Upload = false;    // the volume went to the device (by setVolume since the last frame)
  bool LightPass = false; // the light field was recomputed
  bool ScatteredLight = false; // the light scattered more than once was solved (ScatteringOrders all)
  // The march evaluated that light from its tally grid: the device's budget
  // did not hold its field per voxel (docs/design.md §3.10).
  bool ScatteredLightFromGrid = false;
  // SurfaceDistance and the light fields were held as pairs (a voxel's and
  // its +x neighbour's); false: one value per voxel, read by address (a
  // volume beyond one storage buffer's range, or pairs beyond the device's
  // budget; docs/design.md §3.7). Rows of one voxel are always paired.
  bool PairedFields = true;
  bool Exposure = false;  // the automatic exposure's thumbnail was marched
  bool March = false;
  bool Colour = false;
  bool Readback = false;
  bool Preview = false;   // the preview's own stages: the per-voxel light read and the longer step
};

enum class FrameStatus
{
  Completed,
  Aborted, // the progress callback returned false; Image is empty
};

struct RenderFrame
{
  FrameStatus Status = FrameStatus::Aborted;
  RenderImage Image;
  FrameStages Ran;
};

// Called with the fraction done; returning false aborts the frame.
using RenderProgress = std::function<bool(double)>;

// A background frame's state: none started (or taken), running, or finished and waiting to be taken.
enum class BackgroundState
{
  None,
  Running,
  Finished,
};

// The layers z of the medium's arrays (ScatteringCoefficient, DomainId, the
// absorption pair) of a volume of `layers` layers that setVolume reads with
// share `share` of `shares` held (RenderSession::holdPiece): the layers the
// medium's cells hold and the one beside them whose voxels fill their skin
// (skinCells); all for one share. The rest a caller need not hold (docs/design.md §8.1).
std::pair<int, int> mediumLayersRead(int layers, int share, int shares);

class RenderSession
{
public:
  // Creates the Vulkan context and the pipelines (throws NoVulkanDeviceError / VulkanError).
  explicit RenderSession(const VulkanOptions& options = {});
  ~RenderSession();
  RenderSession(const RenderSession&) = delete;
  RenderSession& operator=(const RenderSession&) = delete;

  // Uploads the volume's fields and domain table to the device; the caller's
  // arrays are not needed afterwards. Throws std::invalid_argument for an
  // unusable volume (naming what is wrong) and VulkanError if it does not fit.
  // A medium held by layers (RenderVolume::Held) must hold at least the
  // layers mediumLayersRead names for the piece held (holdPiece).
  void setVolume(const RenderVolume& volume);

  // Refuses, before any volume exists, a volume of `dimensions` whose device
  // fields for frames with `parameters` (resolved) exceed the device's
  // memory: the VulkanError a frame would throw after the upload (a program
  // that builds the volume checks first; a 10 um stone takes minutes).
  void checkVolumeFits(const std::array<int, 3>& dimensions, bool absorbs, const RenderParameters& parameters);

  // Renders a frame of the volume. Throws std::invalid_argument for bad
  // parameters (naming the parameter) or without a volume, VulkanError for
  // device failures.
  RenderFrame render(const RenderParameters& parameters, const RenderProgress& progress = nullptr);
  // Renders a frame resolved by resolveFrame (what the VTK filter renders).
  RenderFrame render(const ResolvedFrame& frame, const RenderProgress& progress = nullptr);

  // Every order's scattered light (docs/design.md §3.10) solved by several
  // processes together, before their frames (§8.1). needsScatteredLight:
  // whether `frame` would solve it (every order, and no field held serves
  // it), having checked what render() checks before any work (the frame's
  // settings and memory: it throws alike). solveScatteredLightShared reads
  // back share `share` of `shares` of the medium the solve reads (the light
  // field's rows, shareLightPass), sends it to every share through `round`
  // (as shareLightPass's fields: a chunk of each share a round) and holds
  // theirs, traces its share of the photons, hands its scores to `exchange`,
  // which gives back every share's in share order (nullopt where any share
  // failed), and holds the field for the frames that follow, which then
  // reuse it. `exchange` is called exactly once whatever happens before it
  // (a failed or aborted trace passes nullopt) unless a round ended the
  // exchange, so that no process waits in an exchange another left; an
  // exception met before it is rethrown after it. False if the trace was
  // aborted or a share failed: a frame then solves on its own.
  // A shared step's exchanges (shareLightPass says how they go).
  using ShareSink = std::function<void(int share, std::uint64_t first, std::uint64_t count, const char* bytes)>;
  using FieldExchange = std::function<bool(const std::optional<std::vector<char>>& mine, const ShareSink& sink)>;
  using LayerExchange = std::function<bool(const std::vector<char>& mine, const ShareSink& sink)>;
  using ScoresExchange =
    std::function<std::optional<std::vector<std::vector<double>>>(const std::optional<std::vector<double>>& mine)>;
  bool needsScatteredLight(const ResolvedFrame& frame) const;
  bool solveScatteredLightShared(const ResolvedFrame& frame, int share, int shares, const ScoresExchange& exchange,
    const LayerExchange& round, const RenderProgress& progress = nullptr);

  // The light field (§3.3) computed by several processes together, before
  // their frames (§8.1), as the solve above: needsLightPass, whether `frame`
  // would compute it (no light field held serves it), having checked what
  // render() checks. shareLightPass computes share `share` of `shares`: the
  // rows z = ⌊share nz / shares⌋ to ⌊(share + 1) nz / shares⌋ of every layer.
  // A light low or to the side is marched from each of their voxels. A light
  // above the grid is swept layer after layer; after each layer but the last
  // the share's rows of it that the shares beside read go to `round`, which
  // sends them, gives every other share's to the sink (share, first byte,
  // count, bytes) as they arrive, and says whether every share goes on
  // (false, or a throw, ends the exchange: neither is called again). The
  // shares' fields then go to every share through `round`, a chunk of each
  // share a round, and `exchange` (the last, with no bytes: nullopt where
  // the share stopped) says whether all arrived; the whole field is held for
  // the frames that follow. `exchange` is called exactly once unless a round
  // ended the exchange; false if the pass was aborted or a share failed: a
  // frame then computes the field alone.
  bool needsLightPass(const ResolvedFrame& frame) const;
  // How a share's bytes are laid out (each field's bytes per voxel, which
  // follow the device: paired or not, §3.7): processes exchange shares only
  // where it is alike. Empty without a volume.
  std::string lightPassLayout(const ResolvedFrame& frame) const;
  bool shareLightPass(const ResolvedFrame& frame, int share, int shares, const FieldExchange& exchange,
    const LayerExchange& round, const RenderProgress& progress = nullptr);

  // The every-order field per voxel written from the tally grid the session
  // holds (§3.10) by several processes together, after the solve: whether
  // `frame` would write it (its grid held, the field read per voxel and not
  // yet written), and the writing of share `share` of `shares` of it (the
  // light field's rows), exchanged as the light field's shares are. False
  // where a share failed: the frame then writes it alone.
  bool needsScatteredField(const ResolvedFrame& frame) const;
  // As lightPassLayout, for the every-order field's shares.
  std::string scatteredFieldLayout() const;
  bool shareScatteredField(
    const ResolvedFrame& frame, int share, int shares, const FieldExchange& exchange, const LayerExchange& round);

  // The piece of the volume's layers z that this session's light field (and
  // its absorption's, the Bragg shadows, the every-order field read per
  // voxel) holds, for a march shared by processes (shareMarch): share
  // `share` of `shares`, the layers it marches, and the rows beside them that
  // its march and the light's sweep read (docs/design.md §8.1); 1 share: the
  // whole volume, as by default. Kept for the volumes set after, which then
  // lay their fields out to be read by address (one value per voxel, §3.7);
  // a volume set before whose fields are bound (not read by address), or a
  // device that cannot address buffers, holds them whole. A refused
  // allocation leaves no layers held (placeholders), made anew by the next
  // frame or shared step. A light field held by piece comes from shareLightPass with
  // the same shares and serves only the march shared so; a frame that
  // computes the light alone computes it whole. The every-order field is
  // written at the voxels held. A new piece drops the light field held and
  // the every-order field (not its grid). A volume set after it uploads the
  // medium (cells, absorption cells, SurfaceDistance) for the piece and MediumHaloLayers
  // beside it alone; then what would read them beyond (a frame not marched
  // shared, a light pass or solve computed alone or by other shares) is
  // refused, and a later piece they do not cover drops the volume, to be set
  // again (mediumServes). Refuses (std::invalid_argument) a
  // share not among the shares, and more shares than one with
  // VulkanOptions::MarchPieces.
  void holdPiece(int share, int shares);
  // The layers z [first, second) the fields holdPiece names hold (none without a volume).
  std::pair<int, int> heldLightLayers() const;
  // The layers z the medium (cells, absorption cells, SurfaceDistance) holds (none without a volume).
  std::pair<int, int> heldMediumLayers() const;
  // Whether the volume held would serve frames after holdPiece(share, shares):
  // its medium held whole, or for that piece (false: it is set again).
  bool mediumServes(int share, int shares) const;
  // Whether a volume is held (setVolume; a piece it does not serve drops it).
  bool holdsVolume() const { return this->Volume != nullptr; }

  // The view march of the frames that follow shared by `Shares` processes,
  // each holding share `Share` of the volume's layers z (docs/design.md
  // §8.1): share 0 starts every ray of a dispatch; each share then marches
  // the rays in its layers, round after round, passing those it took up to
  // every share through `Round` (as shareLightPass's rounds: its bytes, the
  // others' handed to the sink), until no ray goes on; every share then
  // writes every finished ray's pixel and holds the whole image. Each
  // round's bytes begin with whether the share goes on, and each share's
  // Round must say alike whether all went on: a round after each band of
  // rows carries the shares' progress, and a frame that leaves before its
  // march's last round (a failure or an abort anywhere, the light pass
  // included) posts one saying it stopped, so every share's frame stops
  // there (Aborted; the failing share's rethrows). The shares' works, bands
  // and queues of edge pixels are alike (share 0's queues go to all).
  // Refuses (std::invalid_argument) more shares than one with
  // VulkanOptions::MarchPieces; nullopt: the march alone again. startFrame
  // refuses (std::logic_error) while the march is shared.
  struct MarchShare
  {
    int Share = 0;
    int Shares = 1;
    LayerExchange Round;
  };
  void shareMarch(std::optional<MarchShare> share);

  // Whether the frame's eye is inside the opal (which render refuses); false
  // without a volume. It reads only the host copy of the volume's surface,
  // so it may run beside a background frame.
  bool eyeInsideOpal(const ResolvedFrame& frame) const;

  // The frame ticket (docs/design.md §5.2): startFrame renders `frame` on the
  // session's own worker thread and returns; the caller polls
  // backgroundState() (and backgroundProgress()), takes the finished frame
  // with takeFrame() or stops it with cancelFrame(). While a frame runs the
  // session is the worker's: setVolume, render, a new startFrame and the
  // destructor first cancel it and wait (it stops at its next check).
  void startFrame(const ResolvedFrame& frame);
  BackgroundState backgroundState() const;
  double backgroundProgress() const;
  // The finished frame (Completed), or nothing if none has finished; the
  // worker's exception is rethrown here.
  std::optional<RenderFrame> takeFrame();
  // Cancels a running frame and waits for it; drops a finished one not taken.
  void cancelFrame();
  // Background frames that completed (taken, or finished before a cancel)
  // and that a cancel stopped before their end, since the session began.
  int completedBackgroundFrames() const { return this->CompletedFrames; }
  int abandonedBackgroundFrames() const { return this->AbandonedFrames; }

  // The Vulkan context; throws VulkanError once the session is released.
  VulkanContext& context();

  // Ends the session's device objects now (a running background frame
  // first); every later use throws VulkanError. The process's exit runs it
  // for every live session (OpalSessionRegistry.h).
  void release();

private:
  struct FrameSetup;
  struct DeviceVolume;
  struct FrameBuffers;
  struct LightFieldKey
  {
    std::array<double, 3> Light; // in the model's frame
    double RefractiveIndex;
    bool FalloffAtEntry;
    bool BraggShadow; // with the Bragg shadows (energy conservation, docs/design.md §7.2)
    bool operator==(const LightFieldKey& other) const;
  };
  // What the scattered light field holds: it follows the light, the
  // boundary, the photon count and the span of the wavelength table.
  struct ScatteredLightKey
  {
    std::array<double, 3> Light;
    double RefractiveIndex;
    int Photons;
    std::array<double, 2> WavelengthSpan;
    bool operator==(const ScatteredLightKey& other) const;
  };
  class Progress;

  // A frame on the caller's thread (render, and the worker's startFrame).
  RenderFrame renderFrame(const ResolvedFrame& frame, const RenderProgress& progress);
  static LightFieldKey lightFieldKey(const FrameSetup& setup);
  static ScatteredLightKey scatteredLightKey(const FrameSetup& setup);
  // Throws, saying so, where no volume was set.
  void requireVolume() const;
  // The frame's setup; throws, as checkMemoryBudget, where it exceeds the
  // device's or the machine's memory: every step that sets a frame up
  // (the frame, the shared steps and their needs) refuses alike.
  FrameSetup setUpFrame(const ResolvedFrame& frame) const;
  // A shared step's start (shareLightPass, solveScatteredLightShared,
  // shareScatteredField): no frame running, the volume there, the frame set up.
  FrameSetup setUpSharedStep(const ResolvedFrame& frame);
  std::uint64_t frameImageBytes(const FrameSetup& setup, bool kept) const;
  bool scatteredLightFromGrid(const FrameSetup& setup) const;
  bool pairedFieldsFit(std::size_t voxels, bool absorbs) const;
  void writeParameterBlock(FrameSetup& setup) const;
  int boundFirstVoxel() const;
  int boundMediumVoxel() const;
  void dropVolume();
  void writeHeldFirstVoxel() const;
  void uploadParameterBlock(const gpu::RenderParameterBlock& frameBlock) const;
  void uploadSurfaceAndLightFields(
    const RenderVolume& volume, const SurfaceTiles& tiles, std::pair<std::size_t, std::size_t> voxels, DeviceVolume& v);
  void allocateLightPassBuffers(const RenderVolume& volume, DeviceVolume& v);
  void allocateLightFields(DeviceVolume& v) const;
  std::pair<int, int> lightLayersOf(const DeviceVolume& v) const;
  std::pair<int, int> mediumLayersOf(const DeviceVolume& v) const;
  void requireMediumArrays(const RenderVolume& volume) const;
  std::vector<std::pair<VulkanBuffer*, std::uint64_t>> mediumFields() const;
  void requireWholeMedium(const std::string& reader) const;
  void requireMediumOf(std::pair<std::size_t, std::size_t> voxels, const std::string& reader) const;
  void holdLightLayers(std::pair<int, int> layers);
  bool holdShareRows(int share, int shares, int halo);
  std::vector<std::pair<VulkanBuffer*, std::uint64_t>> pieceHeldFields() const;
  bool lightFieldServes(const FrameSetup& setup) const;
  std::uint64_t framedVoxels() const;
  void makeScatteredField(bool perVoxel);
  std::uint64_t volumeBytes(const FrameSetup& setup, bool fieldPerVoxel) const;
  void checkMemoryBudget(const FrameSetup& setup) const;
  // Throws VulkanError (out of device memory) where `bytes` exceed the
  // device's budget: "<needs> about <bytes> of device memory<detail>, more
  // than <the budget>; <remedy>".
  void requireDeviceMemory(
    std::uint64_t bytes, const std::string& needs, const std::string& detail, const std::string& remedy) const;
  void prepareFrameBuffers(const FrameSetup& setup);
  void uploadWavelengthTable(const std::vector<WavelengthBin>& bins, LightSpectrum illuminant);
  void bindBuffers();
  void addressFields(std::vector<const VulkanBuffer*>& buffers) const;
  gpu::VolumeAddresses volumeAddresses(const std::map<const VulkanBuffer*, std::uint64_t>& shifted) const;
  bool runLightPass(const FrameSetup& setup, Progress& progress);
  // Rows z in [rows.first, rows.second) of every layer; `afterLayer` (where
  // given) after each layer but the last, one layer a submit, false stops;
  // `walkQueue` (where given) each layer's queued walks, after its sweep.
  bool sweepLightLayers(bool braggShadow, Progress& progress, std::pair<int, int> rows,
    const std::function<bool(int layer)>& afterLayer = nullptr, const std::function<bool(int layer)>& walkQueue = nullptr);
  bool marchLightPerVoxel(bool braggShadow, Progress& progress);
  bool dispatchOverVoxels(const ComputePipeline& pass, SubmitPacer& pacer, const std::function<bool(double)>& keepGoing,
    std::size_t first, std::size_t end, bool forwarded = false);
  std::vector<std::pair<VulkanBuffer*, std::uint64_t>> lightPassFields(bool braggShadow) const;
  std::vector<std::pair<VulkanBuffer*, std::uint64_t>> scatteredFieldFields() const;
  bool prepareScatteredLight(const FrameSetup& setup, double sharedSolveSeconds, Progress& progress, RenderFrame& frame);
  void readFrame(const FrameSetup& setup, double exposure, RenderFrame& frame) const;
  bool runScatteredLight(const FrameSetup& setup, Progress& progress);
  const ScatteringMedium& scatteringMedium();
  const ScatteringMedium* shareScatteringMedium(int share, int shares, const LayerExchange& round, bool& exchanging);
  void releaseScatteringMedium();
  // Releases the medium's fields when a solve ends, however it ends.
  struct MediumRelease
  {
    explicit MediumRelease(RenderSession& session)
      : Session(session)
    {
    }
    ~MediumRelease() { this->Session.releaseScatteringMedium(); }
    MediumRelease(const MediumRelease&) = delete;
    MediumRelease& operator=(const MediumRelease&) = delete;
    RenderSession& Session;
  };
  bool scatteredLightServes(const FrameSetup& setup) const;
  static ScatteredLightRequest scatteredLightRequest(const FrameSetup& setup);
  void holdScatteredLight(const FrameSetup& setup, const opal::ScatteredLight& field);
  void placeScatteredField(const FrameSetup& setup);
  void writeScatteredField();
  void prepareShadowField();
  void runShadowTable(const FrameSetup& setup);
  // What a march covers: a rectangle (x, y, width, height) of an image of
  // `Size`, whether it fills the spectrum and the sub-rays per axis of its
  // edge pixels (1: none refined).
  struct MarchTarget
  {
    std::array<int, 2> Size;
    std::array<int, 4> Rect;
    bool Spectrum;
    int PixelSamples;
  };
  bool marchRegion(const FrameSetup& setup, const MarchTarget& target, Progress& progress, double from, double to);
  static int marchGroups(int width);
  void recordMarchRows(
    VkCommandBuffer commands, const ComputePipeline& march, int mode, int width, int firstRow, int rows) const;
  using MarchDispatch = std::function<void(const gpu::MarchWork& work, std::uint32_t groupsX, std::uint32_t groupsY)>;
  void forMarchColumns(int mode, int width, int firstRow, int rows, const MarchDispatch& dispatch) const;
  class MarchRounds;
  class FrameRounds;
  bool marchRegionShared(const FrameSetup& setup, const ComputePipeline& march, const MarchTarget& target,
    Progress& progress, double from, double to);
  static int marchBandRows(const std::array<int, 4>& rect, int firstRow, std::int64_t pixels, int rowStep);
  bool refineEdgesShared(const ComputePipeline& march, int pixelSamples, const std::array<int, 4>& rect,
    Progress& progress, double at, MarchRounds& rounds);
  bool selectShared(const ComputePipeline& march, const std::array<int, 4>& rect, bool refine, MarchRounds& rounds);
  bool shareEdgeQueue(MarchRounds& rounds, int queue, std::uint64_t rectPixels);
  static gpu::MarchWork ringWork(int ring);
  static gpu::MarchWork refineWork(std::int64_t first, std::int64_t count, int subRay);
  static std::uint32_t queuedGroups(std::int64_t count);
  bool marchShared(const ComputePipeline& march, gpu::MarchWork work, std::uint32_t groupsX, std::uint32_t groupsY,
    MarchRounds& rounds);
  struct SharedForwarding;
  bool forwardShared(const SharedForwarding& pass, MarchRounds& rounds);
  std::vector<char> forwardedRound(
    const SharedForwarding& pass, MarchRounds& rounds, bool started, std::vector<std::uint32_t>& slots);
  void dispatchShared(const ComputePipeline& march, const gpu::MarchWork& work, std::uint32_t groupsX,
    std::uint32_t groupsY, MarchRounds& rounds);
  void writeFreshStates(MarchRounds& rounds);
  struct SharedWalks;
  std::unique_ptr<SharedWalks> beginSharedWalks(const LayerExchange& round, std::uint64_t perShare);
  using WalkWork = std::function<gpu::LightPassWork(int share, bool resumed, std::uint64_t taken)>;
  bool walkShared(SharedWalks& walks, const ComputePipeline& pass, std::uint64_t started, const WalkWork& workOf);
  bool marchLightShared(bool braggShadow, Progress& progress, const LayerExchange& round, bool& exchanging);
  bool sweepLightShared(bool braggShadow, Progress& progress, std::pair<int, int> rows,
    const std::function<bool(int layer)>& afterLayer, const LayerExchange& round, bool& exchanging);
  bool walkQueueShared(SharedWalks& walks, const ComputePipeline& enter, int layer);
  std::uint64_t queuedWalksPerShare() const;
  bool holdsPieceOf(int share, int shares) const;
  void readRayStates(const std::vector<std::uint32_t>& slots, MarchRounds& rounds, std::uint32_t* after) const;
  int marchPieces() const;
  void recordMarchRing(VkCommandBuffer commands, const ComputePipeline& march, const std::array<int, 4>& rect) const;
  void recordMarch(VkCommandBuffer commands, const ComputePipeline& march, const gpu::MarchWork& work, std::uint32_t groupsX,
    std::uint32_t groupsY = 1) const;
  struct PieceField;
  struct PiecePass;
  // Records `dispatch` once per pass of `sweeps` sweeps through MarchPieces
  // pieces, each with `fields`' piece alone.
  void recordPiecePasses(VkCommandBuffer commands, const std::vector<PieceField>& fields, int sweeps,
    const std::function<void(const PiecePass& pass)>& dispatch) const;
  void resetForwardedLeft();
  void requireForwardedFinished(const std::string& pass) const;
  void recordSweepLayer(VkCommandBuffer commands, const ComputePipeline& sweep, const std::vector<PieceField>& fields,
    std::pair<int, int> rows, int layer, int pieces) const;
  void recordWholeFields(VkCommandBuffer commands, const std::vector<PieceField>& fields) const;
  static int marchNodes(const FrameSetup& setup);
  static std::uint64_t rayStateWords(const FrameSetup& setup);
  std::uint64_t rayStateBytes(const FrameSetup& setup, const std::array<int, 4>& rect) const;
  std::uint64_t frameRayStateBytes(const FrameSetup& setup) const;
  std::uint64_t frameStateBytes(const FrameSetup& setup) const;
  std::int64_t forwardedLightVoxels() const;
  std::uint64_t lightStateBytes(bool queued) const;
  std::uint64_t frameLightStateBytes(const FrameSetup& setup) const;
  void prepareRayStates(std::uint64_t bytes);
  // A field the march reads per voxel, its bytes per voxel, the layers
  // beyond a piece its reads take, the buffer that holds a piece's
  // (VulkanOptions::MarchPieceFieldsOnly), and whether a pass writes it
  // (its piece's layers then copied back after each dispatch).
  struct PieceField
  {
    VulkanBuffer* Whole;
    std::uint64_t VoxelBytes;
    int Halo;
    VulkanBuffer* Piece;
    bool Written;
  };
  std::vector<PieceField> marchFields() const;
  std::pair<std::uint64_t, std::uint64_t> pieceBytes(const PieceField& field, std::pair<int, int> layers) const;
  void preparePieceFields(int pieces);
  std::vector<PieceField> pieceFields() const;
  std::vector<PieceField> lightPassPieceFields(int pieces, int cellsHalo, int distanceHalo, int lightHalo) const;
  std::vector<PieceField> lightPieceFields(int pieces) const;
  std::vector<PieceField> sweepPieceFields(int pieces) const;
  void recordPieceFields(VkCommandBuffer commands, const std::vector<PieceField>& fields, std::pair<int, int> layers) const;
  void recordWrittenBack(VkCommandBuffer commands, const std::vector<PieceField>& fields, std::pair<int, int> layers) const;
  bool refineEdges(const ComputePipeline& march, int pixelSamples, Progress& progress, double at);
  void recordHighlightSelect(VkCommandBuffer commands, const std::array<int, 4>& rect);
  bool shadeHighlight(Progress& progress, double at);
  std::int64_t queuedCount(const VulkanBuffer& headers, int index) const;
  bool drainQueue(std::int64_t queued, SubmitPacer& pacer, Progress& progress, double at,
    const std::function<void(VkCommandBuffer, std::int64_t, std::int64_t)>& record);
  bool measureExposure(const FrameSetup& setup, Progress& progress, double& exposure);
  void runColourPass(const FrameSetup& setup, double exposure);
  RenderImage readBack(const FrameSetup& setup) const;
  ComputePipeline& marchPipeline(const FrameSetup& setup);
  ComputePipeline& lightPass(int mode, bool braggShadow, bool forwarded = false);
  ComputePipeline& highlightPass(int mode);
  ComputePipeline& shadowTablePass(int wavelengths, bool coupledWave);

  std::unique_ptr<VulkanContext> Context;
  std::unique_ptr<StorageBufferBindings> Bindings;
  // The light pass's three modes (shaders/opal_render_contract.h), by mode,
  // whether the volume absorbs (docs/design.md §3.9) and whether the pass
  // records Bragg shadows (§7.2), and whether it reads the fields by address (§3.7).
  std::map<std::array<int, 6>, std::unique_ptr<ComputePipeline>> LightPasses;
  // The highlight pass's two modes (select and shade), by mode and address reads.
  std::map<std::array<int, 3>, std::unique_ptr<ComputePipeline>> HighlightPasses;
  std::unique_ptr<ComputePipeline> ColourPass;
  // By wavelength count, spectral nodes (0: every wavelength), absorption,
  // coupled-wave and energy conservation (0 or 1), the bins' first centre
  // and step (their float bits), the preview's light read, the scattered
  // light and address reads and the forwarded march (0 or 1).
  std::map<std::array<std::int32_t, 12>, std::unique_ptr<ComputePipeline>> MarchPasses;
  // The Bragg shadow table's pass (§7.2), by wavelength count and Bragg model (0 paper, 1 coupled-wave).
  std::map<std::array<int, 2>, std::unique_ptr<ComputePipeline>> ShadowTablePasses;
  std::unique_ptr<DeviceVolume> Volume;
  std::unique_ptr<FrameBuffers> Buffers;
  int MarchPieces = 1; // VulkanOptions::MarchPieces
  bool MarchPieceFieldsOnly = false; // VulkanOptions::MarchPieceFieldsOnly
  std::optional<MarchShare> SharedMarch; // shareMarch
  std::pair<int, int> HeldPiece{ 0, 1 }; // holdPiece: share, shares
  std::unique_ptr<MarchRounds> Rounds;   // a shared march's, while a frame runs (FrameRounds)
  // The sweeps of the forwarded passes: MarchSweeps and LightWalkSweeps, or
  // fewer where VulkanOptions' ForwardedMarchSweeps and ForwardedLightSweeps ask.
  struct
  {
    int March, LightWalks;
  } Sweeps;
  std::vector<std::unique_ptr<VulkanBuffer>> PieceFieldBuffers; // preparePieceFields
  std::optional<LightFieldKey> LightField;                     // what the light buffers hold
  std::optional<ScatteredLightKey> ScatteredLight;             // what the scattered light buffer holds
  std::string ScatteredLightWarning;                           // the solve's shortfall, if any
  std::optional<std::array<double, 4>> WavelengthSampling;    // range, step and illuminant of the table
  double PendingUploadSeconds = -1;                            // >= 0: setVolume ran since the last frame
  double PendingScatteredSeconds = -1; // >= 0: solveScatteredLightShared solved the field the next frame reads
  double PendingLightSeconds = -1;     // >= 0: shareLightPass computed the light field the next frame reads
  double PendingFieldSeconds = -1;     // >= 0: shareScatteredField wrote the every-order field the next frame reads
  std::unique_ptr<FrameWorker<RenderFrame>> Background;        // the frame ticket's worker
  // Each pass's work per submit, from its last submit's cost (docs/design.md
  // §3.7); until measured, what took a fraction of a second on lavapipe.
  SubmitPacer MarchPacer{ 1 << 17 };    // pixels
  SubmitPacer SweepPacer{ 1 << 20 };    // voxels, in whole layers
  SubmitPacer SlabPacer{ 1 << 18 };     // voxels marched to the light
  SubmitPacer FieldPacer{ 1 << 20 };    // voxels given their every-order value
  SubmitPacer HighlightPacer{ 1 << 12 }; // queued pixels shaded
  SubmitPacer RefinePacer{ 1 << 14 };     // queued edge pixels, their first stage (PixelSamples rays each)
  SubmitPacer RefineRestPacer{ 1 << 12 }; // and their second (PixelSamples^2 - PixelSamples rays)
  int CompletedFrames = 0;
  int AbandonedFrames = 0;
};

} // namespace opal
