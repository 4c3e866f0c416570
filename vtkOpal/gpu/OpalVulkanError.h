// Every VkResult is checked; a failure becomes an exception that names the call.
#pragma once

#include <vulkan/vulkan.h>

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

const char* vulkanResultName(VkResult result);

// Throws VulkanError("<call> failed: <VK_ERROR_...>") unless result is VK_SUCCESS.
inline void checkVulkan(VkResult result, const char* call)
{
  if (result != VK_SUCCESS)
  {
    throw VulkanError(std::string(call) + " failed: " + vulkanResultName(result), result);
  }
}

} // namespace opal
