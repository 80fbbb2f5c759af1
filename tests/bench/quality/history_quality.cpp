// history_quality: what temporal reprojection (the path tracer's `history`
// parameter) buys while the camera orbits, against restarting at every
// change as the viewport did before. A scripted orbit swings the camera
// about a point ahead of it, `--step` degrees a frame, out to +-amplitude
// and back (frames revisit poses, whose references are cached), one traced
// sample per pixel a frame. Each frame is compared with a converged image
// of its own view: the seen error (seen_error.hpp), relMSE, and the flicker
// of the sequence (tRelMSE, rel_mse.hpp). Rows: restarting with the
// programs' preview filter and with the denoiser; the history with each; and
// a still camera's 4-spp denoised image of every frame's view, the bar the
// history must reach from frame 8 on. Also the time a frame takes with and
// without the history, unfiltered, and a strip of frames as PNGs.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "quality_scene.hpp"
#include "rel_mse.hpp"
#include "seen_error.hpp"
#include "suite_scenes.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/med/viewport.hpp"

using namespace tsr;
using Image = std::vector<glm::vec4>;

namespace {

struct Options {
  std::vector<std::string> scenes{"builtin-cornell", "indirect-room", "rough-metal"};
  std::string suite;
  std::uint32_t width = 500, height = 400;
  int frames = 60;
  float step = 2.0f;        // degrees a frame
  float amplitude = 30.0f;  // degrees either side
  float pivot = 0.5f;       // the pivot's distance ahead, as a fraction of the depth at the image's centre
  std::uint32_t refSpp = 128;
  std::uint32_t historyLimit = 16;
  std::string previewFilter = "pixel";  // the programs' default (apps/common/preview_defaults.hpp)
  int fromFrame = 8;
  int threads = 0;
  std::string cache = "build/quality-cache";
  std::string out, pngDir;
  std::vector<int> strip{0, 1, 2, 4, 8, 16};
};

void note(const std::string& s) { std::cerr << "[history_quality] " << s << std::endl; }

// The orbit's angle at a frame: 0, step, ..., amplitude, ..., -amplitude, ...
float angleAt(const Options& o, int frame) {
  const int quarter = std::max(1, int(std::lround(o.amplitude / o.step)));
  const int phase = frame % (4 * quarter);
  const int k = phase <= quarter ? phase : phase <= 3 * quarter ? 2 * quarter - phase : phase - 4 * quarter;
  return float(k) * o.step;
}

// A way of rendering the orbit: viewport parameters, and whether each frame
// starts a new viewport's worth of samples (the still camera's 4 spp).
struct Method {
  std::string name;
  med::Parameters parameters;
  std::uint32_t spp = 1;
};

struct Result {
  std::vector<double> seen, rel;
  double flicker = 0;
  double seconds = 0;  // per frame
};

std::string num(double v) {
  if (!std::isfinite(v)) return "n/a";
  if (v != 0 && (std::abs(v) < 1e-3 || std::abs(v) >= 1e5)) return fmt::format("{:.2e}", v);
  return fmt::format("{:.4g}", v);
}

double meanFrom(const std::vector<double>& v, int first) {
  double s = 0;
  int n = 0;
  for (int i = first; i < int(v.size()); ++i) s += v[i], ++n;
  return n ? s / n : std::nan("");  // no frames from `first` on: n/a, not 0
}

med::Parameters base(const Options& o) {
  med::Parameters p;
  p.set("threads", std::int64_t{o.threads});
  return p;
}

std::vector<Method> methods(const Options& o) {
  auto with = [&](std::vector<std::pair<std::string, med::ParameterValue>> values) {
    med::Parameters p = base(o);
    for (auto& [k, v] : values) p.set(k, v);
    return p;
  };
  const std::int64_t limit = o.historyLimit;
  return {
      {"restart, " + o.previewFilter, with({{"filter", o.previewFilter}})},
      {"restart, denoise", with({{"filter", std::string("denoise")}})},
      {"history, " + o.previewFilter, with({{"filter", o.previewFilter}, {"history", true}, {"historyLimit", limit}})},
      {"history, denoise", with({{"filter", std::string("denoise")}, {"history", true}, {"historyLimit", limit}})},
      {"still camera, 4 spp denoised", with({{"filter", std::string("denoise")}}), 4},
  };
}

void writePng(const Options& o, const std::string& name, const med::FrameBuffer& fb) {
  if (o.pngDir.empty()) return;
  std::filesystem::create_directories(o.pngDir);
  med::writeImage((std::filesystem::path(o.pngDir) / (name + ".png")).string(), fb);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"Temporal reprojection on an orbiting camera: seen error, relMSE and flicker per method"};
  app.add_option("--scene", o.scenes,
                 "scene keys: builtin-cornell or the suite's (default: builtin-cornell, indirect-room, "
                 "rough-metal)");
  app.add_option("--suite", o.suite, "the suite's folder (make_suite.py's output)")->required();
  app.add_option("--width", o.width, "image width")->check(CLI::Range(8, 4096));
  app.add_option("--height", o.height, "image height")->check(CLI::Range(8, 4096));
  app.add_option("--frames", o.frames, "frames of the orbit")->check(CLI::Range(2, 100000));
  app.add_option("--step", o.step, "degrees the camera turns a frame")->check(CLI::Range(0.01, 90.0));
  app.add_option("--amplitude", o.amplitude, "degrees the orbit swings either side")->check(CLI::Range(0.01, 180.0));
  app.add_option("--pivot", o.pivot, "the pivot's distance ahead, as a fraction of the centre pixel's depth")
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--ref-spp", o.refSpp, "samples of each frame's reference (cached)")->check(CLI::Range(1, 1 << 20));
  app.add_option("--history-limit", o.historyLimit, "historyLimit of the history rows")->check(CLI::Range(1, 65536));
  app.add_option("--preview-filter", o.previewFilter, "the preview filter of the first and third rows");
  app.add_option("--from-frame", o.fromFrame, "first frame of the averaged errors")->check(CLI::Range(0, 100000));
  app.add_option("--threads", o.threads, "render threads (0: all)");
  app.add_option("--cache", o.cache, "folder of the cached references");
  app.add_option("--out", o.out, "also write the table here");
  app.add_option("--png", o.pngDir, "write a strip of frames (restart and history, denoised) here");
  CLI11_PARSE(app, argc, argv);

