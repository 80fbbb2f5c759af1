#pragma once
// Renderer::Impl, shared by the files that record a frame: renderer.cpp
// (set-up, frame preparation, draw order, read-back), frame_lights.cpp
// (lights and shadow maps) and main_pass.cpp (the main pass, full or
// guided). Private to the back-end.
#include "tsr/vk/renderer.hpp"

#include "culling/depth_pyramid.hpp"
#include "culling/occlusion_culler.hpp"
#include "gpu_types.hpp"
#include "lights/emitter_lights.hpp"
#include "lights/shadow_map.hpp"
#include "lights/shadow_update.hpp"
#include "passes/id_pass.hpp"
#include "reflections/brdf_table.hpp"
#include "resources/buffer.hpp"
#include "resources/command_slot.hpp"
#include "resources/pipeline.hpp"
#include "resources/readback.hpp"
#include "resources/render_target.hpp"
#include "scene/scene_state.hpp"
#include "spirv.hpp"

#include "tsr/vk/error.hpp"
#include "vk_struct.hpp"

#include <spdlog/spdlog.h>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>

namespace tsr::vk {

inline constexpr std::uint32_t kMaxShadowMaps = 8;

VkSampleCountFlagBits sampleBits(std::uint32_t samples);
// A host-visible buffer of at least `needed` bytes; grown geometrically.
void ensureHost(const Device& device, Buffer& buffer, VkDeviceSize needed, VkBufferUsageFlags usage);

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
  Pipeline maskedShadowPipeline;  // glTF MASK materials: cut by their base colour's alpha
  Pipeline volumeBackPipeline;    // see-through volumes' back faces, depth only

  Buffer frameBuffer;  // GpuFrame uniform
  Buffer lightBuffer;
  Buffer drawOrderBuffer;
  std::optional<RenderTarget> target;
  // The reflection probes (reflection_probe.cpp): the scene's, from the
  // centre of its bounds, and up to kObjectProbes of mirrors and glass
  // objects, from their own centres; six layers each in two images, one
  // sampled while the other is drawn, and what the current one shows.
  static constexpr std::uint32_t kProbeSize = 128;
  static constexpr std::uint32_t kObjectProbes = 4;  // GpuFrame::objectProbes
  static constexpr std::uint32_t kProbeLayers = 6 * (1 + kObjectProbes);
  Image probe[2];
  Image probeDepth;
  std::uint32_t probeCurrent = 0;
  bool probeFresh = false;
  struct ProbeKey {
    std::uint64_t scene = 0;  // SceneState::uid
    std::uint64_t version = 0;
    std::uint64_t irradianceVersion = 0;  // the faces' diffuse light reads the irradiance volume
    bool operator==(const ProbeKey&) const = default;
  };
  std::optional<ProbeKey> probeHeld;
  glm::vec3 probeCentreHeld{0.0f};
  // What the held probe is seen in (wantsProbe()).
  enum class ProbeUse { None, Mirrors, RoughReflections };
  ProbeUse probeUseHeld = ProbeUse::None;
  ProbeUse probeWanted = ProbeUse::None;  // wantsProbe() of the scene version probeWantedFor
  std::optional<ProbeKey> probeWantedFor;
  struct ObjectProbe {
    glm::vec3 centre{0.0f};
    float radius = 0.0f;
    std::uint32_t slot = 0;  // the instance's
    bool operator==(const ObjectProbe&) const = default;
  };
  std::vector<ObjectProbe> objectProbesHeld, objectProbesWanted;  // objectProbes(), held and of probeWantedFor
  Image probeLevels;     // prefilterProbe() of the held probe (probe_prefilter.hpp)
  Buffer probeReadback;  // its faces, for prefilterProbe()
  GpuFrame frameData{};
  bool drawingProbe = false;       // drawOpaque leaves out what samples the probe
  bool drawingSceneProbe = false;  // ... and glossy instances inside the scene (hiddenFromProbe)
  static bool reflective(const Material& m) { return m.type == MaterialType::Mirror || m.type == MaterialType::Glass; }
  // Glossy enough for the probe to show in its reflections.
  static bool glossy(const Material& m) {
    return m.type == MaterialType::Conductor || m.type == MaterialType::Dielectric ||
           (m.type == MaterialType::MetallicRoughness &&
            (m.metallic > 0.0f || m.roughness < 0.9f || m.metallicRoughnessTexture));
  }
  // A glossy instance inside the scene (not a wall of it) is left out of
  // the probe, as mirrors are: it would reflect itself. Rough glass is left
  // out also where it touches the scene's bounds (a ball on the floor): it
  // would be seen, dark, through itself.
  static bool hiddenFromProbe(const SceneState& s,
                              std::uint32_t slot);  // this frame's uniform, as prepareFrame wrote it
  // Reversed depth of the nearer of opaque geometry and see-through volumes'
  // back faces (volume.frag reads it). Single-sample, region-sized; kept in
  // SHADER_READ_ONLY_OPTIMAL between frames.
  std::optional<Image> volumeBack;
  bool volumeBackFresh = false;  // made this frame: still UNDEFINED
  VkSampler depthSampler = VK_NULL_HANDLE;
  Image brdfTable;  // the split-sum table, made once (brdf_table.hpp)
  VkSampler tableSampler = VK_NULL_HANDLE;
  bool fog = false;             // this frame's environment has a medium
  glm::vec4 clearColour{0.0f};  // the background, seen through the fog
  std::optional<ShadowMap> shadowMap;
  // What the shadow maps hold. They do not depend on the camera, so they are
  // drawn again only when the scene (any edit bumps its version) or the
  // lights' projections change, and after edits of single instances only
  // where those instances were and are (lights/shadow_update.hpp).
  std::optional<ShadowContents> shadowsHeld;     // after a completed frame
  std::optional<ShadowContents> shadowsPending;  // recorded this frame
  std::unique_ptr<IdPass> idPass;                // made on first renderIds
  std::unique_ptr<OcclusionCuller> culler;       // made on the first guided frame
  std::unique_ptr<DepthPyramid> pyramid;
  glm::mat4 viewProj{1.0f};                   // this frame's
  VkPipeline boundPipeline = VK_NULL_HANDLE;  // in the current main pass
  std::uint32_t boundBlock = ~0u;
  std::uint32_t boundMaterial = ~0u;

