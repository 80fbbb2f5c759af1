// The reflection probes: the scene seen from the centre of its bounds, and
// from the centres of its largest mirrors and glass objects, each as six
// 90-degree faces (shaders/probe.glsl samples them), so mirrors and glass
// show the room instead of the environment's average. Drawn only when an
// instance is a Mirror or Glass and the scene changed since the last
// probe; each face is its own submission because the frame uniform holds
// one camera. The faces are drawn without shadows (the shadow maps of this
// frame come later), without transparent instances and without the mirrors
// and glass themselves (they would hide what they reflect).
#include "projection.hpp"
#include "reflections/probe_prefilter.hpp"
#include "renderer_impl.hpp"
#include "resources/rendering.hpp"

#include <glm/gtc/constants.hpp>

#include <algorithm>

namespace tsr::vk {

// Usable only when its centre is outside every mirror and glass instance
// (a probe inside a mirror sphere sees its inside); rough surfaces reflect
// it only when the centre is outside every instance but a room around the
// whole scene, so that what it sees is the scene around that centre, and
// when some surface is glossy enough to show it.
Renderer::Impl::ProbeUse Renderer::Impl::wantsProbe(const SceneState& s) const {
  if (s.sceneEmpty) return ProbeUse::None;
  const glm::vec3 centre = 0.5f * (s.sceneMin + s.sceneMax);
  const auto alive = std::count_if(s.instances.begin(), s.instances.end(), [](const auto& i) { return i.alive; });
  bool anyReflective = false, anyGlossy = false, centreFree = true;
  for (const DrawGroup& g : s.opaqueGroups) {
    const Material& m = s.materials[g.material].material;
    const bool mirror = reflective(m);
    anyReflective = anyReflective || mirror;
    anyGlossy = anyGlossy || glossy(m);
    for (std::uint32_t i = g.first; i < g.first + g.count; ++i) {
      glm::vec3 lo, hi;
      s.instanceBounds(s.opaqueOrder[i], lo, hi);
      if (glm::all(glm::greaterThanEqual(centre, lo)) && glm::all(glm::lessThanEqual(centre, hi))) {
        if (mirror) return ProbeUse::None;
        // A room around the rest of the scene does not hide it from its centre.
        const bool container = alive > 1 && glm::all(glm::greaterThanEqual(hi - lo, 0.99f * (s.sceneMax - s.sceneMin)));
        centreFree = centreFree && container;
      }
    }
  }
  if (centreFree && anyGlossy) return ProbeUse::RoughReflections;
  return anyReflective ? ProbeUse::Mirrors : ProbeUse::None;
}

// Mirrors and glass objects, the largest first (by their boxes' diagonals),
// up to kObjectProbes: each gets a probe drawn from its box's centre, which
// sees what a ball reflects and refracts from where the ball is, whatever
// stands between it and the scene's centre (builtin:cornell's centre is a
// hand's breadth in front of the tall block). Not one whose centre lies
// inside another opaque instance (a jar round a block): that probe would
// see the block alone. The shader finds an instance's probe by its slot.
std::vector<Renderer::Impl::ObjectProbe> Renderer::Impl::objectProbes(const SceneState& s) {
  std::vector<ObjectProbe> candidates;
  for (const DrawGroup& g : s.opaqueGroups) {
    if (!reflective(s.materials[g.material].material)) continue;
    for (std::uint32_t i = g.first; i < g.first + g.count; ++i) {
      glm::vec3 lo, hi;
      s.instanceBounds(s.opaqueOrder[i], lo, hi);
      const float radius = 0.5f * glm::length(hi - lo);
      if (radius > 0.0f) candidates.push_back({0.5f * (lo + hi), radius, s.opaqueOrder[i]});
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const ObjectProbe& a, const ObjectProbe& b) { return a.radius > b.radius; });
  // Each candidate tested costs a pass over the instances: a few at most.
  if (candidates.size() > 4 * kObjectProbes) candidates.resize(4 * kObjectProbes);
  const glm::vec3 sceneSize = s.sceneMax - s.sceneMin;
  auto enclosed = [&](const ObjectProbe& p) {
    for (const DrawGroup& g : s.opaqueGroups)
      for (std::uint32_t i = g.first; i < g.first + g.count; ++i) {
        const std::uint32_t slot = s.opaqueOrder[i];
        if (slot == p.slot) continue;
        glm::vec3 lo, hi;
        s.instanceBounds(slot, lo, hi);
        const bool room = glm::all(glm::greaterThanEqual(hi - lo, 0.99f * sceneSize));
        if (!room && glm::all(glm::greaterThan(p.centre, lo)) && glm::all(glm::lessThan(p.centre, hi))) return true;
      }
    return false;
  };
  std::vector<ObjectProbe> found;
  for (const ObjectProbe& p : candidates) {
    if (found.size() == kObjectProbes) break;
    if (!enclosed(p)) found.push_back(p);
  }
  return found;
}

bool Renderer::Impl::hiddenFromProbe(const SceneState& s, std::uint32_t slot) {
  glm::vec3 lo, hi;
  s.instanceBounds(slot, lo, hi);
  if (s.materials[s.instances[slot].material].material.type == MaterialType::Dielectric) {
    // Rough glass is seen through, itself included: every one but a wall
    // (spanning the scene along two axes), also one standing on the floor.
    const glm::bvec3 spans = glm::greaterThanEqual(hi - lo, 0.99f * (s.sceneMax - s.sceneMin));
    return int(spans.x) + int(spans.y) + int(spans.z) < 2;
  }
  const glm::vec3 margin = 1e-3f * (s.sceneMax - s.sceneMin);
  return glm::all(glm::greaterThan(lo, s.sceneMin + margin)) && glm::all(glm::lessThan(hi, s.sceneMax - margin));
}

void Renderer::Impl::ensureProbeImages() {
  if (probe[0]) return;
  for (Image& img : probe) {
    ImageDesc d;
    d.width = d.height = kProbeSize;
    d.layers = kProbeLayers;
    d.arrayView = true;
    d.format = colourFormat(1);
    d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    img = Image(device, d);
  }
  ImageDesc d;
  d.width = d.height = kProbeSize;
  d.format = kDepthFormat;
  d.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  probeDepth = Image(device, d);
  const std::vector<glm::vec4> black(std::size_t(ProbeLevels::kSize) * ProbeLevels::kHeight, glm::vec4(0.0f));
  probeLevels = uploadImage(device, ProbeLevels::kSize, ProbeLevels::kHeight, VK_FORMAT_R32G32B32A32_SFLOAT,
                            black.data(), black.size() * sizeof(glm::vec4));
  probeFresh = true;
}

void Renderer::Impl::writeProbeDescriptor(const SceneState& s, const Image& image) {
  const VkDescriptorImageInfo info[2] = {{s.sampler, image.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                                         {s.sampler, probeLevels.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
  VkWriteDescriptorSet w[2];
  for (std::uint32_t i = 0; i < 2; ++i) {
    w[i] = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w[i].dstSet = frameSet;
    w[i].dstBinding = 9 + i;
    w[i].descriptorCount = 1;
    w[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w[i].pImageInfo = &info[i];
  }
  vkUpdateDescriptorSets(device.handle(), 2, w, 0, nullptr);
}

// After the faces were drawn into probe[probeCurrent] (SHADER_READ_ONLY):
// copies them to the host and prefilters them into the rough levels.
void Renderer::Impl::prefilterProbeLevels(const SceneState& s) {
  const Image& faces = probe[probeCurrent];
  const bool full = faces.desc().format == VK_FORMAT_R32G32B32A32_SFLOAT;
  const std::size_t texels = std::size_t(6) * kProbeSize * kProbeSize;
  const VkDeviceSize bytes = texels * (full ? 16 : 8);
  ensureHost(device, probeReadback, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  VkCommandBuffer cmd = commands->buffer();
  check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo bi = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  imageBarrier(cmd, faces.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
               VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT, 6);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 6};
  region.imageExtent = {kProbeSize, kProbeSize, 1};
  vkCmdCopyImageToBuffer(cmd, faces.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, probeReadback.handle(), 1, &region);
  imageBarrier(cmd, faces.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
               VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT, 6);
  VkBufferMemoryBarrier host = vkStruct<VkBufferMemoryBarrier>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER);
  host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  host.srcQueueFamilyIndex = host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  host.buffer = probeReadback.handle();
  host.size = VK_WHOLE_SIZE;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &host, 0,
                       nullptr);
  check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  commands->submitAndWait("reflection probe readback");

  std::vector<glm::vec4> radiance(texels);
  if (full) {
    std::memcpy(radiance.data(), probeReadback.mapped(), texels * sizeof(glm::vec4));
  } else {
    const auto* half = static_cast<const std::uint16_t*>(probeReadback.mapped());
    for (std::size_t i = 0; i < texels; ++i)
      for (int c = 0; c < 4; ++c) radiance[i][c] = glm::unpackHalf1x16(half[4 * i + c]);
  }
  const std::vector<glm::vec4> levels = prefilterProbe(radiance, kProbeSize, s.environment, fog);
  probeLevels = uploadImage(device, ProbeLevels::kSize, ProbeLevels::kHeight, VK_FORMAT_R32G32B32A32_SFLOAT,
                            levels.data(), levels.size() * sizeof(glm::vec4));
}

// Called after prepareFrame (which wrote this frame's uniform and
// descriptors); leaves both as the frame needs them.
void Renderer::Impl::updateProbe(const SceneState& s, const RenderSettings& settings, GpuFrame& frame, bool shadows,
                                 RenderStats& stats) {
  ensureProbeImages();
  const ProbeKey key{s.uid, s.version, irradianceVersion};
  // Bounds of every instance: once per scene version, not every frame.
  if (probeWantedFor != key) {
    probeWanted = wantsProbe(s);
    objectProbesWanted = objectProbes(s);
    probeWantedFor = key;
  }
  const ProbeUse wanted = settings.reflectionProbe ? probeWanted : ProbeUse::None;
  static const std::vector<ObjectProbe> kNone;
  const std::vector<ObjectProbe>& objects = settings.reflectionProbe ? objectProbesWanted : kNone;
  const bool use = wanted != ProbeUse::None || !objects.empty();
  if (use && (probeHeld != key || probeUseHeld != wanted || objectProbesHeld != objects)) {
    // Draw into the image the shader does not read; the probe flag is off
    // while drawing, so the faces never sample a probe.
    Image& into = probe[1 - probeCurrent];
    writeProbeDescriptor(s, probe[probeCurrent]);
    const glm::vec3 centre = 0.5f * (s.sceneMin + s.sceneMax);
    const float size = std::max(glm::length(s.sceneMax - s.sceneMin), 1e-3f);
    RenderSettings faceSettings = settings;
    faceSettings.msaaSamples = 1;
    // (first layer, centre) of each probe drawn: the scene's at layer 0.
    std::vector<std::pair<std::uint32_t, glm::vec3>> views;
    if (wanted != ProbeUse::None) views.emplace_back(0, centre);
    for (std::uint32_t k = 0; k < objects.size(); ++k) views.emplace_back(6 * (k + 1), objects[k].centre);
    for (std::size_t v = 0; v < views.size(); ++v) {
      const auto [firstLayer, from] = views[v];
      for (std::uint32_t f = 0; f < 6; ++f) {
        const Camera camera = Camera::lookAt(from, from + kProbeFaceForward[f], kProbeFaceUp[f], glm::half_pi<float>(),
                                             1.0f, 1e-3f * size, 4.0f * size);
        const Region region = Region::full(kProbeSize, kProbeSize);
        GpuFrame face = frame;
        const glm::mat4 proj = projection(camera, region);
        face.viewProj = proj * camera.worldToCamera();
        face.invViewProj = glm::inverse(face.viewProj);
        face.cameraPos = glm::vec4(from, 1.0f);
        face.viewport = viewportOf(proj, kProbeSize, kProbeSize);
        face.probeCentre = glm::vec4(from, -1.0f);  // no probe to sample; alpha holds the distance
        for (glm::vec4& o : face.objectProbes) o = glm::vec4(0.0f);
        std::memcpy(frameBuffer.mapped(), &face, sizeof(face));

        VkCommandBuffer cmd = commands->buffer();
        check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
        VkCommandBufferBeginInfo bi = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
        bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
        if (v == 0 && f == 0) prepareProbeLayouts(cmd, into);
        imageBarrier(cmd, probeDepth.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                     VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &frameSet, 0, nullptr);
        // Alpha -1 marks the background (geometry's alpha is its distance,
        // shaders/probe.glsl), for prefilterProbe() and the lookups.
        VkClearValue colourClear{};
        colourClear.color = {{clearColour.r, clearColour.g, clearColour.b, -1.0f}};
        const VkRenderingAttachmentInfo ca = renderingAttachment(
            into.layerView(firstLayer + f), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, /*load=*/false, colourClear);
        VkClearValue depthClear{};
        depthClear.depthStencil = {0.0f, 0};
        const VkRenderingAttachmentInfo da = renderingAttachment(
            probeDepth.view(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, /*load=*/false, depthClear, /*store=*/false);
        beginRendering(cmd, kProbeSize, kProbeSize, &ca, da);
        boundPipeline = VK_NULL_HANDLE;
        boundBlock = boundMaterial = ~0u;
        RenderStats ignored;
        drawingProbe = true;
        drawingSceneProbe = firstLayer == 0;
        drawOpaque(cmd, s, faceSettings, shadows, VK_NULL_HANDLE, ignored);
        drawingProbe = drawingSceneProbe = false;
        vkCmdEndRendering(cmd);
        if (v + 1 == views.size() && f == 5)
          imageBarrier(cmd, into.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                       VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                       VK_ACCESS_SHADER_READ_BIT, kProbeLayers);
        check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
        commands->submitAndWait("reflection probe");
      }
    }
    probeCurrent = 1 - probeCurrent;
    probeHeld = key;
    probeUseHeld = wanted;
    objectProbesHeld = objects;
    probeCentreHeld = centre;
    if (wanted == ProbeUse::RoughReflections) prefilterProbeLevels(s);
    ++stats.probes;
  } else if (probeFresh) {
    VkCommandBuffer cmd = commands->buffer();
    check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo bi = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
    prepareProbeLayouts(cmd, probe[1 - probeCurrent]);
    imageBarrier(cmd, probe[1 - probeCurrent].handle(), VK_IMAGE_ASPECT_COLOR_BIT,
                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                 VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                 VK_ACCESS_SHADER_READ_BIT, kProbeLayers);
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    commands->submitAndWait("reflection probe layouts");
  }
  const bool held = use && probeHeld;
  frame.probeCentre = held && probeUseHeld != ProbeUse::None
                          ? glm::vec4(probeCentreHeld, probeUseHeld == ProbeUse::RoughReflections ? 2.0f : 1.0f)
                          : glm::vec4(0.0f);
  for (std::uint32_t k = 0; k < kObjectProbes; ++k) {
    const bool has = held && k < objectProbesHeld.size();
    frame.objectProbes[k] = has ? glm::vec4(objectProbesHeld[k].centre, 1.0f) : glm::vec4(0.0f);
    frame.objectProbeSlots[k] = has ? objectProbesHeld[k].slot : 0u;
  }
  std::memcpy(frameBuffer.mapped(), &frame, sizeof(frame));
  writeProbeDescriptor(s, probe[probeCurrent]);
}

// Both probe images and the frame's sampled images get defined layouts
// before anything samples them: `into` is made a colour attachment, the
// other probe image (first time) and fresh shadow and volume images
// shader-readable (their contents are drawn later, where used).
void Renderer::Impl::prepareProbeLayouts(VkCommandBuffer cmd, const Image& into) {
  imageBarrier(cmd, into.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0,
               VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, kProbeLayers);
  if (probeFresh) {
    const Image& other = &into == &probe[0] ? probe[1] : probe[0];
    imageBarrier(cmd, other.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                 VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT, kProbeLayers);
    probeFresh = false;
  }
  if (!shadowsHeld)
    imageBarrier(cmd, shadowMap->image().handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                 VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT, shadowMap->layers());
  if (volumeBackFresh) {
    imageBarrier(cmd, volumeBack->handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                 VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    volumeBackFresh = false;
  }
}

}  // namespace tsr::vk
