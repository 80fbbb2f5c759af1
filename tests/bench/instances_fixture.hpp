#pragma once
// builtin:instances:10000 imported once per benchmark program, with a
// registry holding the one back-end measured, and the transforms that each
// carry one object (what the edit benchmarks move).
#include <string>
#include <vector>

#include "../mediators/imported_scene.hpp"

namespace tsr::bench {

struct InstancesFixture : test::ImportedScene {
  InstancesFixture(std::string backendName, void (*registerBackend)(med::ViewportRegistry&),
                   med::Parameters viewportParameters = {})
      : ImportedScene(std::move(backendName), registerBackend, "builtin:instances:10000",
                      std::move(viewportParameters)) {
    source.commit();
    for (auto id : source.ids())
      if (auto* t = source.find<sg::Transform>(id); t && t->children().size() == 1) transforms.push_back(t);
  }

  // One pixel in the middle of a 64x64 image: a render that costs only what
  // bringing the back-end up to date costs.
  med::View onePixel(const sg::Scene& scene) const { return view(scene, 64, 64).cropped({32, 32, 33, 33}); }

  std::vector<sg::Transform*> transforms;
};

}  // namespace tsr::bench
