#include "tsr/med/embree/register.hpp"

#include "embree_parameters.hpp"

#include "embree_viewport.hpp"
#include "photon_viewport.hpp"
#include "tsr/embree/device.hpp"

namespace tsr::med {

void registerEmbree(ViewportRegistry& registry) {
  registry.add(
      "embree", embree_mediator::embreeCapabilities(),
      [](ViewportSettings settings, ContextPool& contexts) -> std::unique_ptr<Viewport> {
        std::string key = "embree:" + std::to_string(settings.root) + ":" + std::to_string(settings.background);
        sg::ContainerId root = settings.root, background = settings.background;
        // Photon animations keep two scenes of their own (the one shown and one
        // posed ahead), shared with no other viewport.
        if (const auto temporal = embree_mediator::embreeParameters().choice(settings.parameters, "temporal");
            temporal == "photons" || temporal == "objectPca") {
          return std::make_unique<embree_mediator::PhotonViewport>(std::move(settings),
                                                                   std::make_shared<embree::Device>());
        }
        auto context = contexts.acquire<embree_mediator::EmbreeContext>(key, [&] {
          return std::make_shared<embree_mediator::EmbreeContext>(std::make_shared<embree::Device>(), root, background);
        });
        return std::make_unique<embree_mediator::EmbreeViewport>(std::move(settings), std::move(context));
      });
}

}  // namespace tsr::med
