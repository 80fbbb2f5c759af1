#pragma once

#include "tsr/vk/device.hpp"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>

namespace tsr::vk {

// A VkBuffer with its own memory allocation. Host-visible buffers are
// persistently mapped (and coherent). Move-only.
class Buffer {
 public:
  Buffer() = default;
  Buffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags memory);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  void* mapped() const { return mapped_; }
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }

  static constexpr VkMemoryPropertyFlags kHost =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  static constexpr VkMemoryPropertyFlags kDevice = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;

 private:
  void release();

  VkDevice device_ = VK_NULL_HANDLE;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
};

// Copies `bytes` into dst at dstOffset through a staging buffer sized to the
// data, waiting for completion.
void uploadToBuffer(const Device& device, const Buffer& dst, VkDeviceSize dstOffset, const void* bytes,
                    VkDeviceSize size);
// The reverse: `size` bytes of src (which needs TRANSFER_SRC usage) from srcOffset.
void downloadFromBuffer(const Device& device, const Buffer& src, VkDeviceSize srcOffset, void* bytes,
                        VkDeviceSize size);

}  // namespace tsr::vk
