#pragma once

#include "resources/buffer.hpp"
#include "scene/vertex_encoding.hpp"

#include "tsr/vk/device.hpp"
#include "tsr/vk/mesh.hpp"
#include "tsr/vk/vocabulary.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <vector>

namespace tsr::vk {

// Where one mesh lives in the arena: its block, first vertex and first
// index, and the boxes its positions and uvs are fractions of.
struct GeometrySpan {
  std::uint32_t block = 0;
  std::uint32_t baseVertex = 0;
  std::uint32_t firstIndex = 0;
  PositionQuantization quantization;
  UvQuantization uvQuantization;
  float uvDensity = 0.0f;  // uv_density.hpp
};

// The geometry of many meshes in few large buffers (the seed's static
// geometry chunk): each block holds four streams (positions, normals, uvs,
// mesh-local indices; positions and normals compact, vertex_encoding.hpp)
// filled front to back, so consecutive draws of
// different meshes bind nothing new and can share one indirect call. A mesh
// of at most 65536 vertices goes to a block of 16-bit indices, others to
// one of 32-bit indices (half the index memory of a CAD model's parts, and
// the same triangles). Blocks
// double in size up to a cap; a mesh larger than the cap gets a block of
// its own. Space of removed meshes is reused only when its whole block
// empties. Memory that is device-local and host-visible (lavapipe, BAR) is
// written directly, other memory through staging copies.
class GeometryArena {
 public:
  explicit GeometryArena(const Device& device);

  // Copies the mesh in; missing normals and uvs are zero. Returns where it is.
  GeometrySpan add(const MeshData& data);
  // Stores the edit's range of positions (and normals when it carries
  // them). When the bounds of all the edit's positions differ from the
  // mesh's box, the box becomes those bounds and every position is stored
  // again from the edit's exact ones — what add() would store for them, so
  // no edit history shows — and true is returned (instances must follow).
  bool updateVertices(GeometrySpan& span, const VertexEdit& edit);
  void release(const GeometrySpan& span);
  // A mesh's positions (as drawn: decoded) and indices read back, for the
  // rare uses that need them on the CPU (emitter patches, bounds after a
  // vertex edit): the scene keeps no copy.
  std::vector<glm::vec3> positions(const GeometrySpan& span, std::uint32_t count) const;
  std::vector<std::uint32_t> indices(const GeometrySpan& span, std::uint32_t count) const;

  // Binds the block's position stream (streams = 1) or all three, and its indices.
  void bind(VkCommandBuffer cmd, std::uint32_t block, std::uint32_t streams) const;
  std::uint64_t bytesAllocated() const { return allocated_; }
  // Bytes a vertex takes in a block's streams (position, normal, uv).
  std::uint64_t vertexBytes() const { return positionBytes_ + sizeof(OctNormal) + sizeof(QuantizedUv); }
  std::uint64_t positionBytes() const { return positionBytes_; }

 private:
  struct Block {
    Buffer positions, normals, uvs, indices;
    std::uint32_t vertexCapacity = 0, indexCapacity = 0;
    std::uint32_t vertices = 0, indexCount = 0;
    std::uint32_t live = 0;  // meshes in it
    bool wide = true;        // 32-bit indices, else 16-bit
    VkDeviceSize indexBytes() const { return wide ? 4 : 2; }
  };
  std::uint32_t blockFor(std::uint32_t vertices, std::uint32_t indices, bool wide);
  void write(const Buffer& dst, VkDeviceSize offset, const void* bytes, VkDeviceSize size);
  void writePositions(const GeometrySpan& span, std::uint32_t first, std::span<const glm::vec3> positions);
  void writeNormals(const GeometrySpan& span, std::uint32_t first, std::span<const glm::vec3> normals,
                    std::uint32_t count);
  void read(const Buffer& src, VkDeviceSize offset, void* bytes, VkDeviceSize size) const;

  const Device& device_;
  std::vector<Block> blocks_;
  std::uint32_t current_[2] = {kNoBlock, kNoBlock};  // the blocks being filled: 16-bit, 32-bit indices
  static constexpr std::uint32_t kNoBlock = UINT32_MAX;
  std::uint64_t allocated_ = 0;
  bool hostVisible_ = true;
  std::uint32_t positionBytes_;  // Device::positionBytes: 6 or 8
};

}  // namespace tsr::vk
