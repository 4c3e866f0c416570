#include "OpalVulkanContext.h"

#include "OpalMemory.h"
#include "OpalVulkanError.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>
#include <system_error>
#include <utility>

namespace opal
{

namespace
{
const char* const ValidationLayer = "VK_LAYER_KHRONOS_validation";

// The environment's numbers are read strictly, the whole value in decimal
// digits (std::from_chars: no sign, space or "0x"): atoi and strtoull let
// "-1", " 0" and an index past INT_MAX fall back to a default without a word.

// The variable's value, digits only and at most `max`; nothing otherwise.
std::optional<std::uint64_t> environmentDigits(const std::string& value, std::uint64_t max)
{
  std::uint64_t number = 0;
  const char* last = value.data() + value.size();
  const auto [stop, error] = std::from_chars(value.data(), last, number);
  const bool digits = !value.empty() && std::isdigit(static_cast<unsigned char>(value.front()));
  if (!digits || stop != last || error != std::errc() || number > max)
  {
    return std::nullopt;
  }
  return number;
}

// A switch: unset or empty is off, 0 off, 1 on; anything else is refused
// naming the variable (a "false" or "no" must not turn it on).
bool environmentFlag(const char* name)
{
  const char* value = std::getenv(name);
  if (!value || !*value)
  {
    return false;
  }
  const std::optional<std::uint64_t> flag = environmentDigits(value, 1);
  if (!flag)
  {
    throw VulkanError(std::string(name) + " must be 0 or 1, got \"" + value + "\"", VK_ERROR_INITIALIZATION_FAILED);
  }
  return *flag == 1;
}

bool layerAvailable(const char* name)
{
  std::uint32_t count = 0;
  checkVulkan(vkEnumerateInstanceLayerProperties(&count, nullptr), "vkEnumerateInstanceLayerProperties");
  std::vector<VkLayerProperties> layers(count);
  checkVulkan(vkEnumerateInstanceLayerProperties(&count, layers.data()), "vkEnumerateInstanceLayerProperties");
  return std::any_of(layers.begin(), layers.end(),
    [name](const VkLayerProperties& layer) { return std::strcmp(layer.layerName, name) == 0; });
}

VulkanHandle<VkInstance> createInstance(bool validation)
{
  auto application = vulkanStruct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
  application.pApplicationName = "Opal";
  application.pEngineName = "Opal";
  application.apiVersion = VK_API_VERSION_1_2; // the most used: 1.1 devices still do (bufferDeviceAddresses)
  auto info = vulkanStruct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
  info.pApplicationInfo = &application;
  // Both extensions come with the validation layer. Synchronization validation
  // is off in the layer by default; on, a missing barrier (a hazard between
  // dispatches, copies or submits) is an error message like any other, so it
  // fails whatever checks validation, under ctest or a user's own run.
  const char* extensions[] = { VK_EXT_DEBUG_UTILS_EXTENSION_NAME, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME };
  const VkValidationFeatureEnableEXT synchronization = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  auto features = vulkanStruct<VkValidationFeaturesEXT>(VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT);
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &synchronization;
  if (validation)
  {
    info.pNext = &features;
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = &ValidationLayer;
    info.enabledExtensionCount = 2;
    info.ppEnabledExtensionNames = extensions;
  }
  VkInstance instance = VK_NULL_HANDLE;
  const VkResult result = vkCreateInstance(&info, nullptr, &instance);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER)
  {
    throw NoVulkanDeviceError("vkCreateInstance failed: no Vulkan driver (VK_ERROR_INCOMPATIBLE_DRIVER); "
                              "install mesa-vulkan-drivers for the CPU device lavapipe",
      result);
  }
  checkVulkan(result, "vkCreateInstance");
  return VulkanHandle<VkInstance>(instance, [](VkInstance i) { vkDestroyInstance(i, nullptr); });
}

bool deviceExtensionAvailable(VkPhysicalDevice device, const char* name)
{
  std::uint32_t count = 0;
  checkVulkan(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr), "vkEnumerateDeviceExtensionProperties");
  std::vector<VkExtensionProperties> extensions(count);
  checkVulkan(
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()), "vkEnumerateDeviceExtensionProperties");
  return std::any_of(extensions.begin(), extensions.end(),
    [name](const VkExtensionProperties& extension) { return std::strcmp(extension.extensionName, name) == 0; });
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance)
{
  std::uint32_t count = 0;
  checkVulkan(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(count);
  checkVulkan(vkEnumeratePhysicalDevices(instance, &count, devices.data()), "vkEnumeratePhysicalDevices");
  return devices;
}

// Index of a queue family with compute, or -1.
int computeQueueFamily(VkPhysicalDevice device)
{
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (std::uint32_t i = 0; i < count; ++i)
  {
    if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)
    {
      return static_cast<int>(i);
    }
  }
  return -1;
}

