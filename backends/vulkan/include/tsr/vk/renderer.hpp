#pragma once

#include "tsr/backend/irradiance_volume.hpp"
#include "tsr/vk/device.hpp"
#include "tsr/vk/framebuffer.hpp"
#include "tsr/vk/id_buffer.hpp"
#include "tsr/vk/scene.hpp"
#include "tsr/vk/vocabulary.hpp"

#include <glm/vec4.hpp>

#include <cstdint>
#include <memory>

namespace tsr::vk {

// Which opaque objects a frame draws: all of them, or those seen last frame
// plus those a depth-pyramid test finds may have become visible (two-phase
// occlusion culling; the same image once the camera is still).
enum class Visibility : std::uint8_t { All, Guided };

struct RenderSettings {
  std::uint32_t msaaSamples = 1;  // 1 or 4
  Visibility visibility = Visibility::All;
  bool shadows = true;  // shadow maps for spot and directional lights (and flat emitters)
  std::uint32_t shadowMapSize = 1024;
  // Emissive geometry lights the scene through at most this many area-like
  // lights (patches of the emissive meshes, merged when there are more); 0:
  // emissive surfaces glow but light nothing.
  std::uint32_t emitterLights = 32;
  // Adds the emitters' interreflected light as ambient (Cohen's ambient
  // term, see src/emitter_lights.hpp), so a room lit by a panel is not
  // black wherever the panel does not shine directly.
  bool emitterAmbient = true;
  // The reflection probe: mirrors, glass and glossy surfaces reflect the
  // scene (light that has bounced once); false: they reflect the
  // environment only, as with direct light alone.
  bool reflectionProbe = true;
  // The camera's thin lens blurs what is out of focus, as in the path
  // tracer (src/post/depth_of_field.hpp); false: a pinhole image.
  bool depthOfField = true;
  glm::vec4 background{0.0f};  // colour and alpha where nothing is drawn
  bool operator==(const RenderSettings&) const = default;
};

struct RenderStats {
  std::uint32_t drawCalls = 0;    // main pass
  std::uint64_t triangles = 0;    // main pass, all instances drawn
  std::uint32_t objects = 0;      // main pass, instances drawn
  std::uint32_t lateObjects = 0;  // guided: drawn because they became visible this frame
  std::uint32_t shadowMaps = 0;   // shadow passes rendered
  std::uint64_t shadowTriangles = 0;
  // Reflection probes drawn (six faces each): when mirrors or glass are in
  // the scene and it changed since the last one.
  std::uint32_t probes = 0;
};

// Rasterizes a Scene into a FrameBuffer: shadow passes, then opaque
// instances grouped by (material, mesh) and drawn instanced, then
// transparent instances back to front; MSAA resolve; readback. Each render
// waits for the GPU, so scenes may be edited as soon as it returns.
class Renderer {
 public:
  explicit Renderer(std::shared_ptr<Device> device, RenderSettings settings = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  const RenderSettings& settings() const { return settings_; }
  void setSettings(const RenderSettings& settings);  // throws on unsupported sample counts
  // Light bounced off the scene, computed elsewhere (a path tracer's
  // probes): diffuse surfaces read it instead of the constant ambient term
  // of the environment's average and the emitters' interreflection. Null:
  // that ambient term. Uploaded when the volume or its version changes;
  // throws for a volume whose arrays do not match its probes.
  void setIrradianceVolume(std::shared_ptr<const backend::IrradianceVolume> volume);

  // fb must be region-sized. Same scene and inputs give identical pixels.
  // With a lens, a crop of the image is drawn with a margin its blur
  // gathers from, so tiles of one image join without seams.
  void render(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb);

  // The id pass for coverage: each opaque instance's object id
  // (Scene::setInstanceObject) through every pixel centre, no MSAA, no
  // shading; transparent instances (material opacity < 1) are left out, so
  // pixels behind them show what lies further back. `ids` must be
  // region-sized. Independent of the settings.
  void renderIds(Scene& scene, const Camera& camera, const Region& region, IdBuffer& ids);

  const RenderStats& lastStats() const { return stats_; }

 private:
  struct Impl;
  void renderSharp(Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb);
  std::shared_ptr<Device> device_;
  RenderSettings settings_;
  RenderStats stats_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tsr::vk
