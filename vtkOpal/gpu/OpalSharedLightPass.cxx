// The light field marched per voxel by several processes together, each a
// share of the voxels, before their frames (docs/design.md §8.1).
#include "OpalRenderSession.h"

#include "OpalRenderSessionState.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace opal
{

using namespace sessiondetail;

namespace
{
// Voxels [first, end) of share `share` of `shares`: whole rows, so that each
// row's pairs (a voxel's and its +x neighbour's, §3.7) are one share's writes.
std::pair<std::size_t, std::size_t> shareVoxels(const std::array<int, 3>& dims, int share, int shares)
{
  const std::size_t rows = static_cast<std::size_t>(dims[1]) * static_cast<std::size_t>(dims[2]);
  const auto rowAt = [&](int s) { return rows * static_cast<std::size_t>(s) / static_cast<std::size_t>(shares); };
  const auto width = static_cast<std::size_t>(dims[0]);
  return { rowAt(share) * width, rowAt(share + 1) * width };
}

using Fields = std::vector<std::pair<VulkanBuffer*, std::uint64_t>>;

// A share's bytes: each field's records of voxels [first, end), field after field.
std::vector<char> readShare(const Fields& fields, std::pair<std::size_t, std::size_t> voxels)
{
  std::vector<char> bytes;
  for (const auto& [buffer, record] : fields)
  {
    const std::size_t at = bytes.size();
    bytes.resize(at + (voxels.second - voxels.first) * record);
    buffer->readRange(voxels.first * record, (voxels.second - voxels.first) * record,
      [&bytes, at](std::uint64_t first, std::uint64_t count, const void* from) {
        std::memcpy(bytes.data() + at + first, from, count);
      });
  }
  return bytes;
}

// Bytes [first, first + count) of a share of `voxels` (as readShare lays
// them out) written into the fields, a field's part at a time.
void writeShare(const Fields& fields, std::pair<std::size_t, std::size_t> voxels, std::uint64_t first,
  std::uint64_t count, const char* bytes)
{
  std::uint64_t fieldStart = 0;
  for (const auto& [buffer, record] : fields)
  {
    const std::uint64_t fieldBytes = (voxels.second - voxels.first) * record;
    const std::uint64_t from = std::max(first, fieldStart), to = std::min(first + count, fieldStart + fieldBytes);
    if (from < to)
    {
      buffer->write(voxels.first * record + (from - fieldStart), to - from, bytes + (from - first));
    }
    fieldStart += fieldBytes;
  }
}
} // namespace

bool RenderSession::needsLightMarch(const ResolvedFrame& frame) const
{
  if (!this->Volume)
  {
    return false;
  }
  const FrameSetup setup = this->setUpFrame(frame);
  this->checkMemoryBudget(setup);
  const bool held = this->LightField && *this->LightField == lightFieldKey(setup);
  return !held && !this->Volume->Medium.Geometry.lightAboveGrid(setup.Camera.Light);
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

bool RenderSession::marchLightFieldShared(
  const ResolvedFrame& frame, int share, int shares, const FieldExchange& exchange, const RenderProgress& callback)
{
  const auto start = Clock::now();
  std::optional<FrameSetup> setup;
  std::optional<std::vector<char>> mine;
  std::exception_ptr failure;
  Fields fields; // none until known: other shares' bytes then go nowhere
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
    const auto voxels = shareVoxels(this->Volume->Shape.Dimensions, share, shares);
    fields = this->lightPassFields(braggShadow);
    if (this->dispatchOverVoxels(this->lightPass(gpu::LightPassMarchTowardsLight, braggShadow), this->SlabPacer,
          progress.stageCallback(), voxels.first, voxels.second))
    {
      mine = readShare(fields, voxels);
    }
  }
  catch (...)
  {
    failure = std::current_exception();
    mine.reset();
    fields.clear();
  }
  const bool whole = exchange(mine, [&](int from, std::uint64_t first, std::uint64_t count, const char* bytes) {
    if (from != share && !fields.empty())
    {
      writeShare(fields, shareVoxels(this->Volume->Shape.Dimensions, from, shares), first, count, bytes);
    }
  });
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