bool suitable(VkPhysicalDevice device)
{
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(device, &properties);
  return properties.apiVersion >= VK_API_VERSION_1_1 && computeQueueFamily(device) >= 0;
}

int typeRank(VkPhysicalDeviceType type)
{
  switch (type)
  {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 3;
    default:
      return 4;
  }
}

// The device asked for: an index (-1: none), or part of a name (empty: any).
struct DeviceSelector
{
  int Index = -1;
  std::string Name;
};

// OPAL_VULKAN_DEVICE: a device's index or part of a device's name. A value
// that reads as a number (digits, perhaps with a sign or spaces) is an index
// and must be digits naming one of the devices.
DeviceSelector environmentDevice(std::size_t deviceCount)
{
  const char* value = std::getenv("OPAL_VULKAN_DEVICE");
  const std::string text = value ? value : "";
  const bool numeric = text.find_first_of("0123456789") != std::string::npos &&
    text.find_first_not_of("0123456789+- \t") == std::string::npos;
  if (!numeric)
  {
    return { -1, text };
  }
  const std::optional<std::uint64_t> device = environmentDigits(text, deviceCount - 1);
  if (!device)
  {
    throw VulkanError("OPAL_VULKAN_DEVICE must be a device index from 0 to " + std::to_string(deviceCount - 1) +
        " in digits (" + std::to_string(deviceCount) + " device(s) exist) or part of a device's name, got \"" +
        text + "\"",
      VK_ERROR_INITIALIZATION_FAILED);
  }
  return { static_cast<int>(*device), {} };
}

VkPhysicalDevice chooseDevice(const std::vector<VkPhysicalDevice>& devices, int requested)
{
  auto name = [](VkPhysicalDevice d) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    return std::string(p.deviceName);
  };
  if (requested < -1)
  {
    throw VulkanError("DeviceIndex must be -1 (OPAL_VULKAN_DEVICE or the best device) or a device's index, got " +
        std::to_string(requested),
      VK_ERROR_INITIALIZATION_FAILED);
  }
  const DeviceSelector selector = requested < 0 ? environmentDevice(devices.size()) : DeviceSelector{ requested, {} };
  requested = selector.Index;
  if (requested >= 0)
  {
    if (requested >= static_cast<int>(devices.size()))
    {
      throw NoVulkanDeviceError("Vulkan device " + std::to_string(requested) + " requested, but only " +
        std::to_string(devices.size()) + " device(s) exist");
    }
    VkPhysicalDevice device = devices[static_cast<std::size_t>(requested)];
    if (!suitable(device))
    {
      throw NoVulkanDeviceError("Vulkan device " + std::to_string(requested) + " (" + name(device) +
        ") lacks Vulkan 1.1 or a compute queue");
    }
    return device;
  }
  VkPhysicalDevice best = VK_NULL_HANDLE;
  int bestRank = 1 << 20;
  for (VkPhysicalDevice device : devices)
  {
    if (!suitable(device) || name(device).find(selector.Name) == std::string::npos)
    {
      continue;
    }
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(device, &properties);
    if (typeRank(properties.deviceType) < bestRank)
    {
      bestRank = typeRank(properties.deviceType);
      best = device;
    }
  }
  if (best == VK_NULL_HANDLE)
  {
    throw NoVulkanDeviceError(selector.Name.empty()
        ? "no Vulkan 1.1 device with a compute queue; install mesa-vulkan-drivers for lavapipe"
        : "no Vulkan device whose name contains \"" + selector.Name + "\" (OPAL_VULKAN_DEVICE)");
  }
  return best;
}
// The environment's memory limit, which must be a whole number of MB (no
// silent "no limit" for a typo); 0 when unset.
std::uint64_t environmentMemoryLimit()
{
  const char* limit = std::getenv("OPAL_VULKAN_MEMORY_LIMIT_MB");
  if (!limit || !*limit)
  {
    return 0;
  }
  constexpr std::uint64_t MaxMegabytes = 1ull << 40;
  const std::optional<std::uint64_t> megabytes = environmentDigits(limit, MaxMegabytes);
  if (!megabytes)
  {
    throw VulkanError(std::string("OPAL_VULKAN_MEMORY_LIMIT_MB must be a whole number of MB from 0 to ") +
        std::to_string(MaxMegabytes) + " in digits, got \"" + limit + "\"",
      VK_ERROR_INITIALIZATION_FAILED);
  }
  return *megabytes << 20;
}

