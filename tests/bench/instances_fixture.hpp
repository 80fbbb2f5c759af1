#pragma once
// builtin:instances:N (10000 unless told) imported once per benchmark
// program, with a registry holding the one back-end measured, and what the
// edit benchmarks change: the transforms that each carry one object, the
// materials and the geometries.
#include <cstdint>
#include <string>
#include <vector>

#include "../mediators/imported_scene.hpp"

namespace tsr::bench {

struct InstancesFixture : test::ImportedScene {
  InstancesFixture(std::string backendName, void (*registerBackend)(med::ViewportRegistry&),
                   med::Parameters viewportParameters = {}, std::int64_t count = 10000)
      : ImportedScene(std::move(backendName), registerBackend, "builtin:instances:" + std::to_string(count),
                      std::move(viewportParameters)) {
    source.commit();
    for (auto id : source.ids()) {
      if (auto* t = source.find<sg::Transform>(id); t && t->children().size() == 1) transforms.push_back(t);
      if (auto* m = source.find<sg::SurfaceMaterial>(id)) materials.push_back(m);
      if (auto* g = source.find<sg::Geometry>(id)) geometries.push_back(g);
    }
  }

  // One pixel in the middle of a 64x64 image: a render that costs only what
  // bringing the back-end up to date costs.
  med::View onePixel(const sg::Scene& scene) const { return view(scene, 64, 64).cropped({32, 32, 33, 33}); }

  std::vector<sg::Transform*> transforms;
  std::vector<sg::SurfaceMaterial*> materials;
  std::vector<sg::Geometry*> geometries;
};

}  // namespace tsr::bench
