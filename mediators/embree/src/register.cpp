#include "tsr/med/embree/register.hpp"

#include "embree_viewport.hpp"
#include "tsr/embree/device.hpp"

namespace tsr::med {

void registerEmbree(ViewportRegistry& registry) {
  registry.add("embree", [](ViewportSettings settings, ContextPool& contexts) -> std::unique_ptr<Viewport> {
    std::string key = "embree:" + std::to_string(settings.root) + ":" + std::to_string(settings.background);
    sg::ContainerId root = settings.root, background = settings.background;
    auto context = contexts.acquire<embree_mediator::EmbreeContext>(key, [&] {
      return std::make_shared<embree_mediator::EmbreeContext>(std::make_shared<embree::Device>(), root, background);
    });
    return std::make_unique<embree_mediator::EmbreeViewport>(std::move(settings), std::move(context));
  });
}

}  // namespace tsr::med
