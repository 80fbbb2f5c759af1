#pragma once
// The scenes the quality harnesses measure (make_suite.py's suite.json)
// and their cached high-spp references, shared by filter_quality and
// sampling_quality.
#include <cstdint>
#include <string>
#include <vector>

#include "quality_scene.hpp"

namespace tsr::quality {

struct SceneSpec {
  std::string key, label, source, environment, kind;
  Motion motion;  // suite.json's time, frameInterval and shutter; none: an instant
};

// builtin:cornell first, then the suite's scenes in suite.json's order
// (folder empty: builtin:cornell alone).
std::vector<SceneSpec> suiteScenes(const std::string& folder);

struct ReferenceOptions {
  std::uint32_t size = 128;
  std::uint32_t spp = 8192;
  std::uint64_t seed = 900001;  // independent of the measured renders' seeds
  std::uint32_t maxDepth = 8;
  int threads = 0;
  std::string cache = "build/quality-cache";
  std::uint32_t height = 0;  // 0: size (square)
  std::string pose;          // names a camera moved from the scene's own (empty: as imported)
};

// The unfiltered reference of a scene with the path tracer's defaults, from
// the cache when it holds one (never recomputed); rendered in steps that
// report progress on stderr and cached otherwise. A moving scene's file
// name says its time, frame interval and shutter.
med::FrameBuffer reference(QualityScene& scene, const ReferenceOptions& o);

// Prints a harness's markdown tables and writes them to `path` too
// (unless empty); throws when the file cannot be written.
void publishTables(const std::string& markdown, const std::string& path);

}  // namespace tsr::quality
