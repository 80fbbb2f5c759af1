#pragma once
// One reusable command buffer with its pool and fence, recorded, submitted
// and waited for once per frame; and one descriptor set from its own pool.
// The colour pass and the id pass each own one of both.
#include <span>

#include "tsr/vk/device.hpp"

namespace tsr::vk {

class CommandSlot {
 public:
  CommandSlot(const Device& device, const char* what);
  ~CommandSlot();
  CommandSlot(const CommandSlot&) = delete;
  CommandSlot& operator=(const CommandSlot&) = delete;

  VkCommandBuffer buffer() const { return cmd_; }
  // Submits the recorded buffer and blocks until the device has run it.
  void submitAndWait(const char* what);

 private:
  const Device& device_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
};

class DescriptorSlot {
 public:
  DescriptorSlot(const Device& device, std::span<const VkDescriptorPoolSize> sizes, VkDescriptorSetLayout layout,
                 const char* what);
  ~DescriptorSlot();
  DescriptorSlot(const DescriptorSlot&) = delete;
  DescriptorSlot& operator=(const DescriptorSlot&) = delete;

  VkDescriptorSet set() const { return set_; }

 private:
  const Device& device_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace tsr::vk
