#include "tsr/vk/renderer.hpp"

#include "post/depth_of_field.hpp"
#include "projection.hpp"
#include "renderer_impl.hpp"
#include "tsr/backend/validate.hpp"

namespace tsr::vk {

VkSampleCountFlagBits sampleBits(std::uint32_t samples) {
  switch (samples) {
    case 1:
      return VK_SAMPLE_COUNT_1_BIT;
    case 4:
      return VK_SAMPLE_COUNT_4_BIT;
    default:
      throw Error("msaaSamples must be 1 or 4, got " + std::to_string(samples));
  }
}

void ensureHost(const Device& device, Buffer& buffer, VkDeviceSize needed, VkBufferUsageFlags usage) {
  if (buffer && buffer.size() >= needed) return;
  buffer = Buffer(device, std::max<VkDeviceSize>({needed, buffer ? 2 * buffer.size() : 0, 1024}), usage, Buffer::kHost);
}

Renderer::Impl::Impl(const Device& d) : device(d) {
  VkDevice dev = device.handle();
  constexpr std::uint32_t kFrameBindings = 12;
  VkDescriptorSetLayoutBinding b[kFrameBindings]{};
  const VkDescriptorType types[kFrameBindings] = {
      VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,         VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
      VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,         VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
      VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,         VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
      VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
      VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
      VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  for (std::uint32_t i = 0; i < kFrameBindings; ++i) {
    b[i].binding = i;
    b[i].descriptorType = types[i];
    b[i].descriptorCount = 1;
    b[i].stageFlags = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  }
  VkDescriptorSetLayoutCreateInfo lci =
      vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  lci.bindingCount = kFrameBindings;
  lci.pBindings = b;
  check(vkCreateDescriptorSetLayout(dev, &lci, nullptr, &frameLayout), "vkCreateDescriptorSetLayout (frame)");
  materialLayout = createMaterialSetLayout(dev);

  const VkDescriptorSetLayout sets[2] = {frameLayout, materialLayout};
  VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(PushConstants)};
  VkPipelineLayoutCreateInfo pci = vkStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
  pci.setLayoutCount = 2;
  pci.pSetLayouts = sets;
  pci.pushConstantRangeCount = 1;
  pci.pPushConstantRanges = &push;
  check(vkCreatePipelineLayout(dev, &pci, nullptr, &layout), "vkCreatePipelineLayout");

  const VkDescriptorPoolSize sizes[3] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                         {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 5},
                                         {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 6}};
  frameDescriptors.emplace(device, sizes, frameLayout, "frame");
  frameSet = frameDescriptors->set();
  commands.emplace(device, "frame");

  PipelineDesc sd;
  sd.layout = layout;
  sd.vertexSpirv = spirv::shadow_vert;
  sd.vertexStreams = 1;
  sd.depthCompare = VK_COMPARE_OP_LESS;
  sd.depthBias = true;
  shadowPipeline = Pipeline(device, sd);
  PipelineDesc masked = sd;
  masked.vertexSpirv = spirv::shadow_masked_vert;
  masked.fragmentSpirv = spirv::shadow_masked_frag;
  masked.vertexStreams = 3;
  masked.normals = false;
  maskedShadowPipeline = Pipeline(device, masked);
  sd.depthCompare = VK_COMPARE_OP_GREATER;  // reversed depth: the nearest back face
  sd.depthBias = false;
  sd.cull = VK_CULL_MODE_FRONT_BIT;
  volumeBackPipeline = Pipeline(device, sd);