  std::vector<std::uint32_t> drawOrder;
  std::vector<GpuLight> gpuLights;
  glm::vec3 ambientFromEmitters{0.0f};  // emitterAmbient() of this frame
  // setIrradianceVolume's volume and its upload: kFaces vec4 per
  // probe, then the distance maps, two texels to a vec4 (probe_volume.glsl).
  std::shared_ptr<const backend::IrradianceVolume> irradianceVolume;
  Buffer irradianceBuffer;
  std::uint64_t irradianceVersion = 0;  // bumped by every upload: what was drawn with the old one is stale
  std::vector<std::uint32_t> transparentSorted;

  explicit Impl(const Device& d);
  ~Impl();
  VkFormat colourFormat(std::uint32_t samples);
  VkPipeline mainPipeline(std::uint32_t samples, const Material& material, bool shadows,
                          Primitive primitive = Primitive::Triangles);
  // Whether see-through volumes are drawn in this frame.
  bool drawsVolumes() const;

  // The passes of one frame, in order. Returns where transparent instances
  // start in the draw order (lines and points follow them).
  std::uint32_t sortDrawOrder(const SceneState& s, const Camera& camera);
  // Fills the light buffer; returns the shadowed lights' view-projections.
  std::vector<glm::mat4> gatherLights(SceneState& s, const RenderSettings& settings);
  void addEmitterLights(SceneState& s, const RenderSettings& settings, bool shadows,
                        std::vector<glm::mat4>& shadowViewProj);
  void prepareFrame(const SceneState& s, const Camera& camera, const Region& region, const RenderSettings& settings,
                    std::uint32_t shadowLayers);
  ProbeUse wantsProbe(const SceneState& s) const;
  static std::vector<ObjectProbe> objectProbes(const SceneState& s);
  void prefilterProbeLevels(const SceneState& s);
  void ensureProbeImages();
  void writeProbeDescriptor(const SceneState& s, const Image& image);
  void prepareProbeLayouts(VkCommandBuffer cmd, const Image& into);
  // Draws the probe if it is wanted and stale; leaves the uniform and the
  // descriptors as the frame needs them.
  void updateProbe(const SceneState& s, const RenderSettings& settings, GpuFrame& frame, bool shadows,
                   RenderStats& stats);
  // Records what of the shadow maps is stale; false when nothing was.
  bool recordShadows(VkCommandBuffer cmd, const SceneState& s, const std::vector<glm::mat4>& shadowViewProj,
                     RenderStats& stats);
  void prepareAttachments(VkCommandBuffer cmd);
  void beginMain(VkCommandBuffer cmd, bool load);
  void bindDraw(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                std::uint32_t meshIndex, std::uint32_t material);
  void drawOpaque(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                  VkBuffer indirect, RenderStats& stats);
  void drawTransparent(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                       std::uint32_t transparentBase, RenderStats& stats);
  // Lines and points, unlit, never culled; their draw order follows the transparent instances'.
  void drawLines(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings,
                 std::uint32_t transparentBase, RenderStats& stats);
  // Ends the main pass, draws the volumes' back faces over a copy of the
  // opaque depth into volumeBack, and resumes the main pass.
  void recordVolumeBacks(VkCommandBuffer cmd, const SceneState& s, std::uint32_t transparentBase);
  void recordMain(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                  std::uint32_t transparentBase, RenderStats& stats);
  void recordGuided(VkCommandBuffer cmd, const SceneState& s, const RenderSettings& settings, bool shadows,
                    std::uint32_t transparentBase, RenderStats& stats);
  void testAgainstDepth(VkCommandBuffer cmd, const std::function<void()>& test);
  void readColour(FrameBuffer& fb) const;
};

}  // namespace tsr::vk
