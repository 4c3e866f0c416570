// RAII ownership of a Vulkan handle: destroyed exactly once, movable, not copyable.
#pragma once

#include <functional>
#include <utility>

namespace opal
{

template <typename Handle>
class VulkanHandle
{
public:
  using Destroy = std::function<void(Handle)>;

  VulkanHandle() = default;
  VulkanHandle(Handle handle, Destroy destroy)
    : Value(handle)
    , Destroyer(std::move(destroy))
  {
  }
  ~VulkanHandle() { this->reset(); }
  VulkanHandle(const VulkanHandle&) = delete;
  VulkanHandle& operator=(const VulkanHandle&) = delete;
  VulkanHandle(VulkanHandle&& other) noexcept
    : Value(std::exchange(other.Value, Handle{}))
    , Destroyer(std::move(other.Destroyer))
  {
  }
  VulkanHandle& operator=(VulkanHandle&& other) noexcept
  {
    if (this != &other)
    {
      this->reset();
      this->Value = std::exchange(other.Value, Handle{});
      this->Destroyer = std::move(other.Destroyer);
    }
    return *this;
  }

  Handle get() const { return this->Value; }
  explicit operator bool() const { return this->Value != Handle{}; }

  void reset()
  {
    if (this->Value != Handle{} && this->Destroyer)
    {
      this->Destroyer(this->Value);
    }
    this->Value = Handle{};
  }

private:
  Handle Value{};
  Destroy Destroyer;
};

// A zero-initialised Vulkan create-info structure of the given type.
template <typename Info, typename StructureType>
Info vulkanStruct(StructureType type)
{
  Info info{};
  info.sType = type;
  return info;
}

} // namespace opal
