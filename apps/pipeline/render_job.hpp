#pragma once
// One job of the programs' pipeline: what to render (scene, view, back-end
// and its parameters, layers, a cluster, a sequence) and where the image
// goes. tessera-render fills it from its command line (render_options.hpp);
// the viewer and the wall fill the parts they use.
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "scene/scene_session.hpp"
#include "sequence/sequence_options.hpp"
#include "sequence/temporal_options.hpp"
#include "tsr/med/display_transform.hpp"
#include "tsr/med/parameters.hpp"
#include "tsr/sg/import/importer.hpp"

namespace tsr::app {

struct RenderJob {
  std::string scene;
  std::string backend = "embree";
  bool backendGiven = false;  // named on the command line (a cluster config names its own)
  std::uint32_t width = 512, height = 512;
  std::string output = "render.png";
  std::vector<std::string> aovs;
  std::string statsJson;
  med::Parameters parameters;                // spp, maxDepth, seed, threads and --param extras
  std::set<std::string> explicitParameters;  // those the command line named (they beat a config's)
  bool quiet = false;
  sg::ImportOptions import;       // --max-file-mb, --max-elements
  TemporalOptions temporal;       // --temporal and its settings (with --frames)
  SequenceOptions sequence;       // --frames, --fps, --cluster, --nodes, --token-file
  std::string layers;             // --layers value (layers.hpp parses it); empty: one back-end
  ViewChoice view;                // --camera, --look-from, --look-at, --fov, --no-default-light
  med::DisplayTransform display;  // --exposure, --tonemap (8-bit outputs only)
};

// How an --aov is written to an 8-bit file: as the picture (--exposure,
// --tonemap), except the workload image, whose colours say which node
// rendered a tile and stay as drawn.
med::DisplayTransform aovDisplay(const RenderJob& job, const std::string& aov);
// Whether --aov asks for the workload image (cluster::kWorkloadOutput).
bool asksWorkload(const RenderJob& job);

// --spp as the job's back-end reads it (its default when unset); 1 for a
// back-end without samples.
std::int64_t samplesPerPixel(const RenderJob& job);

}  // namespace tsr::app
