// The driver's cache of compiled pipelines, kept on disk between runs
// (docs/design.md §3.7), so that a later process creates its pipelines
// without compiling them again where the driver caches them. One file per
// device: its vendor, device, driver version and pipelineCacheUUID name it.
// The cache only saves time: a file that cannot be read, does not belong to
// the device or cannot be written is passed over without a word.
#pragma once

#include "OpalVulkanHandle.h"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <string>

namespace opal
{

class PipelineCache
{
public:
  // Loads the device's file from the folder OPAL_VULKAN_PIPELINE_CACHE names
  // (unset, empty or 1: $XDG_CACHE_HOME/opal, else ~/.cache/opal; 0: no file,
  // the cache lives in memory only). Throws VulkanError if the driver cannot
  // create even an empty cache.
  PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& properties);
  // Writes the cache back (a temporary file renamed over the old one) if the
  // driver's data changed size since it was loaded.
  ~PipelineCache();
  PipelineCache(const PipelineCache&) = delete;
  PipelineCache& operator=(const PipelineCache&) = delete;

  VkPipelineCache get() const { return this->Cache.get(); }
  // The file it is loaded from and saved to; empty when there is none.
  const std::string& file() const { return this->File; }

private:
  void save() const;

  VkDevice Device;
  std::string File;
  std::size_t LoadedBytes = 0; // what the driver accepted from the file
  VulkanHandle<VkPipelineCache> Cache;
};

} // namespace opal