  med::ViewportRegistry registry;
  med::registerEmbree(registry);
  std::map<std::string, quality::SceneSpec> specs;
  for (const auto& spec : quality::suiteScenes(o.suite)) specs[spec.key] = spec;
  std::string table = fmt::format(
      "## Orbit: {} frames, {} deg a frame (swinging +-{} deg), {}x{}, 1 traced spp a frame, references {} spp\n\n"
      "| scene | method | seen error (frames {}+) | seen error (all) | relMSE ({}+) | flicker (tRelMSE) | s / frame |\n"
      "|---|---|---|---|---|---|---|\n",
      o.frames, o.step, o.amplitude, o.width, o.height, o.refSpp, o.fromFrame, o.fromFrame);
  std::string ratios =
      "\n| scene | seen error: restart / history (denoise) | vs still 4 spp denoised (frames 8+) | flicker: "
      "restart / history (denoise) | restart / history (" +
      o.previewFilter + ") | reprojection share of an unfiltered frame |\n|---|---|---|---|---|---|\n";
  for (const auto& key : o.scenes) {
    const auto it = specs.find(key);
    if (it == specs.end()) {
      std::cerr << "unknown scene " << key << "\n";
      return 2;
    }
    const quality::SceneSpec& spec = it->second;
    quality::QualityScene scene(spec.key, spec.label, spec.source, false, registry, spec.environment);
    // The pivot: part of the way to what the centre pixel sees.
    float pivot = 1.0f;
    {
      auto vp = scene.viewport(base(o));
      const auto shot = scene.renderSized(*vp, o.width, o.height);
      const float d = shot.image.depth[shot.image.index(o.width / 2, o.height / 2)];
      pivot = std::isfinite(d) ? o.pivot * d : 1.0f;
    }
    std::vector<Image> references;
    std::map<int, Image> byAngle;
    for (int f = 0; f < o.frames; ++f) {
      const float angle = angleAt(o, f);
      const int tenths = int(std::lround(angle * 10));
      if (!byAngle.count(tenths)) {
        scene.orbit(angle, pivot);
        const quality::ReferenceOptions r{.size = o.width,
                                          .spp = o.refSpp,
                                          .threads = o.threads,
                                          .cache = o.cache,
                                          .height = o.height,
                                          .pose = fmt::format("orbit{}_pivot{:.3f}", tenths, pivot)};
        byAngle[tenths] = quality::reference(scene, r).colour;
      }
      references.push_back(byAngle[tenths]);
    }
    std::map<std::string, Result> results;
    for (const Method& m : methods(o)) {
      note(spec.key + ": " + m.name);
      auto vp = scene.viewport(m.parameters);
      vp->setParameter("spp", std::int64_t{m.spp});
      Result& res = results[m.name];
      std::vector<Image> frames;
      for (int f = 0; f < o.frames; ++f) {
        scene.orbit(angleAt(o, f), pivot);
        const quality::Shot shot = scene.renderSized(*vp, o.width, o.height, {"samples"});
        res.seconds += shot.totalSeconds / o.frames;
        const auto seen = quality::seenError(shot.image.colour, references[f], int(o.width), int(o.height));
        res.seen.push_back(seen.whole);
        res.rel.push_back(quality::relMse(shot.image.colour, references[f]));
        frames.push_back(shot.image.colour);
        if (key == o.scenes.front() && std::find(o.strip.begin(), o.strip.end(), f) != o.strip.end())
          writePng(o,
                   fmt::format("{}_{}_frame{:02}", spec.key,
                               m.name.substr(0, m.name.find(',')) +
                                   (m.name.find("denoise") != std::string::npos ? "-denoise" : "-" + o.previewFilter),
                               f),
                   shot.image);
        if (key == o.scenes.front() && !o.pngDir.empty() && m.name == "history, denoise" &&
            std::find(o.strip.begin(), o.strip.end(), f) != o.strip.end())
          med::writeImage(
              (std::filesystem::path(o.pngDir) / fmt::format("{}_carried_frame{:02}.png", spec.key, f)).string(),
              shot.image, "samples");
      }
      res.flicker = quality::temporalRelMse(frames, references);
      table += fmt::format("| {} | {} | {} | {} | {} | {} | {:.3f} |\n", spec.label, m.name,
                           num(meanFrom(res.seen, o.fromFrame)), num(meanFrom(res.seen, 0)),
                           num(meanFrom(res.rel, o.fromFrame)), num(res.flicker), res.seconds);
    }
    if (key == o.scenes.front())
      for (int f : o.strip)
        if (f < o.frames) {
          med::FrameBuffer ref(o.width, o.height);
          ref.colour = references[f];
          writePng(o, fmt::format("{}_reference_frame{:02}", spec.key, f), ref);
        }
    // The reprojection's cost: unfiltered frames with and without it.
    double plain = 0, carried = 0;
    for (bool history : {false, true}) {
      med::Parameters p = base(o);
      p.set("history", history);
      auto vp = scene.viewport(p);
      vp->setParameter("spp", std::int64_t{1});
      double& seconds = history ? carried : plain;
      for (int f = 0; f < o.frames; ++f) {
        scene.orbit(angleAt(o, f), pivot);
        seconds += scene.renderSized(*vp, o.width, o.height).totalSeconds / o.frames;
      }
    }
    const Result& rd = results["restart, denoise"];
    const Result& hd = results["history, denoise"];
    const Result& rp = results["restart, " + o.previewFilter];
    const Result& hp = results["history, " + o.previewFilter];
    const Result& still = results["still camera, 4 spp denoised"];
    ratios += fmt::format(
        "| {} | {:.2f}x | {:.2f}x ({} vs {}) | {:.2f}x | {:.2f}x | {:+.1f} % ({:.3f} vs {:.3f} s) |\n", spec.label,
        meanFrom(rd.seen, o.fromFrame) / meanFrom(hd.seen, o.fromFrame),
        meanFrom(still.seen, o.fromFrame) / meanFrom(hd.seen, o.fromFrame), num(meanFrom(hd.seen, o.fromFrame)),
        num(meanFrom(still.seen, o.fromFrame)), rd.flicker / hd.flicker, rp.flicker / hp.flicker,
        100.0 * (carried - plain) / plain, carried, plain);
  }
  quality::publishTables(table + ratios, o.out);
  return 0;
}
