#include "tsr/vk/renderer.hpp"

#include "buffer.hpp"
#include "command_slot.hpp"
#include "depth_pyramid.hpp"
#include "emitter_lights.hpp"
#include "gpu_types.hpp"
#include "id_pass.hpp"
#include "occlusion_culler.hpp"
#include "pipeline.hpp"
#include "readback.hpp"
#include "render_target.hpp"
#include "scene_state.hpp"
#include "shadow_map.hpp"
#include "spirv.hpp"

#include "tsr/vk/error.hpp"
#include "vk_struct.hpp"

#include <spdlog/spdlog.h>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cstring>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>

namespace tsr::vk {

namespace {

constexpr std::uint32_t kMaxShadowMaps = 8;

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

}  // namespace

struct Renderer::Impl {
  const Device& device;
  VkDescriptorSetLayout frameLayout = VK_NULL_HANDLE;
  VkDescriptorSetLayout materialLayout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  std::optional<DescriptorSlot> frameDescriptors;  // made once the layout exists
  VkDescriptorSet frameSet = VK_NULL_HANDLE;
  std::optional<CommandSlot> commands;

  std::map<std::uint32_t, VkFormat> colourFormats;  // by sample count
  std::map<std::uint64_t, Pipeline> mainPipelines;  // by pipelineKey()
  Pipeline shadowPipeline;

  Buffer frameBuffer;  // GpuFrame uniform
  Buffer lightBuffer;
  Buffer drawOrderBuffer;
  std::optional<RenderTarget> target;
  std::optional<ShadowMap> shadowMap;
  // What the shadow maps hold. They do not depend on the camera, so they are
  // drawn again only when the scene (any edit bumps its version) or the
  // lights' projections change.
  struct ShadowKey {
    const SceneState* scene = nullptr;
    std::uint64_t version = 0;
    std::vector<glm::mat4> viewProj;
    bool operator==(const ShadowKey&) const = default;
  };
  std::optional<ShadowKey> shadowsHeld;     // after a completed frame
  std::optional<ShadowKey> shadowsPending;  // recorded this frame
  std::unique_ptr<IdPass> idPass;           // made on first renderIds
  std::unique_ptr<OcclusionCuller> culler;  // made on the first guided frame
  std::unique_ptr<DepthPyramid> pyramid;
  glm::mat4 viewProj{1.0f};                   // this frame's
  VkPipeline boundPipeline = VK_NULL_HANDLE;  // in the current main pass
  std::uint32_t boundBlock = ~0u;
  std::uint32_t boundMaterial = ~0u;

  std::vector<std::uint32_t> drawOrder;
  std::vector<GpuLight> gpuLights;
  glm::vec3 ambientFromEmitters{0.0f};  // emitterAmbient() of this frame
  std::vector<std::uint32_t> transparentSorted;

  explicit Impl(const Device& d);
  ~Impl();
  VkFormat colourFormat(std::uint32_t samples);
  VkPipeline mainPipeline(std::uint32_t samples, const Material& material, bool shadows);

  // The passes of one frame, in order. Returns where transparent instances
  // start in the draw order.
  std::uint32_t sortDrawOrder(const SceneState& s, const Camera& camera);
  // Fills the light buffer; returns the shadowed lights' view-projections.
  std::vector<glm::mat4> gatherLights(SceneState& s, const RenderSettings& settings);
  void addEmitterLights(SceneState& s, const RenderSettings& settings, bool shadows,
                        std::vector<glm::mat4>& shadowViewProj);
  void prepareFrame(const SceneState& s, const Camera& camera, const Region& region, const RenderSettings& settings,
                    std::uint32_t shadowLayers);
  void recordShadows(VkCommandBuffer cmd, const SceneState& s, const std::vector<glm::mat4>& shadowViewProj,
                     RenderStats& stats);
  void prepareAttachments(VkCommandBuffer cmd);
  void beginMain(VkCommandBuffer cmd, const RenderSettings& settings, bool load);
  void bindDraw(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                std::uint32_t meshIndex, std::uint32_t material);
  void drawOpaque(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                  VkBuffer indirect, RenderStats& stats);
  void drawTransparent(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                       std::uint32_t transparentBase, RenderStats& stats);
  void recordMain(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                  std::uint32_t transparentBase, RenderStats& stats);
  void recordGuided(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                    std::uint32_t transparentBase, RenderStats& stats);
  void testAgainstDepth(VkCommandBuffer cmd, const std::function<void()>& test);
  void readColour(FrameBuffer& fb) const;
};

Renderer::Impl::Impl(const Device& d) : device(d) {
  VkDevice dev = device.handle();
  VkDescriptorSetLayoutBinding b[6]{};
  const VkDescriptorType types[6] = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                     VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                     VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
  for (std::uint32_t i = 0; i < 6; ++i) {
    b[i].binding = i;
    b[i].descriptorType = types[i];
    b[i].descriptorCount = 1;
    b[i].stageFlags = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  }
  VkDescriptorSetLayoutCreateInfo lci =
      vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  lci.bindingCount = 6;
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
                                         {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4},
                                         {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}};
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

