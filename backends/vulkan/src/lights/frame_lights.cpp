#include "renderer_impl.hpp"
#include "resources/rendering.hpp"

namespace tsr::vk {

// Lights, with a shadow layer for each shadowed spot/directional light.
std::vector<glm::mat4> Renderer::Impl::gatherLights(SceneState& s, const RenderSettings& settings) {
  gpuLights.clear();
  std::vector<glm::mat4> shadowViewProj;
  const bool shadows = settings.shadows && !s.sceneEmpty && !s.opaqueOrder.empty();
  for (const LightRecord& lr : s.lights) {
    if (!lr.alive) continue;
    GpuLight g{};
    g.direction.w = -1.0f;
    g.cone = glm::vec4(1.0f, 1.0f, 0.0f, 1.0f / float(settings.shadowMapSize));
    std::optional<ShadowProjection> sp;
    if (const auto* p = std::get_if<PointLight>(&lr.light)) {
      g.position = glm::vec4(p->position, float(kGpuPoint));
      g.intensity = glm::vec4(p->intensity, 0.0f);
    } else if (const auto* sl = std::get_if<SpotLight>(&lr.light)) {
      g.position = glm::vec4(sl->position, float(kGpuSpot));
      g.direction = glm::vec4(glm::normalize(sl->direction), -1.0f);
      g.intensity = glm::vec4(sl->intensity, 0.0f);
      g.cone.x = std::cos(sl->innerAngle);
      g.cone.y = std::cos(sl->outerAngle);
      if (shadows && sl->castShadows) sp = spotShadow(*sl, s.sceneMin, s.sceneMax, settings.shadowMapSize);
    } else {
      const auto& dl = std::get<DirectionalLight>(lr.light);
      g.position = glm::vec4(0.0f, 0.0f, 0.0f, float(kGpuDirectional));
      g.direction = glm::vec4(glm::normalize(dl.direction), -1.0f);
      g.intensity = glm::vec4(dl.irradiance, 0.0f);
      if (shadows && dl.castShadows) sp = directionalShadow(dl, s.sceneMin, s.sceneMax, settings.shadowMapSize);
    }
    if (sp) {
      if (shadowViewProj.size() < kMaxShadowMaps) {
        g.direction.w = float(shadowViewProj.size());
        g.cone.z = sp->normalOffset;
        g.shadowMatrix = sp->viewProj;
        shadowViewProj.push_back(sp->viewProj);
      } else {
        spdlog::warn("tsr::vk: more than {} shadowed lights; the rest cast no shadows", kMaxShadowMaps);
      }
    }
    gpuLights.push_back(g);
  }
  addEmitterLights(s, settings, shadows, shadowViewProj);
  ensureHost(device, lightBuffer, std::max<std::size_t>(gpuLights.size(), 1) * sizeof(GpuLight),
             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  if (!gpuLights.empty()) std::memcpy(lightBuffer.mapped(), gpuLights.data(), gpuLights.size() * sizeof(GpuLight));

  return shadowViewProj;
}

// Emissive geometry as area-like lights (emitter_lights.hpp). Mostly flat
// patches get a shadow map while layers remain (brightest first), with a
// wide cone: what lies outside it is at grazing angles and left unshadowed.
void Renderer::Impl::addEmitterLights(SceneState& s, const RenderSettings& settings, bool shadows,
                                      std::vector<glm::mat4>& shadowViewProj) {
  constexpr float kShadowHalfAngle = 1.309f;  // 75 degrees
  const std::vector<EmitterLight> emitters = emitterLights(s, settings.emitterLights);
  ambientFromEmitters = settings.emitterAmbient ? emitterAmbient(s, emitters) : glm::vec3(0.0f);
  for (const EmitterLight& e : emitters) {
    GpuLight g{};
    // Just off the surface, so the emitter does not shadow itself.
    const glm::vec3 position = e.position + e.normal * (1e-3f * std::sqrt(e.area));
    g.position = glm::vec4(position, float(kGpuEmitter));
    g.direction = glm::vec4(e.normal, -1.0f);
    g.intensity = glm::vec4(e.radiance, e.area);
    g.cone = glm::vec4(e.directionalArea, 0.0f, 0.0f, 1.0f / float(settings.shadowMapSize));
    if (shadows && e.directionalArea > 0.5f * e.area && shadowViewProj.size() < kMaxShadowMaps) {
      const SpotLight proxy{position, e.normal, glm::vec3(0.0f), kShadowHalfAngle, kShadowHalfAngle, true};
      const ShadowProjection sp = spotShadow(proxy, s.sceneMin, s.sceneMax, settings.shadowMapSize);
      g.direction.w = float(shadowViewProj.size());
      g.cone.z = sp.normalOffset;
      g.shadowMatrix = sp.viewProj;
      shadowViewProj.push_back(sp.viewProj);
    }
    gpuLights.push_back(g);
  }
}

namespace {

// A medium whose light is mostly gone (optical depth 1 or more, 63 %)
// across the instance's thinnest extent.
bool castsShadowAsSolid(const SceneState& s, std::uint32_t slot) {
  const Material& m = s.materials[s.instances[slot].material].material;
  if (!m.isVolume()) return false;
  glm::vec3 lo, hi;
  s.instanceBounds(slot, lo, hi);
  const glm::vec3 extent = hi - lo, sigma = m.interior->extinction();
  return std::min(sigma.r, std::min(sigma.g, sigma.b)) * std::min(extent.x, std::min(extent.y, extent.z)) >= 1.0f;
}

}  // namespace

// Shadow passes: opaque instances only, positions only, and media dense
// enough to hide what is behind them. After edits of single instances, only
// the rectangles they were and are in are drawn again
// (lights/shadow_update.hpp), from the casters over them.
bool Renderer::Impl::recordShadows(VkCommandBuffer cmd, const SceneState& s,
                                   const std::vector<glm::mat4>& shadowViewProj, RenderStats& stats) {
  if (shadowsHeld && shadowsHeld->scene == s.uid && shadowsHeld->version == s.version &&
      shadowsHeld->viewProj == shadowViewProj)
    return false;  // still in SHADER_READ_ONLY_OPTIMAL from that frame
  // The casters are kept only when there are maps to update partially later.
  ShadowContents now{s.uid, s.version, s.casterEdits, shadowViewProj,
                     shadowViewProj.empty() ? std::vector<ShadowCaster>{} : shadowCasters(s)};
  const ShadowMap& sm = *shadowMap;
  std::optional<std::vector<VkRect2D>> redraw;
  if (shadowsHeld && !shadowViewProj.empty()) redraw = shadowRedraw(*shadowsHeld, now, s, sm.size());
  shadowsHeld.reset();
  shadowsPending = std::move(now);
  if (redraw && std::all_of(redraw->begin(), redraw->end(), [](const VkRect2D& r) { return r.extent.width == 0; }))
    return false;  // no caster changed (the edit was another kind): the maps stay as they are
  // A whole redraw starts from nothing; a partial one keeps the rest.
  const VkImageLayout from = redraw ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED;
  imageBarrier(
      cmd, sm.image().handle(), VK_IMAGE_ASPECT_DEPTH_BIT, from,
      shadowViewProj.empty() ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
      VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0,
      shadowViewProj.empty() ? VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT : VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT,
      shadowViewProj.empty()
          ? VK_ACCESS_SHADER_READ_BIT
          : VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
      sm.layers());
  // Dense media shadow as solids do (a milky glass ball); thinner ones cast
  // none. Their draw-order positions follow the opaque instances'.
  std::vector<std::uint32_t> denseMedia;
  for (std::uint32_t i = 0; i < transparentSorted.size() && !shadowViewProj.empty(); ++i)
    if (castsShadowAsSolid(s, transparentSorted[i])) denseMedia.push_back(std::uint32_t(s.opaqueOrder.size()) + i);
  for (std::uint32_t layer = 0; layer < shadowViewProj.size(); ++layer) {
    const VkRect2D area = redraw ? (*redraw)[layer] : VkRect2D{{0, 0}, {sm.size(), sm.size()}};
    if (area.extent.width == 0 || area.extent.height == 0) continue;  // nothing there changed
    VkClearValue depthClear{};
    depthClear.depthStencil = {1.0f, 0};
    const VkRenderingAttachmentInfo da = renderingAttachment(
        sm.image().layerView(layer), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, /*load=*/bool(redraw), depthClear);
    beginRendering(cmd, sm.size(), sm.size(), nullptr, da);
    if (redraw) {
      vkCmdSetScissor(cmd, 0, 1, &area);
      const VkClearAttachment clear{VK_IMAGE_ASPECT_DEPTH_BIT, 0, depthClear};
      const VkClearRect rect{area, 0, 1};
      vkCmdClearAttachments(cmd, 1, &clear, 1, &rect);
    }
    vkCmdSetDepthBias(cmd, 1.25f, 0.0f, 1.75f);
    PushConstants pc;
    pc.lightViewProj = shadowViewProj[layer];
    // Plain groups first (positions only), then masked ones with their
    // material, whose fragments cut the shadow as they cut the surface.
    for (const bool maskedPass : {false, true}) {
      std::uint32_t bound = ~0u;
      bool pipelineBound = false;
      for (const DrawGroup& g : s.opaqueGroups) {
        const Material& material = s.materials[g.material].material;
        if ((material.alphaCutoff > 0.0f) != maskedPass) continue;
        const MeshRecord& m = s.meshes[g.mesh];
        // The group's instances to draw: all of them, or the runs over the area.
        auto drawRun = [&](std::uint32_t first, std::uint32_t count) {
          if (!pipelineBound) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                              (maskedPass ? maskedShadowPipeline : shadowPipeline).handle());
            pipelineBound = true;
          }
          if (maskedPass) {
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &s.materials[g.material].set, 0,
                                    nullptr);
            pc.material = g.material;
          }
          vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(pc),
                             &pc);
          if (m.span.block != bound) s.geometry->bind(cmd, bound = m.span.block, maskedPass ? 3 : 1);
          vkCmdDrawIndexed(cmd, m.indexCount, count, firstIndexOf(m), vertexOffsetOf(m), first);
          stats.shadowTriangles += std::uint64_t(m.indexCount / 3) * count;
        };
        if (!redraw) {
          drawRun(g.first, g.count);
          continue;
        }
        std::uint32_t run = 0;
        for (std::uint32_t i = 0; i <= g.count; ++i) {
          bool over = false;
          if (i < g.count) {
            const InstanceRecord& inst = s.instances[drawOrder[g.first + i]];
            over = overlaps(area, shadowFootprint(s, inst.mesh, inst.transform, shadowViewProj[layer], sm.size()));
          }
          if (over) {
            ++run;
          } else if (run > 0) {
            drawRun(g.first + i - run, run);
            run = 0;
          }
        }
      }
    }
    bool volumeBound = false;
    for (std::uint32_t position : denseMedia) {
      const InstanceRecord& inst = s.instances[drawOrder[position]];
      if (redraw && !overlaps(area, shadowFootprint(s, inst.mesh, inst.transform, shadowViewProj[layer], sm.size())))
        continue;
      if (!volumeBound) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shadowPipeline.handle());
        vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(pc), &pc);
        volumeBound = true;
      }
      const MeshRecord& m = s.meshes[inst.mesh];
      s.geometry->bind(cmd, m.span.block, 1);
      vkCmdDrawIndexed(cmd, m.indexCount, 1, firstIndexOf(m), vertexOffsetOf(m), position);
      stats.shadowTriangles += m.indexCount / 3;
    }
    vkCmdEndRendering(cmd);
    ++stats.shadowMaps;
  }
  if (!shadowViewProj.empty())
    imageBarrier(cmd, sm.image().handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                 VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                 VK_ACCESS_SHADER_READ_BIT, sm.layers());
  return true;
}

}  // namespace tsr::vk