  VkSamplerCreateInfo sci = vkStruct<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
  sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  check(vkCreateSampler(dev, &sci, nullptr, &depthSampler), "vkCreateSampler (volume depth)");
  sci.magFilter = sci.minFilter = VK_FILTER_LINEAR;
  check(vkCreateSampler(dev, &sci, nullptr, &tableSampler), "vkCreateSampler (BRDF table)");
  {
    constexpr std::uint32_t kTableSize = 32;
    const std::vector<glm::vec2> table = splitSumTable(kTableSize);
    const std::vector<float> average = averageAlbedoByRow(table, kTableSize);
    std::vector<glm::vec4> texels;
    for (std::size_t k = 0; k < table.size(); ++k) texels.emplace_back(table[k], average[k / kTableSize], 1.0f);
    brdfTable = uploadImage(device, kTableSize, kTableSize, VK_FORMAT_R32G32B32A32_SFLOAT, texels.data(),
                            texels.size() * sizeof(glm::vec4));
  }

  frameBuffer = Buffer(device, sizeof(GpuFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, Buffer::kHost);
}

Renderer::Impl::~Impl() {
  VkDevice dev = device.handle();
  vkDeviceWaitIdle(dev);
  commands.reset();
  frameDescriptors.reset();
  vkDestroySampler(dev, depthSampler, nullptr);
  vkDestroySampler(dev, tableSampler, nullptr);
  vkDestroyPipelineLayout(dev, layout, nullptr);
  vkDestroyDescriptorSetLayout(dev, materialLayout, nullptr);
  vkDestroyDescriptorSetLayout(dev, frameLayout, nullptr);
}

VkFormat Renderer::Impl::colourFormat(std::uint32_t samples) {
  auto it = colourFormats.find(samples);
  if (it == colourFormats.end())
    it = colourFormats.emplace(samples, chooseColourFormat(device, sampleBits(samples))).first;
  return it->second;
}

// Pipelines are specialised by what changes the fragment shader's code path:
// material type, which textures exist, shadows, fog; plus blending and
// samples. See-through volumes have a shader of their own (volume.frag).
VkPipeline Renderer::Impl::mainPipeline(std::uint32_t samples, const Material& material, bool shadows,
                                        Primitive primitive) {
  const bool volume = material.isVolume();
  const std::uint32_t type = volume ? 0u : static_cast<std::uint32_t>(material.type);
  const bool baseTex = !volume && material.baseColorTexture.has_value();
  const bool emissionTex = !volume && material.emissionTexture.has_value();
  const bool normalTex = !volume && material.normalTexture.has_value();
  const bool mrTex =
      !volume && material.type == MaterialType::MetallicRoughness && material.metallicRoughnessTexture.has_value();
  const bool occlusionTex = !volume && material.occlusionTexture.has_value();
  const bool blend = material.isTransparent();
  const std::uint64_t key = std::uint64_t(samples) | std::uint64_t(type) << 8 | std::uint64_t(baseTex) << 16 |
                            std::uint64_t(emissionTex) << 17 | std::uint64_t(shadows) << 18 |
                            std::uint64_t(blend) << 19 | std::uint64_t(volume) << 20 | std::uint64_t(fog) << 21 |
                            std::uint64_t(normalTex) << 22 | std::uint64_t(mrTex) << 23 |
                            std::uint64_t(occlusionTex) << 24 | std::uint64_t(primitive) << 25;
  auto it = mainPipelines.find(key);
  if (it != mainPipelines.end()) return it->second.handle();
  PipelineDesc d;
  d.layout = layout;
  d.vertexSpirv = volume ? spirv::volume_vert : spirv::mesh_vert;
  d.vertexStreams = volume ? 2 : 3;  // no uvs
  d.fragmentSpirv = volume ? spirv::volume_frag : spirv::mesh_frag;
  d.colourFormat = colourFormat(samples);
  d.samples = sampleBits(samples);
  d.depthCompare = VK_COMPARE_OP_GREATER;  // reversed depth: nearer is greater
  d.blend = blend && !volume;
  d.dualSourceBlend = volume;
  d.cull = volume ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE;  // a volume's front faces only
  d.depthWrite = !blend;
  const bool unlit = primitive != Primitive::Triangles;
  d.topology = primitive == Primitive::Lines    ? VK_PRIMITIVE_TOPOLOGY_LINE_LIST
               : primitive == Primitive::Points ? VK_PRIMITIVE_TOPOLOGY_POINT_LIST
                                                : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  d.fragmentConstants = {type, baseTex, emissionTex, shadows, fog, normalTex, mrTex, occlusionTex, unlit};
  return mainPipelines.emplace(key, Pipeline(device, d)).first->second.handle();
}

bool Renderer::Impl::drawsVolumes() const { return device.dualSourceBlend(); }

Renderer::Renderer(std::shared_ptr<Device> device, RenderSettings settings) : device_(std::move(device)) {
  if (!device_) throw Error("renderer needs a device");
  impl_ = std::make_unique<Impl>(*device_);
  setSettings(settings);
}

Renderer::~Renderer() = default;

void Renderer::setSettings(const RenderSettings& settings) {
  sampleBits(settings.msaaSamples);
  if (settings.shadowMapSize < 16 || settings.shadowMapSize > 8192)
    throw Error("shadowMapSize must be in [16, 8192], got " + std::to_string(settings.shadowMapSize));
  for (int i = 0; i < 4; ++i)
    if (!std::isfinite(settings.background[i])) throw Error("background colour contains NaN or infinity");
  if (settings.visibility == Visibility::Guided && !device_->multiDrawIndirect())
    throw Error("guided visibility needs multiDrawIndirect, which " + device_->name() + " lacks");
  impl_->mainPipeline(settings.msaaSamples, Material{}, settings.shadows);  // fails here, not mid-frame
  // The probes' faces were drawn with the old settings (shadows, lights, background).
  if (!(settings == settings_)) impl_->probeHeld.reset();
  settings_ = settings;
}

void Renderer::render(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb) {
  backend::validate<Error>(camera);
  backend::validate<Error>(region);
  if (fb.width() != region.regionWidth() || fb.height() != region.regionHeight())
    throw Error("frame buffer is " + std::to_string(fb.width()) + "x" + std::to_string(fb.height()) +
                " but the region is " + std::to_string(region.regionWidth()) + "x" +
                std::to_string(region.regionHeight()));
  if (&scene.device() != device_.get()) throw Error("scene and renderer use different devices");
  if (!settings_.depthOfField || !(camera.apertureRadius > 0.0f)) return renderSharp(scene, camera, region, fb);

  if (region == Region::full(region.width, region.height)) {
    renderSharp(scene, camera, region, fb);
    return applyDepthOfField(camera, region, fb.colour_, fb.depth_);
  }
  // A crop gathers from beyond its edges as the whole image would.
  const std::uint32_t margin = kBlurMargin;
  Region grown = region;
  grown.x0 = region.x0 > margin ? region.x0 - margin : 0;
  grown.y0 = region.y0 > margin ? region.y0 - margin : 0;
  grown.x1 = std::min(region.width, region.x1 + margin);
  grown.y1 = std::min(region.height, region.y1 + margin);
  FrameBuffer drawn(grown.regionWidth(), grown.regionHeight());
  renderSharp(scene, camera, grown, drawn);
  applyDepthOfField(camera, grown, drawn.colour_, drawn.depth_);
  for (std::uint32_t y = 0; y < fb.height_; ++y)
    for (std::uint32_t x = 0; x < fb.width_; ++x) {
      const std::size_t from = drawn.at(x + region.x0 - grown.x0, y + region.y0 - grown.y0);
      fb.colour_[fb.at(x, y)] = drawn.colour_[from];
      fb.depth_[fb.at(x, y)] = drawn.depth_[from];
    }
}

void Renderer::renderSharp(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb) {
  Impl& r = *impl_;
  SceneState& s = scene.state();
  s.prepare();
  const std::uint32_t transparentBase = r.sortDrawOrder(s, camera);
  const std::vector<glm::mat4> shadowViewProj = r.gatherLights(s, settings_);
  r.prepareFrame(s, camera, region, settings_, std::uint32_t(shadowViewProj.size()));
  RenderStats stats;
  VkCommandBuffer cmd = r.commands->buffer();
  VkCommandBufferBeginInfo bi = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  // The shadow maps first, on their own: the probes' faces are drawn with
  // them. (The frame's descriptor set is bound whole, so the probe's image
  // must be written into it already.)
  r.ensureProbeImages();
  r.writeProbeDescriptor(s, r.probe[r.probeCurrent]);
  check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
  check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.layout, 0, 1, &r.frameSet, 0, nullptr);
  const bool recorded = r.recordShadows(cmd, s, shadowViewProj, stats);
  check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  if (recorded) r.commands->submitAndWait("shadows");
  if (r.shadowsPending) r.shadowsHeld = std::exchange(r.shadowsPending, std::nullopt);
  r.updateProbe(s, settings_, r.frameData, !shadowViewProj.empty(), stats);