  frameBuffer = Buffer(device, sizeof(GpuFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, Buffer::kHost);
}

Renderer::Impl::~Impl() {
  VkDevice dev = device.handle();
  vkDeviceWaitIdle(dev);
  commands.reset();
  frameDescriptors.reset();
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
// material type, which textures exist, shadows; plus blending and samples.
VkPipeline Renderer::Impl::mainPipeline(std::uint32_t samples, const Material& material, bool shadows) {
  const std::uint32_t type = static_cast<std::uint32_t>(material.type);
  const bool baseTex = material.baseColorTexture.has_value();
  const bool emissionTex = material.emissionTexture.has_value();
  const bool blend = material.isTransparent();
  const std::uint64_t key = std::uint64_t(samples) | std::uint64_t(type) << 8 | std::uint64_t(baseTex) << 16 |
                            std::uint64_t(emissionTex) << 17 | std::uint64_t(shadows) << 18 |
                            std::uint64_t(blend) << 19;
  auto it = mainPipelines.find(key);
  if (it != mainPipelines.end()) return it->second.handle();
  PipelineDesc d;
  d.layout = layout;
  d.vertexSpirv = spirv::mesh_vert;
  d.fragmentSpirv = spirv::mesh_frag;
  d.colourFormat = colourFormat(samples);
  d.samples = sampleBits(samples);
  d.depthCompare = VK_COMPARE_OP_GREATER;  // reversed depth: nearer is greater
  d.blend = blend;
  d.depthWrite = !blend;
  d.fragmentConstants = {type, baseTex, emissionTex, shadows};
  return mainPipelines.emplace(key, Pipeline(device, d)).first->second.handle();
}

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
  settings_ = settings;
}

void Renderer::render(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb) {
  camera.validate();
  region.validate();
  if (fb.width() != region.regionWidth() || fb.height() != region.regionHeight())
    throw Error("frame buffer is " + std::to_string(fb.width()) + "x" + std::to_string(fb.height()) +
                " but the region is " + std::to_string(region.regionWidth()) + "x" +
                std::to_string(region.regionHeight()));
  if (&scene.device() != device_.get()) throw Error("scene and renderer use different devices");

  Impl& r = *impl_;
  SceneState& s = scene.state();
  s.prepare();
  const std::uint32_t transparentBase = r.sortDrawOrder(s, camera);
  const std::vector<glm::mat4> shadowViewProj = r.gatherLights(s, settings_);
  r.prepareFrame(s, camera, region, settings_, std::uint32_t(shadowViewProj.size()));

  RenderStats stats;
  VkCommandBuffer cmd = r.commands->buffer();
  check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo bi = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.layout, 0, 1, &r.frameSet, 0, nullptr);
  r.recordShadows(cmd, s, shadowViewProj, stats);
  const bool guided = settings_.visibility == Visibility::Guided;
  if (guided)
    r.recordGuided(cmd, s, settings_, !shadowViewProj.empty(), transparentBase, stats);
  else
    r.recordMain(cmd, s, settings_, !shadowViewProj.empty(), transparentBase, stats);
  const RenderTarget& t = *r.target;
  recordReadback(cmd, t.resolvedColour(), t.resolvedDepth(), t.colourReadback, t.depthReadback, t.width, t.height);
  check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  r.commands->submitAndWait("frame");
  if (r.shadowsPending) r.shadowsHeld = std::exchange(r.shadowsPending, std::nullopt);

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
  ensureHost(device, drawOrderBuffer, std::max<std::size_t>(drawOrder.size(), 1) * 4,
             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  if (!drawOrder.empty()) std::memcpy(drawOrderBuffer.mapped(), drawOrder.data(), drawOrder.size() * 4);

  return transparentBase;
}

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

// The frame's uniforms, targets sized for the region, and the frame's descriptors.
void Renderer::Impl::prepareFrame(const SceneState& s, const Camera& camera, const Region& region,
                                  const RenderSettings& settings, std::uint32_t shadowLayers) {
  const std::uint32_t w = region.regionWidth(), h = region.regionHeight();
  const VkSampleCountFlagBits samples = sampleBits(settings.msaaSamples);
  const glm::vec3 camPos(camera.cameraToWorld[3]);
  GpuFrame frame{};
  viewProj = camera.projection(region) * camera.worldToCamera();
  frame.viewProj = viewProj;
  frame.cameraPos = glm::vec4(camPos, 1.0f);
  frame.ambient = glm::vec4(s.environment.averageRadiance() + ambientFromEmitters, 0.0f);
  frame.counts = glm::uvec4(std::uint32_t(gpuLights.size()), 0u, 0u, 0u);
  std::memcpy(frameBuffer.mapped(), &frame, sizeof(frame));

  if (!target || target->width != w || target->height != h || target->samples != samples)
    target.emplace(device, w, h, colourFormat(settings.msaaSamples), samples);
  const std::uint32_t layers = std::max<std::uint32_t>(1, shadowLayers);
  if (!shadowMap || shadowMap->size() != settings.shadowMapSize || shadowMap->layers() < layers) {
    shadowMap.reset();
    shadowsHeld.reset();
    shadowMap.emplace(device, settings.shadowMapSize, layers);
  }
  const ShadowMap& sm = *shadowMap;

  {
    VkDescriptorBufferInfo bufs[5] = {
        {frameBuffer.handle(), 0, VK_WHOLE_SIZE},     {s.instanceBuffer.handle(), 0, VK_WHOLE_SIZE},
        {drawOrderBuffer.handle(), 0, VK_WHOLE_SIZE}, {s.materialBuffer.handle(), 0, VK_WHOLE_SIZE},
        {lightBuffer.handle(), 0, VK_WHOLE_SIZE},
    };
    VkDescriptorImageInfo shadowInfo{sm.sampler(), sm.image().view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet writes[6]{};
    for (std::uint32_t i = 0; i < 6; ++i) {
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
        writes[i].pImageInfo = &shadowInfo;
      }
    }
    vkUpdateDescriptorSets(device.handle(), 6, writes, 0, nullptr);
  }
}

// Shadow passes: opaque instances only, positions only.
void Renderer::Impl::recordShadows(VkCommandBuffer cmd, const SceneState& s,
                                   const std::vector<glm::mat4>& shadowViewProj, RenderStats& stats) {
  ShadowKey key{&s, s.version, shadowViewProj};
  if (shadowsHeld == key) return;  // still in SHADER_READ_ONLY_OPTIMAL from that frame
  shadowsHeld.reset();
  shadowsPending = std::move(key);
  const ShadowMap& sm = *shadowMap;
  imageBarrier(
      cmd, sm.image().handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
      shadowViewProj.empty() ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
      VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0,
      shadowViewProj.empty() ? VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT : VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT,
      shadowViewProj.empty() ? VK_ACCESS_SHADER_READ_BIT : VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, sm.layers());
  for (std::uint32_t layer = 0; layer < shadowViewProj.size(); ++layer) {
    VkRenderingAttachmentInfo da = vkStruct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
    da.imageView = sm.image().layerView(layer);
    da.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    da.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    da.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    da.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo ri = vkStruct<VkRenderingInfo>(VK_STRUCTURE_TYPE_RENDERING_INFO);
    ri.renderArea = {{0, 0}, {sm.size(), sm.size()}};
    ri.layerCount = 1;
    ri.pDepthAttachment = &da;
    vkCmdBeginRendering(cmd, &ri);
    VkViewport vp{0.0f, 0.0f, float(sm.size()), float(sm.size()), 0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &ri.renderArea);
    vkCmdSetDepthBias(cmd, 1.25f, 0.0f, 1.75f);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shadowPipeline.handle());
    PushConstants pc;
    pc.lightViewProj = shadowViewProj[layer];
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(pc), &pc);
    std::uint32_t bound = ~0u;
    for (const DrawGroup& g : s.opaqueGroups) {
      const MeshRecord& m = s.meshes[g.mesh];
      if (m.span.block != bound) s.geometry->bind(cmd, bound = m.span.block, 1);
      vkCmdDrawIndexed(cmd, m.indexCount, g.count, firstIndexOf(m), vertexOffsetOf(m), g.first);
      stats.shadowTriangles += std::uint64_t(m.indexCount / 3) * g.count;
    }
    vkCmdEndRendering(cmd);
    ++stats.shadowMaps;
  }
  if (!shadowViewProj.empty())
    imageBarrier(cmd, sm.image().handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                 VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                 VK_ACCESS_SHADER_READ_BIT, sm.layers());
}

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
}

