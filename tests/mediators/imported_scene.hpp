#pragma once
// A source scene imported from a file or built-in, with a registry holding
// the one back-end under test: the viewport settings and camera views over
// it. Shared by the mediator test rig and the benchmark fixtures, so it
// needs no test framework.
#include <cstdint>
#include <string>

#include "tsr/med/view.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/sg/import/importer.hpp"

namespace tsr::test {

struct ImportedScene {
  ImportedScene(std::string backendName, void (*registerBackend)(med::ViewportRegistry&), const std::string& scene,
                med::Parameters viewportParameters = {})
      : backend(std::move(backendName)), parameters(std::move(viewportParameters)) {
    imported = sg::importScene(source, scene);
    registerBackend(registry);
  }

  // A viewport of the back-end over the whole imported scene.
  med::ViewportSettings settings() const {
    med::ViewportSettings s;
    s.backend = backend;
    s.root = imported.root;
    s.background = imported.background;
    s.parameters = parameters;
    return s;
  }
  // The imported scene's first camera, as `scene` holds it now.
  med::View view(const sg::Scene& scene, std::uint32_t width, std::uint32_t height) const {
    return med::View::fromCamera(*scene.find<sg::Camera>(imported.cameras.front()), width, height);
  }

  std::string backend;
  med::Parameters parameters;
  sg::Scene source;
  sg::ImportResult imported;
  med::ViewportRegistry registry;
};

}  // namespace tsr::test