  check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
  check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.layout, 0, 1, &r.frameSet, 0, nullptr);
  const bool guided = settings_.visibility == Visibility::Guided;
  if (guided)
    r.recordGuided(cmd, s, settings_, !shadowViewProj.empty(), transparentBase, stats);
  else
    r.recordMain(cmd, s, settings_, !shadowViewProj.empty(), transparentBase, stats);
  const RenderTarget& t = *r.target;
  recordReadback(cmd, t.resolvedColour(), t.resolvedDepth(), t.colourReadback, t.depthReadback, t.width, t.height);
  check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  r.commands->submitAndWait("frame");

  r.readColour(fb);
  readLinearDepth(t.depthReadback, camera, fb.depth_);
  if (guided) {
    const OcclusionCuller::Drawn d = r.culler->drawn();
    stats.triangles += d.earlyTriangles + d.lateTriangles;
    stats.objects += d.earlyObjects + d.lateObjects;
    stats.lateObjects = d.lateObjects;
  }
  stats_ = stats;
}

// Sort: opaque groups as the scene sorted them, each front to back (early
// depth tests then skip shading hidden fragments, which dominates on CPUs),
// then transparent instances back to front by their bounds' centre.
std::uint32_t Renderer::Impl::sortDrawOrder(const SceneState& s, const Camera& camera) {
  const glm::vec3 camPos(camera.cameraToWorld[3]);
  const glm::vec3 forward = -glm::normalize(glm::vec3(camera.cameraToWorld[2]));
  transparentSorted = s.transparent;
  {
    std::vector<std::pair<float, std::uint32_t>> keyed;
    keyed.reserve(s.transparent.size());
    for (std::uint32_t slot : s.transparent) {
      glm::vec3 lo, hi;
      s.instanceBounds(slot, lo, hi);
      keyed.emplace_back(glm::dot(0.5f * (lo + hi) - camPos, forward), slot);
    }
    std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) {
      return a.first != b.first ? a.first > b.first : a.second < b.second;
    });
    for (std::size_t i = 0; i < keyed.size(); ++i) transparentSorted[i] = keyed[i].second;
  }
  drawOrder.assign(s.opaqueOrder.begin(), s.opaqueOrder.end());
  {
    std::vector<std::pair<float, std::uint32_t>> keyed;
    for (const DrawGroup& g : s.opaqueGroups) {
      const MeshRecord& m = s.meshes[g.mesh];
      const glm::vec4 centre(0.5f * (m.boundsMin + m.boundsMax), 1.0f);
      keyed.clear();
      for (std::uint32_t i = g.first; i < g.first + g.count; ++i) {
        const std::uint32_t slot = drawOrder[i];
        keyed.emplace_back(glm::dot(glm::vec3(s.instances[slot].transform * centre) - camPos, forward), slot);
      }
      std::sort(keyed.begin(), keyed.end());
      for (std::uint32_t i = 0; i < g.count; ++i) drawOrder[g.first + i] = keyed[i].second;
    }
  }
  const std::uint32_t transparentBase = std::uint32_t(drawOrder.size());
  drawOrder.insert(drawOrder.end(), transparentSorted.begin(), transparentSorted.end());
  drawOrder.insert(drawOrder.end(), s.lineOrder.begin(), s.lineOrder.end());
  ensureHost(device, drawOrderBuffer, std::max<std::size_t>(drawOrder.size(), 1) * 4,
             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  if (!drawOrder.empty()) std::memcpy(drawOrderBuffer.mapped(), drawOrder.data(), drawOrder.size() * 4);

  return transparentBase;
}

