#include "OpalVulkanBuffer.h"

#include "OpalVulkanContext.h"
#include "OpalVulkanError.h"

#include <algorithm>
#include <cstring>
#include <functional>
#include <memory>

namespace opal
{

VulkanBuffer::VulkanBuffer(
  VulkanContext& context, std::uint64_t bytes, const std::string& what, BufferPlacement placement)
  : Context(context)
  , Size(std::max<std::uint64_t>(bytes, 16))
  , What(what)
{
  const std::uint64_t range = context.limits().maxStorageBufferRange;
  if (this->Size > range && placement != BufferPlacement::DeviceAddressed)
  {
    throw storageRangeError("the " + what + " needs", this->Size, "storage buffer", range, "; use fewer voxels or pixels");
  }
  VkDevice device = context.device();
  auto info = vulkanStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
  info.size = this->Size;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
    VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
    (placement == BufferPlacement::DeviceAddressed ? VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT : 0);
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  checkVulkan(vkCreateBuffer(device, &info, nullptr, &buffer), "vkCreateBuffer");
  this->Buffer = VulkanHandle<VkBuffer>(buffer, [device](VkBuffer b) { vkDestroyBuffer(device, b, nullptr); });
  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(device, buffer, &requirements);
  this->allocate(requirements, placement, what);
}

namespace
{
// The memory properties a placement asks for (VulkanContext::memoryType).
VkMemoryPropertyFlags preferredMemory(BufferPlacement placement)
{
  switch (placement)
  {
    case BufferPlacement::DeviceLocal:
    case BufferPlacement::DeviceAddressed:
      return VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    case BufferPlacement::HostReadback:
      return HostVisibleMemory | VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    case BufferPlacement::HostVisible:
      break;
  }
  return HostVisibleMemory;
}
} // namespace

// Memory of the placement's kind, bound to the buffer, mapped where the host may.
void VulkanBuffer::allocate(VkMemoryRequirements requirements, BufferPlacement placement, const std::string& what)
{
  VkDevice device = this->Context.device();
  // Released by the member's destructor also when a later step throws.
  this->Reservation = this->Context.reserveMemory(requirements.size);
  const bool deviceLocal = placement == BufferPlacement::DeviceLocal || placement == BufferPlacement::DeviceAddressed;
  const std::uint32_t type = this->Context.memoryType(requirements.memoryTypeBits, preferredMemory(placement));
  auto allocateInfo = vulkanStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
  allocateInfo.allocationSize = requirements.size;
  allocateInfo.memoryTypeIndex = type;
  auto addressed = vulkanStruct<VkMemoryAllocateFlagsInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO);
  addressed.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  allocateInfo.pNext = placement == BufferPlacement::DeviceAddressed ? &addressed : nullptr;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  checkVulkan(vkAllocateMemory(device, &allocateInfo, nullptr, &memory),
    ("vkAllocateMemory (" + what + ", " + std::to_string(requirements.size) + " bytes)").c_str());
  this->Memory =
    VulkanHandle<VkDeviceMemory>(memory, [device](VkDeviceMemory m) { vkFreeMemory(device, m, nullptr); });
  checkVulkan(vkBindBufferMemory(device, this->Buffer.get(), memory, 0), "vkBindBufferMemory");
  const bool mappable = (this->Context.memoryTypeFlags(type) & HostVisibleMemory) == HostVisibleMemory &&
    !(deviceLocal && this->Context.stagingTransfers());
  if (mappable)
  {
    checkVulkan(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &this->Mapped), "vkMapMemory");
  }
}

