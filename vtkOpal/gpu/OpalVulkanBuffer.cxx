#include "OpalVulkanBuffer.h"

#include "OpalVulkanContext.h"
#include "OpalVulkanError.h"

#include <algorithm>

namespace opal
{

VulkanBuffer::VulkanBuffer(VulkanContext& context, std::uint64_t bytes, const std::string& what)
  : Context(context)
  , Size(std::max<std::uint64_t>(bytes, 16))
{
  const std::uint64_t range = context.limits().maxStorageBufferRange;
  if (this->Size > range)
  {
    throw VulkanError("the " + what + " needs a " + std::to_string(this->Size) +
        "-byte storage buffer, more than the device's maxStorageBufferRange of " + std::to_string(range) +
        " bytes; use fewer voxels or pixels",
      VK_ERROR_OUT_OF_DEVICE_MEMORY);
  }
  VkDevice device = context.device();
  auto info = vulkanStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
  info.size = this->Size;
  info.usage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  checkVulkan(vkCreateBuffer(device, &info, nullptr, &buffer), "vkCreateBuffer");
  this->Buffer = VulkanHandle<VkBuffer>(buffer, [device](VkBuffer b) { vkDestroyBuffer(device, b, nullptr); });

  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(device, buffer, &requirements);
  // Released by the member's destructor also when a later step throws.
  this->Reservation = context.reserveMemory(requirements.size);
  auto allocate = vulkanStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
  allocate.allocationSize = requirements.size;
  allocate.memoryTypeIndex = context.memoryType(
    requirements.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VkDeviceMemory memory = VK_NULL_HANDLE;
  const VkResult result = vkAllocateMemory(device, &allocate, nullptr, &memory);
  if (result != VK_SUCCESS)
  {
    checkVulkan(result, ("vkAllocateMemory (" + what + ", " + std::to_string(requirements.size) + " bytes)").c_str());
  }
  this->Memory =
    VulkanHandle<VkDeviceMemory>(memory, [device](VkDeviceMemory m) { vkFreeMemory(device, m, nullptr); });
  checkVulkan(vkBindBufferMemory(device, buffer, memory, 0), "vkBindBufferMemory");
  checkVulkan(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &this->Mapped), "vkMapMemory");
}

VulkanBuffer::~VulkanBuffer()
{
  if (this->Mapped)
  {
    vkUnmapMemory(this->Context.device(), this->Memory.get());
  }
}

} // namespace opal