// Begins the main pass: cleared, or (the guided late phase) loading what the
// early phase drew.
void Renderer::Impl::beginMain(VkCommandBuffer cmd, const RenderSettings& settings, bool load) {
  const RenderTarget& t = *target;
  const std::uint32_t w = t.width, h = t.height;
  VkRenderingAttachmentInfo ca = vkStruct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
  ca.imageView = t.colour.view();
  ca.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  ca.loadOp = load ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
  ca.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  ca.clearValue.color = {{settings.background.r, settings.background.g, settings.background.b, settings.background.a}};
  VkRenderingAttachmentInfo da = vkStruct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
  da.imageView = t.depth.view();
  da.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  da.loadOp = load ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
  da.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  da.clearValue.depthStencil = {0.0f, 0};  // reversed depth: 0 is the far plane
  if (t.multisampled()) {
    ca.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
    ca.resolveImageView = t.colourResolve.view();
    ca.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    // Averaging depths across an edge would invent surfaces; keep sample 0.
    da.resolveMode = VK_RESOLVE_MODE_SAMPLE_ZERO_BIT;
    da.resolveImageView = t.depthResolve.view();
    da.resolveImageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  }
  VkRenderingInfo ri = vkStruct<VkRenderingInfo>(VK_STRUCTURE_TYPE_RENDERING_INFO);
  ri.renderArea = {{0, 0}, {w, h}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &ca;
  ri.pDepthAttachment = &da;
  vkCmdBeginRendering(cmd, &ri);
  VkViewport vp{0.0f, 0.0f, float(w), float(h), 0.0f, 1.0f};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &ri.renderArea);
  boundPipeline = VK_NULL_HANDLE;
  boundBlock = boundMaterial = ~0u;
}

// Pipeline, geometry block, material set and push constants for one draw,
// each only when it differs from what the pass has bound.
void Renderer::Impl::bindDraw(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                              std::uint32_t meshIndex, std::uint32_t material) {
  VkPipeline p = mainPipeline(settings.msaaSamples, s.materials[material].material, shadows);
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
    bindDraw(cmd, s, settings, shadows, inst.mesh, inst.material);
    const MeshRecord& m = s.meshes[inst.mesh];
    vkCmdDrawIndexed(cmd, m.indexCount, 1, firstIndexOf(m), vertexOffsetOf(m), transparentBase + i);
    ++stats.drawCalls;
    stats.triangles += m.indexCount / 3;
    ++stats.objects;
  }
}

// Main pass drawing everything.
void Renderer::Impl::recordMain(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                                std::uint32_t transparentBase, RenderStats& stats) {
  prepareAttachments(cmd);
  beginMain(cmd, settings, false);
  drawOpaque(cmd, s, settings, shadows, VK_NULL_HANDLE, stats);
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
  beginMain(cmd, settings, false);
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

  beginMain(cmd, settings, true);
  drawOpaque(cmd, s, settings, shadows, culler->lateCommands(), stats);
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
  camera.validate();
  region.validate();
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