// The test hook's countdown, shared by every context: the one that replaces
// a lost device must not lose its own.
std::atomic<std::uint64_t>& submitsUntilLoss()
{
  static std::atomic<std::uint64_t> submits{ 0 };
  return submits;
}

// Counts a submit down; true for the one that reaches the loss.
bool deviceLossDue()
{
  std::atomic<std::uint64_t>& submits = submitsUntilLoss();
  std::uint64_t left = submits.load();
  while (left > 0 && !submits.compare_exchange_weak(left, left - 1))
  {
  }
  return left == 1;
}

// OPAL_VULKAN_TEST_LOSE_DEVICE=<n>: the n-th submit of the process reports
// the loss. Read once, so that the context made after the loss renders.
void armDeviceLossFromEnvironment()
{
  static const bool armed = [] {
    const char* value = std::getenv("OPAL_VULKAN_TEST_LOSE_DEVICE");
    if (!value || !*value)
    {
      return false;
    }
    const std::optional<std::uint64_t> submits = environmentDigits(value, UINT32_MAX);
    if (!submits)
    {
      throw VulkanError(std::string("OPAL_VULKAN_TEST_LOSE_DEVICE must be a submit's number in digits, got \"") +
          value + "\"",
        VK_ERROR_INITIALIZATION_FAILED);
    }
    VulkanContext::loseDeviceAtSubmitForTesting(*submits);
    return true;
  }();
  (void)armed;
}
} // namespace

void VulkanContext::loseDeviceAtSubmitForTesting(std::uint64_t submits)
{
  submitsUntilLoss().store(submits);
}

VulkanContext::VulkanContext(const VulkanOptions& options)
{
  const bool validation = options.Validation || environmentFlag("OPAL_VULKAN_VALIDATION");
  if (validation && !layerAvailable(ValidationLayer))
  {
    throw VulkanError("Vulkan validation was requested but VK_LAYER_KHRONOS_validation is not installed "
                      "(Debian: vulkan-validationlayers)",
      VK_ERROR_LAYER_NOT_PRESENT);
  }
  this->Instance = createInstance(validation);
  if (validation)
  {
    this->createMessenger();
  }
  this->choosePhysicalDevice(options);
  this->createDevice(!options.Simulated.WithoutBufferDeviceAddress);
  this->createCommandObjects();
  this->Pipelines = std::make_unique<PipelineCache>(this->Device.get(), this->Properties);
  armDeviceLossFromEnvironment();
  this->StagingTransfers = options.StagingTransfers;
  // An explicit limit wins over the environment's.
  this->MemoryLimit = options.MemoryLimitBytes ? options.MemoryLimitBytes : environmentMemoryLimit();
}

// Routes the validation layer's warnings and errors to onValidationMessage.
void VulkanContext::createMessenger()
{
  VkInstance instance = this->Instance.get();
  auto info = vulkanStruct<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
    VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = &VulkanContext::onValidationMessage;
  info.pUserData = this;
  auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
    vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
  if (!create)
  {
    throw VulkanError(
      "vkGetInstanceProcAddr(vkCreateDebugUtilsMessengerEXT) found no function", VK_ERROR_EXTENSION_NOT_PRESENT);
  }
  auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
    vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  checkVulkan(create(instance, &info, nullptr, &messenger), "vkCreateDebugUtilsMessengerEXT");
  this->Messenger = VulkanHandle<VkDebugUtilsMessengerEXT>(
    messenger, [instance, destroy](VkDebugUtilsMessengerEXT m) { destroy(instance, m, nullptr); });
}

// The physical device (OPAL_VULKAN_DEVICE or options.DeviceIndex, else the
// best), its properties and its compute queue family.
void VulkanContext::choosePhysicalDevice(const VulkanOptions& options)
{
  const std::vector<VkPhysicalDevice> devices = physicalDevices(this->Instance.get());
  if (devices.empty())
  {
    throw NoVulkanDeviceError("no Vulkan device; install mesa-vulkan-drivers for the CPU device lavapipe");
  }
  this->PhysicalDevice = chooseDevice(devices, options.DeviceIndex);
  vkGetPhysicalDeviceProperties(this->PhysicalDevice, &this->Properties);
  VkPhysicalDeviceLimits& limits = this->Properties.limits;
  const VulkanOptions::SimulatedLimits& simulated = options.Simulated;
  for (auto [limit, smaller] : { std::pair<std::uint32_t*, std::uint32_t>{ &limits.maxComputeWorkGroupCount[0],
           simulated.MaxComputeWorkGroupCount },
         { &limits.maxComputeWorkGroupInvocations, simulated.MaxComputeWorkGroupInvocations },
         { &limits.maxStorageBufferRange, simulated.MaxStorageBufferRange } })
  {
    *limit = smaller ? std::min(*limit, smaller) : *limit;
  }
  vkGetPhysicalDeviceMemoryProperties(this->PhysicalDevice, &this->MemoryProperties);
  this->QueueFamily = static_cast<std::uint32_t>(computeQueueFamily(this->PhysicalDevice));
}

