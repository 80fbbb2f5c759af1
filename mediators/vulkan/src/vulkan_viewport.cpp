#include "vulkan_viewport.hpp"

#include <chrono>

#include <spdlog/spdlog.h>

#include "translation.hpp"
#include "tsr/med/view_translation.hpp"

namespace tsr::med::vulkan_mediator {

const BackendCapabilities& vulkanCapabilities() {
  static const BackendCapabilities capabilities{
      .parameters = ParameterTable(
          "vulkan", {integerParameter("msaa", 1, 1, 4, "samples per pixel of multisampling: 1 or 4"),
                     flagParameter("shadows", true, "shadow maps for spot and directional lights"),
                     integerParameter("shadowMapSize", 1024, 16, 8192, "shadow map side, texels"),
                     integerParameter("emitterLights", 32, 0, 256, "emissive triangles lit as point lights"),
                     flagParameter("emitterAmbient", true, "emitters' remaining light as ambient"),
                     flagParameter("reflectionProbe", true,
                                   "mirrors, glass and glossy surfaces reflect the scene, not only "
                                   "the environment"),
                     choiceParameter("bouncedLight", "auto", {"auto", "probes", "ambient"},
                                     "diffuse light that bounced: probes: an irradiance volume the "
                                     "path tracer traces; ambient: one constant term; auto: probes "
                                     "up to 256 MB of geometry"),
                     integerParameter("probesPerFrame", 128, 1, 4096,
                                      "probes traced again per frame after the scene changed, in "
                                      "an interactive session (the viewer; elsewhere all at once)"),
                     choiceParameter("visibility", "all", {"all", "guided"},
                                     "all: draw every object; guided: draw what was visible last frame, "
                                     "then what a depth-pyramid test finds newly visible"),
                     flagParameter("depthOfField", true,
                                   "the camera's lens blurs what is out of focus, from the depth "
                                   "after the frame")}),
      .progressive = false,
      .depthOfField = true};
  return capabilities;
}

VulkanViewport::VulkanViewport(ViewportSettings settings, std::shared_ptr<VulkanContext> context,
                               std::shared_ptr<BouncedLight> bouncedLight)
    : Viewport(std::move(settings)), context_(std::move(context)), bouncedLight_(std::move(bouncedLight)) {}

// The irradiance volume this frame reads, brought up to date; null for the
// constant ambient term.
std::shared_ptr<const backend::IrradianceVolume> VulkanViewport::bouncedLight(const sg::Replica& replica,
                                                                              const RenderControl& control,
                                                                              RenderStats& stats) {
  constexpr std::uint64_t kAutoGeometryBytes = 256ull << 20;
  const Parameters& p = settings_.parameters;
  const ParameterTable& t = vulkanCapabilities().parameters;
  const std::string mode = t.choice(p, "bouncedLight");
  if (!bouncedLight_ && mode == "probes" && !warnedNoBouncedLight_) {
    spdlog::warn("vulkan: bouncedLight=probes, but no back-end of this build traces bounced light (the path "
                 "tracer is not built in): the ambient term lights diffuse surfaces");
    warnedNoBouncedLight_ = true;
  }
  if (!bouncedLight_ || mode == "ambient" ||
      (mode == "auto" && context_->adapter.scene().geometryBytesHeld() > kAutoGeometryBytes))
    return nullptr;
  // Only an interactive frame may show the probes half traced again.
  const BouncedLightState state = bouncedLight_->update(
      replica, control.interactive ? static_cast<std::uint32_t>(t.integer(p, "probesPerFrame")) : 0u);
  stats.rays += state.rays;
  staleProbes_ = state.staleProbes;
  return state.volume;
}

vk::RenderSettings VulkanViewport::renderSettings() const {
  const Parameters& p = settings_.parameters;
  vk::RenderSettings s;
  const ParameterTable& t = vulkanCapabilities().parameters;
  const auto msaa = t.integer(p, "msaa");
  if (msaa != 1 && msaa != 4) throw BadParameterValue("parameter msaa = " + std::to_string(msaa) + ": expected 1 or 4");
  s.msaaSamples = static_cast<std::uint32_t>(msaa);
  s.shadows = t.flag(p, "shadows");
  s.shadowMapSize = static_cast<std::uint32_t>(t.integer(p, "shadowMapSize"));
  s.emitterLights = static_cast<std::uint32_t>(t.integer(p, "emitterLights"));
  s.emitterAmbient = t.flag(p, "emitterAmbient");
  s.reflectionProbe = t.flag(p, "reflectionProbe");
  s.depthOfField = t.flag(p, "depthOfField");
  s.visibility = t.choice(p, "visibility") == "guided" ? vk::Visibility::Guided : vk::Visibility::All;
  s.background = backgroundColour(context_->adapter.environment());
  return s;
}

SceneAdapter::Update VulkanViewport::synchronize(const sg::Replica& replica) {
  std::lock_guard lock(context_->shared->mutex);
  return context_->adapter.catchUp(replica);
}

RenderStats VulkanViewport::render(const sg::Replica& replica, const View& view, FrameBuffer& out,
                                   const RenderControl& control) {
  view.validate();
  const auto start = std::chrono::steady_clock::now();
  std::lock_guard lock(context_->shared->mutex);
  RenderStats stats;
  stats.update = context_->adapter.catchUp(replica);
  stats.syncSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (control.cancel && control.cancel->load()) return stats;

  // Parameters are read after catching up: the background colour comes from the scene.
  const vk::RenderSettings settings = renderSettings();
  if (!renderer_)
    renderer_ = std::make_unique<vk::Renderer>(context_->shared->device, settings);
  else
    renderer_->setSettings(settings);

  const vk::Camera camera = cameraOf(view);
  const vk::Region region = regionOf(view);
  vk::FrameBuffer fb(region.regionWidth(), region.regionHeight());
  renderer_->setIrradianceVolume(bouncedLight(replica, control, stats));
  renderer_->render(context_->adapter.scene(), camera, region, fb);

  out = FrameBuffer(fb.width(), fb.height());
  out.colour = fb.colourImage();
  out.depth = fb.depthImage();
  stats.samples = settings.msaaSamples;
  if (control.progress) control.progress(1.0);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace tsr::med::vulkan_mediator
