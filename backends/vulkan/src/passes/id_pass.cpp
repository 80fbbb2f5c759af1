#include "passes/id_pass.hpp"
#include "resources/rendering.hpp"

#include "projection.hpp"
#include "resources/readback.hpp"
#include "scene/scene_state.hpp"
#include "spirv.hpp"
#include "vk_struct.hpp"

#include "tsr/vk/error.hpp"

#include <cstring>

namespace tsr::vk {

namespace {
constexpr VkFormat kIdFormat = VK_FORMAT_R32_UINT;
constexpr VkFormat kIdDepthFormat = VK_FORMAT_D32_SFLOAT;
}  // namespace

IdPass::IdPass(const Device& device) : device_(device) {
  VkDevice dev = device.handle();
  VkDescriptorSetLayoutBinding b[4]{};
  for (std::uint32_t i = 0; i < 4; ++i) {
    b[i].binding = i;
    b[i].descriptorType = i == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    b[i].descriptorCount = 1;
    b[i].stageFlags = VK_SHADER_STAGE_VERTEX_BIT;
  }
  VkDescriptorSetLayoutCreateInfo lci =
      vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  lci.bindingCount = 4;
  lci.pBindings = b;
  check(vkCreateDescriptorSetLayout(dev, &lci, nullptr, &setLayout_), "vkCreateDescriptorSetLayout (ids)");
  VkPipelineLayoutCreateInfo pci = vkStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
  pci.setLayoutCount = 1;
  pci.pSetLayouts = &setLayout_;
  check(vkCreatePipelineLayout(dev, &pci, nullptr, &layout_), "vkCreatePipelineLayout (ids)");

  const VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                         {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3}};
  descriptors_.emplace(device, sizes, setLayout_, "ids");
  set_ = descriptors_->set();
  commands_.emplace(device, "ids");

  PipelineDesc d;
  d.layout = layout_;
  d.vertexSpirv = spirv::ids_vert;
  d.fragmentSpirv = spirv::ids_frag;
  d.vertexStreams = 1;
  d.colourFormat = kIdFormat;
  d.depthFormat = kIdDepthFormat;
  d.depthCompare = VK_COMPARE_OP_GREATER;  // reversed depth, as in the colour pass
  pipeline_ = Pipeline(device, d);
  d.topology = VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
  linePipeline_ = Pipeline(device, d);
  d.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
  pointPipeline_ = Pipeline(device, d);
  frame_ = Buffer(device, sizeof(glm::mat4), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, Buffer::kHost);
}

IdPass::~IdPass() {
  VkDevice dev = device_.handle();
  vkDeviceWaitIdle(dev);
  commands_.reset();
  descriptors_.reset();
  vkDestroyPipelineLayout(dev, layout_, nullptr);
  vkDestroyDescriptorSetLayout(dev, setLayout_, nullptr);
}

