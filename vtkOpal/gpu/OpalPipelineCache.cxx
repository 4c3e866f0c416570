#include "OpalPipelineCache.h"

#include "OpalVulkanError.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include <unistd.h>

namespace opal
{

namespace
{
namespace fs = std::filesystem;

// The folder of the cache files; empty for none.
fs::path cacheFolder()
{
  const char* setting = std::getenv("OPAL_VULKAN_PIPELINE_CACHE");
  const std::string value = setting ? setting : "";
  if (value == "0")
  {
    return {};
  }
  if (!value.empty() && value != "1")
  {
    return value;
  }
  // The XDG base directories: a relative XDG_CACHE_HOME is to be ignored.
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && fs::path(xdg).is_absolute())
  {
    return fs::path(xdg) / "opal";
  }
  const char* home = std::getenv("HOME");
  return home && *home ? fs::path(home) / ".cache" / "opal" : fs::path();
}

// vulkan-pipelines-<vendor>-<device>-<driver version>-<pipelineCacheUUID>.bin, in hexadecimal.
std::string cacheFileName(const VkPhysicalDeviceProperties& properties)
{
  char name[64];
  std::snprintf(name, sizeof(name), "vulkan-pipelines-%08x-%08x-%08x-", properties.vendorID, properties.deviceID,
    properties.driverVersion);
  std::string file = name;
  for (const std::uint8_t byte : properties.pipelineCacheUUID)
  {
    std::snprintf(name, sizeof(name), "%02x", byte);
    file += name;
  }
  return file + ".bin";
}

// The file's bytes if its header is this device's, else nothing. Drivers
// must refuse another device's data, but a file cut short or overwritten is
// not worth the risk of a driver that does not look.
std::vector<char> readCacheFile(const fs::path& file, const VkPhysicalDeviceProperties& properties)
{
  std::ifstream in(file, std::ios::binary);
  std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  VkPipelineCacheHeaderVersionOne header{};
  if (data.size() < sizeof(header))
  {
    return {};
  }
  std::memcpy(&header, data.data(), sizeof(header));
  const bool ours = header.headerSize >= sizeof(header) && header.headerSize <= data.size() &&
    header.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE && header.vendorID == properties.vendorID &&
    header.deviceID == properties.deviceID &&
    std::memcmp(header.pipelineCacheUUID, properties.pipelineCacheUUID, VK_UUID_SIZE) == 0;
  return ours ? data : std::vector<char>();
}

// Writes `data` to a temporary file beside `file` and renames it over
// `file`, so that another process never reads half a cache; on any failure
// the temporary file goes and `file` stays as it was.
void replaceFile(const fs::path& file, const std::vector<char>& data)
{
  std::error_code ignored;
  fs::create_directories(file.parent_path(), ignored);
  std::string temporary = file.string() + ".XXXXXX";
  const int descriptor = mkstemp(temporary.data()); // O_EXCL, a name no one could plant
  if (descriptor < 0)
  {
    return;
  }
  bool complete = true;
  for (std::size_t written = 0; complete && written < data.size();)
  {
    const ssize_t step = write(descriptor, data.data() + written, data.size() - written);
    complete = step > 0;
    written += complete ? static_cast<std::size_t>(step) : 0;
  }
  const bool closed = close(descriptor) == 0;
  if (!closed || !complete || std::rename(temporary.c_str(), file.c_str()) != 0)
  {
    unlink(temporary.c_str());
  }
}
} // namespace

PipelineCache::PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& properties)
  : Device(device)
{
  const fs::path folder = cacheFolder();
  std::vector<char> data;
  if (!folder.empty())
  {
    this->File = (folder / cacheFileName(properties)).string();
    data = readCacheFile(this->File, properties);
  }
  auto info = vulkanStruct<VkPipelineCacheCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO);
  info.initialDataSize = data.size();
  info.pInitialData = data.data();
  VkPipelineCache cache = VK_NULL_HANDLE;
  VkResult result = vkCreatePipelineCache(device, &info, nullptr, &cache);
  if (result != VK_SUCCESS && !data.empty())
  {
    // A driver may refuse data with its own header (a file damaged past the
    // header): the cache starts empty, and the file is replaced at the end.
    data.clear();
    info.initialDataSize = 0;
    info.pInitialData = nullptr;
    result = vkCreatePipelineCache(device, &info, nullptr, &cache);
  }
  checkVulkan(result, "vkCreatePipelineCache");
  this->LoadedBytes = data.size();
  this->Cache =
    VulkanHandle<VkPipelineCache>(cache, [device](VkPipelineCache c) { vkDestroyPipelineCache(device, c, nullptr); });
}

PipelineCache::~PipelineCache()
{
  try
  {
    this->save();
  }
  catch (const std::exception&)
  {
    // Out of memory for the data or the file's name: the cache only saves time.
  }
}

void PipelineCache::save() const
{
  std::size_t size = 0;
  VkPipelineCache cache = this->Cache.get();
  if (this->File.empty() || vkGetPipelineCacheData(this->Device, cache, &size, nullptr) != VK_SUCCESS ||
    size == this->LoadedBytes)
  {
    return;
  }
  std::vector<char> data(size);
  if (vkGetPipelineCacheData(this->Device, cache, &size, data.data()) == VK_SUCCESS)
  {
    data.resize(size);
    replaceFile(this->File, data);
  }
}

} // namespace opal
