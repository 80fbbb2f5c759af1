#include "scene/geometry_arena.hpp"

#include "tsr/vk/error.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cstring>

namespace tsr::vk {

namespace {

constexpr std::uint32_t kFirstVertices = 1u << 16;
constexpr std::uint32_t kMaxVertices = 1u << 23;  // 8 Mi vertices, 256 MiB of streams
constexpr VkBufferUsageFlags kTransfer = VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
constexpr VkBufferUsageFlags kVertexUsage = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | kTransfer;
constexpr VkBufferUsageFlags kIndexUsage = VK_BUFFER_USAGE_INDEX_BUFFER_BIT | kTransfer;

}  // namespace

GeometryArena::GeometryArena(const Device& device) : device_(device) {}

std::uint32_t GeometryArena::blockFor(std::uint32_t vertices, std::uint32_t indices, bool wide) {
  std::uint32_t& current = current_[wide ? 1 : 0];
  if (current != kNoBlock) {
    const Block& b = blocks_[current];
    if (b.vertexCapacity - b.vertices >= vertices && b.indexCapacity - b.indexCount >= indices) return current;
  }
  // A new block, twice the last one of its kind's size (capped), or the mesh's own size.
  std::uint32_t capacity =
      current == kNoBlock ? kFirstVertices : std::min(2 * blocks_[current].vertexCapacity, kMaxVertices);
  capacity = std::max(capacity, vertices);
  const std::uint32_t indexCapacity = std::max<std::uint32_t>(3 * capacity, indices);
  Block b;
  auto make = [&](VkDeviceSize bytes, VkBufferUsageFlags usage) {
    allocated_ += bytes;
    if (hostVisible_) {
      try {
        return Buffer(device_, bytes, usage, Buffer::kDevice | Buffer::kHost);
      } catch (const Error&) {
        hostVisible_ = false;
      }
    }
    return Buffer(device_, bytes, usage, Buffer::kDevice);
  };
  b.positions = make(VkDeviceSize(capacity) * sizeof(glm::vec3), kVertexUsage);
  b.normals = make(VkDeviceSize(capacity) * sizeof(glm::vec3), kVertexUsage);
  b.uvs = make(VkDeviceSize(capacity) * sizeof(glm::vec2), kVertexUsage);
  b.wide = wide;
  b.indices = make(VkDeviceSize(indexCapacity) * b.indexBytes(), kIndexUsage);
  b.vertexCapacity = capacity;
  b.indexCapacity = indexCapacity;
  // Reuse an emptied slot, so removing and adding meshes does not grow the list.
  for (std::uint32_t i = 0; i < blocks_.size(); ++i)
    if (!blocks_[i].positions) {
      blocks_[i] = std::move(b);
      return current = i;
    }
  blocks_.push_back(std::move(b));
  return current = std::uint32_t(blocks_.size() - 1);
}

void GeometryArena::write(const Buffer& dst, VkDeviceSize offset, const void* bytes, VkDeviceSize size) {
  if (size == 0) return;
  if (dst.mapped())
    std::memcpy(static_cast<std::uint8_t*>(dst.mapped()) + offset, bytes, size);
  else
    uploadToBuffer(device_, dst, offset, bytes, size);
}

void GeometryArena::read(const Buffer& src, VkDeviceSize offset, void* bytes, VkDeviceSize size) const {
  if (size == 0) return;
  if (src.mapped())
    std::memcpy(bytes, static_cast<const std::uint8_t*>(src.mapped()) + offset, size);
  else
    downloadFromBuffer(device_, src, offset, bytes, size);
}

std::vector<glm::vec3> GeometryArena::positions(const GeometrySpan& span, std::uint32_t count) const {
  std::vector<glm::vec3> out(count);
  read(blocks_[span.block].positions, VkDeviceSize(span.baseVertex) * sizeof(glm::vec3), out.data(),
       VkDeviceSize(count) * sizeof(glm::vec3));
  return out;
}

std::vector<std::uint32_t> GeometryArena::indices(const GeometrySpan& span, std::uint32_t count) const {
  const Block& b = blocks_[span.block];
  std::vector<std::uint32_t> out(count);
  if (b.wide) {
    read(b.indices, VkDeviceSize(span.firstIndex) * 4, out.data(), VkDeviceSize(count) * 4);
  } else {
    std::vector<std::uint16_t> narrow(count);
    read(b.indices, VkDeviceSize(span.firstIndex) * 2, narrow.data(), VkDeviceSize(count) * 2);
    std::copy(narrow.begin(), narrow.end(), out.begin());
  }
  return out;
}

GeometrySpan GeometryArena::add(const MeshData& data) {
  const auto n = std::uint32_t(data.positions.size());
  const auto ni = std::uint32_t(data.indices.size());
  const bool wide = n > (1u << 16);
  const std::uint32_t index = blockFor(n, ni, wide);
  Block& b = blocks_[index];
  const GeometrySpan span{index, b.vertices, b.indexCount};
  write(b.positions, VkDeviceSize(span.baseVertex) * sizeof(glm::vec3), data.positions.data(),
        VkDeviceSize(n) * sizeof(glm::vec3));
  // Blocks may hold a removed mesh's data here: zero what the mesh lacks.
  const std::vector<glm::vec3> noNormals(data.normals.empty() ? n : 0, glm::vec3(0.0f));
  const std::vector<glm::vec2> noUvs(data.uvs.empty() ? n : 0, glm::vec2(0.0f));
  write(b.normals, VkDeviceSize(span.baseVertex) * sizeof(glm::vec3),
        data.normals.empty() ? noNormals.data() : data.normals.data(), VkDeviceSize(n) * sizeof(glm::vec3));
  write(b.uvs, VkDeviceSize(span.baseVertex) * sizeof(glm::vec2), data.uvs.empty() ? noUvs.data() : data.uvs.data(),
        VkDeviceSize(n) * sizeof(glm::vec2));
  if (wide) {
    write(b.indices, VkDeviceSize(span.firstIndex) * 4, data.indices.data(), VkDeviceSize(ni) * 4);
  } else {
    const std::vector<std::uint16_t> narrow(data.indices.begin(), data.indices.end());  // each below 65536
    write(b.indices, VkDeviceSize(span.firstIndex) * 2, narrow.data(), VkDeviceSize(ni) * 2);
  }
  b.vertices += n;
  b.indexCount += ni;
  ++b.live;
  return span;
}

void GeometryArena::updateVertices(const GeometrySpan& span, std::uint32_t first, std::span<const glm::vec3> positions,
                                   std::span<const glm::vec3> normals) {
  const Block& b = blocks_[span.block];
  const VkDeviceSize at = VkDeviceSize(span.baseVertex + first) * sizeof(glm::vec3);
  write(b.positions, at, positions.data(), positions.size_bytes());
  write(b.normals, at, normals.data(), normals.size_bytes());
}

void GeometryArena::release(const GeometrySpan& span) {
  Block& b = blocks_[span.block];
  if (--b.live > 0) return;
  if (span.block == current_[b.wide ? 1 : 0]) {
    b.vertices = b.indexCount = 0;  // empty: fill it again from the front
    return;
  }
  allocated_ -= b.positions.size() + b.normals.size() + b.uvs.size() + b.indices.size();
  b = Block{};
}

void GeometryArena::bind(VkCommandBuffer cmd, std::uint32_t block, std::uint32_t streams) const {
  const Block& b = blocks_[block];
  const VkBuffer buffers[3] = {b.positions.handle(), b.normals.handle(), b.uvs.handle()};
  const VkDeviceSize offsets[3] = {0, 0, 0};
  vkCmdBindVertexBuffers(cmd, 0, streams, buffers, offsets);
  vkCmdBindIndexBuffer(cmd, b.indices.handle(), 0, b.wide ? VK_INDEX_TYPE_UINT32 : VK_INDEX_TYPE_UINT16);
}

}  // namespace tsr::vk
