#pragma once
// tessera-render's command line, parsed and checked; nothing rendered yet.
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "scene_session.hpp"
#include "sequence_options.hpp"
#include "temporal_options.hpp"
#include "tsr/med/display_transform.hpp"
#include "tsr/med/parameters.hpp"
#include "tsr/sg/import/importer.hpp"

namespace tsr::app {

struct RenderOptions {
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

// Parses argv (every option is declared, so --help lists them all and an
// unknown one is an error); throws std::invalid_argument with a one-line
// message for bad input or options that cannot combine. Returns false when
// help was printed (exit 0).
bool parseRenderOptions(int argc, char** argv, RenderOptions& options);

// "1,2.5,-3" -> a point; throws std::invalid_argument naming `option`.
sg::Vec3 parsePoint(const std::string& option, const std::string& text);

// "640x480" -> width, height; throws std::invalid_argument.
void parseSize(const std::string& text, std::uint32_t& width, std::uint32_t& height);

// The option that raises the import limit an error names, for its message.
std::string importLimitOption(const sg::ImportLimitError& e);

// out.png + "albedo" -> out.albedo.png
std::string aovPath(const std::string& output, const std::string& aov);

}  // namespace tsr::app
