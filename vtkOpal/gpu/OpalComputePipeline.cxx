#include "OpalComputePipeline.h"

#include "OpalVulkanBuffer.h"
#include "OpalVulkanContext.h"
#include "OpalVulkanError.h"

#include <stdexcept>
#include <string>

namespace opal
{

StorageBufferBindings::StorageBufferBindings(
  VulkanContext& context, const std::vector<VkDescriptorType>& types, std::uint32_t pushConstantBytes)
  : Context(context)
  , Types(types)
  , PushConstantBytes(pushConstantBytes)
{
  VkDevice device = context.device();
  const auto bindingCount = static_cast<std::uint32_t>(types.size());
  std::vector<VkDescriptorSetLayoutBinding> layoutBindings(bindingCount);
  std::uint32_t uniformCount = 0;
  for (std::uint32_t i = 0; i < bindingCount; ++i)
  {
    layoutBindings[i] = { i, types[i], 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr };
    uniformCount += types[i] == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER ? 1 : 0;
  }
  auto layoutInfo = vulkanStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  layoutInfo.bindingCount = bindingCount;
  layoutInfo.pBindings = layoutBindings.data();
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  checkVulkan(vkCreateDescriptorSetLayout(device, &layoutInfo, nullptr, &setLayout), "vkCreateDescriptorSetLayout");
  this->SetLayout = VulkanHandle<VkDescriptorSetLayout>(
    setLayout, [device](VkDescriptorSetLayout l) { vkDestroyDescriptorSetLayout(device, l, nullptr); });

  VkPushConstantRange range{ VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes };
  auto pipelineLayoutInfo = vulkanStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
  pipelineLayoutInfo.setLayoutCount = 1;
  pipelineLayoutInfo.pSetLayouts = &setLayout;
  pipelineLayoutInfo.pushConstantRangeCount = pushConstantBytes > 0 ? 1 : 0;
  pipelineLayoutInfo.pPushConstantRanges = &range;
  VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
  checkVulkan(vkCreatePipelineLayout(device, &pipelineLayoutInfo, nullptr, &pipelineLayout), "vkCreatePipelineLayout");
  this->PipelineLayout = VulkanHandle<VkPipelineLayout>(
    pipelineLayout, [device](VkPipelineLayout l) { vkDestroyPipelineLayout(device, l, nullptr); });

  std::vector<VkDescriptorPoolSize> poolSizes;
  if (uniformCount > 0)
  {
    poolSizes.push_back({ VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uniformCount });
  }
  if (bindingCount > uniformCount)
  {
    poolSizes.push_back({ VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, bindingCount - uniformCount });
  }
  auto poolInfo = vulkanStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = static_cast<std::uint32_t>(poolSizes.size());
  poolInfo.pPoolSizes = poolSizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  checkVulkan(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
  this->Pool =
    VulkanHandle<VkDescriptorPool>(pool, [device](VkDescriptorPool p) { vkDestroyDescriptorPool(device, p, nullptr); });

  auto allocateInfo = vulkanStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
  allocateInfo.descriptorPool = pool;
  allocateInfo.descriptorSetCount = 1;
  allocateInfo.pSetLayouts = &setLayout;
  checkVulkan(vkAllocateDescriptorSets(device, &allocateInfo, &this->Set), "vkAllocateDescriptorSets");
}

void StorageBufferBindings::bind(const std::vector<const VulkanBuffer*>& buffers)
{
  if (buffers.size() != this->Types.size())
  {
    throw VulkanError("vkUpdateDescriptorSets: " + std::to_string(buffers.size()) + " buffers for " +
      std::to_string(this->Types.size()) + " bindings");
  }
  std::vector<VkDescriptorBufferInfo> infos(buffers.size());
  std::vector<VkWriteDescriptorSet> writes(buffers.size());
  for (std::size_t i = 0; i < buffers.size(); ++i)
  {
    infos[i] = { buffers[i]->buffer(), 0, VK_WHOLE_SIZE };
    writes[i] = vulkanStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    writes[i].dstSet = this->Set;
    writes[i].dstBinding = static_cast<std::uint32_t>(i);
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = this->Types[i];
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(
    this->Context.device(), static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

ComputePipeline::ComputePipeline(VulkanContext& context, const StorageBufferBindings& bindings,
  const std::uint32_t* spirv, std::size_t spirvWords, const std::vector<std::int32_t>& specialisation)
  : Bindings(bindings)
  , MaxGroupsX(context.limits().maxComputeWorkGroupCount[0])
  , MaxGroupsY(context.limits().maxComputeWorkGroupCount[1])
{
  VkDevice device = context.device();
  auto moduleInfo = vulkanStruct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
  moduleInfo.codeSize = spirvWords * sizeof(std::uint32_t);
  moduleInfo.pCode = spirv;
  VkShaderModule rawModule = VK_NULL_HANDLE;
  checkVulkan(vkCreateShaderModule(device, &moduleInfo, nullptr, &rawModule), "vkCreateShaderModule");
  VulkanHandle<VkShaderModule> shaderModule(
    rawModule, [device](VkShaderModule m) { vkDestroyShaderModule(device, m, nullptr); });

  std::vector<VkSpecializationMapEntry> entries(specialisation.size());
  for (std::size_t i = 0; i < specialisation.size(); ++i)
  {
    entries[i] = { static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i * sizeof(std::int32_t)),
      sizeof(std::int32_t) };
  }
  VkSpecializationInfo specialisationInfo{ static_cast<std::uint32_t>(entries.size()), entries.data(),
    specialisation.size() * sizeof(std::int32_t), specialisation.data() };

  auto info = vulkanStruct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
  info.stage = vulkanStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = rawModule;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = specialisation.empty() ? nullptr : &specialisationInfo;
  info.layout = bindings.pipelineLayout();
  VkPipeline pipeline = VK_NULL_HANDLE;
  checkVulkan(vkCreateComputePipelines(device, context.pipelineCache(), 1, &info, nullptr, &pipeline),
    "vkCreateComputePipelines");
  this->Pipeline = VulkanHandle<VkPipeline>(pipeline, [device](VkPipeline p) { vkDestroyPipeline(device, p, nullptr); });
}

void ComputePipeline::bindAndPush(VkCommandBuffer commands, const void* pushConstants, std::uint32_t bytes) const
{
  if (bytes > this->Bindings.pushConstantBytes())
  {
    throw VulkanError("push constants of " + std::to_string(bytes) + " bytes exceed the layout's " +
        std::to_string(this->Bindings.pushConstantBytes()),
      VK_ERROR_UNKNOWN);
  }
  VkDescriptorSet set = this->Bindings.set();
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, this->Pipeline.get());
  vkCmdBindDescriptorSets(
    commands, VK_PIPELINE_BIND_POINT_COMPUTE, this->Bindings.pipelineLayout(), 0, 1, &set, 0, nullptr);
  vkCmdPushConstants(commands, this->Bindings.pipelineLayout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, bytes, pushConstants);
}

namespace
{
// After a dispatch: its writes visible to the next dispatch (as storage or as
// indirect arguments) and to the host.
void barrierAfterDispatch(VkCommandBuffer commands)
{
  auto barrier = vulkanStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
    VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
    &barrier, 0, nullptr, 0, nullptr);
}
} // namespace

void ComputePipeline::dispatchBytes(VkCommandBuffer commands, const void* pushConstants, std::uint32_t bytes,
  std::uint32_t groupsX, std::uint32_t groupsY, std::uint32_t groupsZ) const
{
  this->bindAndPush(commands, pushConstants, bytes);
  if (groupsX > this->MaxGroupsX && groupsY == 1 && groupsZ == 1)
  {
    // A one-dimensional pass beyond the device's count: laid out as rows of
    // MaxGroupsX groups, which passItem (opal_render_bindings.glsl) reads back
    // as one sequence; the groups past the end find no item.
    groupsY = (groupsX + this->MaxGroupsX - 1) / this->MaxGroupsX;
    groupsX = this->MaxGroupsX;
  }
  if (groupsX > this->MaxGroupsX || groupsY > this->MaxGroupsY)
  {
    throw VulkanError("a dispatch of " + std::to_string(groupsX) + " x " + std::to_string(groupsY) +
        " workgroups exceeds the device's maxComputeWorkGroupCount of " + std::to_string(this->MaxGroupsX) + " x " +
        std::to_string(this->MaxGroupsY),
      VK_ERROR_FEATURE_NOT_PRESENT);
  }
  vkCmdDispatch(commands, groupsX, groupsY, groupsZ);
  barrierAfterDispatch(commands);
}

void ComputePipeline::dispatchIndirectRecorded(
  VkCommandBuffer commands, const VulkanBuffer& arguments, std::uint64_t offset) const
{
  vkCmdDispatchIndirect(commands, arguments.buffer(), offset);
  barrierAfterDispatch(commands);
}

std::vector<std::int32_t> specialisation(int count, std::initializer_list<std::pair<int, std::int32_t>> byId)
{
  std::vector<std::int32_t> values(static_cast<std::size_t>(count));
  std::vector<bool> given(values.size(), false);
  for (const auto& [id, value] : byId)
  {
    if (id < 0 || id >= count || given[static_cast<std::size_t>(id)])
    {
      throw std::logic_error("specialisation constant " + std::to_string(id) + " is out of range or given twice");
    }
    given[static_cast<std::size_t>(id)] = true;
    values[static_cast<std::size_t>(id)] = value;
  }
  if (byId.size() != values.size())
  {
    throw std::logic_error("a pass's specialisation constants are not all given");
  }
  return values;
}

} // namespace opal
