#include "vulkan_viewport.hpp"

#include <chrono>

#include "translation.hpp"
#include "tsr/med/view_translation.hpp"

namespace tsr::med::vulkan_mediator {

const BackendCapabilities& vulkanCapabilities() {
  static const BackendCapabilities capabilities{
      ParameterTable("vulkan", {integerParameter("msaa", 1, 1, 4, "samples per pixel of multisampling: 1 or 4"),
                                flagParameter("shadows", true, "shadow maps for spot and directional lights"),
                                integerParameter("shadowMapSize", 1024, 16, 8192, "shadow map side, texels"),
                                integerParameter("emitterLights", 32, 0, 256, "emissive triangles lit as point lights"),
                                flagParameter("emitterAmbient", true, "emitters' remaining light as ambient"),
                                flagParameter("reflectionProbe", true,
                                              "mirrors, glass and glossy surfaces reflect the scene, not only "
                                              "the environment"),
                                choiceParameter("visibility", "all", {"all", "guided"},
                                                "all: draw every object; guided: draw what was visible last frame, "
                                                "then what a depth-pyramid test finds newly visible")}),
      false};
  return capabilities;
}

VulkanViewport::VulkanViewport(ViewportSettings settings, std::shared_ptr<VulkanContext> context)
    : Viewport(std::move(settings)), context_(std::move(context)) {}

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
