#include "tsr/med/coverage/register.hpp"

#include "coverage_viewport.hpp"
#include "tsr/cov/embree_id_renderer.hpp"

namespace tsr::med {

void registerCoverage(ViewportRegistry& registry) {
  registry.add("coverage", [](ViewportSettings settings, ContextPool& contexts) -> std::unique_ptr<Viewport> {
    const int threads = static_cast<int>(settings.parameters.getInt("threads", 0, 0, 4096));
    const std::string key = "coverage:" + std::to_string(settings.root) + ":" + std::to_string(threads);
    const sg::ContainerId root = settings.root;
    auto context = contexts.acquire<coverage_mediator::CoverageContext>(key, [&] {
      auto make = [threads]() -> std::unique_ptr<cov::IdRenderer> {
        cov::EmbreeIdSettings s;
        s.threads = threads;
        return std::make_unique<cov::EmbreeIdRenderer>(s);
      };
      return std::make_shared<coverage_mediator::CoverageContext>(make, root);
    });
    return std::make_unique<coverage_mediator::CoverageViewport>(std::move(settings), std::move(context));
  });
}

}  // namespace tsr::med
