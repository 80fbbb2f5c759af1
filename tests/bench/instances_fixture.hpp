#pragma once
// builtin:instances:10000 imported once per benchmark program, with a
// registry holding the one back-end measured, and the transforms that each
// carry one object (what the edit benchmarks move).
#include <string>
#include <vector>

#include "tsr/med/view.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/sg/import/importer.hpp"

namespace tsr::bench {

struct InstancesFixture {
  InstancesFixture(std::string backendName, void (*registerBackend)(med::ViewportRegistry&),
                   med::Parameters viewportParameters = {})
      : backend(std::move(backendName)), parameters(std::move(viewportParameters)) {
    imported = sg::importScene(source, "builtin:instances:10000");
    source.commit();
    registerBackend(registry);
    for (auto id : source.ids())
      if (auto* t = source.find<sg::Transform>(id); t && t->children().size() == 1) transforms.push_back(t);
  }

  med::ViewportSettings settings() const {
    med::ViewportSettings s;
    s.backend = backend;
    s.root = imported.root;
    s.background = imported.background;
    s.parameters = parameters;
    return s;
  }
  med::View view(const sg::Scene& scene, std::uint32_t width, std::uint32_t height) const {
    return med::View::fromCamera(*scene.find<sg::Camera>(imported.cameras.front()), width, height);
  }
  // One pixel in the middle of a 64x64 image: a render that costs only what
  // bringing the back-end up to date costs.
  med::View onePixel(const sg::Scene& scene) const { return view(scene, 64, 64).cropped({32, 32, 33, 33}); }

  std::string backend;
  med::Parameters parameters;
  sg::Scene source;
  sg::ImportResult imported;
  med::ViewportRegistry registry;
  std::vector<sg::Transform*> transforms;
};

}  // namespace tsr::bench
