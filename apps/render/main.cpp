// tessera-render: renders a scene with the back-end a viewport names and
// writes the image. Errors: one line on stderr, exit status 2.
#include <algorithm>
#include <iostream>

#include <spdlog/spdlog.h>

#include "backends.hpp"
#include "cluster/cluster_layer.hpp"
#include "error_line.hpp"
#include "layers.hpp"
#include "option_values.hpp"
#include "outputs/coverage_output.hpp"
#include "outputs/stats_json.hpp"
#include "program_main.hpp"
#include "progress_bar.hpp"
#include "render_options.hpp"
#include "scene/scene_session.hpp"
#include "sequence/sequence_render.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/med/viewport_registry.hpp"

namespace {

int run(int argc, char** argv) {
  tsr::app::RenderJob options;
  std::string listParams;
  if (!tsr::app::parseRenderOptions(argc, argv, options, listParams)) return 0;
  if (!listParams.empty()) {
    const auto& capabilities = tsr::app::backendRegistry().capabilities(listParams);  // unknown: names those it has
    std::cout << listParams << (capabilities.progressive ? " (progressive)" : "") << ": --param NAME=VALUE\n"
              << capabilities.parameters.describe();
    return 0;
  }
  // --layers: a layered window (layers.hpp)
  const auto layers =
      options.layers.empty() ? std::vector<tsr::app::LayerSpec>{} : tsr::app::parseLayers(options.layers);
  tsr::app::checkRenderJob(options, layers);
  const auto& sequence = options.sequence;
  // --frames renders sequences, locally or on nodes (sequence_render.cpp);
  // so does --cluster without --layers (the whole window on the nodes).
  if (sequence.framesGiven || (!sequence.cluster.empty() && layers.empty()))
    return tsr::app::renderSequence(options, sequence, layers);

  tsr::app::SceneSession session;
  session.load(options.scene, options.import, options.view);
  // One image of an animated scene through an open shutter shows the
  // motion of the animation's first frame interval (1 / --fps); an
  // instant's image is the scene as loaded.
  if (session.shutterStaysOpen() && !session.imported.animations.empty())
    session.poseAnimations(0.0, 1.0 / sequence.fps);
  session.publish();

  tsr::med::ViewportRegistry registry;
  tsr::app::registerBackends(registry);
  tsr::med::ContextPool contexts;
  tsr::med::ViewportSettings settings;
  settings.backend = options.backend;
  settings.root = session.imported.root;
  settings.background = session.imported.background;
  settings.parameters = options.parameters;

  const auto* camera = session.replica.scene().find<tsr::sg::Camera>(session.camera);
  auto view = tsr::med::View::fromCamera(*camera, options.width, options.height);
  tsr::app::ProgressBar bar("rendering", !options.quiet);
  tsr::med::RenderControl control;
  control.progress = [&](double f) { bar.update(f); };
  tsr::med::FrameBuffer image;
  tsr::app::RemoteLayers remote;  // --cluster with --layers: one layer on the nodes
  if (!sequence.cluster.empty()) remote = tsr::app::clusterLayer(options, layers, registry, *camera);
  auto window = tsr::app::makeLayeredWindow(layers, session.replica.scene(), settings, registry, contexts, remote);
  tsr::app::checkOutputsOffered(options.aovs, window);  // before the render, not after it
  control.outputs = options.aovs;
  if (tsr::app::isRankingPath(options.output)) control.outputs->push_back(tsr::app::kRankingOutput);
  auto stats = tsr::app::renderLayered(window, session.replica, view, image, control);
  bar.finish();

  if (tsr::app::isRankingPath(options.output))
    tsr::app::writeRanking(options.output, image, session.replica.scene());
  else
    tsr::med::writeImage(options.output, image, "colour", options.display);
  for (const auto& aov : options.aovs)
    tsr::med::writeImage(tsr::app::aovPath(options.output, aov), image, aov, tsr::app::aovDisplay(options, aov));
  if (!options.statsJson.empty()) tsr::app::writeStatsJson(options, stats, 1);
  if (!options.quiet)
    std::cout << "wrote " << options.output << " (" << options.width << "x" << options.height << ", " << stats.samples
              << " spp, " << stats.seconds << " s)\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  spdlog::set_level(spdlog::level::warn);
  return tsr::app::runProgram(run, argc, argv);
}
