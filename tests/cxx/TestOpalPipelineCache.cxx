// The pipeline cache on disk (docs/design.md §3.7), in a folder of its own
// (OPAL_VULKAN_PIPELINE_CACHE): the first session writes the device's file
// when it ends, a second one loads it, renders the same image and, having
// compiled nothing new, leaves the file as it was; a corrupt file and another
// device's are passed over and replaced; a folder that cannot be made costs
// nothing; 0 turns the file off; unset, it lies under $XDG_CACHE_HOME/opal.
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"
#include "OpalVulkanContext.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

namespace
{
namespace fs = std::filesystem;

std::vector<char> readBytes(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  return std::vector<char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void writeBytes(const fs::path& file, const std::vector<char>& bytes)
{
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

ino_t inodeOf(const fs::path& file)
{
  struct stat status{};
  return stat(file.c_str(), &status) == 0 ? status.st_ino : 0;
}

// Whether `bytes` begin with a Vulkan pipeline cache header of version one.
bool cacheHeader(const std::vector<char>& bytes)
{
  VkPipelineCacheHeaderVersionOne header{};
  if (bytes.size() < sizeof(header))
  {
    return false;
  }
  std::memcpy(&header, bytes.data(), sizeof(header));
  return header.headerSize >= sizeof(header) && header.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE;
}

// A session's render of the slab, and the file its context named.
opal::RenderImage renderSlab(std::string& file)
{
  opaltest::SlabScene scene;
  scene.Dimensions = { 40, 10, 40 };
  scene.Spacing = 0.2;
  scene.Scattering = 2.0;
  scene.WithDomain = true;
  opaltest::SceneRenderer renderer{ opal::VulkanOptions{} };
  file = renderer.context().pipelineCacheFile();
  opal::RenderImage image = renderer.render(scene.build(), opaltest::slabView());
  OPAL_CHECK(renderer.context().validationMessages().empty(), "the validation layer is silent");
  return image;
}

// A corrupt file, another device's (its pipelineCacheUUID changed) and one
// with this device's header over a corrupt body are passed over, the render
// unharmed, and replaced by a file with this device's header.
void checkDamagedFiles(const fs::path& file, const opal::RenderImage& first)
{
  const std::vector<char> good = readBytes(file);
  const std::vector<char> header(good.begin(), good.begin() + sizeof(VkPipelineCacheHeaderVersionOne));
  std::vector<char> otherDevice = good;
  otherDevice[16] = static_cast<char>(otherDevice[16] ^ 0xff);
  std::vector<char> corruptBody = header;
  corruptBody.resize(header.size() + 256, '\x5a');
  const std::vector<char> corrupt(good.size(), '\x5a');
  for (const auto& [bytes, what] : { std::pair<std::vector<char>, std::string>{ corrupt, "a corrupt file" },
         { otherDevice, "another device's" }, { corruptBody, "a corrupt body" } })
  {
    writeBytes(file, bytes);
    std::string named;
    const opal::RenderImage image = renderSlab(named);
    OPAL_CHECK(image.RGB == first.RGB, what + ": the render is unharmed");
    const std::vector<char> replaced = readBytes(file);
    OPAL_CHECK(replaced.size() >= header.size() && std::equal(header.begin(), header.end(), replaced.begin()) &&
        replaced != bytes,
      what + ": replaced by one with this device's header");
  }
}

void checkFolders(const fs::path& folder)
{
  std::string file;
  writeBytes(folder / "a-file", { 'x' });
  setenv("OPAL_VULKAN_PIPELINE_CACHE", (folder / "a-file" / "cache").c_str(), 1);
  OPAL_CHECK(!renderSlab(file).RGB.empty(), "a folder that cannot be made: the render goes on");
  setenv("OPAL_VULKAN_PIPELINE_CACHE", "0", 1);
  renderSlab(file);
  OPAL_CHECK(file.empty(), "OPAL_VULKAN_PIPELINE_CACHE=0: no file");
  unsetenv("OPAL_VULKAN_PIPELINE_CACHE");
  setenv("XDG_CACHE_HOME", (folder / "xdg").c_str(), 1);
  renderSlab(file);
  OPAL_CHECK(fs::path(file).parent_path() == folder / "xdg" / "opal" && fs::exists(file),
    "unset: the file lies under $XDG_CACHE_HOME/opal (" + file + ")");
}
} // namespace

int TestOpalPipelineCache(int, char*[])
{
  if (!opaltest::vulkanDeviceAvailable())
  {
    return opaltest::noDeviceReturnCode();
  }
  const fs::path folder = fs::temp_directory_path() / ("opal-pipeline-cache-" + std::to_string(getpid()));
  fs::remove_all(folder);
  setenv("OPAL_VULKAN_PIPELINE_CACHE", (folder / "pipelines").c_str(), 1);

  std::string file;
  const opal::RenderImage first = renderSlab(file);
  OPAL_CHECK(fs::path(file).parent_path() == folder / "pipelines" &&
      fs::path(file).filename().string().rfind("vulkan-pipelines-", 0) == 0,
    "the device's file in the folder named (" + file + ")");
  OPAL_CHECK(cacheHeader(readBytes(file)), "written when the session ended, with the cache's header");
  const ino_t written = inodeOf(file);
  std::string again;
  OPAL_CHECK(renderSlab(again).RGB == first.RGB && again == file, "a second session renders the same image");
  OPAL_CHECK(inodeOf(file) == written, "from the file, left as it was: nothing new was compiled");
  checkDamagedFiles(file, first);
  checkFolders(folder);
  fs::remove_all(folder);
  return opaltest::finish("TestOpalPipelineCache");
}