namespace
{
void barrier(VkCommandBuffer commands, VkPipelineStageFlags from, VkAccessFlags written, VkPipelineStageFlags to,
  VkAccessFlags read)
{
  auto memory = vulkanStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  memory.srcAccessMask = written;
  memory.dstAccessMask = read;
  vkCmdPipelineBarrier(commands, from, to, 0, 1, &memory, 0, nullptr, 0, nullptr);
}

// Before copies out of a buffer (copiesAccess: transfer reads) or into one
// (transfer writes): the passes' and copies' writes made visible to the
// copies (a fence wait orders execution, not memory, between submits), and
// the passes' reads done before a copy overwrites what they read.
void beforeCopies(VkCommandBuffer commands, VkAccessFlags copiesAccess)
{
  barrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
    VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, copiesAccess);
}

// After copies out: their writes visible to the host.
void afterCopiesOut(VkCommandBuffer commands)
{
  barrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
    VK_ACCESS_HOST_READ_BIT);
}

// After copies in: their writes visible to the passes.
void afterCopiesIn(VkCommandBuffer commands)
{
  barrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

// A staging buffer's place for `bytes`: 16-byte aligned, as any field's values.
std::uint64_t stagedSize(std::uint64_t bytes)
{
  return (bytes + 15) / 16 * 16;
}

// Each run's bytes where the host reads them: in its buffer where mapped,
// else copied, all in one submit, into one staging buffer (returned; null
// where every run is mapped).
std::unique_ptr<VulkanBuffer> stageOut(
  VulkanContext& context, const std::vector<ReadRun>& runs, std::vector<const char*>& views)
{
  std::uint64_t total = 0;
  for (const ReadRun& run : runs)
  {
    const char* mapped = run.Buffer->as<const char>();
    views.push_back(mapped ? mapped + run.Begin : nullptr);
    total += mapped ? 0 : stagedSize(run.Bytes);
  }
  if (total == 0)
  {
    return nullptr;
  }
  auto staging = std::make_unique<VulkanBuffer>(context, total, "read-back staging", BufferPlacement::HostReadback);
  context.submitAndWait([&](VkCommandBuffer commands) {
    beforeCopies(commands, VK_ACCESS_TRANSFER_READ_BIT);
    std::uint64_t offset = 0;
    for (std::size_t i = 0; i < runs.size(); ++i)
    {
      if (views[i])
      {
        continue; // mapped
      }
      if (runs[i].Bytes > 0)
      {
        const VkBufferCopy region{ runs[i].Begin, offset, runs[i].Bytes };
        vkCmdCopyBuffer(commands, runs[i].Buffer->buffer(), staging->buffer(), 1, &region);
      }
      views[i] = staging->as<const char>() + offset;
      offset += stagedSize(runs[i].Bytes);
    }
    afterCopiesOut(commands);
  });
  return staging;
}
} // namespace

HostReadback::HostReadback(
  VulkanContext& context, const std::vector<std::pair<const VulkanBuffer*, std::uint64_t>>& parts)
{
  std::vector<ReadRun> runs;
  for (const auto& [buffer, bytes] : parts)
  {
    runs.push_back({ buffer, 0, bytes });
  }
  std::vector<const char*> views;
  this->Staging = stageOut(context, runs, views);
  this->Views.assign(views.begin(), views.end());
}

