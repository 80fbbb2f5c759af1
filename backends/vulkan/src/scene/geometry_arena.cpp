#include "scene/geometry_arena.hpp"
#include "scene/uv_density.hpp"

#include "tsr/vk/error.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cstring>

namespace tsr::vk {

namespace {

constexpr std::uint32_t kFirstVertices = 1u << 16;
constexpr std::uint32_t kMaxVertices = 1u << 23;  // 8 Mi vertices, 112 MiB of streams (128 with 8-byte positions)
constexpr VkBufferUsageFlags kTransfer = VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
constexpr VkBufferUsageFlags kVertexUsage = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | kTransfer;
constexpr VkBufferUsageFlags kIndexUsage = VK_BUFFER_USAGE_INDEX_BUFFER_BIT | kTransfer;

}  // namespace

GeometryArena::GeometryArena(const Device& device) : device_(device), positionBytes_(device.positionBytes()) {}

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
  b.positions = make(VkDeviceSize(capacity) * positionBytes_, kVertexUsage);
  b.normals = make(VkDeviceSize(capacity) * sizeof(OctNormal), kVertexUsage);
  b.uvs = make(VkDeviceSize(capacity) * sizeof(QuantizedUv), kVertexUsage);
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
  const std::uint32_t components = positionBytes_ / 2;
  std::vector<std::uint16_t> stored(std::size_t(count) * components);
  read(blocks_[span.block].positions, VkDeviceSize(span.baseVertex) * positionBytes_, stored.data(),
       VkDeviceSize(count) * positionBytes_);
  std::vector<glm::vec3> out(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint16_t* v = &stored[std::size_t(i) * components];
    out[i] = dequantize(span.quantization, QuantizedPosition{v[0], v[1], v[2], 0});
  }
  return out;
}

void GeometryArena::writePositions(const GeometrySpan& span, std::uint32_t first,
                                   std::span<const glm::vec3> positions) {
  const std::uint32_t components = positionBytes_ / 2;
  std::vector<std::uint16_t> stored(positions.size() * components, 0);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const QuantizedPosition q = quantize(span.quantization, positions[i]);
    std::copy_n(q.begin(), 3, &stored[i * components]);
  }
  write(blocks_[span.block].positions, VkDeviceSize(span.baseVertex + first) * positionBytes_, stored.data(),
        VkDeviceSize(positions.size()) * positionBytes_);
}

// Missing normals (empty) are written as count zero normals.
void GeometryArena::writeNormals(const GeometrySpan& span, std::uint32_t first, std::span<const glm::vec3> normals,
                                 std::uint32_t count) {
  std::vector<OctNormal> stored(count, kNoNormal);
  for (std::size_t i = 0; i < normals.size(); ++i) stored[i] = octEncode(normals[i]);
  write(blocks_[span.block].normals, VkDeviceSize(span.baseVertex + first) * sizeof(OctNormal), stored.data(),
        VkDeviceSize(count) * sizeof(OctNormal));
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
  const GeometrySpan span{
      index,
      b.vertices,
      b.indexCount,
      PositionQuantization::of(data.positions),
      UvQuantization::of(data.uvs),
      data.primitive == Primitive::Triangles ? uvDensity(data.positions, data.uvs, data.indices) : 0.0f};
  writePositions(span, 0, data.positions);
  // Blocks may hold a removed mesh's data here: zero what the mesh lacks.
  writeNormals(span, 0, data.normals, n);
  std::vector<QuantizedUv> uvs(n, QuantizedUv{0, 0});  // no uvs: the box is the point (0, 0)
  for (std::size_t i = 0; i < data.uvs.size(); ++i) uvs[i] = quantize(span.uvQuantization, data.uvs[i]);
  write(b.uvs, VkDeviceSize(span.baseVertex) * sizeof(QuantizedUv), uvs.data(), VkDeviceSize(n) * sizeof(QuantizedUv));
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

bool GeometryArena::updateVertices(GeometrySpan& span, const VertexEdit& edit) {
  const PositionQuantization box = PositionQuantization::of(edit.positions);
  const bool requantize = box.lo != span.quantization.lo || box.hi != span.quantization.hi;
  if (requantize) {
    span.quantization = box;
    writePositions(span, 0, edit.positions);
  } else {
    writePositions(span, edit.first, edit.changedPositions());
  }
  if (!edit.normals.empty()) writeNormals(span, edit.first, edit.changedNormals(), edit.count);
  return requantize;
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
