// A Vulkan instance, one compute-capable device and its queue. Any Vulkan 1.1
// device with a compute queue will do; on machines without a GPU that is
// Mesa lavapipe. The Khronos validation layer can be switched on, and then
// every message it emits is recorded (tests fail on any).
#pragma once

#include "OpalPipelineCache.h"
#include "OpalVulkanHandle.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace opal
{

// Memory the host maps and reads or writes without flushes.
constexpr VkMemoryPropertyFlags HostVisibleMemory = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;

struct VulkanOptions
{
  // Device to use: an index into the physical devices, or -1 to pick the
  // OPAL_VULKAN_DEVICE environment variable (an index or part of a name),
  // else the first discrete, integrated, virtual, then CPU device.
  int DeviceIndex = -1;
  // Enable VK_LAYER_KHRONOS_validation; also on when OPAL_VULKAN_VALIDATION=1.
  bool Validation = false;
  // Refuse device allocations beyond this many bytes in all (0: no limit);
  // also settable by OPAL_VULKAN_MEMORY_LIMIT_MB. Simulates a small device.
  std::uint64_t MemoryLimitBytes = 0;
  // Treat device-local memory as the host's to neither map nor read (a
  // discrete GPU's) even where it is host-visible (lavapipe): uploads and
  // read-backs go through staging buffers, the path a discrete GPU takes.
  bool StagingTransfers = false;
  // The view march forwards each ray, and the light pass each walk to the
  // light, through this many pieces of the volume (slabs of layers z) as the
  // data-parallel render would between ranks (docs/design.md §8.1), in one
  // process: 1, none.
  int MarchPieces = 1;
  // With MarchPieces (or a march shared by processes, RenderSession::
  // shareMarch: each share's piece, its march alone), each piece's dispatch
  // reads the fields the march and the walks to the light read per voxel
  // (and the walks write their light) in buffers holding only its layers
  // and their halo (the march one layer, the walks five, none for their
  // light; SurfaceDistance TraceStepLayers + 2), addressed from the first
  // layer they hold, as a rank holding only its piece will: a test that
  // they reach no further (docs/design.md §8.1). The
  // volume's fields are then read by address, one value per voxel, also in
  // a session that forwards nothing; a device that cannot address buffers
  // is refused.
  bool MarchPieceFieldsOnly = false;
  // With MarchPieces, fewer sweeps through the pieces than the march's and
  // the walks to the light's forwarded passes take (4 and 5, which take every
  // state to its end; 0 or more: those): states left unfinished refuse the
  // frame, naming the pass (a test that they do, docs/design.md §8.1).
  int ForwardedMarchSweeps = 0;
  int ForwardedLightSweeps = 0;
  // Limits smaller than the device's to plan with (0: the device's own), so
  // that the tests run on lavapipe the paths a GPU's limits take.
  struct SimulatedLimits
  {
    std::uint32_t MaxComputeWorkGroupCount = 0; // along x
    std::uint32_t MaxComputeWorkGroupInvocations = 0;
    std::uint32_t MaxStorageBufferRange = 0;
    bool WithoutBufferDeviceAddress = false; // create the device without bufferDeviceAddress, as one lacking it
  } Simulated;
};

class VulkanContext;

// Bytes counted against VulkanContext's memory limit while this object lives.
class MemoryReservation
{
public:
  MemoryReservation() = default;
  MemoryReservation(VulkanContext* context, std::uint64_t bytes) : Context(context), Bytes(bytes) {}
  MemoryReservation(MemoryReservation&& other) noexcept { *this = std::move(other); }
  MemoryReservation& operator=(MemoryReservation&& other) noexcept;
  ~MemoryReservation() { this->release(); }

private:
  void release();
  VulkanContext* Context = nullptr;
  std::uint64_t Bytes = 0;
};

class VulkanContext
{
public:
  // Throws NoVulkanDeviceError if no suitable device exists, VulkanError on any failure.
  explicit VulkanContext(const VulkanOptions& options = {});
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  VkDevice device() const { return this->Device.get(); }
  VkPhysicalDevice physicalDevice() const { return this->PhysicalDevice; }
  // The device's limits as the session plans with them (VulkanOptions::Simulated applied).
  const VkPhysicalDeviceLimits& limits() const { return this->Properties.limits; }
  std::string deviceName() const { return this->Properties.deviceName; }

  // The first memory type among the allowed type bits with the `preferred`
  // properties, else the first host-visible, coherent one; throws where
  // there is neither. Device-local for the fields; host-cached for what the
  // host reads back (a discrete GPU's uncached, write-combined memory reads
  // slowly element by element).
  std::uint32_t memoryType(std::uint32_t typeBits, VkMemoryPropertyFlags preferred) const;
  VkMemoryPropertyFlags memoryTypeFlags(std::uint32_t type) const
  {
    return this->MemoryProperties.memoryTypes[type].propertyFlags;
  }
  bool stagingTransfers() const { return this->StagingTransfers; }
  // Whether shaders may address buffers (Vulkan 1.2's bufferDeviceAddress).
  bool bufferDeviceAddresses() const { return this->BufferDeviceAddresses; }

  // Book-keeping of the optional memory limit: a reservation of `bytes`,
  // released when the returned object goes; throws a VulkanError naming the
  // limit when it would be exceeded.
  MemoryReservation reserveMemory(std::uint64_t bytes);
  // The most bytes of device memory this context's buffers held at once.
  std::uint64_t memoryPeak() const { return this->MemoryPeak; }

  // What the render may use: the memory limit if one is set, else the budget
  // of the heap the device-local buffers come from (VK_EXT_memory_budget's,
  // what other programs leave, where the device reports it; else its size).
  std::uint64_t memoryBudget() const;
  // memoryBudget() in words for a refusal: "the device memory limit of 2.0
  // GB" where one is set, else "the 2.0 GB of device memory the device offers".
  std::string memoryBudgetText() const;

  // Records commands into a one-time command buffer, submits it and waits.
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record);

  // Test hook: the n-th submitAndWait from now, in any context of the
  // process, reports VK_ERROR_DEVICE_LOST (after its work ran), as a GPU
  // reset would, and so does every later submit of that context, as on a
  // lost device; 0 disarms. OPAL_VULKAN_TEST_LOSE_DEVICE=<n> arms it when
  // the process's first context is created (for pvpython and the programs).
  static void loseDeviceAtSubmitForTesting(std::uint64_t submits);

  // The pipeline cache every compute pipeline is created with, kept on disk
  // between runs (OpalPipelineCache.h).
  VkPipelineCache pipelineCache() const { return this->Pipelines->get(); }
  // Its file (empty for none: OPAL_VULKAN_PIPELINE_CACHE=0).
  const std::string& pipelineCacheFile() const { return this->Pipelines->file(); }

  // Messages the validation layer emitted (warnings and errors) so far.
  std::vector<std::string> validationMessages() const;
  bool validationEnabled() const { return static_cast<bool>(this->Messenger); }

private:
  friend class MemoryReservation;
  void releaseMemory(std::uint64_t bytes);
  static VkBool32 VKAPI_PTR onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
    VkDebugUtilsMessageTypeFlagsEXT types, const VkDebugUtilsMessengerCallbackDataEXT* data,
    void* user);
  // The constructor's steps, in order.
  void createMessenger();
  void choosePhysicalDevice(const VulkanOptions& options);
  void createDevice(bool bufferAddressesWanted);
  void createCommandObjects();

  // Declared in creation order: members are destroyed in reverse.
  VulkanHandle<VkInstance> Instance;
  VulkanHandle<VkDebugUtilsMessengerEXT> Messenger;
  VkPhysicalDevice PhysicalDevice = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties Properties{};
  VkPhysicalDeviceMemoryProperties MemoryProperties{};
  VulkanHandle<VkDevice> Device;
  VkQueue Queue = VK_NULL_HANDLE;
  std::uint32_t QueueFamily = 0;
  VulkanHandle<VkCommandPool> CommandPool;
  VulkanHandle<VkFence> Fence;
  std::unique_ptr<PipelineCache> Pipelines; // saved to its file before the device goes
  bool Lost = false; // by the test hook: the device runs nothing more
  std::uint64_t MemoryLimit = 0;
  bool StagingTransfers = false;
  bool BufferDeviceAddresses = false;
  bool MemoryBudgets = false; // VK_EXT_memory_budget enabled
  std::uint64_t MemoryInUse = 0;
  std::uint64_t MemoryPeak = 0;
  mutable std::mutex MessageMutex;
  std::vector<std::string> Messages;
};

} // namespace opal
