#include "culling/occlusion_culler.hpp"

#include "spirv.hpp"

#include "tsr/vk/error.hpp"
#include "vk_struct.hpp"

#include <algorithm>
#include <cstring>

namespace tsr::vk {

namespace {

constexpr VkDescriptorType kBindings[] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                          VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                          VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
constexpr VkDescriptorPoolSize kPoolSizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 5},
                                               {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}};

// Matches Record in shaders/cull.comp.
struct GpuCullRecord {
  std::uint32_t slot, indexCount, firstIndex, vertexOffset;
  glm::vec4 lo, hi;
};

struct CullPush {
  glm::mat4 viewProj;
  std::uint32_t count, phase, width, height;
};

constexpr VkBufferUsageFlags kCommandUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;

// Host-visible, so records are written and drawn counts read without copies.
void ensure(const Device& device, Buffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage) {
  if (buffer && buffer.size() >= bytes) return;
  buffer = Buffer(device, std::max<VkDeviceSize>({bytes, buffer ? 2 * buffer.size() : 0, 256}), usage, Buffer::kHost);
}

}  // namespace

OcclusionCuller::OcclusionCuller(const Device& device)
    : device_(device),
      cull_(device, spirv::cull_comp, kBindings, sizeof(CullPush)),
      descriptors_(device, kPoolSizes, cull_.setLayout(), "occlusion culling") {}

void OcclusionCuller::prepare(const SceneState& s, std::span<const std::uint32_t> opaqueOrder) {
  count_ = std::uint32_t(opaqueOrder.size());
  ensure(device_, records_, std::max<std::size_t>(count_, 1) * sizeof(GpuCullRecord),
         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  ensure(device_, early_, std::max<std::size_t>(count_, 1) * sizeof(VkDrawIndexedIndirectCommand), kCommandUsage);
  ensure(device_, late_, std::max<std::size_t>(count_, 1) * sizeof(VkDrawIndexedIndirectCommand), kCommandUsage);
  auto* records = static_cast<GpuCullRecord*>(records_.mapped());
  for (std::uint32_t i = 0; i < count_; ++i) {
    const std::uint32_t slot = opaqueOrder[i];
    const MeshRecord& m = s.meshes[s.instances[slot].mesh];
    records[i] = {slot,
                  m.indexCount,
                  firstIndexOf(m),
                  std::uint32_t(vertexOffsetOf(m)),
                  glm::vec4(m.boundsMin, 1.0f),
                  glm::vec4(m.boundsMax, 1.0f)};
  }

  // Visibility by slot: a new scene starts from nothing seen; new slots start unseen.
  const std::size_t slots = std::max<std::size_t>(s.instances.size(), 1);
  if (&s != scene_ || !visibility_ || slots * 4 > visibility_.size()) {
    Buffer grown(device_, std::max(slots, 2 * slots_) * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Buffer::kHost);
    std::memset(grown.mapped(), 0, grown.size());
    if (&s == scene_ && visibility_) std::memcpy(grown.mapped(), visibility_.mapped(), visibility_.size());
    visibility_ = std::move(grown);
    slots_ = visibility_.size() / 4;
  }
  scene_ = &s;
}

void OcclusionCuller::recordEarly(VkCommandBuffer cmd, const SceneState& s, const glm::mat4& viewProj,
                                  const DepthPyramid& pyramid, std::uint32_t width, std::uint32_t height) {
  const VkDescriptorBufferInfo buffers[5] = {{records_.handle(), 0, VK_WHOLE_SIZE},
                                             {s.instanceBuffer.handle(), 0, VK_WHOLE_SIZE},
                                             {visibility_.handle(), 0, VK_WHOLE_SIZE},
                                             {early_.handle(), 0, VK_WHOLE_SIZE},
                                             {late_.handle(), 0, VK_WHOLE_SIZE}};
  const VkDescriptorImageInfo image{pyramid.fetchSampler(), pyramid.view(), VK_IMAGE_LAYOUT_GENERAL};
  VkWriteDescriptorSet writes[6];
  for (std::uint32_t b = 0; b < 6; ++b) {
    writes[b] = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    writes[b].dstSet = descriptors_.set();
    writes[b].dstBinding = b;
    writes[b].descriptorCount = 1;
    writes[b].descriptorType = kBindings[b];
    if (b < 5)
      writes[b].pBufferInfo = &buffers[b];
    else
      writes[b].pImageInfo = &image;
  }
  vkUpdateDescriptorSets(device_.handle(), 6, writes, 0, nullptr);
  dispatch(cmd, viewProj, 0, width, height);
}

void OcclusionCuller::recordLate(VkCommandBuffer cmd, const glm::mat4& viewProj, std::uint32_t width,
                                 std::uint32_t height) {
  dispatch(cmd, viewProj, 1, width, height);
}

void OcclusionCuller::recordVisibility(VkCommandBuffer cmd, const glm::mat4& viewProj, std::uint32_t width,
                                       std::uint32_t height) {
  dispatch(cmd, viewProj, 2, width, height);
}

void OcclusionCuller::dispatch(VkCommandBuffer cmd, const glm::mat4& viewProj, std::uint32_t phase, std::uint32_t width,
                               std::uint32_t height) {
  if (count_ > 0) {
    const CullPush push{viewProj, count_, phase, width, height};
    cull_.dispatch(cmd, descriptors_.set(), &push, (count_ + 63) / 64);
  }
  computeBarrier(cmd, VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                 VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT);
}

OcclusionCuller::Drawn OcclusionCuller::drawn() const {
  Drawn d;
  const auto* early = static_cast<const VkDrawIndexedIndirectCommand*>(early_.mapped());
  const auto* late = static_cast<const VkDrawIndexedIndirectCommand*>(late_.mapped());
  for (std::uint32_t i = 0; i < count_; ++i) {
    d.earlyObjects += early[i].instanceCount;
    d.lateObjects += late[i].instanceCount;
    d.earlyTriangles += std::uint64_t(early[i].instanceCount) * (early[i].indexCount / 3);
    d.lateTriangles += std::uint64_t(late[i].instanceCount) * (late[i].indexCount / 3);
  }
  return d;
}

}  // namespace tsr::vk
