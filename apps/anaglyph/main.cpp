// tessera-anaglyph SCENE [--nodes A,B --token-file F] [--output FILE] [options]
// Red/cyan stereo: the left and right eye rendered here (one converted
// scene, two views) or on two render nodes (cluster stereo mode), combined
// per pixel (red-cyan or Dubois), shown in a window with navigation or,
// with --output, written as one frame. Errors: one "error:" line, exit 2.
#include <spdlog/spdlog.h>

#include <iostream>

#include "anaglyph_options.hpp"
#include "anaglyph_window.hpp"
#include "backends.hpp"
#include "error_line.hpp"
#include "preview_defaults.hpp"
#include "program_main.hpp"
#include "progress_bar.hpp"
#include "tsr/cluster/auth.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/sg/import/scene_stats.hpp"
#include "tsr/sg/node_world.hpp"

namespace {

std::unique_ptr<tsr::app::StereoRenderer> makeRenderer(const tsr::app::AnaglyphOptions& o,
                                                       const tsr::app::SceneSession& session,
                                                       const tsr::med::ViewportRegistry& registry) {
  if (o.nodes.empty()) {
    tsr::med::ViewportSettings settings;
    settings.backend = o.backend;
    settings.root = session.imported.root;
    settings.background = session.imported.background;
    settings.parameters = registry.parametersFor(o.backend, o.parameters);
    return tsr::app::localStereo(registry, settings);
  }
  tsr::cluster::ClusterConfig config;
  config.mode = tsr::cluster::ClusterMode::Stereo;
  for (const auto& address : tsr::cluster::parseNodeList(o.nodes))
    config.nodes.push_back({address, o.backend, registry.parametersFor(o.backend, o.parameters)});
  if (config.nodes.size() > 2)
    throw std::invalid_argument("--nodes: a stereo pair takes 1 or 2 nodes (left eye, right eye), not " +
                                std::to_string(config.nodes.size()));
  config.validate();
  tsr::cluster::ClientOptions client;
  if (!o.tokenFile.empty()) client.token = tsr::cluster::readTokenFile(o.tokenFile);
  client.name = "tessera-anaglyph";
  client.registry = &registry;
  return tsr::app::clusterStereo(config, client, session);
}

// Where nothing is given: the screen plane through the centre of the
// scene's bounds, eyes 1/30 of that apart (the usual comfortable budget),
// whatever units the scene uses (builtin:cornell is in millimetres).
tsr::app::StereoSettings defaultStereo(const tsr::app::AnaglyphOptions& o, const tsr::app::SceneSession& session) {
  const auto& camera = *session.source.find<tsr::sg::Camera>(session.camera);
  float distance = camera.zeroParallaxDistance();
  const auto stats = tsr::sg::computeSceneStats(session.source, session.imported.root);
  if (stats.hasBounds) {
    // The camera's place in the world: a glTF camera hangs under a node.
    const tsr::sg::Mat4 pose = tsr::sg::cameraWorldPose(camera);
    const glm::vec3 eye(pose[3]), forward = -glm::normalize(glm::vec3(pose[2]));
    const glm::vec3 centre = (stats.boundsMin + stats.boundsMax) * 0.5f;
    const float along = glm::dot(centre - eye, forward);
    if (along > camera.nearPlane()) distance = along;
  }
  const float zeroParallax = o.zeroParallax.value_or(distance);
  return {o.eyeSeparation.value_or(zeroParallax / 30.0f), zeroParallax, o.method};
}

int run(int argc, char** argv) {
  tsr::app::AnaglyphOptions o;
  if (!tsr::app::parseAnaglyphOptions(argc, argv, o)) return 0;
  const auto script = o.script.empty() ? std::vector<tsr::app::WindowAction>{} : tsr::app::parseWindowScript(o.script);
  spdlog::set_level(spdlog::level::warn);
  tsr::app::SceneSession session;
  session.load(o.scene, o.import);
  const auto& camera = *session.source.find<tsr::sg::Camera>(session.camera);
  const auto stereo = defaultStereo(o, session);
  tsr::med::ViewportRegistry registry;
  tsr::app::registerBackends(registry);
  if (!registry.has(o.backend)) throw std::invalid_argument("--backend " + o.backend + ": not in this build");
  registry.requireDeclared(o.parameters, registry.backends());
  auto renderer = makeRenderer(o, session, registry);

  if (!o.output.empty()) {
    renderer->publish(session);
    const auto view = tsr::med::View::fromCamera(camera, o.width, o.height);
    tsr::app::ProgressBar bar("rendering both eyes");
    auto pair =
        renderer->render(session, view, stereo.separation, stereo.zeroParallax, [&](double f) { bar.update(f); });
    bar.finish();
    tsr::med::writeImage(o.output, tsr::med::anaglyph(pair.left, pair.right, stereo.method));
    std::cout << "wrote " << o.output << " (" << o.width << "x" << o.height << ", "
              << tsr::app::methodName(stereo.method) << ", eye separation " << stereo.separation << ", zero parallax "
              << stereo.zeroParallax << ")\n";
    return 0;
  }
  if (registry.capabilities(o.backend).parameters.declares("filter"))
    std::cout << tsr::app::previewDefaultsLine(o.parameters) << std::endl;
  tsr::app::AnaglyphWindow window(session, *renderer, stereo, o.width, o.height, !script.empty());
  if (script.empty())
    window.run();
  else
    window.run(script);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return tsr::app::runProgram(run, argc, argv); }