void VulkanBuffer::recordClear(VkCommandBuffer commands) const
{
  beforeCopies(commands, VK_ACCESS_TRANSFER_WRITE_BIT);
  vkCmdFillBuffer(commands, this->buffer(), 0, VK_WHOLE_SIZE, 0);
  auto barrier = vulkanStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT,
    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void VulkanBuffer::recordCopyFrom(VkCommandBuffer commands, const VulkanBuffer& source, std::uint64_t sourceBegin,
  std::uint64_t begin, std::uint64_t bytes) const
{
  beforeCopies(commands, VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
  const VkBufferCopy region{ sourceBegin, begin, bytes };
  vkCmdCopyBuffer(commands, source.buffer(), this->buffer(), 1, &region);
  afterCopiesIn(commands);
}

void VulkanBuffer::recordWrite(VkCommandBuffer commands, const void* source, std::uint64_t bytes) const
{
  beforeCopies(commands, VK_ACCESS_TRANSFER_WRITE_BIT);
  vkCmdUpdateBuffer(commands, this->buffer(), 0, bytes, source);
  afterCopiesIn(commands);
  // The host may write it again once the submit's fence is signalled (the
  // volume's address table, uploaded when its buffers are bound).
  barrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
    VK_ACCESS_HOST_READ_BIT | VK_ACCESS_HOST_WRITE_BIT);
}

std::uint64_t VulkanBuffer::address() const
{
  auto info = vulkanStruct<VkBufferDeviceAddressInfo>(VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO);
  info.buffer = this->Buffer.get();
  return vkGetBufferDeviceAddress(this->Context.device(), &info);
}

VulkanBuffer::~VulkanBuffer()
{
  if (this->Mapped)
  {
    vkUnmapMemory(this->Context.device(), this->Memory.get());
  }
}

void VulkanBuffer::upload(const void* source, std::uint64_t bytes)
{
  this->write(0, bytes, source);
}

void VulkanBuffer::inStagingRounds(std::uint64_t bytes, BufferPlacement placement, const std::string& what,
  const std::function<void(std::uint64_t first, std::uint64_t count, VulkanBuffer& staging)>& round) const
{
  VulkanBuffer staging(this->Context, std::min(bytes, FillRoundBytes), this->What + what, placement);
  for (std::uint64_t first = 0; first < bytes; first += FillRoundBytes)
  {
    round(first, std::min(bytes - first, FillRoundBytes), staging);
  }
}

void VulkanBuffer::fill(std::uint64_t bytes, const ContentWriter& write)
{
  this->fillRange(0, bytes, write);
}

void VulkanBuffer::write(std::uint64_t begin, std::uint64_t bytes, const void* source)
{
  this->fillRange(begin, bytes, [source](std::uint64_t first, std::uint64_t count, void* into) {
    std::memcpy(into, static_cast<const char*>(source) + first, count);
  });
}

void VulkanBuffer::fillRange(std::uint64_t begin, std::uint64_t bytes, const ContentWriter& write)
{
  if (this->Mapped || bytes == 0)
  {
    if (bytes > 0)
    {
      write(0, bytes, static_cast<char*>(this->Mapped) + begin);
    }
    return;
  }
  this->inStagingRounds(bytes, BufferPlacement::HostVisible, " (staging)",
    [&](std::uint64_t first, std::uint64_t count, VulkanBuffer& staging) {
      write(first, count, staging.Mapped);
      this->Context.submitAndWait([&](VkCommandBuffer commands) {
        beforeCopies(commands, VK_ACCESS_TRANSFER_WRITE_BIT);
        const VkBufferCopy region{ 0, begin + first, count };
        vkCmdCopyBuffer(commands, staging.buffer(), this->buffer(), 1, &region);
        afterCopiesIn(commands);
      });
    });
}

void VulkanBuffer::readRange(std::uint64_t begin, std::uint64_t bytes, const ContentReader& reader) const
{
  if (this->Mapped || bytes == 0)
  {
    if (bytes > 0)
    {
      reader(0, bytes, static_cast<const char*>(this->Mapped) + begin);
    }
    return;
  }
  this->inStagingRounds(bytes, BufferPlacement::HostReadback, " (read-back staging)",
    [&](std::uint64_t first, std::uint64_t count, VulkanBuffer& staging) {
      this->Context.submitAndWait([&](VkCommandBuffer commands) {
        beforeCopies(commands, VK_ACCESS_TRANSFER_READ_BIT);
        const VkBufferCopy region{ begin + first, 0, count };
        vkCmdCopyBuffer(commands, this->buffer(), staging.buffer(), 1, &region);
        afterCopiesOut(commands);
      });
      reader(first, count, staging.Mapped);
    });
}

namespace
{
// `runs` (with their host bytes `at`) in batches whose staging takes at most
// VulkanBuffer::FillRoundBytes, as fill's rounds do, a longer run split
// into pieces of that size: `batch` is called on each, in order.
template <typename Run, typename Host>
void inRunBatches(const std::vector<Run>& runs, const std::vector<Host*>& at,
  const std::function<void(const std::vector<Run>&, const std::vector<Host*>&)>& batch)
{
  constexpr std::uint64_t most = VulkanBuffer::FillRoundBytes;
  std::vector<Run> batchRuns;
  std::vector<Host*> batchAt;
  std::uint64_t staged = 0;
  for (std::size_t i = 0; i < runs.size(); ++i)
  {
    for (std::uint64_t first = 0; first == 0 || first < runs[i].Bytes; first += most)
    {
      const std::uint64_t bytes = std::min(runs[i].Bytes - first, most);
      if (staged + stagedSize(bytes) > most)
      {
        batch(batchRuns, batchAt);
        batchRuns.clear();
        batchAt.clear();
        staged = 0;
      }
      batchRuns.push_back({ runs[i].Buffer, runs[i].Begin + first, bytes });
      batchAt.push_back(at[i] + first);
      staged += stagedSize(bytes);
    }
  }
  if (!batchRuns.empty())
  {
    batch(batchRuns, batchAt);
  }
}

// One batch of readRuns: one staging buffer, one submit.
void readBatch(const std::vector<ReadRun>& runs, const std::vector<char*>& into)
{
  std::vector<const char*> views;
  const std::unique_ptr<VulkanBuffer> staging = stageOut(runs.front().Buffer->context(), runs, views);
  for (std::size_t i = 0; i < runs.size(); ++i)
  {
    std::copy_n(views[i], runs[i].Bytes, into[i]);
  }
}

// One batch of writeRuns: one staging buffer, one submit.
void writeBatch(const std::vector<WrittenRun>& runs, const std::vector<const char*>& from)
{
  std::uint64_t total = 0;
  for (const WrittenRun& run : runs)
  {
    total += run.Buffer->as<char>() ? 0 : stagedSize(run.Bytes);
  }
  std::unique_ptr<VulkanBuffer> staging;
  if (total > 0)
  {
    staging = std::make_unique<VulkanBuffer>(runs.front().Buffer->context(), total, "staging (runs)");
  }
  std::vector<VkBufferCopy> copies(runs.size(), VkBufferCopy{ 0, 0, 0 });
  std::uint64_t offset = 0;
  for (std::size_t i = 0; i < runs.size(); ++i)
  {
    char* mapped = runs[i].Buffer->as<char>();
    if (runs[i].Bytes == 0)
    {
      continue; // no staging where every run is empty or mapped
    }
    std::copy_n(from[i], runs[i].Bytes, mapped ? mapped + runs[i].Begin : staging->as<char>() + offset);
    copies[i] = VkBufferCopy{ offset, runs[i].Begin, mapped ? 0 : runs[i].Bytes };
    offset += mapped ? 0 : stagedSize(runs[i].Bytes);
  }
  if (total == 0)
  {
    return;
  }
  runs.front().Buffer->context().submitAndWait([&](VkCommandBuffer commands) {
    beforeCopies(commands, VK_ACCESS_TRANSFER_WRITE_BIT);
    for (std::size_t i = 0; i < runs.size(); ++i)
    {
      if (copies[i].size > 0)
      {
        vkCmdCopyBuffer(commands, staging->buffer(), runs[i].Buffer->buffer(), 1, &copies[i]);
      }
    }
    afterCopiesIn(commands);
  });
}
} // namespace

void readRuns(const std::vector<ReadRun>& runs, const std::vector<char*>& into)
{
  inRunBatches<ReadRun, char>(runs, into, readBatch);
}

void writeRuns(const std::vector<WrittenRun>& runs, const std::vector<const char*>& from)
{
  inRunBatches<WrittenRun, const char>(runs, from, writeBatch);
}

} // namespace opal
