#include "OpalVulkanError.h"

namespace opal
{

const char* vulkanResultName(VkResult result)
{
  switch (result)
  {
#define OPAL_RESULT_CASE(name)                                                                    \
  case name:                                                                                       \
    return #name;
    OPAL_RESULT_CASE(VK_SUCCESS)
    OPAL_RESULT_CASE(VK_NOT_READY)
    OPAL_RESULT_CASE(VK_TIMEOUT)
    OPAL_RESULT_CASE(VK_INCOMPLETE)
    OPAL_RESULT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    OPAL_RESULT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    OPAL_RESULT_CASE(VK_ERROR_INITIALIZATION_FAILED)
    OPAL_RESULT_CASE(VK_ERROR_DEVICE_LOST)
    OPAL_RESULT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    OPAL_RESULT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    OPAL_RESULT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    OPAL_RESULT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    OPAL_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    OPAL_RESULT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    OPAL_RESULT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    OPAL_RESULT_CASE(VK_ERROR_FRAGMENTED_POOL)
    OPAL_RESULT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    OPAL_RESULT_CASE(VK_ERROR_UNKNOWN)
#undef OPAL_RESULT_CASE
    default:
      return "VkResult (unnamed)";
  }
}

VulkanError storageRangeError(
  const std::string& needs, std::uint64_t bytes, const std::string& buffer, std::uint64_t range, const std::string& remedy)
{
  return VulkanError(needs + " a " + std::to_string(bytes) + "-byte " + buffer +
      ", more than the device's maxStorageBufferRange of " + std::to_string(range) + " bytes" + remedy,
    VK_ERROR_OUT_OF_DEVICE_MEMORY);
}

} // namespace opal
