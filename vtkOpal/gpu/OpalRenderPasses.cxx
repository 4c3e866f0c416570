// The render session's passes (docs/design.md §3.3-3.5): the light field,
// the view march with its highlight, the exposure and the colour.
#include "OpalRenderSession.h"

#include "OpalEmbeddedShaders.h"
#include "OpalRenderSessionState.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <optional>
#include <stdexcept>
#include <functional>
#include <vector>

namespace opal
{

using namespace sessiondetail;

// Light pass: the optical depth to the light and its geometry factor for
// every voxel (docs/design.md §3.3). The buffers hold no light from the
// pass's first write until it completes, so an aborted pass leaves nothing
// stale behind: not the new light, nor the old one it half overwrote.
bool RenderSession::runLightPass(const FrameSetup& setup, Progress& progress)
{
  this->requireWholeMedium("A light field computed by one process alone");
  this->LightField.reset();
  this->holdLightLayers({ 0, this->Volume->Shape.Dimensions[2] }); // alone it computes the whole field
  const bool braggShadow = conservesEnergy(setup.Parameters);
  if (braggShadow)
  {
    this->prepareShadowField();
  }
  this->resetForwardedLeft();
  const bool completed = this->Volume->Medium.Geometry.lightAboveGrid(setup.Camera.Light)
    ? this->sweepLightLayers(braggShadow, progress, { 0, this->Volume->Shape.Dimensions[2] })
    : this->marchLightPerVoxel(braggShadow, progress);
  if (completed)
  {
    this->requireForwardedFinished("light pass");
    this->LightField = lightFieldKey(setup);
  }
  return completed;
}

// Layer by layer from the top: each layer reads the one above. With
// `walkQueue` each layer's queued walks are its (the walks shared between
// processes, walkQueueShared) after the layer's sweep, before `afterLayer`.
bool RenderSession::sweepLightLayers(bool braggShadow, Progress& progress, std::pair<int, int> rows,
  const std::function<bool(int layer)>& afterLayer, const std::function<bool(int layer)>& walkQueue)
{
  const std::array<int, 3>& dims = this->Volume->Shape.Dimensions;
  const int layers = dims[1];
  const std::int64_t layerVoxels = static_cast<std::int64_t>(dims[0]) * (rows.second - rows.first);
  const ComputePipeline& sweep = this->lightPass(gpu::LightPassSweepFromAbove, braggShadow);
  // With MarchPieces the queued walks are forwarded between the pieces (docs/design.md §8.1).
  const bool forwarded = this->MarchPieces > 1;
  const ComputePipeline& enter = this->lightPass(gpu::LightPassMarchQueued, braggShadow, forwarded);
  if (forwarded)
  {
    this->prepareRayStates(this->lightStateBytes(true));
    this->preparePieceFields(this->MarchPieces);
  }
  const std::vector<PieceField> walkFields = this->lightPieceFields(this->MarchPieces);
  // Shared with its walks (walkQueue), the pass's rows are this share's piece (HeldPiece).
  const int sweepPieces = walkQueue ? this->HeldPiece.second : this->MarchPieces;
  const std::vector<PieceField> sweepFields = this->sweepPieceFields(sweepPieces);
  for (int top = layers - 1; top >= 0;)
  {
    const int layersPerSubmit = afterLayer || walkQueue
      ? 1
      : static_cast<int>(std::clamp<std::int64_t>(this->SweepPacer.items() / std::max<std::int64_t>(layerVoxels, 1), 1, layers));
    const auto start = Clock::now();
    this->Context->submitAndWait([&](VkCommandBuffer commands) {
      if (top == layers - 1)
      {
        this->Volume->EntryQueues->recordClear(commands); // every layer's queue empty, a dispatch of none
      }
      for (int layer = top; layer > top - layersPerSubmit && layer >= 0; --layer)
      {
        this->recordSweepLayer(commands, sweep, sweepFields, rows, layer, sweepPieces);
        if (walkQueue)
        {
          continue;
        }
        const gpu::LightPassWork work{ 0, 0, layer, 0, gpu::ivec2(0, 0), 0, 0 }; // count 0: the layer's queue
        this->recordPiecePasses(commands, walkFields, this->Sweeps.LightWalks, [&](const PiecePass& pass) {
          enter.dispatchIndirect(commands, pass.of(work), *this->Volume->EntryQueues,
            static_cast<std::uint64_t>(layer) * sizeof(gpu::DispatchQueue));
        });
      }
    });
    const int swept = std::min(layersPerSubmit, top + 1);
    this->SweepPacer.measured(swept * layerVoxels, secondsSince(start));
    if (walkQueue && !walkQueue(top))
    {
      return false;
    }
    top -= swept;
    if (!progress.stageDone(static_cast<double>(layers - 1 - top) / layers) || (afterLayer && top >= 0 && !afterLayer(top + 1)))
    {
      return false;
    }
  }
  return true;
}

// Every voxel marches to the light (lights low or to the side); with
// MarchPieces, its walk forwarded between the pieces (docs/design.md §8.1).
bool RenderSession::marchLightPerVoxel(bool braggShadow, Progress& progress)
{
  const bool forwarded = this->MarchPieces > 1;
  if (forwarded)
  {
    this->prepareRayStates(this->lightStateBytes(false));
    this->preparePieceFields(this->MarchPieces);
  }
  return this->dispatchOverVoxels(this->lightPass(gpu::LightPassMarchTowardsLight, braggShadow, forwarded),
    this->SlabPacer, progress.stageCallback(), 0, this->Volume->Shape.voxelCount(), forwarded);
}

// `pass` (a light pass's mode over voxel ranges) over voxels [begin, end), in
// submits `pacer` sizes; `keepGoing` (the fraction done) after each, false
// stops. `forwarded`: each submit's walks forwarded between the pieces
// (recordPiecePasses), forwardedLightVoxels at most.
bool RenderSession::dispatchOverVoxels(const ComputePipeline& pass, SubmitPacer& pacer,
  const std::function<bool(double)>& keepGoing, std::size_t begin, std::size_t end, bool forwarded)
{
  const std::int64_t most = forwarded ? this->forwardedLightVoxels() : std::int64_t(1) << 30;
  for (std::size_t first = begin; first < end;)
  {
    const auto count = static_cast<std::int32_t>(
      std::min<std::size_t>(static_cast<std::size_t>(std::min<std::int64_t>(pacer.items(), most)), end - first));
    const gpu::LightPassWork work{ static_cast<std::uint32_t>(first), count, 0, 0, gpu::ivec2(0, 0), 0, 0 };
    const auto groups = static_cast<std::uint32_t>((count + gpu::LightPassGroupSize - 1) / gpu::LightPassGroupSize);
    const auto start = Clock::now();
    this->Context->submitAndWait([&](VkCommandBuffer commands) {
      if (!forwarded)
      {
        pass.dispatch(commands, work, groups);
        return;
      }
      this->recordPiecePasses(commands, this->lightPieceFields(this->MarchPieces), this->Sweeps.LightWalks,
        [&](const PiecePass& piecePass) { pass.dispatch(commands, piecePass.of(work), groups); });
    });
    pacer.measured(count, secondsSince(start));
    first += static_cast<std::size_t>(count);
    if (keepGoing && !keepGoing(static_cast<double>(first - begin) / static_cast<double>(end - begin)))
    {
      return false;
    }
  }
  return true;
}

// A light pass's mode for the volume: with ABSORPTION if it absorbs, with
// BRAGG_SHADOW if asked, FORWARDED if `forwarded` (made on first use).
ComputePipeline& RenderSession::lightPass(int mode, bool braggShadow, bool forwarded)
{
  const int absorbs = this->Volume->Absorbs ? 1 : 0;
  const int shadow = braggShadow ? 1 : 0;
  const bool addressed = this->Volume->addressed();
  const int paired = this->Volume->PairedFields ? 1 : 0;
  const int forwards = forwarded ? 1 : 0;
  std::unique_ptr<ComputePipeline>& pass = this->LightPasses[{ mode, absorbs, shadow, addressed ? 1 : 0, paired, forwards }];
  if (!pass)
  {
    const embedded::Spirv code =
      addressed ? embedded::lightOpticalDepthAddressedShader() : embedded::lightOpticalDepthShader();
    pass = std::make_unique<ComputePipeline>(*this->Context, *this->Bindings, code.Words, code.WordCount,
      specialisation(gpu::LightPassConstantCount,
        { { gpu::LightPassModeConstant, mode }, { gpu::LightAbsorptionConstant, absorbs },
          { gpu::LightBraggShadowConstant, shadow }, { gpu::LightPairedFieldsConstant, paired },
          { gpu::LightForwardedConstant, forwards } }));
  }
  return *pass;
}

// The light scattered more than once (docs/design.md §3.10), solved on the
// host for the frame's light and uploaded; nothing is held while it runs, so
// an aborted solve leaves no stale field.
bool RenderSession::runScatteredLight(const FrameSetup& setup, Progress& progress)
{
  this->requireWholeMedium("The every-order solve of one process alone");
  this->ScatteredLight.reset();
  const MediumRelease release(*this);
  const ScatteringMedium& medium = this->scatteringMedium();
  const std::optional<opal::ScatteredLight> field = solveScatteredLight(
    medium, scatteredLightRequest(setup), progress.stageCallback());
  if (!field)
  {
    return false;
  }
  this->holdScatteredLight(setup, *field);
  return true;
}

// A preview (the live view's drag, where a headlight moves with the eye)
// reads the field the session holds, solved for an earlier light; the final
// frame solves for its own (docs/design.md §3.10).
bool RenderSession::scatteredLightServes(const FrameSetup& setup) const
{
  return this->ScatteredLight && (setup.Preview || *this->ScatteredLight == scatteredLightKey(setup));
}

ScatteredLightRequest RenderSession::scatteredLightRequest(const FrameSetup& setup)
{
  ScatteredLightRequest request;
  request.Light = setup.Camera.Light;
  request.LightStrength = setup.Block.apexDistanceSquared;
  request.RefractiveIndex = setup.Parameters.RefractiveIndex;
  request.NodeScales = scatteredLightScales(setup.Bins.front().Lambda, setup.Bins.back().Lambda);
  request.Photons = setup.Parameters.ScatteringPhotons;
  return request;
}

void RenderSession::holdScatteredLight(const FrameSetup& setup, const opal::ScatteredLight& field)
{
  DeviceVolume& v = *this->Volume;
  // The solve's tally grid goes to the device, and the frame's light pass
  // writes each voxel's value from it (writeScatteredField), or the march
  // evaluates it (placeScatteredField): the host never evaluates the field
  // per voxel (docs/design.md §3.10).
  const std::vector<opal::ScatteredLight::GridNode> grid = field.gridNodes();
  std::vector<gpu::ScatteredLightNode> nodes(grid.size()); // zeroed, padding included
  for (std::size_t n = 0; n < grid.size(); ++n)
  {
    nodes[n].tally = gpu::vec4(grid[n].Tally[0], grid[n].Tally[1], grid[n].Tally[2], grid[n].Tally[3]);
    nodes[n].volume = grid[n].Volume;
  }
  const std::uint64_t gridBytes = nodes.size() * sizeof(gpu::ScatteredLightNode);
  // Made before the old grid goes (a few MB): a failed allocation leaves a
  // bound grid, and no key, so the next frame solves again.
  auto held = std::make_unique<VulkanBuffer>(*this->Context, gridBytes, "scattered light tally grid", v.FieldPlacement);
  held->upload(nodes.data(), gridBytes);
  v.ScatteredLightGrid = std::move(held);
  v.ScatteredFieldPending = true;
  this->bindBuffers();
  this->ScatteredLightWarning = field.Warning;
  this->ScatteredLight = scatteredLightKey(setup);
}

// The every-order field per voxel where the frame's budget holds it, else its
// placeholder, and the march evaluates the tally grid (setUpFrame,
// docs/design.md §3.10). Before the frame's buffers grow, so that a field the
// budget no longer counts is freed first.
void RenderSession::placeScatteredField(const FrameSetup& setup)
{
  DeviceVolume& v = *this->Volume;
  const bool perVoxel = !setup.ScatteredLightFromGrid;
  if (!scattersEveryOrder(setup.Parameters) || perVoxel == v.HasScatteredField)
  {
    return;
  }
  this->makeScatteredField(perVoxel);
  this->bindBuffers();
}

// The every-order field per voxel for the layers held, or its placeholder,
// to be written from the grid held. Made before the old one goes (the
// placeholder is a vec4): a failed allocation leaves the old buffer and the
// flags as they were.
void RenderSession::makeScatteredField(bool perVoxel)
{
  DeviceVolume& v = *this->Volume;
  std::unique_ptr<VulkanBuffer> next = perVoxel
    ? std::make_unique<VulkanBuffer>(
        *this->Context, v.heldFieldBytes(sizeof(gpu::vec4)), "scattered light field", v.FieldPlacement)
    : scatteredLightPlaceholder(*this->Context, v.FieldPlacement);
  v.ScatteredLight = std::move(next);
  v.HasScatteredField = perVoxel;
  v.ScatteredFieldPending = true;
}

// The held grid's field per voxel, by the light pass (LightPassScatteredField),
// at the voxels held (all, or a piece: holdPiece; each voxel's value is the
// grid's at it alone). In the frame, once its buffers are bound and its
// parameters (the grid's shape) uploaded: a solve shared by processes holds
// its grid before them.
void RenderSession::writeScatteredField()
{
  const DeviceVolume& v = *this->Volume;
  if (v.ScatteredLight->size() < v.lightVoxels() * sizeof(gpu::vec4))
  {
    throw std::logic_error("writeScatteredField: the every-order field holds fewer voxels than its layers.");
  }
  this->dispatchOverVoxels(this->lightPass(gpu::LightPassScatteredField, false), this->FieldPacer, nullptr,
    v.lightFirstVoxel(), v.lightFirstVoxel() + v.lightVoxels());
  this->Volume->ScatteredFieldPending = false;
}

bool RenderSession::needsScatteredLight(const ResolvedFrame& frame) const
{
  if (!this->Volume || !scattersEveryOrder(frame.Parameters))
  {
    return false;
  }
  return !this->scatteredLightServes(this->setUpFrame(frame));
}

bool RenderSession::solveScatteredLightShared(const ResolvedFrame& frame, int share, int shares,
  const ScoresExchange& exchange, const LayerExchange& round, const RenderProgress& callback)
{
  const auto start = Clock::now();
  std::optional<FrameSetup> setup;
  const ScatteringMedium* medium = nullptr;
  std::optional<std::vector<double>> mine;
  std::exception_ptr failure;
  bool exchanging = true;
  const MediumRelease release(*this);
  try
  {
    setup = this->setUpSharedStep(frame);
    this->ScatteredLight.reset();
    Progress progress(callback);
    // After a light field the processes marched (its first half), and the
    // frame's light pass then reports none (renderFrame).
    progress.stage(this->PendingLightSeconds >= 0 ? FrameLightShare * 0.5 : 0.0, FrameLightShare);
    medium = this->shareScatteringMedium(share, shares, round, exchanging);
    if (medium)
    {
      mine = traceScatteredLightShare(*medium, scatteredLightRequest(*setup), share, shares, progress.stageCallback());
    }
  }
  catch (...)
  {
    failure = std::current_exception();
    mine.reset();
  }
  const std::optional<std::vector<std::vector<double>>> scores = exchanging ? exchange(mine) : std::nullopt;
  if (failure)
  {
    std::rethrow_exception(failure);
  }
  if (!mine || !scores)
  {
    return false;
  }
  this->holdScatteredLight(*setup, scatteredLightFromShares(*medium, scatteredLightRequest(*setup), *scores));
  this->PendingScatteredSeconds = secondsSince(start);
  return true;
}

// The Bragg shadow field, made the first time a light pass records it.
void RenderSession::prepareShadowField()
{
  DeviceVolume& v = *this->Volume;
  if (v.HasShadowField)
  {
    return;
  }
  v.LightShadow.reset();
  v.LightShadow = std::make_unique<VulkanBuffer>(*this->Context, v.heldFieldBytes(sizeof(gpu::LightShadow)),
    "light Bragg shadow field", v.FieldPlacement);
  v.HasShadowField = true;
  this->bindBuffers();
}

// The Bragg shadow table (docs/design.md §7.2): what each domain passes of
// the light, read by the march that conserves energy. Every frame: it follows
// the light, the bins and the model, and costs a dispatch of one invocation
// per domain.
void RenderSession::runShadowTable(const FrameSetup& setup)
{
  const int domains = setup.Block.domainCount;
  if (!conservesEnergy(setup.Parameters) || domains == 0)
  {
    return;
  }
  const ComputePipeline& pass = this->shadowTablePass(
    setup.Block.wavelengthCount, setup.Parameters.BraggModel == BraggModelKind::CoupledWave);
  const gpu::MarchWork unused{};
  this->Context->submitAndWait([&](VkCommandBuffer commands) {
    pass.dispatch(commands, unused, static_cast<std::uint32_t>((domains + gpu::ShadowTableGroupSize - 1) / gpu::ShadowTableGroupSize));
  });
}

// The Bragg shadow table's pass for a wavelength count and Bragg model (made on first use).
ComputePipeline& RenderSession::shadowTablePass(int wavelengths, bool coupledWave)
{
  std::unique_ptr<ComputePipeline>& pass = this->ShadowTablePasses[{ wavelengths, coupledWave ? 1 : 0 }];
  if (!pass)
  {
    const embedded::Spirv code = embedded::braggShadowTableShader();
    pass = std::make_unique<ComputePipeline>(*this->Context, *this->Bindings, code.Words, code.WordCount,
      specialisation(gpu::ShadowTableConstantCount, { { gpu::ShadowTableWavelengthsConstant, wavelengths },
        { gpu::ShadowTableCoupledWaveConstant, coupledWave ? 1 : 0 } }));
  }
  return *pass;
}

namespace
{
// The bits of a float, as a specialisation constant takes them.
std::int32_t floatBits(double value)
{
  const float single = static_cast<float>(value);
  std::int32_t bits;
  std::memcpy(&bits, &single, sizeof bits);
  return bits;
}
} // namespace

// The march for the frame's wavelength bins: the scattering spectrum on
// nodes, or at every wavelength where nodes are off or would not be fewer
// than the bins; with ABSORPTION if the volume absorbs; with the frame's
// Bragg model. The bins' first centre and step are constants of the pipeline,
// whether the light field is read per voxel (the preview; docs/design.md §3.4)
// and where the every-order field is read from (§3.10).
ComputePipeline& RenderSession::marchPipeline(const FrameSetup& setup)
{
  const int wavelengths = static_cast<int>(setup.Bins.size());
  const RenderParameters& p = setup.Parameters;
  const bool exact = marchNodes(setup) == 0;
  const int nodes = exact ? 4 : marchNodes(setup);
  const int absorbs = this->Volume->Absorbs ? 1 : 0;
  const int coupled = p.BraggModel == BraggModelKind::CoupledWave ? 1 : 0;
  const int energy = conservesEnergy(p) ? 1 : 0;
  const std::int32_t first = floatBits(setup.Bins.front().Lambda), step = floatBits(setup.Bins.front().Width);
  const int nearestLight = setup.Preview ? 1 : 0;
  const int scattered = !scattersEveryOrder(p) ? gpu::MarchScatteredLightNone
    : setup.ScatteredLightFromGrid                                    ? gpu::MarchScatteredLightFromGrid
                                                                      : gpu::MarchScatteredLightPerVoxel;
  const bool addressed = this->Volume->addressed();
  const int paired = this->Volume->PairedFields ? 1 : 0;
  const int forwarded = this->marchPieces() > 1 ? 1 : 0;
  std::unique_ptr<ComputePipeline>& march = this->MarchPasses[{ wavelengths, exact ? 0 : nodes, absorbs, coupled,
    energy, first, step, nearestLight, scattered, addressed ? 1 : 0, paired, forwarded }];
  if (!march)
  {
    const embedded::Spirv code = addressed ? embedded::viewMarchAddressedShader() : embedded::viewMarchShader();
    march = std::make_unique<ComputePipeline>(*this->Context, *this->Bindings, code.Words, code.WordCount,
      specialisation(gpu::MarchConstantCount,
        { { gpu::MarchWavelengthsConstant, wavelengths }, { gpu::MarchSpectralNodesConstant, nodes },
          { gpu::MarchExactScatteringConstant, exact ? 1 : 0 }, { gpu::MarchAbsorptionConstant, absorbs },
          { gpu::MarchCoupledWaveConstant, coupled }, { gpu::MarchEnergyConservationConstant, energy },
          { gpu::MarchFirstWavelengthConstant, first }, { gpu::MarchWavelengthStepConstant, step },
          { gpu::MarchNearestLightConstant, nearestLight }, { gpu::MarchScatteredLightConstant, scattered },
          { gpu::MarchPairedFieldsConstant, paired }, { gpu::MarchForwardedConstant, forwarded } }));
  }
  return *march;
}

// March a rectangle of an image (docs/design.md §3.4) in bands of rows, one
// submit each (so no frame trips a device timeout); then, with PixelSamples
// above 1, refine the pixels an edge crosses; then the highlight. Progress
// in [from, to].
bool RenderSession::marchRegion(const FrameSetup& setup, const MarchTarget& target, Progress& progress, double from, double to)
{
  const std::array<int, 4>& rect = target.Rect;
  gpu::RenderParameterBlock block = setup.Block;
  block.imageWidth = target.Size[0];
  block.imageHeight = target.Size[1];
  block.rectOrigin = gpu::ivec2(rect[0], rect[1]);
  block.rectSize = gpu::ivec2(rect[2], rect[3]);
  block.writeSpectrum = target.Spectrum ? 1 : 0;
  block.pixelSamples = target.PixelSamples;
  this->uploadParameterBlock(block);
  this->prepareRayStates(this->rayStateBytes(setup, rect));
  this->preparePieceFields(this->marchPieces());
  const ComputePipeline& march = this->marchPipeline(setup);
  if (this->SharedMarch)
  {
    return this->marchRegionShared(setup, march, target, progress, from, to);
  }
  const bool refine = target.PixelSamples > 1;
  const std::int64_t rowPixels = static_cast<std::int64_t>(marchGroups(rect[2])) * gpu::MarchGroupSide;
  for (int firstRow = 0; firstRow < rect[3];)
  {
    const int rows = this->marchBandRows(rect, firstRow, this->MarchPacer.items(), MarchTileSize);
    const bool last = firstRow + rows == rect[3];
    const auto start = Clock::now();
    this->Context->submitAndWait([&](VkCommandBuffer commands) {
      if (last && refine) // emptied before the march, whose pipeline reads it
      {
        this->Buffers->EdgeQueue->recordClear(commands);
      }
      recordMarchRows(commands, march, gpu::MarchPixels, rect[2], firstRow, rows);
      if (last && refine) // every pixel's centre ray is marched: the ring's too, then the select
      {
        recordMarchRing(commands, march, rect);
        recordMarchRows(commands, march, gpu::MarchSelectEdges, rect[2], 0, rect[3]);
      }
      if (last)
      {
        this->recordHighlightSelect(commands, rect); // the march recorded every mirror ray
      }
    });
    this->MarchPacer.measured(static_cast<std::int64_t>(rows) * rowPixels, secondsSince(start));
    firstRow += rows;
    if (!progress.report(from + (to - from) * 0.8 * firstRow / rect[3]))
    {
      return false;
    }
  }
  const double refined = from + (to - from) * 0.9;
  return (!refine || this->refineEdges(march, target.PixelSamples, progress, refined)) &&
    this->shadeHighlight(progress, refined) &&
    progress.report(to);
}

// The rows of the rectangle's band from `firstRow`: bands of whole rows of
// `rowStep` (MarchTileSize; a shared march's, a workgroup's), one dispatch
// each (the pixels are independent: no barrier between them), as many rows
// per submit as `pixels` allow (the pacer's), one step at least.
int RenderSession::marchBandRows(const std::array<int, 4>& rect, int firstRow, std::int64_t pixels, int rowStep)
{
  const std::int64_t rowPixels = static_cast<std::int64_t>(marchGroups(rect[2])) * gpu::MarchGroupSide;
  return static_cast<int>(
    std::min<std::int64_t>(std::max<std::int64_t>(1, pixels / (rowPixels * rowStep)) * rowStep, rect[3] - firstRow));
}

// The march's workgroups across `width` pixels.
int RenderSession::marchGroups(int width)
{
  return (width + gpu::MarchGroupSide - 1) / gpu::MarchGroupSide;
}

// The march's work in `mode` over `rows` rows of the rectangle from
// `firstRow`, its whole width, handed to `dispatch`: one dispatch, in
// columns only beyond the device's group count.
void RenderSession::forMarchColumns(int mode, int width, int firstRow, int rows, const MarchDispatch& dispatch) const
{
  const int groupsX = marchGroups(width);
  const auto groupsY = static_cast<std::uint32_t>((rows + gpu::MarchGroupSide - 1) / gpu::MarchGroupSide);
  const auto maxGroupsX = static_cast<int>(std::min<std::uint32_t>(this->Context->limits().maxComputeWorkGroupCount[0], 1u << 30));
  for (int column = 0; column < groupsX; column += maxGroupsX)
  {
    const gpu::MarchWork work{ gpu::ivec2(column * gpu::MarchGroupSide, firstRow), mode, 0, 0, 0, gpu::ivec2(0, 0), 0, 0, 0 };
    dispatch(work, static_cast<std::uint32_t>(std::min(maxGroupsX, groupsX - column)), groupsY);
  }
}

// Records the march in `mode` over `rows` rows of the rectangle from `firstRow` (forMarchColumns).
void RenderSession::recordMarchRows(
  VkCommandBuffer commands, const ComputePipeline& march, int mode, int width, int firstRow, int rows) const
{
  this->forMarchColumns(mode, width, firstRow, rows, [&](const gpu::MarchWork& work, std::uint32_t groups, std::uint32_t groupsY) {
    if (mode == gpu::MarchSelectEdges)
    {
      march.dispatch(commands, work, groups, groupsY); // marches no ray
    }
    else
    {
      this->recordMarch(commands, march, work, groups, groupsY);
    }
  });
}

// The march's centre rays of the ring of pixels around the rectangle (the
// edge select's neighbours beyond it), in one dispatch.
void RenderSession::recordMarchRing(
  VkCommandBuffer commands, const ComputePipeline& march, const std::array<int, 4>& rect) const
{
  const int ring = MARCH_RING_PIXELS(rect[2], rect[3]);
  this->recordMarch(commands, march, ringWork(ring), queuedGroups(ring));
}

// The march's work over the `ring` pixels around the rectangle.
gpu::MarchWork RenderSession::ringWork(int ring)
{
  return gpu::MarchWork{ gpu::ivec2(0, 0), gpu::MarchRing, 0, ring, 0, gpu::ivec2(0, 0), 0, 0, 0 };
}

// The march's work over queued edge pixels [first, first + count), their sub-ray `subRay`.
gpu::MarchWork RenderSession::refineWork(std::int64_t first, std::int64_t count, int subRay)
{
  return gpu::MarchWork{ gpu::ivec2(0, 0), gpu::MarchRefineEdges, static_cast<std::int32_t>(first),
    static_cast<std::int32_t>(count), subRay, gpu::ivec2(0, 0), 0, 0, 0 };
}

// The march's workgroups over `count` queued items (ring or edge pixels).
std::uint32_t RenderSession::queuedGroups(std::int64_t count)
{
  constexpr std::int64_t groupPixels = gpu::MarchGroupSide * gpu::MarchGroupSide;
  return static_cast<std::uint32_t>((count + groupPixels - 1) / groupPixels);
}

// The pixels the edge select queued, each the mean of PixelSamples^2
// sub-rays, one dispatch per sub-ray (docs/design.md §3.4), in submits the
// pacers size: the first stage's PixelSamples sub-rays for every queued
// pixel, then the rest for those the first stage queued again.
bool RenderSession::refineEdges(const ComputePipeline& march, int pixelSamples, Progress& progress, double at)
{
  const int n = pixelSamples;
  const auto stage = [&](int queue, int fromRay, int toRay, SubmitPacer& pacer) {
    const std::int64_t queued = queuedCount(*this->Buffers->EdgeQueue, queue);
    return this->drainQueue(queued, pacer, progress, at,
      [&](VkCommandBuffer commands, std::int64_t first, std::int64_t count) {
        for (int subRay = fromRay; subRay < toRay; ++subRay)
        {
          this->recordMarch(commands, march, refineWork(first, count, subRay), queuedGroups(count));
        }
      });
  };
  return stage(0, 0, n, this->RefinePacer) && stage(1, n, n * n, this->RefineRestPacer);
}

// The highlight's select over the rectangle the march wrote (it recorded
// the mirror rays): the queue emptied, every pixel selects.
void RenderSession::recordHighlightSelect(VkCommandBuffer commands, const std::array<int, 4>& rect)
{
  const std::int64_t pixels = static_cast<std::int64_t>(rect[2]) * rect[3];
  this->Buffers->HighlightQueue->recordClear(commands);
  this->highlightPass(gpu::HighlightSelect)
    .dispatch(commands, gpu::HighlightWork{ 0, 0 },
      static_cast<std::uint32_t>((pixels + gpu::HighlightGroupSize - 1) / gpu::HighlightGroupSize));
}

// The highlight's shade over the queued few, in submits the pacer sizes: a
// pixel near the light's image takes up to 64 x 64 sub-rays, so the shade's
// cost is not the image's.
bool RenderSession::shadeHighlight(Progress& progress, double at)
{
  const std::int64_t queued = queuedCount(*this->Buffers->HighlightQueue, 0);
  return this->drainQueue(queued, this->HighlightPacer, progress, at,
    [&](VkCommandBuffer commands, std::int64_t first, std::int64_t count) {
      this->highlightPass(gpu::HighlightShade)
        .dispatch(commands, gpu::HighlightWork{ static_cast<std::int32_t>(first), static_cast<std::int32_t>(count) },
          static_cast<std::uint32_t>((count + gpu::HighlightGroupSize - 1) / gpu::HighlightGroupSize));
    });
}

// How many items a pass queued in the DispatchQueue `index` of the array `headers`.
std::int64_t RenderSession::queuedCount(const VulkanBuffer& headers, int index) const
{
  const auto bytes = static_cast<std::uint64_t>(index + 1) * sizeof(gpu::DispatchQueue);
  const HostReadback queue(*this->Context, { { &headers, bytes } });
  return static_cast<std::int64_t>(queue.view<gpu::DispatchQueue>(0)[index].count);
}

// Runs `queued` items in submits of the pacer's size, `record` recording the
// dispatch of items [first, first + count); false once the caller aborts.
bool RenderSession::drainQueue(std::int64_t queued, SubmitPacer& pacer, Progress& progress, double at,
  const std::function<void(VkCommandBuffer, std::int64_t, std::int64_t)>& record)
{
  for (std::int64_t first = 0; first < queued;)
  {
    const std::int64_t count = std::min(queued - first, pacer.items());
    const auto start = Clock::now();
    this->Context->submitAndWait([&](VkCommandBuffer commands) { record(commands, first, count); });
    pacer.measured(count, secondsSince(start));
    first += count;
    if (!progress.report(at))
    {
      return false;
    }
  }
  return true;
}

// A highlight pass's mode for the volume's field reads (made on first use).
ComputePipeline& RenderSession::highlightPass(int mode)
{
  const bool addressed = this->Volume->addressed();
  const int paired = this->Volume->PairedFields ? 1 : 0;
  std::unique_ptr<ComputePipeline>& pass = this->HighlightPasses[{ mode, addressed ? 1 : 0, paired }];
  if (!pass)
  {
    const embedded::Spirv code =
      addressed ? embedded::specularHighlightAddressedShader() : embedded::specularHighlightShader();
    pass = std::make_unique<ComputePipeline>(*this->Context, *this->Bindings, code.Words, code.WordCount,
      specialisation(gpu::HighlightConstantCount,
        { { gpu::HighlightModeConstant, mode }, { gpu::HighlightPairedFieldsConstant, paired } }));
  }
  return *pass;
}

// Automatic exposure: the body's median luminance to a mid grey (0.18),
// measured on a thumbnail of the whole image, so that any region or piece
// of the image gets the same exposure and pieces agree with the whole.
bool RenderSession::measureExposure(const FrameSetup& setup, Progress& progress, double& exposure)
{
  const std::array<int, 2>& size = setup.Thumbnail;
  // One ray per pixel: the thumbnail's median needs no edges.
  if (!this->marchRegion(setup, MarchTarget{ size, { 0, 0, size[0], size[1] }, false, 1 }, progress, FrameLightShare, 0.25))
  {
    return false;
  }
  const std::size_t pixels = static_cast<std::size_t>(size[0]) * static_cast<std::size_t>(size[1]);
  const HostReadback host(*this->Context, { { this->Buffers->PixelColour.get(), pixels * sizeof(gpu::PixelColour) },
    { this->Buffers->PixelBragg.get(), pixels * sizeof(gpu::PixelBragg) } });
  const auto* colour = host.view<gpu::PixelColour>(0);
  const auto* bragg = host.view<gpu::PixelBragg>(1);
  std::vector<float> luminance;
  for (std::size_t i = 0; i < pixels; ++i)
  {
    if (bragg[i].coverage > 0 && colour[i].xyz.y > 0)
    {
      luminance.push_back(colour[i].xyz.y);
    }
  }
  exposure = 1.0;
  if (!luminance.empty())
  {
    std::nth_element(luminance.begin(), luminance.begin() + luminance.size() / 2, luminance.end());
    exposure = std::min(0.18 / luminance[luminance.size() / 2], MaxExposure); // a subnormal median
  }
  return true;
}

// Colour: XYZ to linear and 8-bit sRGB with the exposure (one dispatch,
// split by ComputePipeline where it exceeds the device's group count).
void RenderSession::runColourPass(const FrameSetup& setup, double exposure)
{
  gpu::RenderParameterBlock* block = this->Buffers->Parameters->as<gpu::RenderParameterBlock>();
  block->exposure = static_cast<float>(exposure);
  const gpu::MarchWork unused{};
  this->Context->submitAndWait([&](VkCommandBuffer commands) {
    this->ColourPass->dispatch(commands, unused,
      static_cast<std::uint32_t>((setup.Pixels + gpu::ColourGroupSize - 1) / gpu::ColourGroupSize));
  });
}

// Read-back: the pixel buffers into the image's arrays.
} // namespace opal