std::uint32_t IdPass::render(SceneState& s, const Camera& camera, const Region& region, IdBuffer& out) {
  const VkDevice dev = device_.handle();
  const std::uint32_t w = region.regionWidth(), h = region.regionHeight();
  s.prepare();

  // Opaque instances only: transparent ones neither occlude nor count.
  // Lines and points follow the triangles in the draw order.
  const std::size_t lineBase = s.opaqueOrder.size();
  const std::size_t drawn = std::max<std::size_t>(lineBase + s.lineOrder.size(), 1);
  if (!drawOrder_ || drawOrder_.size() < drawn * 4)
    drawOrder_ =
        Buffer(device_, std::max<VkDeviceSize>(drawn * 4, 1024), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Buffer::kHost);
  if (!s.opaqueOrder.empty()) std::memcpy(drawOrder_.mapped(), s.opaqueOrder.data(), lineBase * 4);
  if (!s.lineOrder.empty())
    std::memcpy(static_cast<std::uint32_t*>(drawOrder_.mapped()) + lineBase, s.lineOrder.data(),
                s.lineOrder.size() * 4);
  const glm::mat4 viewProj = projection(camera, region) * camera.worldToCamera();
  std::memcpy(frame_.mapped(), &viewProj, sizeof viewProj);
  if (!s.objectBuffer)  // a scene that never had an instance
    s.objectBuffer = Buffer(device_, 4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Buffer::kHost);

  if (!target_ || target_->width != w || target_->height != h) {
    target_.reset();
    Target t;
    t.width = w;
    t.height = h;
    ImageDesc c;
    c.width = w;
    c.height = h;
    c.format = kIdFormat;
    c.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    t.ids = Image(device_, c);
    ImageDesc d = c;
    d.format = kIdDepthFormat;
    d.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    t.depth = Image(device_, d);
    t.idReadback = Buffer(device_, VkDeviceSize(w) * h * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, Buffer::kHost);
    t.depthReadback = Buffer(device_, VkDeviceSize(w) * h * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, Buffer::kHost);
    target_.emplace(std::move(t));
  }
  const Target& t = *target_;

  VkDescriptorBufferInfo bufs[4] = {{frame_.handle(), 0, VK_WHOLE_SIZE},
                                    {s.instanceBuffer.handle(), 0, VK_WHOLE_SIZE},
                                    {drawOrder_.handle(), 0, VK_WHOLE_SIZE},
                                    {s.objectBuffer.handle(), 0, VK_WHOLE_SIZE}};
  VkWriteDescriptorSet writes[4]{};
  for (std::uint32_t i = 0; i < 4; ++i) {
    writes[i] = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    writes[i].dstSet = set_;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = i == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &bufs[i];
  }
  vkUpdateDescriptorSets(dev, 4, writes, 0, nullptr);

  VkCommandBuffer cmd = commands_->buffer();
  check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer (ids)");
  VkCommandBufferBeginInfo bi = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer (ids)");
  const VkPipelineStageFlags depthStages =
      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  imageBarrier(cmd, t.ids.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
               VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
  imageBarrier(cmd, t.depth.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, depthStages,
               VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT);

  VkClearValue idClear{};
  idClear.color.uint32[0] = kNoObject;
  const VkRenderingAttachmentInfo ca =
      renderingAttachment(t.ids.view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, /*load=*/false, idClear);
  VkClearValue depthClear{};
  depthClear.depthStencil = {0.0f, 0};  // reversed depth: 0 is the far plane
  const VkRenderingAttachmentInfo da =
      renderingAttachment(t.depth.view(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, /*load=*/false, depthClear);
  beginRendering(cmd, w, h, &ca, da);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.handle());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0, nullptr);
  std::uint32_t draws = 0;
  std::uint32_t bound = ~0u;
  for (const DrawGroup& g : s.opaqueGroups) {  // grouped by (material, mesh); here only the mesh matters
    const MeshRecord& m = s.meshes[g.mesh];
    if (m.span.block != bound) s.geometry->bind(cmd, bound = m.span.block, 1);
    vkCmdDrawIndexed(cmd, m.indexCount, g.count, firstIndexOf(m), vertexOffsetOf(m), g.first);
    ++draws;
  }
  for (const DrawGroup& g : s.lineGroups) {
    if (s.materials[g.material].material.isTransparent()) continue;
    const MeshRecord& m = s.meshes[g.mesh];
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                      (m.primitive == Primitive::Lines ? linePipeline_ : pointPipeline_).handle());
    if (m.span.block != bound) s.geometry->bind(cmd, bound = m.span.block, 1);
    vkCmdDrawIndexed(cmd, m.indexCount, g.count, firstIndexOf(m), vertexOffsetOf(m), std::uint32_t(lineBase) + g.first);
    ++draws;
  }
  vkCmdEndRendering(cmd);

  recordReadback(cmd, t.ids, t.depth, t.idReadback, t.depthReadback, w, h);
  check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer (ids)");
  commands_->submitAndWait("ids");

  const std::size_t pixels = std::size_t(w) * h;
  std::memcpy(out.ids.data(), t.idReadback.mapped(), pixels * 4);
  readLinearDepth(t.depthReadback, camera, out.depth);
  return draws;
}

}  // namespace tsr::vk
