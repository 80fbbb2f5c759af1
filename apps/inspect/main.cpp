// tessera-inspect SCENE [--json] [--max-file-mb N] [--max-elements N]: loads
// a scene (a glTF file or a built-in) and prints what it holds. Errors: one
// line on stderr, exit status 2.
#include <cstdio>
#include <fstream>
#include <iostream>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "error_line.hpp"
#include "import_limit_options.hpp"
#include "scene/scene_glb.hpp"
#include "tsr/med/file_replacement.hpp"
#include "tsr/med/scene_flattening.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/import/scene_stats.hpp"
#include "tsr/sg/scene.hpp"

using tsr::app::oneLine;

namespace {

constexpr int kErrorExit = 2;

nlohmann::json toJson(const std::string& source, const tsr::sg::ImportResult& r, const tsr::sg::SceneStats& s) {
  nlohmann::json j;
  j["scene"] = source;
  j["containers"] = s.containers;
  j["containersByType"] = s.containersByType;
  j["triangles"] = s.triangles;
  j["uniqueTriangles"] = s.uniqueTriangles;
  j["geometryInstances"] = s.geometryInstances;
  j["lights"] = s.lights;
  j["lightInstances"] = s.lightInstances;
  j["emissiveGeometries"] = s.emissiveGeometries;
  j["cameras"] = s.cameras;
  j["animations"] = r.animations.size();
  double duration = 0.0;
  for (const auto& a : r.animations) duration = std::max(duration, static_cast<double>(a.duration()));
  j["animationDuration"] = duration;
  if (s.hasBounds)
    j["bounds"] = {{"min", {s.boundsMin.x, s.boundsMin.y, s.boundsMin.z}},
                   {"max", {s.boundsMax.x, s.boundsMax.y, s.boundsMax.z}}};
  else
    j["bounds"] = nullptr;
  j["warnings"] = r.warnings;
  return j;
}

void printText(const std::string& source, const tsr::sg::ImportResult& r, const tsr::sg::SceneStats& s) {
  std::cout << "scene: " << source << "\n";
  std::cout << "containers: " << s.containers << "\n";
  for (const auto& [type, n] : s.containersByType) std::cout << "  " << type << ": " << n << "\n";
  std::cout << "triangles: " << s.triangles << " (unique " << s.uniqueTriangles << ")\n";
  std::cout << "geometry instances: " << s.geometryInstances << "\n";
  std::cout << "lights: " << s.lights << " (instances " << s.lightInstances << ", emissive geometries "
            << s.emissiveGeometries << ")\n";
  std::cout << "cameras: " << s.cameras << "\n";
  std::cout << "animations: " << r.animations.size() << "\n";
  if (s.hasBounds)
    std::cout << "bounds: (" << s.boundsMin.x << ", " << s.boundsMin.y << ", " << s.boundsMin.z << ") - ("
              << s.boundsMax.x << ", " << s.boundsMax.y << ", " << s.boundsMax.z << ")\n";
  else
    std::cout << "bounds: empty\n";
  for (const std::string& w : r.warnings) std::cout << "warning: " << oneLine(w) << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Print what a scene holds: containers, triangles, lights, cameras, animations, bounds."};
  std::string source;
  bool json = false;
  bool verbose = false;
  app.add_option("SCENE", source, tsr::app::sceneArgumentHelp())->required();
  app.add_flag("--json", json, "print a JSON object instead of text");
  app.add_flag("-v,--verbose", verbose, "log the importer's progress to stderr");
  std::string glb;
  app.add_option("--write-glb", glb,
                 "also write the scene as one .glb, every instance a mesh in world space (e.g. a built-in scene for "
                 "other tools)");
  tsr::sg::ImportOptions options;
  tsr::app::ImportLimitOptions limits;
  limits.add(app, options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "error: " << oneLine(e.what()) << "\n";
    return kErrorExit;
  }
  limits.apply(options);

  // stdout carries only the report, so logs go to stderr, and only on request.
  spdlog::set_default_logger(spdlog::stderr_color_mt("tessera-inspect"));
  spdlog::set_level(verbose ? spdlog::level::debug : spdlog::level::off);

  try {
    tsr::sg::Scene scene;
    const tsr::sg::ImportResult result = tsr::sg::importScene(scene, source, options);
    const tsr::sg::SceneStats stats = tsr::sg::computeSceneStats(scene, result.root);
    if (!glb.empty()) {
      const std::vector<std::uint8_t> bytes =
          tsr::app::glbOf(scene, tsr::med::flatten(scene, result.root).instances, result.cameras, result.metresPerUnit);
      tsr::med::replaceFile(glb, [&](const std::string& temporary) {  // a failed write leaves no partial .glb
        std::ofstream out(temporary, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
        if (!out.flush()) throw std::runtime_error("cannot write " + glb);
      });
    }
    if (json)
      std::cout << toJson(source, result, stats).dump(2) << "\n";
    else
      printText(source, result, stats);
    std::cout.flush();
    return std::cout ? 0 : kErrorExit;
  } catch (const tsr::sg::ImportLimitError& e) {
    const bool file = e.limit() == tsr::sg::ImportLimitError::Limit::FileBytes;
    std::cerr << "error: " << oneLine(e.what()) << " (raise it with " << (file ? "--max-file-mb" : "--max-elements")
              << ")\n";
  } catch (const tsr::sg::ImportError& e) {
    std::cerr << "error: " << oneLine(e.what()) << "\n";
  } catch (const std::exception& e) {
    std::cerr << "error: " << oneLine(source + ": " + e.what()) << "\n";
  }
  return kErrorExit;
}
