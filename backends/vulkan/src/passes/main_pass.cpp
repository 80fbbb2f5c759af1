#include "renderer_impl.hpp"
#include "resources/rendering.hpp"

namespace tsr::vk {

// Main pass attachments made writable; previous contents are discarded (UNDEFINED).
void Renderer::Impl::prepareAttachments(VkCommandBuffer cmd) {
  const RenderTarget& t = *target;
  const VkPipelineStageFlags attachStages =
      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  std::vector<const Image*> colourImages = {&t.colour};
  std::vector<const Image*> depthImages = {&t.depth};
  if (t.multisampled()) {
    colourImages.push_back(&t.colourResolve);
    depthImages.push_back(&t.depthResolve);
  }
  for (const Image* img : colourImages)
    imageBarrier(cmd, img->handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                 VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
  for (const Image* img : depthImages)
    imageBarrier(cmd, img->handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                 attachStages | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                     VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
  // Every frame's descriptors name it, volumes or not.
  if (volumeBackFresh) {
    imageBarrier(cmd, volumeBack->handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                 VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    volumeBackFresh = false;
  }
}

// Begins the main pass: cleared, or (the guided late phase) loading what the
// early phase drew.
void Renderer::Impl::beginMain(VkCommandBuffer cmd, bool load) {
  const RenderTarget& t = *target;
  const std::uint32_t w = t.width, h = t.height;
  VkClearValue colourClear{};
  colourClear.color = {{clearColour.r, clearColour.g, clearColour.b, clearColour.a}};
  VkRenderingAttachmentInfo ca =
      renderingAttachment(t.colour.view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, load, colourClear);
  VkClearValue depthClear{};
  depthClear.depthStencil = {0.0f, 0};  // reversed depth: 0 is the far plane
  VkRenderingAttachmentInfo da =
      renderingAttachment(t.depth.view(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, load, depthClear);
  if (t.multisampled()) {
    ca.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
    ca.resolveImageView = t.colourResolve.view();
    ca.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    // Averaging depths across an edge would invent surfaces; keep sample 0.
    da.resolveMode = VK_RESOLVE_MODE_SAMPLE_ZERO_BIT;
    da.resolveImageView = t.depthResolve.view();
    da.resolveImageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  }
  beginRendering(cmd, w, h, &ca, da);
  boundPipeline = VK_NULL_HANDLE;
  boundBlock = boundMaterial = ~0u;
}

// Pipeline, geometry block, material set and push constants for one draw,
// each only when it differs from what the pass has bound.
void Renderer::Impl::bindDraw(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                              std::uint32_t meshIndex, std::uint32_t material) {
  VkPipeline p =
      mainPipeline(settings.msaaSamples, s.materials[material].material, shadows, s.meshes[meshIndex].primitive);
  if (p != boundPipeline) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p);
    boundPipeline = p;
  }
  const std::uint32_t block = s.meshes[meshIndex].span.block;
  if (block != boundBlock) s.geometry->bind(cmd, boundBlock = block, 3);
  if (material != boundMaterial) {
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &s.materials[material].set, 0, nullptr);
    PushConstants pc;
    pc.material = material;
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(pc), &pc);
    boundMaterial = material;
  }
}

// Opaque groups in draw order: instanced, or (guided) one indirect command
// per draw position, 20 bytes each, whose instance count the culler set. A
// run of groups with the same material and geometry block needs no new
// bindings, so it is one indirect call.
void Renderer::Impl::drawOpaque(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                                VkBuffer indirect, RenderStats& stats) {
  const auto& groups = s.opaqueGroups;
  for (std::size_t i = 0; i < groups.size();) {
    const DrawGroup& g = groups[i];
    const Material& material = s.materials[g.material].material;
    if (drawingProbe && reflective(material)) {
      ++i;
      continue;
    }
    if (drawingSceneProbe && glossy(material)) {  // instance by instance, leaving out what would reflect itself
      const MeshRecord& m = s.meshes[g.mesh];
      for (std::uint32_t k = g.first; k < g.first + g.count; ++k) {
        if (hiddenFromProbe(s, drawOrder[k])) continue;  // draw position k shows drawOrder[k]
        bindDraw(cmd, s, settings, shadows, g.mesh, g.material);
        vkCmdDrawIndexed(cmd, m.indexCount, 1, firstIndexOf(m), vertexOffsetOf(m), k);
        ++stats.drawCalls;
      }
      ++i;
      continue;
    }
    bindDraw(cmd, s, settings, shadows, g.mesh, g.material);
    ++stats.drawCalls;
    if (indirect) {
      std::size_t end = i + 1;
      while (end < groups.size() && groups[end].material == g.material &&
             s.meshes[groups[end].mesh].span.block == s.meshes[g.mesh].span.block)
        ++end;
      const std::uint32_t count = groups[end - 1].first + groups[end - 1].count - g.first;
      vkCmdDrawIndexedIndirect(cmd, indirect, VkDeviceSize(g.first) * sizeof(VkDrawIndexedIndirectCommand), count,
                               sizeof(VkDrawIndexedIndirectCommand));
      i = end;
      continue;
    }
    const MeshRecord& m = s.meshes[g.mesh];
    vkCmdDrawIndexed(cmd, m.indexCount, g.count, firstIndexOf(m), vertexOffsetOf(m), g.first);
    stats.triangles += std::uint64_t(m.indexCount / 3) * g.count;
    stats.objects += g.count;
    ++i;
  }
}

void Renderer::Impl::drawTransparent(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings,
                                     bool shadows, std::uint32_t transparentBase, RenderStats& stats) {
  for (std::uint32_t i = 0; i < transparentSorted.size(); ++i) {
    const InstanceRecord& inst = s.instances[transparentSorted[i]];
    if (s.materials[inst.material].material.isVolume() && !drawsVolumes()) continue;
    bindDraw(cmd, s, settings, shadows, inst.mesh, inst.material);
    const MeshRecord& m = s.meshes[inst.mesh];
    vkCmdDrawIndexed(cmd, m.indexCount, 1, firstIndexOf(m), vertexOffsetOf(m), transparentBase + i);
    ++stats.drawCalls;
    stats.triangles += m.indexCount / 3;
    ++stats.objects;
  }
}

void Renderer::Impl::drawLines(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings,
                               std::uint32_t transparentBase, RenderStats& stats) {
  const std::uint32_t base = transparentBase + std::uint32_t(transparentSorted.size());
  for (const DrawGroup& g : s.lineGroups) {
    if (s.materials[g.material].material.isVolume()) continue;  // a medium needs a closed surface
    bindDraw(cmd, s, settings, false, g.mesh, g.material);
    const MeshRecord& m = s.meshes[g.mesh];
    vkCmdDrawIndexed(cmd, m.indexCount, g.count, firstIndexOf(m), vertexOffsetOf(m), base + g.first);
    ++stats.drawCalls;
    stats.objects += g.count;
  }
}

void Renderer::Impl::recordVolumeBacks(VkCommandBuffer cmd, const SceneState& s, std::uint32_t transparentBase) {
  std::vector<std::uint32_t> volumes;  // positions in transparentSorted
  for (std::uint32_t i = 0; i < transparentSorted.size(); ++i)
    if (s.materials[s.instances[transparentSorted[i]].material].material.isVolume()) volumes.push_back(i);
  if (volumes.empty() || !drawsVolumes()) return;
  vkCmdEndRendering(cmd);

  const RenderTarget& t = *target;
  const Image& opaque = t.resolvedDepth();
  const VkPipelineStageFlags depthStages = VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                           VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
                                           VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  const VkAccessFlags depthAccess = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  // Depth resolves count as colour-output writes: wait for those too.
  imageBarrier(cmd, opaque.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
               VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, depthStages, depthAccess, VK_PIPELINE_STAGE_TRANSFER_BIT,
               VK_ACCESS_TRANSFER_READ_BIT);
  imageBarrier(cmd, volumeBack->handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0,
               VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
  VkImageCopy copy{};
  copy.srcSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
  copy.dstSubresource = copy.srcSubresource;
  copy.extent = {t.width, t.height, 1};
  vkCmdCopyImage(cmd, opaque.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, volumeBack->handle(),
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
  imageBarrier(cmd, opaque.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
               VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, depthStages, depthAccess);
  imageBarrier(cmd, volumeBack->handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
               depthStages, depthAccess);

  const VkRenderingAttachmentInfo da =
      renderingAttachment(volumeBack->view(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, /*load=*/true, VkClearValue{});
  beginRendering(cmd, t.width, t.height, nullptr, da);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, volumeBackPipeline.handle());
  PushConstants pc;
  pc.lightViewProj = viewProj;
  vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(pc), &pc);
  std::uint32_t bound = ~0u;
  for (std::uint32_t i : volumes) {
    const MeshRecord& m = s.meshes[s.instances[transparentSorted[i]].mesh];
    if (m.span.block != bound) s.geometry->bind(cmd, bound = m.span.block, 1);
    vkCmdDrawIndexed(cmd, m.indexCount, 1, firstIndexOf(m), vertexOffsetOf(m), transparentBase + i);
  }
  vkCmdEndRendering(cmd);
  imageBarrier(cmd, volumeBack->handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
               VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
               VK_ACCESS_SHADER_READ_BIT);
  // The main pass's attachments, written before, are loaded again.
  VkMemoryBarrier attachments = vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  attachments.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  attachments.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                              VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                              VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  vkCmdPipelineBarrier(cmd, depthStages, depthStages, 0, 1, &attachments, 0, nullptr, 0, nullptr);
  beginMain(cmd, true);
}

// Main pass drawing everything.
void Renderer::Impl::recordMain(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                                std::uint32_t transparentBase, RenderStats& stats) {
  prepareAttachments(cmd);
  beginMain(cmd, false);
  drawOpaque(cmd, s, settings, shadows, VK_NULL_HANDLE, stats);
  drawLines(cmd, s, settings, transparentBase, stats);
  recordVolumeBacks(cmd, s, transparentBase);
  drawTransparent(cmd, s, settings, shadows, transparentBase, stats);
  vkCmdEndRendering(cmd);
}

// Main pass, guided: early draws, depth pyramid, late test, late draws,
// transparent instances (never culled) on top, then next frame's visibility
// from the finished depth.
void Renderer::Impl::recordGuided(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings,
                                  bool shadows, std::uint32_t transparentBase, RenderStats& stats) {
  const RenderTarget& t = *target;
  if (!culler) culler = std::make_unique<OcclusionCuller>(device);
  if (!pyramid) pyramid = std::make_unique<DepthPyramid>(device);
  culler->prepare(s, std::span<const std::uint32_t>(drawOrder.data(), transparentBase));
  pyramid->ensure(t.depth.view(), t.width, t.height, t.samples);
  culler->recordEarly(cmd, s, viewProj, *pyramid, t.width, t.height);

  prepareAttachments(cmd);
  beginMain(cmd, false);
  drawOpaque(cmd, s, settings, shadows, culler->earlyCommands(), stats);
  vkCmdEndRendering(cmd);

  testAgainstDepth(cmd, [&] { culler->recordLate(cmd, viewProj, t.width, t.height); });
  VkMemoryBarrier colour = vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  colour.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  colour.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                         VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  const VkPipelineStageFlags attach = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                      VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  vkCmdPipelineBarrier(cmd, attach, attach, 0, 1, &colour, 0, nullptr, 0, nullptr);

  beginMain(cmd, true);
  drawOpaque(cmd, s, settings, shadows, culler->lateCommands(), stats);
  drawLines(cmd, s, settings, transparentBase, stats);
  recordVolumeBacks(cmd, s, transparentBase);
  drawTransparent(cmd, s, settings, shadows, transparentBase, stats);
  vkCmdEndRendering(cmd);
  testAgainstDepth(cmd, [&] { culler->recordVisibility(cmd, viewProj, t.width, t.height); });
}

// The depth attachment reduced into the pyramid, `test` recorded against
// it, and the attachment made writable again (contents kept).
void Renderer::Impl::testAgainstDepth(VkCommandBuffer cmd, const std::function<void()>& test) {
  const RenderTarget& t = *target;
  imageBarrier(cmd, t.depth.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
               VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
               VK_ACCESS_SHADER_READ_BIT);
  pyramid->record(cmd);
  test();
  imageBarrier(cmd, t.depth.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
               VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0,
               VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
               VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
}

}  // namespace tsr::vk