// The frame's uniforms, targets sized for the region, and the frame's descriptors.
void Renderer::Impl::prepareFrame(const SceneState& s, const Camera& camera, const Region& region,
                                  const RenderSettings& settings, std::uint32_t shadowLayers) {
  const std::uint32_t w = region.regionWidth(), h = region.regionHeight();
  const VkSampleCountFlagBits samples = sampleBits(settings.msaaSamples);
  const glm::vec3 camPos(camera.cameraToWorld[3]);
  GpuFrame frame{};
  const glm::mat4 proj = projection(camera, region);
  viewProj = proj * camera.worldToCamera();
  frame.viewProj = viewProj;
  frame.cameraPos = glm::vec4(camPos, 1.0f);
  frame.ambient = glm::vec4(s.environment.averageRadiance() + ambientFromEmitters, 0.0f);
  frame.counts = glm::uvec4(std::uint32_t(gpuLights.size()), 0u, 0u, 0u);
  frame.invViewProj = glm::inverse(viewProj);
  frame.viewport = viewportOf(proj, w, h);
  frame.emitterAmbient = glm::vec4(ambientFromEmitters, 0.0f);
  frame.sceneMin = glm::vec4(s.sceneMin, 0.0f);
  frame.sceneMax = glm::vec4(s.sceneMax, 0.0f);
  if (irradianceVolume) {
    const backend::IrradianceVolume& v = *irradianceVolume;
    frame.volumeMin = glm::vec4(v.min, 1.0f);
    frame.volumeMax = glm::vec4(v.max, 0.0f);
    frame.volumeCounts = glm::uvec4(v.counts, std::uint32_t(v.probeCount()));
  }
  clearColour = settings.background;
  fog = s.environment.fog().has_value();
  if (fog) {
    const Medium& m = *s.environment.fog();
    frame.fogAbsorption = glm::vec4(m.absorption, std::clamp(m.g, -0.99f, 0.99f));
    frame.fogScattering = glm::vec4(m.scattering, 0.0f);
    frame.fogEmission = glm::vec4(m.emission, 0.0f);
    // An endless ray through fog: nothing of the background is left where the
    // fog absorbs or scatters, only the ambient term scattered in and the
    // emission, (sigma_s L + e) / sigma_t. Where it does neither the
    // background stays (its emission alone would be infinite).
    const glm::vec3 sigmaT = m.extinction();
    for (int c = 0; c < 3; ++c)
      if (sigmaT[c] > 0.0f) clearColour[c] = (m.scattering[c] * frame.ambient[c] + m.emission[c]) / sigmaT[c];
  }
  std::memcpy(frameBuffer.mapped(), &frame, sizeof(frame));
  frameData = frame;

  if (!target || target->width != w || target->height != h || target->samples != samples)
    target.emplace(device, w, h, colourFormat(settings.msaaSamples), samples);
  const std::uint32_t layers = std::max<std::uint32_t>(1, shadowLayers);
  if (!shadowMap || shadowMap->size() != settings.shadowMapSize || shadowMap->layers() < layers) {
    shadowMap.reset();
    shadowsHeld.reset();
    shadowMap.emplace(device, settings.shadowMapSize, layers);
  }
  const ShadowMap& sm = *shadowMap;
  if (!volumeBack || volumeBack->desc().width != w || volumeBack->desc().height != h) {
    ImageDesc vd;
    vd.width = w;
    vd.height = h;
    vd.format = kDepthFormat;
    vd.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    vd.usage =
        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    volumeBack.emplace(device, vd);
    volumeBackFresh = true;
  }

  {
    VkDescriptorBufferInfo bufs[5] = {
        {frameBuffer.handle(), 0, VK_WHOLE_SIZE},     {s.instanceBuffer.handle(), 0, VK_WHOLE_SIZE},
        {drawOrderBuffer.handle(), 0, VK_WHOLE_SIZE}, {s.materialBuffer.handle(), 0, VK_WHOLE_SIZE},
        {lightBuffer.handle(), 0, VK_WHOLE_SIZE},
    };
    VkDescriptorImageInfo shadowInfo{sm.sampler(), sm.image().view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo volumeInfo{depthSampler, volumeBack->view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo tableInfo{tableSampler, brdfTable.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo environmentInfo{s.sampler, s.environmentMap.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    // Without a volume the shader reads none; any storage buffer fills the slot.
    const VkDescriptorBufferInfo irradianceInfo{irradianceVolume ? irradianceBuffer.handle() : drawOrderBuffer.handle(),
                                                0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet writes[10]{};
    writes[9] = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    writes[9].dstSet = frameSet;
    writes[9].dstBinding = 11;
    writes[9].descriptorCount = 1;
    writes[9].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[9].pBufferInfo = &irradianceInfo;
    for (std::uint32_t i = 0; i < 9; ++i) {
      writes[i] = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
      writes[i].dstSet = frameSet;
      writes[i].dstBinding = i;
      writes[i].descriptorCount = 1;
      if (i == 0) {
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        writes[i].pBufferInfo = &bufs[0];
      } else if (i < 5) {
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[i].pBufferInfo = &bufs[i];
      } else {
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        const VkDescriptorImageInfo* images[4] = {&shadowInfo, &volumeInfo, &tableInfo, &environmentInfo};
        writes[i].pImageInfo = images[i - 5];
      }
    }
    vkUpdateDescriptorSets(device.handle(), 10, writes, 0, nullptr);
  }
}

void Renderer::Impl::readColour(FrameBuffer& fb) const {
  const RenderTarget& t = *target;
  const std::size_t pixels = std::size_t(t.width) * t.height;
  if (t.colourFormat == VK_FORMAT_R32G32B32A32_SFLOAT) {
    std::memcpy(fb.colour_.data(), t.colourReadback.mapped(), pixels * sizeof(glm::vec4));
  } else {
    const auto* half = static_cast<const std::uint16_t*>(t.colourReadback.mapped());
    for (std::size_t i = 0; i < pixels; ++i)
      for (int c = 0; c < 4; ++c) fb.colour_[i][c] = glm::unpackHalf1x16(half[4 * i + c]);
  }
}

void Renderer::renderIds(Scene& scene, const Camera& camera, const Region& region, IdBuffer& ids) {
  backend::validate<Error>(camera);
  backend::validate<Error>(region);
  if (ids.width != region.regionWidth() || ids.height != region.regionHeight() ||
      ids.ids.size() != std::size_t(ids.width) * ids.height || ids.depth.size() != ids.ids.size())
    throw Error("id buffer is " + std::to_string(ids.width) + "x" + std::to_string(ids.height) + " but the region is " +
                std::to_string(region.regionWidth()) + "x" + std::to_string(region.regionHeight()));
  if (&scene.device() != device_.get()) throw Error("scene and renderer use different devices");
  if (!impl_->idPass) impl_->idPass = std::make_unique<IdPass>(*device_);
  stats_ = RenderStats{};
  stats_.drawCalls = impl_->idPass->render(scene.state(), camera, region, ids);
}

}  // namespace tsr::vk