// The logical device with one compute queue; buffer device addresses where
// `bufferAddressesWanted` and the device has them.
void VulkanContext::createDevice(bool bufferAddressesWanted)
{
  const float priority = 1.0f;
  auto queueInfo = vulkanStruct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
  queueInfo.queueFamilyIndex = this->QueueFamily;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  auto deviceInfo = vulkanStruct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  // Buffer device addresses where the device has them (Vulkan 1.2): the
  // passes for volumes beyond one storage buffer's range read so (§3.7).
  auto vulkan12 = vulkanStruct<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
  if (this->Properties.apiVersion >= VK_API_VERSION_1_2)
  {
    auto features = vulkanStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
    features.pNext = &vulkan12;
    vkGetPhysicalDeviceFeatures2(this->PhysicalDevice, &features);
    this->BufferDeviceAddresses = bufferAddressesWanted && vulkan12.bufferDeviceAddress == VK_TRUE;
    vulkan12 = vulkanStruct<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
    vulkan12.bufferDeviceAddress = this->BufferDeviceAddresses ? VK_TRUE : VK_FALSE;
    deviceInfo.pNext = &vulkan12;
  }
  // The heaps' budgets where the device reports them (memoryBudget).
  const char* memoryBudget = VK_EXT_MEMORY_BUDGET_EXTENSION_NAME;
  this->MemoryBudgets = deviceExtensionAvailable(this->PhysicalDevice, memoryBudget);
  deviceInfo.enabledExtensionCount = this->MemoryBudgets ? 1 : 0;
  deviceInfo.ppEnabledExtensionNames = &memoryBudget;
  VkDevice device = VK_NULL_HANDLE;
  checkVulkan(vkCreateDevice(this->PhysicalDevice, &deviceInfo, nullptr, &device), "vkCreateDevice");
  this->Device = VulkanHandle<VkDevice>(device, [](VkDevice d) { vkDestroyDevice(d, nullptr); });
  vkGetDeviceQueue(device, this->QueueFamily, 0, &this->Queue);
}

// The command pool and the fence every submission waits on.
void VulkanContext::createCommandObjects()
{
  VkDevice device = this->Device.get();
  auto poolInfo = vulkanStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  poolInfo.queueFamilyIndex = this->QueueFamily;
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  VkCommandPool pool = VK_NULL_HANDLE;
  checkVulkan(vkCreateCommandPool(device, &poolInfo, nullptr, &pool), "vkCreateCommandPool");
  this->CommandPool =
    VulkanHandle<VkCommandPool>(pool, [device](VkCommandPool p) { vkDestroyCommandPool(device, p, nullptr); });
  auto fenceInfo = vulkanStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
  VkFence fence = VK_NULL_HANDLE;
  checkVulkan(vkCreateFence(device, &fenceInfo, nullptr, &fence), "vkCreateFence");
  this->Fence = VulkanHandle<VkFence>(fence, [device](VkFence f) { vkDestroyFence(device, f, nullptr); });
}

VulkanContext::~VulkanContext()
{
  if (this->Device)
  {
    vkDeviceWaitIdle(this->Device.get());
  }
}

std::uint32_t VulkanContext::memoryType(std::uint32_t typeBits, VkMemoryPropertyFlags preferred) const
{
  for (const VkMemoryPropertyFlags properties : { preferred, HostVisibleMemory })
  {
    for (std::uint32_t i = 0; i < this->MemoryProperties.memoryTypeCount; ++i)
    {
      if ((typeBits & (1u << i)) && (this->memoryTypeFlags(i) & properties) == properties)
      {
        return i;
      }
    }
  }
  throw VulkanError("vkGetPhysicalDeviceMemoryProperties: no host-visible, coherent memory type for a buffer",
    VK_ERROR_FEATURE_NOT_PRESENT);
}

MemoryReservation& MemoryReservation::operator=(MemoryReservation&& other) noexcept
{
  if (this != &other)
  {
    this->release();
    this->Context = std::exchange(other.Context, nullptr);
    this->Bytes = std::exchange(other.Bytes, 0);
  }
  return *this;
}

