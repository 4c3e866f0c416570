// A storage (or uniform) buffer in host-visible, coherent memory, mapped for its lifetime.
// (Every Vulkan device offers such memory; lavapipe has no other kind.)
#pragma once

#include "OpalVulkanContext.h"
#include "OpalVulkanHandle.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstring>
#include <string>

namespace opal
{

class VulkanContext;

class VulkanBuffer
{
public:
  // Throws VulkanError naming the limit if `bytes` exceeds the device's
  // storage-buffer range, before anything is allocated. `what` names the
  // buffer in messages.
  VulkanBuffer(VulkanContext& context, std::uint64_t bytes, const std::string& what);
  ~VulkanBuffer();
  VulkanBuffer(const VulkanBuffer&) = delete;
  VulkanBuffer& operator=(const VulkanBuffer&) = delete;

  VkBuffer buffer() const { return this->Buffer.get(); }
  std::uint64_t size() const { return this->Size; }
  void* data() const { return this->Mapped; }
  template <typename T>
  T* as() const
  {
    return static_cast<T*>(this->Mapped);
  }
  void upload(const void* source, std::uint64_t bytes) { std::memcpy(this->Mapped, source, bytes); }

private:
  VulkanContext& Context;
  std::uint64_t Size;
  // Declared first, so released last: after the buffer and its memory.
  MemoryReservation Reservation;
  VulkanHandle<VkBuffer> Buffer;
  VulkanHandle<VkDeviceMemory> Memory;
  void* Mapped = nullptr;
};

} // namespace opal
