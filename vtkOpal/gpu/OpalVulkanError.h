// Every VkResult is checked; a failure becomes an exception that names the call.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace opal
{

class VulkanError : public std::runtime_error
{
public:
  VulkanError(const std::string& message, VkResult result = VK_ERROR_UNKNOWN)
    : std::runtime_error(message)
    , Result(result)
  {
  }
  VkResult result() const { return this->Result; }

private:
  VkResult Result;
};

// No Vulkan 1.1 device with a compute queue (callers may skip, never pass).
class NoVulkanDeviceError : public VulkanError
{
public:
  using VulkanError::VulkanError;
};

// VK_ERROR_DEVICE_LOST: the device and every object made on it are unusable
// (a GPU reset, a watchdog, a driver fault). Unlike other failures it is
// not the request's: whoever holds the device drops it, and a new device
// renders the same request.
class DeviceLostError : public VulkanError
{
public:
  explicit DeviceLostError(const char* call)
    : VulkanError(std::string("The Vulkan device was lost (VK_ERROR_DEVICE_LOST) in ") + call, VK_ERROR_DEVICE_LOST)
  {
  }
};

const char* vulkanResultName(VkResult result);

// The refusal of a buffer beyond the device's maxStorageBufferRange: "<needs>
// a <bytes>-byte <buffer>, more than the device's maxStorageBufferRange of
// <range> bytes<remedy>" (remedy from its "; " or ", ").
VulkanError storageRangeError(
  const std::string& needs, std::uint64_t bytes, const std::string& buffer, std::uint64_t range, const std::string& remedy);

// Throws VulkanError("<call> failed: <VK_ERROR_...>") unless result is
// VK_SUCCESS; DeviceLostError for VK_ERROR_DEVICE_LOST.
inline void checkVulkan(VkResult result, const char* call)
{
  if (result == VK_ERROR_DEVICE_LOST)
  {
    throw DeviceLostError(call);
  }
  if (result != VK_SUCCESS)
  {
    throw VulkanError(std::string(call) + " failed: " + vulkanResultName(result), result);
  }
}

} // namespace opal
