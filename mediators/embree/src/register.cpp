#include "tsr/med/embree/register.hpp"

#include "embree_parameters.hpp"

#include "embree_viewport.hpp"
#include "photon_viewport.hpp"
#include "probe_light.hpp"
#include "tsr/embree/device.hpp"

namespace tsr::med {

namespace {
// The converted scene of a root and background, shared by the Embree
// viewports on them and the bounced light traced in it.
std::shared_ptr<embree_mediator::EmbreeContext> sharedContext(sg::ContainerId root, sg::ContainerId background,
                                                              ContextPool& contexts) {
  const std::string key = "embree:" + std::to_string(root) + ":" + std::to_string(background);
  return contexts.acquire<embree_mediator::EmbreeContext>(key, [&] {
    return std::make_shared<embree_mediator::EmbreeContext>(std::make_shared<embree::Device>(), root, background);
  });
}
}  // namespace

void registerEmbree(ViewportRegistry& registry) {
  registry.add("embree", embree_mediator::embreeCapabilities(),
               [](ViewportSettings settings, ContextPool& contexts) -> std::unique_ptr<Viewport> {
                 sg::ContainerId root = settings.root, background = settings.background;
                 // Photon animations keep two scenes of their own (the one shown and one
                 // posed ahead), shared with no other viewport.
                 if (const auto temporal = embree_mediator::embreeParameters().choice(settings.parameters, "temporal");
                     temporal == "photons" || temporal == "objectPca") {
                   return std::make_unique<embree_mediator::PhotonViewport>(std::move(settings),
                                                                            std::make_shared<embree::Device>());
                 }
                 return std::make_unique<embree_mediator::EmbreeViewport>(std::move(settings),
                                                                          sharedContext(root, background, contexts));
               });
  // The rasterizer's bounced light, traced in the scene the Embree viewports
  // on the same root and background convert.
  registry.addBouncedLight("embree", [](sg::ContainerId root, sg::ContainerId background, ContextPool& contexts) {
    const std::string key = "embree-probes:" + std::to_string(root) + ":" + std::to_string(background);
    auto context = sharedContext(root, background, contexts);  // not inside acquire: the pool locks
    return std::static_pointer_cast<BouncedLight>(contexts.acquire<embree_mediator::ProbeLight>(
        key, [&] { return std::make_shared<embree_mediator::ProbeLight>(context); }));
  });
}

}  // namespace tsr::med
