#include "tsr/med/coverage/register.hpp"

#include "coverage_viewport.hpp"
#include "tsr/cov/embree_id_renderer.hpp"
#if TSR_COVERAGE_HAVE_VULKAN
#include "vulkan_id_renderer.hpp"
#endif

namespace tsr::med {

namespace {
const BackendCapabilities& coverageCapabilities(){static const BackendCapabilities capabilities{
    ParameterTable("coverage",
                   {
                     integerParameter("threads", 0, 0, 4096, "id pass threads (0: all)"),
#if TSR_COVERAGE_HAVE_VULKAN
                         choiceParameter("engine", "embree", {"embree", "vulkan"},
                                         "id pass: rays through pixel centres or the rasterizer")
                   }),
#else
                      choiceParameter("engine", "embree", {"embree"}, "id pass: rays through pixel centres")}),
#endif
    false};
return capabilities;
}  // namespace
}  // namespace tsr::med

void registerCoverage(ViewportRegistry& registry) {
  registry.add("coverage", coverageCapabilities(),
               [](ViewportSettings settings, ContextPool& contexts) -> std::unique_ptr<Viewport> {
                 const ParameterTable& t = coverageCapabilities().parameters;
                 const int threads = static_cast<int>(t.integer(settings.parameters, "threads"));
                 const std::string engine = t.choice(settings.parameters, "engine");
                 const std::string key =
                     "coverage:" + engine + ":" + std::to_string(settings.root) + ":" + std::to_string(threads);
                 const sg::ContainerId root = settings.root;
                 auto context = contexts.acquire<coverage_mediator::CoverageContext>(key, [&] {
                   auto make = [threads, engine]() -> std::unique_ptr<cov::IdRenderer> {
#if TSR_COVERAGE_HAVE_VULKAN
                     if (engine == "vulkan") return std::make_unique<coverage_mediator::VulkanIdRenderer>();
#endif
                     cov::EmbreeIdSettings s;
                     s.threads = threads;
                     return std::make_unique<cov::EmbreeIdRenderer>(s);
                   };
                   return std::make_shared<coverage_mediator::CoverageContext>(
                       std::make_shared<coverage_mediator::IdRendererSource>(coverage_mediator::IdRendererSource{make}),
                       root);
                 });
                 return std::make_unique<coverage_mediator::CoverageViewport>(std::move(settings), std::move(context));
               });
}

}  // namespace tsr::med