void MemoryReservation::release()
{
  if (this->Context)
  {
    this->Context->releaseMemory(this->Bytes);
    this->Context = nullptr;
  }
}

MemoryReservation VulkanContext::reserveMemory(std::uint64_t bytes)
{
  if (this->MemoryLimit > 0 && this->MemoryInUse + bytes > this->MemoryLimit)
  {
    std::ostringstream message;
    message << "vkAllocateMemory refused: " << bytes << " more bytes would exceed the device memory limit of "
            << this->MemoryLimit << " bytes (" << this->MemoryInUse << " in use)";
    throw VulkanError(message.str(), VK_ERROR_OUT_OF_DEVICE_MEMORY);
  }
  this->MemoryInUse += bytes;
  this->MemoryPeak = std::max(this->MemoryPeak, this->MemoryInUse);
  return MemoryReservation(this, bytes);
}

std::string VulkanContext::memoryBudgetText() const
{
  return this->MemoryLimit > 0 ? "the device memory limit of " + formatBytes(this->MemoryLimit)
                               : "the " + formatBytes(this->memoryBudget()) + " of device memory the device offers";
}

std::uint64_t VulkanContext::memoryBudget() const
{
  if (this->MemoryLimit > 0)
  {
    return this->MemoryLimit;
  }
  // The heap of the memory type a device-local buffer takes (on a discrete
  // GPU its own memory, not the host's, which the largest host-visible heap was).
  const std::uint32_t heap = this->MemoryProperties.memoryTypes[this->memoryType(~0u, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)].heapIndex;
  if (!this->MemoryBudgets)
  {
    return this->MemoryProperties.memoryHeaps[heap].size;
  }
  auto budget = vulkanStruct<VkPhysicalDeviceMemoryBudgetPropertiesEXT>(
    VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT);
  auto properties = vulkanStruct<VkPhysicalDeviceMemoryProperties2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2);
  properties.pNext = &budget;
  vkGetPhysicalDeviceMemoryProperties2(this->PhysicalDevice, &properties);
  return budget.heapBudget[heap]; // what this process may hold in all, its own buffers included
}

void VulkanContext::releaseMemory(std::uint64_t bytes)
{
  this->MemoryInUse -= std::min(bytes, this->MemoryInUse);
}

void VulkanContext::submitAndWait(const std::function<void(VkCommandBuffer)>& record)
{
  if (this->Lost)
  {
    checkVulkan(VK_ERROR_DEVICE_LOST, "vkQueueSubmit");
  }
  VkDevice device = this->Device.get();
  auto allocateInfo = vulkanStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
  allocateInfo.commandPool = this->CommandPool.get();
  allocateInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocateInfo.commandBufferCount = 1;
  VkCommandBuffer raw = VK_NULL_HANDLE;
  checkVulkan(vkAllocateCommandBuffers(device, &allocateInfo, &raw), "vkAllocateCommandBuffers");
  VkCommandPool pool = this->CommandPool.get();
  VulkanHandle<VkCommandBuffer> commands(
    raw, [device, pool](VkCommandBuffer c) { vkFreeCommandBuffers(device, pool, 1, &c); });

  auto begin = vulkanStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  checkVulkan(vkBeginCommandBuffer(raw, &begin), "vkBeginCommandBuffer");
  record(raw);
  checkVulkan(vkEndCommandBuffer(raw), "vkEndCommandBuffer");

  auto submit = vulkanStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &raw;
  VkFence fence = this->Fence.get();
  checkVulkan(vkResetFences(device, 1, &fence), "vkResetFences");
  checkVulkan(vkQueueSubmit(this->Queue, 1, &submit, fence), "vkQueueSubmit");
  const VkResult waited = vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX);
  this->Lost = waited == VK_SUCCESS && deviceLossDue();
  checkVulkan(this->Lost ? VK_ERROR_DEVICE_LOST : waited, "vkWaitForFences");
}

std::vector<std::string> VulkanContext::validationMessages() const
{
  std::lock_guard<std::mutex> lock(this->MessageMutex);
  return this->Messages;
}

VkBool32 VKAPI_PTR VulkanContext::onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
  VkDebugUtilsMessageTypeFlagsEXT, const VkDebugUtilsMessengerCallbackDataEXT* data, void* user)
{
  auto* context = static_cast<VulkanContext*>(user);
  std::lock_guard<std::mutex> lock(context->MessageMutex);
  context->Messages.emplace_back(data && data->pMessage ? data->pMessage : "(no message)");
  return VK_FALSE;
}

} // namespace opal
