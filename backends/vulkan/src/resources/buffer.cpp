#include "resources/buffer.hpp"
#include "resources/device_memory.hpp"

#include "tsr/vk/error.hpp"
#include "vk_struct.hpp"

#include <cstring>
#include <utility>

namespace tsr::vk {

Buffer::Buffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags memory)
    : device_(device.handle()), size_(size) {
  if (size == 0) throw Error("buffer size must be non-zero");
  VkBufferCreateInfo bci = vkStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
  bci.size = size;
  bci.usage = usage;
  bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(vkCreateBuffer(device_, &bci, nullptr, &buffer_), "vkCreateBuffer");
  try {
    memory_ = bindNewMemory(device, buffer_, memory, "buffer");
    if (memory & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)
      check(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
  } catch (...) {
    release();
    throw;
  }
}

Buffer::~Buffer() { release(); }

Buffer::Buffer(Buffer&& o) noexcept
    : device_(o.device_),
      buffer_(std::exchange(o.buffer_, VK_NULL_HANDLE)),
      memory_(std::exchange(o.memory_, VK_NULL_HANDLE)),
      size_(std::exchange(o.size_, 0)),
      mapped_(std::exchange(o.mapped_, nullptr)) {}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    release();
    device_ = o.device_;
    buffer_ = std::exchange(o.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
    size_ = std::exchange(o.size_, 0);
    mapped_ = std::exchange(o.mapped_, nullptr);
  }
  return *this;
}

void Buffer::release() {
  if (buffer_) vkDestroyBuffer(device_, buffer_, nullptr);
  if (memory_) vkFreeMemory(device_, memory_, nullptr);  // unmaps implicitly
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
}

void uploadToBuffer(const Device& device, const Buffer& dst, VkDeviceSize dstOffset, const void* bytes,
                    VkDeviceSize size) {
  if (size == 0) return;
  Buffer staging(device, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, Buffer::kHost);
  std::memcpy(staging.mapped(), bytes, size);
  device.submitAndWait([&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, dstOffset, size};
    vkCmdCopyBuffer(cmd, staging.handle(), dst.handle(), 1, &region);
  });
}

void downloadFromBuffer(const Device& device, const Buffer& src, VkDeviceSize srcOffset, void* bytes,
                        VkDeviceSize size) {
  if (size == 0) return;
  Buffer staging(device, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, Buffer::kHost);
  device.submitAndWait([&](VkCommandBuffer cmd) {
    VkBufferCopy region{srcOffset, 0, size};
    vkCmdCopyBuffer(cmd, src.handle(), staging.handle(), 1, &region);
  });
  std::memcpy(bytes, staging.mapped(), size);
}

}  // namespace tsr::vk
