// Renders builtin:cornell at 16x16 through the installed Embree mediator;
// exit 0 when the image has light in it.
#include <cstdio>

#include "tsr/med/embree/register.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/replica.hpp"

int main() {
  tsr::sg::Scene scene;
  const auto imported = tsr::sg::importScene(scene, "builtin:cornell", {});
  tsr::sg::Replica replica;
  replica.apply(scene.commit());
  tsr::med::ViewportRegistry registry;
  tsr::med::registerEmbree(registry);
  tsr::med::ContextPool contexts;
  tsr::med::ViewportSettings settings;
  settings.backend = "embree";
  settings.root = imported.root;
  settings.parameters.set("spp", std::int64_t{2});
  settings.parameters.set("threads", std::int64_t{1});
  auto viewport = registry.create(settings, contexts);
  const auto* camera = replica.scene().find<tsr::sg::Camera>(imported.cameras.front());
  tsr::med::FrameBuffer image;
  viewport->render(replica, tsr::med::View::fromCamera(*camera, 16, 16), image);
  double sum = 0;
  for (const auto& c : image.colour) sum += c.r + c.g + c.b;
  const double mean = sum / (3.0 * image.colour.size());
  std::printf("consumer: %ux%u image, mean %.4f\n", image.width, image.height, mean);
  return mean > 0.01 ? 0 : 1;
}
