#include "OpalRenderSession.h"

#include "OpalCoupledWave.h"
#include "OpalLatticePlanes.h"

#include "OpalEmbeddedShaders.h"
#include "OpalMemory.h"
#include "OpalOptics.h"
#include "OpalParallel.h"
#include "OpalRenderSessionState.h"
#include "OpalSessionRegistry.h"
#include "OpalSkinCells.h"
#include "OpalSurfaceTiles.h"
#include "OpalVulkanError.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace opal
{

using namespace sessiondetail;

namespace
{
// SurfaceDistance as the shaders read it (SurfaceDistanceBinding) at voxel
// i: its value and its +x neighbour's, the last voxel of a row repeating its
// own, so that a trilinear read takes four loads instead of eight.
gpu::vec2 surfaceDistancePair(const RenderVolume& volume, std::size_t i)
{
  const auto rowLength = static_cast<std::size_t>(volume.Dimensions[0]);
  return gpu::vec2(volume.SurfaceDistance[i], volume.SurfaceDistance[(i + 1) % rowLength == 0 ? i : i + 1]);
}

// Writes value(i) for the voxels i in [begin, end) into values[i - begin],
// spread over the threads in blocks, each skin cell among them (in index
// order, skinCells) taking its source's value (docs/design.md §3.3).
template <typename T, typename Value>
void writeVoxels(T* values, std::size_t begin, std::size_t end, const std::vector<SkinCell>& skin, Value&& value)
{
  constexpr std::size_t Block = 4096;
  parallelFor(0, static_cast<int>((end - begin + Block - 1) / Block), [&](int from, int to) {
    for (std::size_t i = begin + from * Block; i < std::min(end, begin + to * Block); ++i)
    {
      values[i - begin] = value(i);
    }
  });
  auto cell = std::lower_bound(skin.begin(), skin.end(), begin,
    [](const SkinCell& c, std::size_t index) { return static_cast<std::size_t>(c.Index) < index; });
  for (; cell != skin.end() && static_cast<std::size_t>(cell->Index) < end; ++cell)
  {
    values[static_cast<std::size_t>(cell->Index) - begin] = value(static_cast<std::size_t>(cell->Source));
  }
}

// The coupled-wave model's settings (docs/design.md §7.2): the crystal's mean
// index and permittivity contrast, the layers and the plane families.
void setCoupledWave(gpu::RenderParameterBlock& block, const RenderParameters& p, const RenderVolume& volume)
{
  ColloidalCrystal crystal;
  crystal.SphereIndex = volume.SphereRefractiveIndex;
  crystal.MatrixIndex = volume.MatrixRefractiveIndex;
  block.meanIndex = static_cast<float>(meanIndex(crystal));
  // eps_G = f (n_s^2 - n_m^2) 3 j1(x)/x: the contrast at x = 0.
  block.permittivityContrast = static_cast<float>(permittivityFourierComponent(crystal, 0.0));
  block.coherentLayers = static_cast<float>(p.CoherentLayers);
  block.latticeFamilies = p.LatticePlanes == LatticePlaneSet::Fcc ? FccPlaneCount : 1;
}

// The domain table as the shaders read it (DomainTableBinding).
std::vector<gpu::DomainRecord> domainRecords(const RenderVolume& volume)
{
  const std::vector<std::array<double, 3>> centres = volume.domainCentres();
  std::vector<gpu::DomainRecord> records;
  for (std::size_t i = 0; i < volume.Domains.size(); ++i)
  {
    const RenderDomain& domain = volume.Domains[i];
    const auto& q = domain.Orientation; // (w, x, y, z) -> the contract's (x, y, z, w)
    records.push_back({ gpu::vec3(domain.LatticeNormal[0], domain.LatticeNormal[1], domain.LatticeNormal[2]),
      domain.PlaneSpacing, gpu::vec4(q[1], q[2], q[3], q[0]), toVec3(centres[i]), 0.0f });
  }
  return records;
}

// The passes' workgroups within the device's limits (docs/design.md §3.7),
// checked once: a device that cannot run one is refused naming the limit.
// (Vulkan guarantees 65535 groups per axis and 128 invocations; the light
// pass takes 256.)
void checkWorkgroupSizes(const VkPhysicalDeviceLimits& limits)
{
  const auto tileGroups = static_cast<std::uint32_t>(MarchTileSize / gpu::MarchGroupSide);
  if (limits.maxComputeWorkGroupCount[0] < tileGroups || limits.maxComputeWorkGroupCount[1] < tileGroups)
  {
    throw VulkanError("the device dispatches fewer than " + std::to_string(tileGroups) +
        " workgroups per axis (maxComputeWorkGroupCount), a march tile's", VK_ERROR_FEATURE_NOT_PRESENT);
  }
  struct Group
  {
    const char* Pass;
    int X, Y;
  };
  for (const Group& group : { Group{ "light pass", gpu::LightPassGroupSize, 1 }, { "highlight", gpu::HighlightGroupSize, 1 },
         { "shadow table", gpu::ShadowTableGroupSize, 1 }, { "colour pass", gpu::ColourGroupSize, 1 },
         { "view march", gpu::MarchGroupSide, gpu::MarchGroupSide } })
  {
    const auto x = static_cast<std::uint32_t>(group.X), y = static_cast<std::uint32_t>(group.Y);
    if (x > limits.maxComputeWorkGroupSize[0] || y > limits.maxComputeWorkGroupSize[1] ||
      x * y > limits.maxComputeWorkGroupInvocations)
    {
      throw VulkanError(std::string("the device's compute workgroups are too small for the ") + group.Pass + " (" +
          std::to_string(group.X) + " x " + std::to_string(group.Y) + " invocations; maxComputeWorkGroupSize " +
          std::to_string(limits.maxComputeWorkGroupSize[0]) + " x " + std::to_string(limits.maxComputeWorkGroupSize[1]) +
          ", maxComputeWorkGroupInvocations " + std::to_string(limits.maxComputeWorkGroupInvocations) + ")",
        VK_ERROR_FEATURE_NOT_PRESENT);
    }
  }
}

// A buffer in device-local memory (addressed by the shaders where
// `placement` says so), holding `values` if given: what only the device
// reads and writes.
std::unique_ptr<VulkanBuffer> deviceLocalBuffer(VulkanContext& context, std::uint64_t bytes, const char* what,
  const void* values = nullptr, BufferPlacement placement = BufferPlacement::DeviceLocal)
{
  auto buffer = std::make_unique<VulkanBuffer>(context, bytes, what, placement);
  if (values)
  {
    buffer->upload(values, bytes);
  }
  return buffer;
}

// A per-voxel field of T on the device, `placement`, of voxels [first,
// second) of the grid (all, or a piece's layers: holdPiece), written round by
// round (VulkanBuffer::fill), so the whole field is never built on the host
// (docs/design.md §3.7).
template <typename T, typename Value>
std::unique_ptr<VulkanBuffer> deviceVoxelField(VulkanContext& context, std::pair<std::size_t, std::size_t> voxels,
  const char* what, BufferPlacement placement, const std::vector<SkinCell>& skin, Value&& value)
{
  const std::uint64_t bytes = std::max<std::uint64_t>((voxels.second - voxels.first) * sizeof(T), 16);
  auto buffer = deviceLocalBuffer(context, bytes, what, nullptr, placement);
  buffer->fill((voxels.second - voxels.first) * sizeof(T), [&](std::uint64_t first, std::uint64_t count, void* into) {
    writeVoxels(static_cast<T*>(into), voxels.first + first / sizeof(T), voxels.first + (first + count) / sizeof(T),
      skin, value);
  });
  return buffer;
}

// AbsorptionCoefficient on the device as the shaders read it
// (AbsorptionCellBinding): per voxel (coloured, grey) mu_a at 550 nm, a voxel
// of exponent 0 grey, the skin filled like the cells (docs/design.md §3.9).
// Without absorption a placeholder, bound but never read (the passes without ABSORPTION).
std::unique_ptr<VulkanBuffer> absorptionBuffer(VulkanContext& context, const RenderVolume& volume,
  std::pair<std::size_t, std::size_t> voxels, const std::vector<SkinCell>& skin, BufferPlacement placement)
{
  if (!volume.absorbs())
  {
    return deviceLocalBuffer(context, sizeof(gpu::LightFieldPair), "absorption placeholder", nullptr, placement);
  }
  return deviceVoxelField<gpu::vec2>(
    context, voxels, "AbsorptionCoefficient volume", placement, skin, [&volume, given = volume.mediumFirstVoxel()](std::size_t i) {
      const float absorption = volume.AbsorptionCoefficient[i - given];
      return volume.AbsorptionExponent[i - given] != 0.0f ? gpu::vec2(absorption, 0.0f) : gpu::vec2(0.0f, absorption);
    });
}

// The halves of a device address, as the shaders read it.
gpu::uvec2 addressWords(std::uint64_t address)
{
  return gpu::uvec2(static_cast<std::uint32_t>(address), static_cast<std::uint32_t>(address >> 32));
}

// Where a volume's fields live and how (docs/design.md §3.7). Bound as
// storage buffers, as pairs, while the widest (the light field's 16 bytes a
// voxel, or a small volume's every-order tally grid, 32 bytes a node) fits
// the device's maxStorageBufferRange and the pairs fit its memory
// (`pairsFit`) or the device cannot address buffers. Else addressed by the
// shaders, unpaired: one load by address gives a voxel's value and the next
// one's, as a pair does, so pairs would only double those fields (rows of
// one voxel keep them: their reads have no next voxel to take). Refused
// naming both limits beyond the range on a device that cannot address.
// Addressed too where each piece's fields are read alone (their addresses
// shifted, MarchPieceFieldsOnly: pairsFit false).
std::pair<BufferPlacement, bool> fieldLayout(const VulkanContext& context, const RenderVolume& volume, bool pairsFit)
{
  const std::uint64_t widest = std::max<std::uint64_t>(
    volume.voxelCount() * sizeof(gpu::LightFieldPair), scatteredLightGridBytes(volume.Dimensions));
  const std::uint64_t range = context.limits().maxStorageBufferRange;
  if (widest <= range && (pairsFit || !context.bufferDeviceAddresses()))
  {
    return { BufferPlacement::DeviceLocal, true };
  }
  if (!context.bufferDeviceAddresses())
  {
    throw storageRangeError("the volume's light field needs", widest, "buffer", range,
      ", and the device cannot address buffers (bufferDeviceAddress); use fewer voxels");
  }
  return { BufferPlacement::DeviceAddressed, volume.Dimensions[0] == 1 };
}
// The volume's grid and optics without its arrays, which the session does not
// keep (the device holds their values).
RenderVolume shapeOf(const RenderVolume& volume)
{
  RenderVolume shape = volume;
  shape.ScatteringCoefficient = nullptr;
  shape.DomainId = nullptr;
  shape.SurfaceDistance = nullptr;
  shape.AbsorptionCoefficient = nullptr;
  shape.AbsorptionExponent = nullptr;
  return shape;
}
} // namespace

// SurfaceDistance of `voxels` (the medium's: all, or a piece's layers and
// their halo, holdPiece) and the light fields (the absorption's where it
// absorbs) on the device, as pairs or one value per voxel (v.PairedFields,
// docs/design.md §3.7), and SurfaceDistance's tiles, which the highlight pass
// reads (§3.4).
void RenderSession::uploadSurfaceAndLightFields(
  const RenderVolume& volume, const SurfaceTiles& tiles, std::pair<std::size_t, std::size_t> voxels, DeviceVolume& v)
{
  std::vector<gpu::SurfaceTile> records(tiles.tileCount());
  for (std::size_t i = 0; i < records.size(); ++i)
  {
    records[i] = { tiles.Slot[i], tiles.Bound[i] };
  }
  v.SurfaceTileRecords = deviceLocalBuffer(*this->Context, records.size() * sizeof(gpu::SurfaceTile), "SurfaceDistance tiles",
    records.data(), v.FieldPlacement);
  v.SurfaceTileBytes = tiles.bytes();
  v.SurfaceTileValues = tiles.Values.empty()
    ? deviceLocalBuffer(*this->Context, sizeof(float), "SurfaceDistance tiles' values placeholder", nullptr, v.FieldPlacement)
    : deviceLocalBuffer(*this->Context, tiles.Values.size() * sizeof(float), "SurfaceDistance tiles' values",
        tiles.Values.data(), v.FieldPlacement);
  v.SurfaceDistance = v.PairedFields
    ? deviceVoxelField<gpu::vec2>(*this->Context, voxels, "SurfaceDistance volume (voxel and +x neighbour)",
        v.FieldPlacement, {}, [&volume](std::size_t i) { return surfaceDistancePair(volume, i); })
    : deviceVoxelField<float>(*this->Context, voxels, "SurfaceDistance volume", v.FieldPlacement, {},
        [&volume](std::size_t i) { return volume.SurfaceDistance[i]; });
  this->allocateLightFields(v);
}

// The light pass's fields for the layers v.LightLayers holds: the light
// field, its absorption's (a placeholder where nothing absorbs) and the
// Bragg shadows' placeholder (a frame with EnergyConservation allocates them).
void RenderSession::allocateLightFields(DeviceVolume& v) const
{
  VulkanContext& context = *this->Context;
  const std::uint64_t lightFieldBytes = v.PairedFields ? sizeof(gpu::LightFieldPair) : sizeof(gpu::vec2);
  v.LightAbsorption = deviceLocalBuffer(context,
    v.Absorbs ? v.heldFieldBytes(lightFieldBytes) : sizeof(gpu::LightFieldPair), "light absorption field", nullptr,
    v.FieldPlacement);
  v.LightField = deviceLocalBuffer(context, v.heldFieldBytes(lightFieldBytes), "light field", nullptr, v.FieldPlacement);
  v.LightShadow =
    deviceLocalBuffer(context, sizeof(gpu::LightShadow), "light Bragg shadow placeholder", nullptr, v.FieldPlacement);
  v.HasShadowField = false;
}

// The light pass's own buffers: a layer's entry voxels and the queues, one
// per layer, emptied on the device before every sweep (docs/design.md §3.3).
void RenderSession::allocateLightPassBuffers(const RenderVolume& volume, DeviceVolume& v)
{
  VulkanContext& context = *this->Context;
  const std::size_t layerVoxels = static_cast<std::size_t>(volume.Dimensions[0]) * volume.Dimensions[2];
  v.EntryVoxels = deviceLocalBuffer(
    context, layerVoxels * sizeof(std::uint32_t), "light entry voxels (a layer)", nullptr, v.FieldPlacement);
  v.EntryQueues = deviceLocalBuffer(
    context, static_cast<std::uint64_t>(volume.Dimensions[1]) * sizeof(gpu::DispatchQueue), "light entry queues");
}

bool RenderSession::LightFieldKey::operator==(const LightFieldKey& other) const
{
  return this->Light == other.Light && this->RefractiveIndex == other.RefractiveIndex &&
    this->FalloffAtEntry == other.FalloffAtEntry && this->BraggShadow == other.BraggShadow;
}

bool RenderSession::ScatteredLightKey::operator==(const ScatteredLightKey& other) const
{
  return this->Light == other.Light && this->RefractiveIndex == other.RefractiveIndex &&
    this->Photons == other.Photons && this->WavelengthSpan == other.WavelengthSpan;
}

RenderSession::RenderSession(const VulkanOptions& options)
  : Context(std::make_unique<VulkanContext>(options))
  , Buffers(std::make_unique<FrameBuffers>())
  , MarchPieces(std::max(options.MarchPieces, 1))
  , MarchPieceFieldsOnly(options.MarchPieceFieldsOnly)
  , Sweeps{ options.ForwardedMarchSweeps > 0 ? std::min(options.ForwardedMarchSweeps, MarchSweeps) : MarchSweeps,
      options.ForwardedLightSweeps > 0 ? std::min(options.ForwardedLightSweeps, LightWalkSweeps) : LightWalkSweeps }
{
  checkWorkgroupSizes(this->Context->limits());
  if (this->MarchPieceFieldsOnly && !this->Context->bufferDeviceAddresses())
  {
    throw VulkanError("MarchPieceFieldsOnly reads each piece's fields by address, and the device cannot address "
                      "buffers (bufferDeviceAddress)",
      VK_ERROR_FEATURE_NOT_PRESENT);
  }
  std::vector<VkDescriptorType> types(gpu::BindingCount, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  types[gpu::ParametersBinding] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  this->Bindings = std::make_unique<StorageBufferBindings>(*this->Context, types, PushConstantBytes);
  const embedded::Spirv light = embedded::lightOpticalDepthShader();
  const embedded::Spirv colour = embedded::spectrumToColourShader();
  // Without absorption and Bragg shadows (pipelines with either made on first use).
  for (int mode : { gpu::LightPassMarchTowardsLight, gpu::LightPassSweepFromAbove, gpu::LightPassMarchQueued })
  {
    this->LightPasses[{ mode, 0, 0, 0, 1, 0 }] = std::make_unique<ComputePipeline>(*this->Context, *this->Bindings,
      light.Words, light.WordCount,
      specialisation(gpu::LightPassConstantCount,
        { { gpu::LightPassModeConstant, mode }, { gpu::LightAbsorptionConstant, 0 }, { gpu::LightBraggShadowConstant, 0 },
          { gpu::LightPairedFieldsConstant, 1 }, { gpu::LightForwardedConstant, 0 } }));
  }
  this->ColourPass =
    std::make_unique<ComputePipeline>(*this->Context, *this->Bindings, colour.Words, colour.WordCount);
  const embedded::Spirv highlight = embedded::specularHighlightShader();
  for (int mode : { gpu::HighlightSelect, gpu::HighlightShade })
  {
    this->HighlightPasses[{ mode, 0, 1 }] = std::make_unique<ComputePipeline>(
      *this->Context, *this->Bindings, highlight.Words, highlight.WordCount,
      specialisation(gpu::HighlightConstantCount,
        { { gpu::HighlightModeConstant, mode }, { gpu::HighlightPairedFieldsConstant, 1 } }));
  }
  this->Buffers->Parameters =
    std::make_unique<VulkanBuffer>(*this->Context, sizeof(gpu::RenderParameterBlock), "render parameters");
  this->Buffers->HighlightQueue = std::make_unique<VulkanBuffer>(
    *this->Context, sizeof(gpu::DispatchQueue), "highlight queue header", BufferPlacement::DeviceLocal);
  this->Buffers->EdgeQueue = std::make_unique<VulkanBuffer>(
    *this->Context, 2 * sizeof(gpu::DispatchQueue), "edge queue headers", BufferPlacement::DeviceLocal);
  this->Buffers->RayStates =
    std::make_unique<VulkanBuffer>(*this->Context, 16, "forwarded rays", BufferPlacement::DeviceLocal);
  this->Buffers->ForwardedLeft =
    std::make_unique<VulkanBuffer>(*this->Context, 16, "forwarded states left", BufferPlacement::DeviceLocal);
  sessionregistry::add(this); // ended at exit before the Vulkan libraries
}

RenderSession::~RenderSession()
{
  sessionregistry::remove(this);
  this->cancelFrame(); // the worker renders with the members below
}

VulkanContext& RenderSession::context()
{
  if (!this->Context)
  {
    throw VulkanError("the render session was released at the process's exit", VK_ERROR_INITIALIZATION_FAILED);
  }
  return *this->Context;
}

void RenderSession::release()
{
  this->cancelFrame();
  // In the reverse of the members' order, as the destructor would.
  this->Buffers.reset();
  this->Volume.reset();
  this->ShadowTablePasses.clear();
  this->MarchPasses.clear();
  this->ColourPass.reset();
  this->HighlightPasses.clear();
  this->LightPasses.clear();
  this->Bindings.reset();
  this->Context.reset();
  this->LightField.reset();
  this->ScatteredLight.reset();
  this->WavelengthSampling.reset();
}

// The volume and what was computed for it: its light field, its every-order
// light and the shared steps' results pending for its next frame.
void RenderSession::dropVolume()
{
  this->Volume.reset();
  this->LightField.reset();
  this->ScatteredLight.reset();
  this->PendingScatteredSeconds = -1;
  this->PendingLightSeconds = -1;
}

void RenderSession::setVolume(const RenderVolume& volume)
{
  this->cancelFrame();
  this->context(); // throws once released
  const std::string error = validate(volume);
  if (!error.empty())
  {
    throw std::invalid_argument(error);
  }
  this->requireMediumArrays(volume); // before the volume held is dropped
  const auto start = Clock::now();
  this->dropVolume();
  const std::size_t voxels = volume.voxelCount();
  const bool absorbs = volume.absorbs();
  // Fields and light field, laid out (fieldLayout), refused up front if too
  // large; the light fields hold the piece held alone (holdPiece).
  auto uploaded = std::make_unique<DeviceVolume>();
  VulkanContext& context = *this->Context;
  std::tie(uploaded->FieldPlacement, uploaded->PairedFields) =
    fieldLayout(context, volume, this->pairedFieldsFit(voxels, absorbs) && !this->MarchPieceFieldsOnly);
  uploaded->Shape = shapeOf(volume);
  uploaded->LightLayers = this->lightLayersOf(*uploaded);
  uploaded->MediumLayers = this->mediumLayersOf(*uploaded);
  // The light fields and the medium for the layers they hold, and the tiles.
  const SurfaceTiles tiles = surfaceTiles(volume, gpu::SurfaceTileCells);
  this->requireDeviceMemory(uploaded->lightVoxels() * lightBytesPerVoxel(absorbs, uploaded->PairedFields) +
      uploaded->mediumVoxels() * mediumBytesPerVoxel(absorbs, uploaded->PairedFields) + tiles.bytes(),
    "the volume needs", "", "use fewer voxels");
  const BufferPlacement placement = uploaded->FieldPlacement;
  // The medium reaches the smooth surface: skin cells filled from inside.
  const std::vector<SkinCell> skin = skinCells(volume, uploaded->MediumLayers);
  const std::pair<std::size_t, std::size_t> medium{ uploaded->mediumFirstVoxel(),
    uploaded->mediumFirstVoxel() + uploaded->mediumVoxels() };
  const std::size_t given = volume.mediumFirstVoxel(); // the arrays' first value (RenderVolume::Held)
  uploaded->Cells = deviceVoxelField<gpu::VoxelCell>(context, medium, "ScatteringCoefficient and DomainId volume",
    placement, skin, [&volume, given](std::size_t i) {
      return gpu::VoxelCell{ volume.ScatteringCoefficient[i - given], volume.DomainId[i - given] };
    });
  uploaded->Absorbs = absorbs;
  uploaded->AbsorptionExponent = volume.colouredAbsorptionExponent();
  uploaded->AbsorptionCells = absorptionBuffer(context, volume, medium, skin, placement);
  this->uploadSurfaceAndLightFields(volume, tiles, medium, *uploaded);
  this->allocateLightPassBuffers(volume, *uploaded);
  uploaded->Addresses = std::make_unique<VulkanBuffer>(context, sizeof(gpu::VolumeAddresses), "volume field addresses");
  const std::vector<gpu::DomainRecord> records = domainRecords(volume);
  uploaded->DomainTable = deviceLocalBuffer(context, records.size() * sizeof(gpu::DomainRecord), "domain table",
    records.empty() ? nullptr : records.data());
  // SurfaceDistance, like the medium's fields, read back by the first every-order solve.
  uploaded->Medium.Geometry = VolumeGeometry(volume, false);
  uploaded->Medium.AbsorptionExponent = uploaded->AbsorptionExponent;
  uploaded->ScatteredLight = scatteredLightPlaceholder(context, placement);
  uploaded->ScatteredLightGrid = deviceLocalBuffer(
    context, sizeof(gpu::ScatteredLightNode), "scattered light tally grid placeholder", nullptr, placement);
  this->Volume = std::move(uploaded);
  this->bindBuffers();
  this->PendingUploadSeconds = secondsSince(start);
}

RenderFrame RenderSession::render(const RenderParameters& parameters, const RenderProgress& callback)
{
  return this->render(resolveFrame(parameters), callback);
}

RenderFrame RenderSession::render(const ResolvedFrame& resolved, const RenderProgress& callback)
{
  this->cancelFrame();
  this->context(); // throws once released
  return this->renderFrame(resolved, callback);
}

void RenderSession::startFrame(const ResolvedFrame& frame)
{
  this->cancelFrame();
  this->context(); // throws once released
  if (this->SharedMarch)
  {
    // Its rounds would run on the worker, beside the processes' exchange.
    throw std::logic_error("startFrame: a march shared by processes (shareMarch) renders with render() alone.");
  }
  if (this->Volume)
  {
    this->requireWholeMedium("A background frame"); // as its renderFrame would, before any work
  }
  if (!frame.Error.empty())
  {
    throw std::invalid_argument(frame.Error); // as render() would, before any work
  }
  this->Background = std::make_unique<FrameWorker<RenderFrame>>(
    [this, frame](const RenderProgress& progress) { return this->renderFrame(frame, progress); });
}

BackgroundState RenderSession::backgroundState() const
{
  if (!this->Background)
  {
    return BackgroundState::None;
  }
  return this->Background->finished() ? BackgroundState::Finished : BackgroundState::Running;
}

double RenderSession::backgroundProgress() const
{
  return this->Background ? this->Background->progress() : 0.0;
}

std::optional<RenderFrame> RenderSession::takeFrame()
{
  if (this->backgroundState() != BackgroundState::Finished)
  {
    return std::nullopt;
  }
  const std::unique_ptr<FrameWorker<RenderFrame>> worker = std::move(this->Background);
  RenderFrame frame = worker->take(); // rethrows the worker's exception
  this->CompletedFrames += frame.Status == FrameStatus::Completed ? 1 : 0;
  return frame;
}

void RenderSession::cancelFrame()
{
  if (!this->Background)
  {
    return;
  }
  this->Background->cancel();
  const bool completed = !this->Background->failed() && this->Background->frame().Status == FrameStatus::Completed;
  (completed ? this->CompletedFrames : this->AbandonedFrames) += 1;
  this->Background.reset();
}

void RenderSession::requireVolume() const
{
  if (!this->Volume)
  {
    throw std::invalid_argument("The render has no volume; connect an Opal Volume.");
  }
}

RenderSession::FrameSetup RenderSession::setUpSharedStep(const ResolvedFrame& frame)
{
  this->cancelFrame();
  this->requireVolume();
  return this->setUpFrame(frame);
}

RenderFrame RenderSession::renderFrame(const ResolvedFrame& resolved, const RenderProgress& callback)
{
  const FrameRounds rounds(*this); // a shared march's (shareMarch)
  this->requireVolume();
  if (!this->SharedMarch)
  {
    this->requireWholeMedium("A frame marched by one process alone");
  }
  RenderFrame frame;
  RenderTimings& timings = frame.Image.Timings;
  // The processes' solve for this frame, if any (solveScatteredLightShared): this frame's alone, used or not.
  const double sharedSolveSeconds = std::exchange(this->PendingScatteredSeconds, -1.0);
  const double sharedLightSeconds = std::exchange(this->PendingLightSeconds, -1.0); // shareLightPass's
  const double sharedFieldSeconds = std::exchange(this->PendingFieldSeconds, -1.0);  // shareScatteredField's
  const auto setupStart = Clock::now();
  const FrameSetup setup = this->setUpFrame(resolved);
  frame.Ran.Preview = setup.Preview;
  frame.Ran.ScatteredLightFromGrid = setup.ScatteredLightFromGrid;
  frame.Ran.PairedFields = this->Volume->PairedFields;
  this->placeScatteredField(setup);
  this->prepareFrameBuffers(setup);
  timings.Setup = secondsSince(setupStart);
  frame.Ran.Upload = this->PendingUploadSeconds >= 0;
  timings.Upload = std::max(0.0, std::exchange(this->PendingUploadSeconds, -1.0));
  Progress progress(callback);

  const auto lightStart = Clock::now();
  // The first FrameLightShare of the progress: the light pass, and half of it
  // the every-order solve where the frame runs it; a solve the processes
  // shared ahead of the frame reported it all (solveScatteredLightShared).
  const bool solves = scattersEveryOrder(setup.Parameters) && !this->scatteredLightServes(setup);
  progress.stage(sharedSolveSeconds >= 0 ? FrameLightShare : 0.0, FrameLightShare * (solves ? 0.5 : 1.0));
  // The light field holds a light in the model's frame: a new camera alone keeps it.
  frame.Ran.LightPass = !this->lightFieldServes(setup);
  if (frame.Ran.LightPass && !this->runLightPass(setup, progress))
  {
    return frame;
  }
  this->runShadowTable(setup);
  timings.LightPass = secondsSince(lightStart) + std::max(0.0, sharedLightSeconds);
  frame.Ran.LightPass = frame.Ran.LightPass || sharedLightSeconds >= 0;
  progress.stage(FrameLightShare * 0.5, FrameLightShare);
  if (!this->prepareScatteredLight(setup, sharedSolveSeconds, progress, frame))
  {
    return frame;
  }
  timings.ScatteredLight += std::max(0.0, sharedFieldSeconds); // the field's writing, where the processes shared it

  const auto marchStart = Clock::now();
  this->resetForwardedLeft();
  double exposure = setup.Parameters.Exposure;
  frame.Ran.Exposure = setup.measuresExposure();
  if (frame.Ran.Exposure && !this->measureExposure(setup, progress, exposure))
  {
    return frame;
  }
  frame.Ran.March = true;
  const MarchTarget image{ setup.Parameters.ImageSize, setup.Region, setup.Parameters.WriteSpectrum,
    setup.Parameters.PixelSamples };
  if (!this->marchRegion(setup, image, progress, 0.25, 0.95))
  {
    return frame;
  }
  if (this->Rounds)
  {
    this->Rounds->finish(); // the rest of the frame is this share's alone
    timings.MarchRounds = this->Rounds->Seconds;
  }
  this->requireForwardedFinished("view march");
  timings.March = secondsSince(marchStart);

  const auto colourStart = Clock::now();
  this->runColourPass(setup, exposure);
  frame.Ran.Colour = true;
  timings.Colour = secondsSince(colourStart);

  this->readFrame(setup, exposure, frame);
  progress.report(1.0);
  return frame;
}

// The light scattered more than once for the frame (docs/design.md §3.10):
// solved unless held (or solved by the processes ahead of it), and its field
// per voxel written from the grid where the frame reads one; false if aborted.
bool RenderSession::prepareScatteredLight(
  const FrameSetup& setup, double sharedSolveSeconds, Progress& progress, RenderFrame& frame)
{
  const auto start = Clock::now();
  const bool everyOrder = scattersEveryOrder(setup.Parameters);
  frame.Ran.ScatteredLight = everyOrder && !this->scatteredLightServes(setup);
  if (frame.Ran.ScatteredLight && !this->runScatteredLight(setup, progress))
  {
    return false;
  }
  if (everyOrder && !setup.ScatteredLightFromGrid && this->Volume->ScatteredFieldPending)
  {
    this->writeScatteredField();
  }
  // A field the processes solved together for this frame (solveScatteredLightShared).
  frame.Ran.ScatteredLight = frame.Ran.ScatteredLight || (everyOrder && sharedSolveSeconds >= 0);
  frame.Image.Timings.ScatteredLight = secondsSince(start) + std::max(0.0, sharedSolveSeconds);
  return true;
}

// The frame's image from the device, with what it was rendered with; no
// image with a NaN or an infinity in it.
void RenderSession::readFrame(const FrameSetup& setup, double exposure, RenderFrame& frame) const
{
  const auto start = Clock::now();
  const bool everyOrder = scattersEveryOrder(setup.Parameters);
  const RenderTimings kept = frame.Image.Timings;
  frame.Image = this->readBack(setup);
  frame.Image.Exposure = exposure;
  frame.Image.ScatteringOrders = everyOrder ? "all" : "single";
  frame.Image.Warning = everyOrder ? this->ScatteredLightWarning : std::string();
  frame.Image.Timings = kept;
  frame.Image.Timings.Readback = secondsSince(start);
  frame.Image.DeviceMemoryPeak = this->Context->memoryPeak();
  frame.Ran.Readback = true;
  const std::string nonFinite = nonFiniteArray(frame.Image);
  if (!nonFinite.empty())
  {
    throw std::runtime_error("The render produced a NaN or an infinity in " + nonFinite +
      "; no image is given. Check the volume's arrays and the optics settings.");
  }
  frame.Status = FrameStatus::Completed;
}

bool RenderSession::eyeInsideOpal(const ResolvedFrame& frame) const
{
  return this->Volume && frame.Error.empty() &&
    this->Volume->Medium.Geometry.insideAt(cameraInModelFrame(frame.Parameters).Eye);
}

// Frame set-up: validation, the camera and light in the model's frame, the
// rectangles, the wavelength bins and the parameter block (writeParameterBlock).
RenderSession::FrameSetup RenderSession::setUpFrame(const ResolvedFrame& frame) const
{
  if (!frame.Error.empty())
  {
    throw std::invalid_argument(frame.Error);
  }
  const RenderParameters& p = frame.Parameters;
  FrameSetup setup;
  setup.Parameters = p;
  setup.Preview = frame.Preview;
  setup.Camera = cameraInModelFrame(p);
  const VolumeGeometry& geometry = this->Volume->Medium.Geometry;
  if (geometry.insideAt(setup.Camera.Light))
  {
    throw std::invalid_argument("LightPosition is inside the opal; place the light outside it.");
  }
  if (geometry.insideAt(setup.Camera.Eye))
  {
    throw std::invalid_argument("EyePosition is inside the opal; place the eye outside it.");
  }
  setup.Region = renderedRegion(p);
  // Only a frame that measures its exposure marches the thumbnail and holds its pixels.
  setup.Thumbnail = p.Exposure <= 0 ? exposureThumbnailSize(p) : std::array<int, 2>{ 0, 0 };
  setup.Pixels = static_cast<std::size_t>(setup.Region[2]) * static_cast<std::size_t>(setup.Region[3]);
  // The image's pixels and the ring around them the edge select reads
  // (docs/design.md §3.4), or the exposure thumbnail's, whichever is more.
  setup.PixelCapacity = std::max(setup.Pixels + static_cast<std::size_t>(MARCH_RING_PIXELS(setup.Region[2], setup.Region[3])),
    static_cast<std::size_t>(setup.Thumbnail[0]) * static_cast<std::size_t>(setup.Thumbnail[1]));
  setup.Bins = sampleWavelengths(p.WavelengthRange[0], p.WavelengthRange[1], p.WavelengthStep);
  this->writeParameterBlock(setup);
  setup.ScatteredLightFromGrid = this->scatteredLightFromGrid(setup);
  this->checkMemoryBudget(setup);
  return setup;
}

// The frame's parameter block, as the passes read it, from its parameters,
// camera and bins and the volume's shape.
void RenderSession::writeParameterBlock(FrameSetup& setup) const
{
  const RenderParameters& p = setup.Parameters;
  const VolumeGeometry& geometry = this->Volume->Medium.Geometry;
  gpu::RenderParameterBlock& block = setup.Block;
  const RenderVolume& shape = this->Volume->Shape;
  block.gridDimensions = gpu::ivec3(shape.Dimensions[0], shape.Dimensions[1], shape.Dimensions[2]);
  block.wavelengthCount = static_cast<int>(setup.Bins.size());
  block.gridOrigin = toVec3(shape.Origin);
  block.smallestSpacing = static_cast<float>(geometry.smallestSpacing());
  block.gridSpacing = toVec3(shape.Spacing);
  block.marchStep = static_cast<float>((p.StepSize > 0 ? p.StepSize : geometry.smallestSpacing()) *
    (setup.Preview ? PreviewStepScale : 1.0));
  block.eye = toVec3(setup.Camera.Eye);
  block.tanHalfViewAngle = static_cast<float>(std::tan(glm::radians(p.ViewAngle) / 2));
  block.forward = toVec3(setup.Camera.Forward);
  block.right = toVec3(setup.Camera.Right);
  block.up = toVec3(setup.Camera.Up);
  block.light = toVec3(setup.Camera.Light);
  block.lightRadius = static_cast<float>(p.LightRadius);
  block.background = gpu::vec3(srgbToLinear(p.Background[0]), srgbToLinear(p.Background[1]), srgbToLinear(p.Background[2]));
  block.refractiveIndex = static_cast<float>(p.RefractiveIndex);
  block.braggBandwidth = static_cast<float>(p.BraggBandwidth);
  block.diffractionGain = static_cast<float>(p.DiffractionGain);
  block.mosaicSpread = static_cast<float>(glm::radians(effectiveMosaicSpread(p)));
  // Irradiance 1 at the apex: intensity = apex distance^2; the light's
  // radiance spreads that intensity over its disc, pi r^2.
  const glm::dvec3 toApex = setup.Camera.Light - geometry.apex();
  const double apexDistanceSquared = glm::dot(toApex, toApex);
  block.apexDistanceSquared = static_cast<float>(apexDistanceSquared);
  block.lightRadiance = static_cast<float>(apexDistanceSquared / (Pi * p.LightRadius * p.LightRadius));
  block.lightFalloffAtEntry = p.LightFalloffAtEntry ? 1 : 0;
  block.specularSamples = p.SpecularSamples;
  block.pixelSamples = p.PixelSamples;
  block.domainCount = static_cast<int>(shape.Domains.size());
  block.braggOrders = p.BraggOrders;
  block.maxGroupsX = static_cast<int>(std::min<std::uint32_t>(
    this->Context->limits().maxComputeWorkGroupCount[0], static_cast<std::uint32_t>(std::numeric_limits<int>::max())));
  block.absorptionExponent = this->Volume->AbsorptionExponent;
  const ScatteredLightGrid tallyGrid = scatteredLightGrid(geometry);
  block.scatteredLightNodes = tallyGrid.Nodes;
  block.scatteredLightStride = tallyGrid.Stride;
  setCoupledWave(block, p, shape); // heldFirstVoxel: at its upload (uploadParameterBlock)
}

// The first voxel the light fields hold where bound (a piece: holdPiece),
// which the passes take from an index; 0 where addressed (volumeAddresses
// shifts their addresses). Below 2^31: a bound field is within a storage
// buffer's range.
int RenderSession::boundFirstVoxel() const
{
  const DeviceVolume& v = *this->Volume;
  return v.addressed() ? 0 : static_cast<int>(v.lightFirstVoxel());
}

// The same for the medium: cells, absorption cells and SurfaceDistance (MediumLayers).
int RenderSession::boundMediumVoxel() const
{
  const DeviceVolume& v = *this->Volume;
  return v.addressed() ? 0 : static_cast<int>(v.mediumFirstVoxel());
}

// The parameter block the passes read, its heldFirstVoxel as the layers
// held now: they change after a frame's block is written (a shared step
// holding its share's rows, a frame computing the light alone).
void RenderSession::uploadParameterBlock(const gpu::RenderParameterBlock& frameBlock) const
{
  gpu::RenderParameterBlock block = frameBlock;
  block.heldFirstVoxel = this->boundFirstVoxel();
  block.mediumFirstVoxel = this->boundMediumVoxel();
  this->Buffers->Parameters->upload(&block, sizeof(block));
}

// The block on the device likewise where the layers held change
// (bindBuffers), as the address table does.
void RenderSession::writeHeldFirstVoxel() const
{
  if (this->Volume && this->Buffers && this->Buffers->Parameters)
  {
    auto* block = this->Buffers->Parameters->as<gpu::RenderParameterBlock>();
    block->heldFirstVoxel = this->boundFirstVoxel();
    block->mediumFirstVoxel = this->boundMediumVoxel();
  }
}

// Every order reads its field per voxel where the device's budget holds it
// beside what the session keeps (the image buffers, which only grow, and the
// Bragg shadow field once made), else evaluates the tally grid
// (docs/design.md §3.10): a field allocated after a larger frame, or after
// energy conservation was turned off, must fit too.
bool RenderSession::scatteredLightFromGrid(const FrameSetup& setup) const
{
  if (!scattersEveryOrder(setup.Parameters))
  {
    return false;
  }
  const DeviceVolume& v = *this->Volume;
  const std::uint64_t keptShadows =
    v.HasShadowField && !conservesEnergy(setup.Parameters) ? v.lightVoxels() * sizeof(gpu::LightShadow) : 0;
  return this->volumeBytes(setup, true) + keptShadows +
    this->frameImageBytes(setup, true) > this->Context->memoryBudget();
}

// Whether the device's budget holds the volume's fields as pairs beside the
// Bragg shadow field that energy conservation adds (else one value per
// voxel, docs/design.md §3.7): the layout is the volume's, for all its
// frames, and a frame's own buffers (images, the every-order field, which
// falls back to its grid) are small beside it.
bool RenderSession::pairedFieldsFit(std::size_t voxels, bool absorbs) const
{
  return voxels * (deviceBytesPerVoxel(absorbs, true) + sizeof(gpu::LightShadow)) <= this->Context->memoryBudget();
}

// Memory budget: refuse up front what cannot fit, with the estimate: on the
// device, the volume (already there) and the images; on the host, the arrays.
void RenderSession::requireDeviceMemory(
  std::uint64_t bytes, const std::string& needs, const std::string& detail, const std::string& remedy) const
{
  if (bytes > this->Context->memoryBudget())
  {
    throw VulkanError(needs + " about " + formatBytes(bytes) + " of device memory" + detail + ", more than " +
        this->Context->memoryBudgetText() + "; " + remedy,
      VK_ERROR_OUT_OF_DEVICE_MEMORY);
  }
}

void RenderSession::checkVolumeFits(
  const std::array<int, 3>& dimensions, bool absorbs, const RenderParameters& parameters)
{
  this->context(); // throws once released
  const std::uint64_t voxels = static_cast<std::uint64_t>(dimensions[0]) * static_cast<std::uint64_t>(dimensions[1]) *
    static_cast<std::uint64_t>(dimensions[2]);
  this->requireDeviceMemory(volumeDeviceBytes(dimensions, voxels, voxels, absorbs, parameters, false, false),
    "the volume's fields for this render need", "", "use fewer voxels");
}

// The frame's image buffers on the device; with `kept`, at the size the
// session keeps them if larger (they only grow, prepareFrameBuffers).
std::uint64_t RenderSession::frameImageBytes(const FrameSetup& setup, bool kept) const
{
  const FrameBuffers& b = *this->Buffers;
  const std::uint64_t capacity = kept ? std::max(setup.PixelCapacity, b.PixelCapacity) : setup.PixelCapacity;
  const std::uint64_t spectrumBytes =
    kept ? std::max<std::uint64_t>(setup.spectrumBytes(), b.SpectrumFloats * sizeof(float)) : setup.spectrumBytes();
  const std::uint64_t rays = this->frameStateBytes(setup);
  return capacity * ImageBytesPerPixel + spectrumBytes +
    (kept ? std::max<std::uint64_t>(rays, b.RayStates->size()) : rays);
}

// The volume's bytes on the device for this frame: its fields
// (volumeDeviceBytes) and SurfaceDistance's tiles.
std::uint64_t RenderSession::volumeBytes(const FrameSetup& setup, bool fieldPerVoxel) const
{
  const DeviceVolume& v = *this->Volume;
  return volumeDeviceBytes(v.Shape.Dimensions, this->framedVoxels(), v.mediumVoxels(), v.Absorbs, setup.Parameters,
           fieldPerVoxel, v.PairedFields) +
    v.SurfaceTileBytes;
}

void RenderSession::checkMemoryBudget(const FrameSetup& setup) const
{
  const bool fieldPerVoxel = !setup.ScatteredLightFromGrid;
  const std::uint64_t volumeBytes = this->volumeBytes(setup, fieldPerVoxel);
  const std::uint64_t deviceBytes = volumeBytes + this->frameImageBytes(setup, false);
  this->requireDeviceMemory(
    deviceBytes, "the render needs", " (volume " + formatBytes(volumeBytes) + ")", "use fewer voxels or pixels");
  // One buffer holds a forwarded pass's states: refused here, before any
  // pass, not by the buffer's own check between the light pass and the march.
  const std::uint64_t range = this->Context->limits().maxStorageBufferRange;
  const std::string forwarded = this->SharedMarch
    ? " shared by " + std::to_string(this->SharedMarch->Shares) + " processes needs"
    : " forwarded through " + std::to_string(this->MarchPieces) + " pieces needs";
  const std::uint64_t rays = this->frameRayStateBytes(setup);
  if (rays > range)
  {
    throw storageRangeError("the march" + forwarded, rays, "buffer of ray states", range, "; use fewer pixels");
  }
  const std::uint64_t walks = this->frameLightStateBytes(setup);
  if (walks > range)
  {
    throw storageRangeError("the light pass" + forwarded, walks, "buffer of walk states", range,
      "; use fewer voxels in x and z");
  }
  const std::uint64_t hostBytes = setup.Pixels * (3 + 12 + 12 + 4 + 4) + setup.spectrumBytes();
  if (physicalMemoryBytes() > 0 && hostBytes + deviceBytes > physicalMemoryBytes())
  {
    throw std::invalid_argument("ImageSize " + std::to_string(setup.Parameters.ImageSize[0]) + " x " +
      std::to_string(setup.Parameters.ImageSize[1]) + " needs about " + formatBytes(hostBytes + deviceBytes) +
      ", more than this machine's " + formatBytes(physicalMemoryBytes()) + " of memory.");
  }
}

// Buffers: the pixel buffers grow to the frame's needs (kept otherwise), the
// wavelength table follows the sampling, the parameter block is written.
void RenderSession::prepareFrameBuffers(const FrameSetup& setup)
{
  FrameBuffers& b = *this->Buffers;
  VulkanContext& context = *this->Context;
  const std::size_t spectrumFloats =
    setup.Parameters.WriteSpectrum ? setup.Pixels * setup.Bins.size() : std::size_t{ 0 };
  bool rebind = false;
  if (setup.PixelCapacity > b.PixelCapacity)
  {
    const std::size_t n = setup.PixelCapacity;
    b.PixelColour.reset();
    b.PixelBragg.reset();
    b.PixelMirror.reset();
    b.HighlightPixels.reset();
    b.EdgePixels.reset();
    b.PixelSums.reset();
    b.PixelRadiance.reset();
    b.PixelRGB8.reset();
    // Device-local: mapped where that memory is host-visible (lavapipe,
    // integrated GPUs), else read back through one staging copy (hostViews).
    b.PixelColour = deviceLocalBuffer(context, n * sizeof(gpu::PixelColour), "XYZ image");
    b.PixelBragg = deviceLocalBuffer(context, n * sizeof(gpu::PixelBragg), "Bragg image");
    b.PixelMirror = deviceLocalBuffer(context, n * sizeof(gpu::PixelMirror), "mirror image");
    b.HighlightPixels = deviceLocalBuffer(context, n * sizeof(std::uint32_t), "highlight queue");
    b.EdgePixels = deviceLocalBuffer(context, 2 * n * sizeof(std::uint32_t), "edge queues");
    b.PixelSums = deviceLocalBuffer(context, n * sizeof(gpu::PixelSum), "edge pixels' sums");
    b.PixelRadiance = deviceLocalBuffer(context, n * 3 * sizeof(float), "Radiance image");
    b.PixelRGB8 = deviceLocalBuffer(context, n * sizeof(std::uint32_t), "RGB image");
    b.PixelCapacity = n;
    rebind = true;
  }
  const std::size_t shadowTableFloats = conservesEnergy(setup.Parameters)
    ? static_cast<std::size_t>(setup.Block.domainCount) * 4 * SHADOW_TABLE_ROW_VEC4S(setup.Bins.size())
    : std::size_t{ 4 };
  if (!b.ShadowTable || shadowTableFloats > b.ShadowTableFloats)
  {
    b.ShadowTable.reset();
    b.ShadowTable = std::make_unique<VulkanBuffer>(context, std::max<std::size_t>(shadowTableFloats, 4) * sizeof(float),
      "Bragg shadow table", BufferPlacement::DeviceLocal);
    b.ShadowTableFloats = shadowTableFloats;
    rebind = true;
  }
  if (!b.PixelSpectrum || spectrumFloats > b.SpectrumFloats)
  {
    b.PixelSpectrum.reset();
    b.PixelSpectrum = deviceLocalBuffer(context, spectrumFloats * sizeof(float), "Spectrum image");
    b.SpectrumFloats = spectrumFloats;
    rebind = true;
  }
  const std::array<double, 4> sampling{ setup.Parameters.WavelengthRange[0], setup.Parameters.WavelengthRange[1],
    setup.Parameters.WavelengthStep, static_cast<double>(setup.Parameters.Illuminant) };
  if (this->WavelengthSampling != sampling)
  {
    this->uploadWavelengthTable(setup.Bins, setup.Parameters.Illuminant);
    this->WavelengthSampling = sampling;
    rebind = true;
  }
  if (rebind)
  {
    this->bindBuffers();
  }
  this->uploadParameterBlock(setup.Block);
}

RenderSession::ScatteredLightKey RenderSession::scatteredLightKey(const FrameSetup& setup)
{
  const glm::dvec3& light = setup.Camera.Light;
  return { { light.x, light.y, light.z }, setup.Parameters.RefractiveIndex, setup.Parameters.ScatteringPhotons,
    { setup.Bins.front().Lambda, setup.Bins.back().Lambda } };
}

RenderSession::LightFieldKey RenderSession::lightFieldKey(const FrameSetup& setup)
{
  const glm::dvec3& light = setup.Camera.Light;
  return { { light.x, light.y, light.z }, setup.Parameters.RefractiveIndex, setup.Parameters.LightFalloffAtEntry,
    conservesEnergy(setup.Parameters) };
}

// The table of the bins, with the light's spectrum: normalised D65, or 1
// (unit spectral irradiance) for LightSpectrum::None.
void RenderSession::uploadWavelengthTable(const std::vector<WavelengthBin>& bins, LightSpectrum illuminant)
{
  FrameBuffers& b = *this->Buffers;
  b.WavelengthTable.reset();
  b.WavelengthTable =
    std::make_unique<VulkanBuffer>(*this->Context, bins.size() * sizeof(gpu::WavelengthBinRecord), "wavelength table");
  auto* record = b.WavelengthTable->as<gpu::WavelengthBinRecord>();
  for (const WavelengthBin& bin : bins)
  {
    *record++ = { static_cast<float>(bin.Lambda), static_cast<float>(bin.Width),
      static_cast<float>(bin.RayleighScale), illuminant == LightSpectrum::D65 ? static_cast<float>(bin.D65) : 1.0f,
      gpu::vec3(static_cast<float>(bin.XBar), static_cast<float>(bin.YBar), static_cast<float>(bin.ZBar)) };
  }
}

// Points every binding of the contract at its buffer, by name.
void RenderSession::bindBuffers()
{
  this->writeHeldFirstVoxel();
  const FrameBuffers& b = *this->Buffers;
  if (!this->Volume || !b.WavelengthTable || !b.PixelColour || !b.PixelSpectrum || !b.ShadowTable)
  {
    return; // bound once the volume and the first frame's buffers exist
  }
  const DeviceVolume& v = *this->Volume;
  std::vector<const VulkanBuffer*> buffers(gpu::BindingCount, nullptr);
  buffers[gpu::VolumeAddressesBinding] = v.Addresses.get();
  buffers[gpu::ParametersBinding] = b.Parameters.get();
  buffers[gpu::WavelengthTableBinding] = b.WavelengthTable.get();
  buffers[gpu::VoxelCellBinding] = v.Cells.get();
  buffers[gpu::SurfaceDistanceBinding] = v.SurfaceDistance.get();
  buffers[gpu::SurfaceTileBinding] = v.SurfaceTileRecords.get();
  buffers[gpu::SurfaceTileValuesBinding] = v.SurfaceTileValues.get();
  buffers[gpu::LightFieldBinding] = v.LightField.get();
  buffers[gpu::LightEntryQueuesBinding] = v.EntryQueues.get();
  buffers[gpu::LightEntryVoxelsBinding] = v.EntryVoxels.get();
  buffers[gpu::DomainTableBinding] = v.DomainTable.get();
  buffers[gpu::PixelColourBinding] = b.PixelColour.get();
  buffers[gpu::PixelBraggBinding] = b.PixelBragg.get();
  buffers[gpu::PixelMirrorBinding] = b.PixelMirror.get();
  buffers[gpu::HighlightQueueBinding] = b.HighlightQueue.get();
  buffers[gpu::HighlightPixelsBinding] = b.HighlightPixels.get();
  buffers[gpu::EdgeQueueBinding] = b.EdgeQueue.get();
  buffers[gpu::EdgePixelsBinding] = b.EdgePixels.get();
  buffers[gpu::PixelSumsBinding] = b.PixelSums.get();
  buffers[gpu::RayStatesBinding] = b.RayStates.get();
  buffers[gpu::ForwardedLeftBinding] = b.ForwardedLeft.get();
  buffers[gpu::PixelSpectrumBinding] = b.PixelSpectrum.get();
  buffers[gpu::PixelRadianceBinding] = b.PixelRadiance.get();
  buffers[gpu::PixelRGB8Binding] = b.PixelRGB8.get();
  buffers[gpu::AbsorptionCellBinding] = v.AbsorptionCells.get();
  buffers[gpu::LightAbsorptionBinding] = v.LightAbsorption.get();
  buffers[gpu::LightShadowBinding] = v.LightShadow.get();
  buffers[gpu::ShadowTableBinding] = b.ShadowTable.get();
  buffers[gpu::ScatteredLightBinding] = v.ScatteredLight.get();
  buffers[gpu::ScatteredLightGridBinding] = v.ScatteredLightGrid.get();
  if (v.addressed())
  {
    this->addressFields(buffers);
  }
  this->Bindings->bind(buffers);
}

// The per-voxel fields of an addressed volume (docs/design.md §3.7): their
// addresses into the table the passes read, and in their bindings, which no
// pass of that volume reads, the table itself (a field may exceed the
// range a binding takes).
void RenderSession::addressFields(std::vector<const VulkanBuffer*>& buffers) const
{
  const DeviceVolume& v = *this->Volume;
  const gpu::VolumeAddresses addresses = this->volumeAddresses({});
  v.Addresses->upload(&addresses, sizeof(addresses));
  for (int binding : { gpu::VoxelCellBinding, gpu::SurfaceDistanceBinding, gpu::LightFieldBinding,
         gpu::LightAbsorptionBinding, gpu::AbsorptionCellBinding, gpu::LightShadowBinding, gpu::LightEntryVoxelsBinding,
         gpu::ScatteredLightBinding, gpu::ScatteredLightGridBinding, gpu::SurfaceTileBinding, gpu::SurfaceTileValuesBinding })
  {
    buffers[static_cast<std::size_t>(binding)] = v.Addresses.get();
  }
}

// The address table: each field's buffer's address, or where `shifted`
// names the buffer, the address given (a piece's, recordPieceFields); a
// field held by piece less the bytes of the layers before it.
gpu::VolumeAddresses RenderSession::volumeAddresses(const std::map<const VulkanBuffer*, std::uint64_t>& shifted) const
{
  const DeviceVolume& v = *this->Volume;
  std::map<const VulkanBuffer*, std::uint64_t> at = shifted;
  // A field held by piece (holdPiece): the passes index the whole grid.
  // Unsigned and modulo 2^64, as the shaders add an index's bytes (voxelAddress).
  const auto shift = [&at](const VulkanBuffer* buffer, std::uint64_t firstVoxel, std::uint64_t record) {
    if (firstVoxel > 0 && at.find(buffer) == at.end())
    {
      at[buffer] = buffer->address() - firstVoxel * record;
    }
  };
  for (const auto& [buffer, record] : this->pieceHeldFields())
  {
    shift(buffer, v.lightFirstVoxel(), record);
  }
  for (const auto& [buffer, record] : this->mediumFields())
  {
    shift(buffer, v.mediumFirstVoxel(), record);
  }
  gpu::VolumeAddresses addresses;
  const std::pair<gpu::uvec2*, const VulkanBuffer*> fields[] = { { &addresses.voxelCells, v.Cells.get() },
    { &addresses.surfaceDistance, v.SurfaceDistance.get() }, { &addresses.lightField, v.LightField.get() },
    { &addresses.lightAbsorption, v.LightAbsorption.get() }, { &addresses.absorptionCells, v.AbsorptionCells.get() },
    { &addresses.lightShadow, v.LightShadow.get() }, { &addresses.entryVoxels, v.EntryVoxels.get() },
    { &addresses.scatteredLight, v.ScatteredLight.get() },
    { &addresses.scatteredLightGrid, v.ScatteredLightGrid.get() }, { &addresses.surfaceTiles, v.SurfaceTileRecords.get() },
    { &addresses.surfaceTileValues, v.SurfaceTileValues.get() } };
  for (const auto& [address, buffer] : fields)
  {
    const auto piece = at.find(buffer);
    *address = addressWords(piece != at.end() ? piece->second : buffer->address());
  }
  return addresses;
}

RenderImage RenderSession::readBack(const FrameSetup& setup) const
{
  const std::size_t pixels = setup.Pixels;
  const FrameBuffers& b = *this->Buffers;
  RenderImage image;
  image.ImageSize = setup.Parameters.ImageSize;
  image.Region = setup.Region;
  for (const WavelengthBin& bin : setup.Bins)
  {
    image.Wavelengths.push_back(bin.Lambda);
  }
  const bool d65 = setup.Parameters.Illuminant == LightSpectrum::D65;
  image.Illuminant = d65 ? "D65" : "none";
  image.IlluminantScale = d65 && !setup.Bins.empty() ? setup.Bins.front().D65Scale : 1.0;
  const std::size_t spectrumFloats = setup.Parameters.WriteSpectrum ? pixels * setup.Bins.size() : 0;
  const HostReadback host(*this->Context, { { b.PixelRGB8.get(), pixels * sizeof(std::uint32_t) },
    { b.PixelColour.get(), pixels * sizeof(gpu::PixelColour) }, { b.PixelBragg.get(), pixels * sizeof(gpu::PixelBragg) },
    { b.PixelRadiance.get(), pixels * 3 * sizeof(float) }, { b.PixelSpectrum.get(), spectrumFloats * sizeof(float) } });
  const auto* rgb8 = host.view<std::uint32_t>(0);
  const auto* colour = host.view<gpu::PixelColour>(1);
  const auto* bragg = host.view<gpu::PixelBragg>(2);
  const auto* radiance = host.view<float>(3);
  image.Radiance.assign(radiance, radiance + 3 * pixels);
  image.RGB.resize(pixels * 3);
  image.XYZ.resize(pixels * 3);
  image.DominantBraggWavelength.resize(pixels);
  image.Depth.resize(pixels);
  for (std::size_t i = 0; i < pixels; ++i)
  {
    for (std::size_t c = 0; c < 3; ++c)
    {
      image.RGB[3 * i + c] = static_cast<std::uint8_t>((rgb8[i] >> (8 * c)) & 0xffu);
      image.XYZ[3 * i + c] = colour[i].xyz[static_cast<glm::length_t>(c)];
    }
    image.Depth[i] = colour[i].depth;
    image.DominantBraggWavelength[i] = bragg[i].dominantWavelength;
  }
  if (spectrumFloats > 0)
  {
    const auto* spectrum = host.view<float>(4);
    image.Spectrum.assign(spectrum, spectrum + spectrumFloats);
  }
  return image;
}

} // namespace opal
