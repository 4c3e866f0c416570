// Compute pipelines over one shared descriptor set of storage buffers.
#pragma once

#include "OpalVulkanHandle.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <initializer_list>
#include <utility>
#include <vector>

namespace opal
{

class VulkanBuffer;
class VulkanContext;

// A descriptor set of buffers, binding i of type types[i] (uniform or
// storage), and the pipeline layout every pass shares, with
// `pushConstantBytes` of push constants.
class StorageBufferBindings
{
public:
  StorageBufferBindings(
    VulkanContext& context, const std::vector<VkDescriptorType>& types, std::uint32_t pushConstantBytes);

  // Points every binding at its buffer (index = binding).
  void bind(const std::vector<const VulkanBuffer*>& buffers);

  VkPipelineLayout pipelineLayout() const { return this->PipelineLayout.get(); }
  VkDescriptorSet set() const { return this->Set; }
  std::uint32_t pushConstantBytes() const { return this->PushConstantBytes; }

private:
  VulkanContext& Context;
  std::vector<VkDescriptorType> Types;
  std::uint32_t PushConstantBytes;
  VulkanHandle<VkDescriptorSetLayout> SetLayout;
  VulkanHandle<VkPipelineLayout> PipelineLayout;
  VulkanHandle<VkDescriptorPool> Pool;
  VkDescriptorSet Set = VK_NULL_HANDLE;
};

// A pass's specialisation constants from (constant_id, value) pairs, the ids
// the contract names (shaders/opal_render_contract.h): the values in id
// order. Throws std::logic_error unless each of the pass's `count` ids is given once.
std::vector<std::int32_t> specialisation(int count, std::initializer_list<std::pair<int, std::int32_t>> byId);

// One compute shader as a pipeline; `specialisation` sets constant_id 0..n-1.
class ComputePipeline
{
public:
  ComputePipeline(VulkanContext& context, const StorageBufferBindings& bindings, const std::uint32_t* spirv,
    std::size_t spirvWords, const std::vector<std::int32_t>& specialisation = {});

  // Records: bind pipeline and set, push constants (one of the contract's
  // push-constant structs, exactly its size), dispatch, then a barrier so the
  // next dispatch or the host sees the writes. A one-dimensional dispatch of
  // more groups than the device takes along x goes as a grid of rows (the
  // shaders' passItem reads it as one sequence).
  template <typename PushConstants>
  void dispatch(VkCommandBuffer commands, const PushConstants& pushConstants, std::uint32_t groupsX,
    std::uint32_t groupsY = 1, std::uint32_t groupsZ = 1) const
  {
    this->dispatchBytes(commands, &pushConstants, sizeof(PushConstants), groupsX, groupsY, groupsZ);
  }

  // The same with the workgroup counts read by the device from `arguments`
  // at `offset` (a VkDispatchIndirectCommand a previous dispatch wrote).
  template <typename PushConstants>
  void dispatchIndirect(VkCommandBuffer commands, const PushConstants& pushConstants, const VulkanBuffer& arguments,
    std::uint64_t offset) const
  {
    this->bindAndPush(commands, &pushConstants, sizeof(PushConstants));
    this->dispatchIndirectRecorded(commands, arguments, offset);
  }

private:
  void dispatchBytes(VkCommandBuffer commands, const void* pushConstants, std::uint32_t bytes,
    std::uint32_t groupsX, std::uint32_t groupsY, std::uint32_t groupsZ) const;
  void bindAndPush(VkCommandBuffer commands, const void* pushConstants, std::uint32_t bytes) const;
  void dispatchIndirectRecorded(VkCommandBuffer commands, const VulkanBuffer& arguments, std::uint64_t offset) const;

  const StorageBufferBindings& Bindings;
  std::uint32_t MaxGroupsX, MaxGroupsY; // the device's maxComputeWorkGroupCount as the context plans with it
  VulkanHandle<VkPipeline> Pipeline;
};

} // namespace opal
