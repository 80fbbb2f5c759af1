#include "resources/command_slot.hpp"

#include <string>

#include "tsr/vk/error.hpp"
#include "vk_struct.hpp"

namespace tsr::vk {

namespace {
std::string label(const char* call, const char* what) { return std::string(call) + " (" + what + ")"; }
}  // namespace

CommandSlot::CommandSlot(const Device& device, const char* what) : device_(device) {
  VkDevice dev = device.handle();
  VkCommandPoolCreateInfo cpci = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  cpci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  cpci.queueFamilyIndex = device.queueFamily();
  check(vkCreateCommandPool(dev, &cpci, nullptr, &pool_), label("vkCreateCommandPool", what).c_str());
  VkCommandBufferAllocateInfo cai =
      vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
  cai.commandPool = pool_;
  cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cai.commandBufferCount = 1;
  try {
    check(vkAllocateCommandBuffers(dev, &cai, &cmd_), label("vkAllocateCommandBuffers", what).c_str());
    VkFenceCreateInfo fci = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    check(vkCreateFence(dev, &fci, nullptr, &fence_), label("vkCreateFence", what).c_str());
  } catch (...) {
    vkDestroyCommandPool(dev, pool_, nullptr);
    throw;
  }
}

CommandSlot::~CommandSlot() {
  VkDevice dev = device_.handle();
  vkDestroyFence(dev, fence_, nullptr);
  vkDestroyCommandPool(dev, pool_, nullptr);
}

void CommandSlot::submitAndWait(const char* what) {
  VkDevice dev = device_.handle();
  VkSubmitInfo si = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd_;
  check(vkQueueSubmit(device_.queue(), 1, &si, fence_), label("vkQueueSubmit", what).c_str());
  check(vkWaitForFences(dev, 1, &fence_, VK_TRUE, UINT64_MAX), label("vkWaitForFences", what).c_str());
  check(vkResetFences(dev, 1, &fence_), label("vkResetFences", what).c_str());
}

DescriptorSlot::DescriptorSlot(const Device& device, std::span<const VkDescriptorPoolSize> sizes,
                               VkDescriptorSetLayout layout, const char* what)
    : device_(device) {
  VkDevice dev = device.handle();
  VkDescriptorPoolCreateInfo dpci = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
  dpci.maxSets = 1;
  dpci.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  dpci.pPoolSizes = sizes.data();
  check(vkCreateDescriptorPool(dev, &dpci, nullptr, &pool_), label("vkCreateDescriptorPool", what).c_str());
  VkDescriptorSetAllocateInfo ai =
      vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout;
  try {
    check(vkAllocateDescriptorSets(dev, &ai, &set_), label("vkAllocateDescriptorSets", what).c_str());
  } catch (...) {
    vkDestroyDescriptorPool(dev, pool_, nullptr);
    throw;
  }
}

DescriptorSlot::~DescriptorSlot() { vkDestroyDescriptorPool(device_.handle(), pool_, nullptr); }

}  // namespace tsr::vk
