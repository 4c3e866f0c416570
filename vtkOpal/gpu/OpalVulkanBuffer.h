// A storage (or uniform) buffer. HostVisible buffers live in host-visible,
// coherent memory, mapped for their lifetime (the pixel images the host reads
// back, what the host writes every frame). DeviceLocal buffers (the volume's
// fields and light field) prefer device-local memory: where that memory is
// also host-visible (lavapipe, integrated GPUs) they are mapped like the
// others; on a device with dedicated memory they are not, and uploads go
// through a staging buffer and a copy on the device.
#pragma once

#include "OpalVulkanContext.h"
#include "OpalVulkanHandle.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace opal
{

class VulkanContext;

enum class BufferPlacement
{
  HostVisible,
  // HostVisible, in host-cached memory where the device offers it: what the
  // host reads back (VulkanContext::memoryType).
  HostReadback,
  DeviceLocal,
  // DeviceLocal, read by shaders through its device address rather than a
  // descriptor, so no maxStorageBufferRange bounds it (docs/design.md §3.7).
  DeviceAddressed,
};

class VulkanBuffer
{
public:
  // Throws VulkanError naming the limit if `bytes` exceeds the device's
  // storage-buffer range, before anything is allocated. `what` names the
  // buffer in messages.
  VulkanBuffer(VulkanContext& context, std::uint64_t bytes, const std::string& what,
    BufferPlacement placement = BufferPlacement::HostVisible);
  ~VulkanBuffer();
  VulkanBuffer(const VulkanBuffer&) = delete;
  VulkanBuffer& operator=(const VulkanBuffer&) = delete;

  VkBuffer buffer() const { return this->Buffer.get(); }
  std::uint64_t size() const { return this->Size; }
  // The device address of a DeviceAddressed buffer.
  std::uint64_t address() const;
  // The mapped memory (nullptr for a DeviceLocal buffer in dedicated memory).
  template <typename T>
  T* as() const
  {
    return static_cast<T*>(this->Mapped);
  }
  // Copies `bytes` from the host into the buffer's start (fill).
  void upload(const void* source, std::uint64_t bytes);
  // Writes the buffer's first `bytes` as write(first, count, into) gives
  // them: bytes [first, first + count) of the content, into `into`. Directly
  // into the mapped memory, else in rounds through a staging buffer of at most
  // FillRoundBytes (waiting for each copy), so that a volume's field never
  // needs a whole host copy besides its source (docs/design.md §3.7).
  using ContentWriter = std::function<void(std::uint64_t first, std::uint64_t count, void* into)>;
  void fill(std::uint64_t bytes, const ContentWriter& write);
  // Reads the buffer's first `bytes` as reader(first, count, from) takes them:
  // bytes [first, first + count) of the content at `from`. Directly from the
  // mapped memory, else in rounds through a staging buffer of at most
  // FillRoundBytes, as fill writes them.
  using ContentReader = std::function<void(std::uint64_t first, std::uint64_t count, const void* from)>;
  void read(std::uint64_t bytes, const ContentReader& reader) const { this->readRange(0, bytes, reader); }
  // read for bytes [begin, begin + bytes) of the buffer (`first` counts from begin).
  void readRange(std::uint64_t begin, std::uint64_t bytes, const ContentReader& reader) const;
  // Copies `bytes` from the host into bytes [begin, begin + bytes) of the
  // buffer, as fill does (the rest of the buffer kept).
  void write(std::uint64_t begin, std::uint64_t bytes, const void* source);
  // A round's bytes: a multiple of every field's value (at most 16 bytes).
  static constexpr std::uint64_t FillRoundBytes = std::uint64_t(64) << 20;
  // Records: the whole buffer set to zero on the device, after the passes'
  // and copies' reads and writes of it, then a barrier so that the next
  // dispatch (or indirect dispatch) sees it.
  void recordClear(VkCommandBuffer commands) const;
  // Records: bytes [sourceBegin, sourceBegin + bytes) of `source` copied into
  // bytes [begin, begin + bytes) of this buffer, after the passes' and
  // copies' reads and writes of either, before the next dispatch's.
  void recordCopyFrom(VkCommandBuffer commands, const VulkanBuffer& source, std::uint64_t sourceBegin,
    std::uint64_t begin, std::uint64_t bytes) const;
  // Records: the buffer's first `bytes` (at most 65536, a multiple of 4)
  // written from `source`, which the call copies, in order with passes and copies.
  void recordWrite(VkCommandBuffer commands, const void* source, std::uint64_t bytes) const;
  VulkanContext& context() const { return this->Context; }

private:
  // fill for bytes [begin, begin + bytes) (`first` counts from begin).
  void fillRange(std::uint64_t begin, std::uint64_t bytes, const ContentWriter& write);
  void allocate(VkMemoryRequirements requirements, BufferPlacement placement, const std::string& what);
  // `bytes` of the buffer in rounds of at most FillRoundBytes through one
  // staging buffer of `placement` (fill, read): round(first, count, staging).
  void inStagingRounds(std::uint64_t bytes, BufferPlacement placement, const std::string& what,
    const std::function<void(std::uint64_t first, std::uint64_t count, VulkanBuffer& staging)>& round) const;

  VulkanContext& Context;
  std::uint64_t Size;
  std::string What;
  // Declared first, so released last: after the buffer and its memory.
  MemoryReservation Reservation;
  VulkanHandle<VkBuffer> Buffer;
  VulkanHandle<VkDeviceMemory> Memory;
  void* Mapped = nullptr;
};

// The host's view of device buffers the passes wrote (docs/design.md §3.7):
// their own memory where it is mapped (lavapipe, integrated GPUs), else one
// staging buffer that one submit fills from all of them (a discrete GPU's
// memory is not the host's to read element by element).
class HostReadback
{
public:
  // The first `bytes` of each buffer.
  HostReadback(VulkanContext& context, const std::vector<std::pair<const VulkanBuffer*, std::uint64_t>>& parts);
  template <typename T>
  const T* view(std::size_t part) const
  {
    return static_cast<const T*>(this->Views.at(part));
  }

private:
  std::unique_ptr<VulkanBuffer> Staging;
  std::vector<const void*> Views;
};

// Runs of bytes of several buffers (of one context) read to or written from
// the host together: mapped buffers directly, the others through one staging
// buffer and one submit. A shared step's layer reads and writes a few short
// rows of each field, for which a staging buffer and a wait each cost more
// than the rows (docs/design.md §8.1). The runs are staged in batches of at
// most FillRoundBytes, as fill's rounds are (a longer run in pieces): one
// staging buffer and one submit a batch.
// Bytes [Begin, Begin + Bytes) of a buffer read (ReadRun) or written (WrittenRun).
template <typename BufferType>
struct RunOf
{
  BufferType* Buffer;
  std::uint64_t Begin;
  std::uint64_t Bytes;
};
using ReadRun = RunOf<const VulkanBuffer>;
using WrittenRun = RunOf<VulkanBuffer>;
// Each run's bytes into into[i].
void readRuns(const std::vector<ReadRun>& runs, const std::vector<char*>& into);
// Each run's bytes from from[i].
void writeRuns(const std::vector<WrittenRun>& runs, const std::vector<const char*>& from);

} // namespace opal
