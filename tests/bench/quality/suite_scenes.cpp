#include "suite_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tsr/med/image_file.hpp"

namespace tsr::quality {

std::vector<SceneSpec> suiteScenes(const std::string& folder) {
  namespace fs = std::filesystem;
  if (folder.empty()) return {{"builtin-cornell", "builtin:cornell", "builtin:cornell", "", "diffuse", {}}};
  const fs::path manifest = fs::path(folder) / "suite.json";
  std::ifstream in(manifest);
  if (!in) throw std::runtime_error(manifest.string() + ": cannot read (run make_suite.py first)");
  const auto json = nlohmann::json::parse(in);
  std::vector<SceneSpec> out{{"builtin-cornell", "builtin:cornell", "builtin:cornell", "", "diffuse", {}}};
  for (const auto& s : json.at("scenes")) {
    SceneSpec spec;
    spec.key = s.at("key").get<std::string>();
    spec.label = s.value("label", spec.key);
    const fs::path file = s.at("file").get<std::string>();
    spec.source = (file.is_absolute() ? file : fs::path(folder) / file).string();
    if (s.contains("environment")) spec.environment = (fs::path(folder) / s["environment"].get<std::string>()).string();
    spec.kind = s.value("kind", "");
    if (s.contains("shutter") || s.contains("frameInterval")) {
      const auto shutter = s.value("shutter", std::vector<float>{0.0f, 0.0f});
      spec.motion.time = s.value("time", 0.0f);
      spec.motion.frameInterval = s.value("frameInterval", 0.0f);
      if (shutter.size() != 2 || !(shutter[0] >= 0.0f && shutter[0] <= shutter[1] && shutter[1] <= 1.0f) ||
          !(spec.motion.frameInterval > 0.0f) || !std::isfinite(spec.motion.time))
        throw std::runtime_error(manifest.string() + ": scene " + spec.key +
                                 ": shutter must be [open, close] with 0 <= open <= close <= 1, frameInterval > 0 "
                                 "seconds and time finite");
      spec.motion.shutterOpen = shutter[0];
      spec.motion.shutterClose = shutter[1];
    }
    out.push_back(spec);
  }
  return out;
}

med::FrameBuffer reference(QualityScene& scene, const ReferenceOptions& o) {
  namespace fs = std::filesystem;
  const Motion& m = scene.motion();
  const std::string moving =
      m.moves() ? fmt::format("_t{}_dt{}_shutter{}-{}", m.time, m.frameInterval, m.shutterOpen, m.shutterClose) : "";
  const std::uint32_t height = o.height ? o.height : o.size;
  const std::string pose = o.pose.empty() ? "" : "_" + o.pose;
  const std::string name = fmt::format("{}{}{}_{}x{}_spp{}_seed{}_depth{}.exr", scene.key(), moving, pose, o.size,
                                       height, o.spp, o.seed, o.maxDepth);
  const fs::path path = fs::path(o.cache) / name;
  if (fs::exists(path)) {
    med::FrameBuffer fb = med::readImage(path.string());
    if (fb.width != o.size || fb.height != height)
      throw std::runtime_error(path.string() + ": cached reference has the wrong size; delete it");
    return fb;
  }
  std::cerr << fmt::format("[quality] rendering reference {} ({} spp at {}x{}); cached afterwards", name, o.spp, o.size,
                           height)
            << std::endl;
  med::Parameters p;
  p.set("spp", std::int64_t{o.spp});
  p.set("seed", std::int64_t(o.seed));
  p.set("maxDepth", std::int64_t{o.maxDepth});
  p.set("threads", std::int64_t{o.threads});
  auto vp = scene.viewport(p);
  // In steps, so a long reference shows progress.
  Shot shot;
  double seconds = 0;
  for (std::uint32_t spp = std::min(o.spp, 256u);; spp = std::min(o.spp, spp * 2)) {
    vp->setParameter("spp", std::int64_t{spp});
    shot = scene.renderSized(*vp, o.size, height);
    seconds += shot.seconds;
    std::cerr << fmt::format("[quality]   {} spp, {:.0f} s", spp, seconds) << std::endl;
    if (spp == o.spp) break;
  }
  fs::create_directories(o.cache);
  const fs::path partial = fs::path(o.cache) / (name + ".partial.exr");
  med::writeImage(partial.string(), shot.image);
  fs::rename(partial, path);
  return shot.image;
}

void publishTables(const std::string& markdown, const std::string& path) {
  std::cout << markdown;
  if (path.empty()) return;
  std::ofstream f(path);
  f << markdown;
  if (!f) throw std::runtime_error(path + ": cannot write");
}

}  // namespace tsr::quality
