// filter_quality: how much the Embree viewport's noise filters buy, in
// relMSE against a high-spp reference of the same path tracer (Schwenk,
// chapters 3 and 4). Prints one markdown table (and writes it with --out):
// pixel filtering at 8 spp and its equivalent spp, radiance vs pixel and
// a-trous vs cross bilateral at equal time, consistency at high spp, and
// the filter's overhead over progressive frames. A mode whose render throws
// (not wired yet) is reported as n/a.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "quality_scene.hpp"
#include "rel_mse.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/med/viewport.hpp"

using namespace tsr;
using quality::QualityScene;
using quality::Shot;

namespace {

struct Options {
  std::uint32_t size = 256;
  std::uint32_t refSpp = 4096;
  std::uint64_t refSeed = 900001;  // independent of the measured renders' seed
  std::uint64_t seed = 1;
  std::uint32_t maxDepth = 8;
  int threads = 0;
  std::uint32_t consistencySize = 128;
  std::uint32_t consistencySpp = 1024;
  std::string cache = "build/quality-cache";
  std::string out;
  std::string pngDir;
  std::string gltf;                 // make_cornell.py's cornell.gltf; empty: built-in scene only
  std::vector<std::string> scenes;  // subset of keys; empty: all
  std::vector<std::string> extra;   // name=value for every filtered render
  bool quick = false;
  std::vector<std::uint32_t> fitSpp, timedSpp;
};

struct Point {
  std::uint32_t spp;
  double seconds, relMse;
};
using Curve = std::vector<Point>;

med::Parameters baseParameters(const Options& o, std::uint32_t spp, const std::string& filter) {
  med::Parameters p;
  p.set("spp", std::int64_t{spp});
  p.set("seed", std::int64_t(o.seed));
  p.set("maxDepth", std::int64_t{o.maxDepth});
  p.set("threads", std::int64_t{o.threads});
  p.set("filter", filter);
  if (filter != "none")
    for (const auto& a : o.extra) {
      auto [name, value] = med::Parameters::parse(a);
      p.set(name, value);
    }
  return p;
}

void note(const std::string& s) { std::cerr << "[filter_quality] " << s << std::endl; }

// The reference, from the cache when it holds one: never recomputed.
med::FrameBuffer reference(QualityScene& scene, const Options& o, std::uint32_t size) {
  namespace fs = std::filesystem;
  const std::string name =
      fmt::format("{}_{}x{}_spp{}_seed{}_depth{}.exr", scene.key(), size, size, o.refSpp, o.refSeed, o.maxDepth);
  const fs::path path = fs::path(o.cache) / name;
  if (fs::exists(path)) {
    med::FrameBuffer fb = med::readImage(path.string());
    if (fb.width != size || fb.height != size)
      throw std::runtime_error(path.string() + ": cached reference has the wrong size; delete it");
    return fb;
  }
  note(fmt::format("rendering reference {} ({} spp at {}x{}); cached afterwards", name, o.refSpp, size, size));
  med::Parameters p = baseParameters(o, o.refSpp, "none");
  p.set("seed", std::int64_t(o.refSeed));
  auto vp = scene.viewport(p);
  Shot shot = scene.render(*vp, size);
  note(fmt::format("  reference took {:.1f} s", shot.seconds));
  fs::create_directories(o.cache);
  const fs::path partial = fs::path(o.cache) / (name + ".partial.exr");
  med::writeImage(partial.string(), shot.image);
  fs::rename(partial, path);
  return shot.image;
}

// relMSE at time t, piecewise linear in log-log through the curve's points
// (sorted by time); outside their range the end segment is extended.
std::optional<double> atTime(Curve c, double t, bool* extrapolated = nullptr) {
  if (c.empty()) return std::nullopt;
  std::sort(c.begin(), c.end(), [](const Point& a, const Point& b) { return a.seconds < b.seconds; });
  if (c.size() == 1) return c[0].relMse;
  std::size_t i = 1;
  while (i + 1 < c.size() && c[i].seconds < t) ++i;
  if (extrapolated) *extrapolated = t < c.front().seconds || t > c.back().seconds;
  const double x0 = std::log(c[i - 1].seconds), x1 = std::log(c[i].seconds);
  const double y0 = std::log(c[i - 1].relMse), y1 = std::log(c[i].relMse);
  if (x1 <= x0) return c[i].relMse;
  return std::exp(y0 + (y1 - y0) * (std::log(t) - x0) / (x1 - x0));
}

// Least squares of relMSE * spp = a over the unfiltered points, i.e. the
// fit relMSE = a/spp with every point weighted by its relative error.
double fitA(const Curve& unfiltered) {
  double sum = 0;
  for (const auto& p : unfiltered) sum += p.relMse * p.spp;
  return unfiltered.empty() ? 0 : sum / double(unfiltered.size());
}

std::string num(double v) {
  if (!std::isfinite(v)) return "n/a";
  if (v != 0 && (std::abs(v) < 1e-3 || std::abs(v) >= 1e5)) return fmt::format("{:.2e}", v);
  return fmt::format("{:.4g}", v);
}

void writePng(const Options& o, const QualityScene& scene, const std::string& what, const med::FrameBuffer& fb,
              const std::string& output = "colour") {
  if (o.pngDir.empty()) return;
  std::filesystem::create_directories(o.pngDir);
  med::writeImage(fmt::format("{}/{}_{}.png", o.pngDir, scene.key(), what), fb, output);
  if (output == "colour") med::writeImage(fmt::format("{}/{}_{}.exr", o.pngDir, scene.key(), what), fb, output);
}

const std::vector<std::string> kFilters{"pixel", "atrous", "radiance", "hybrid"};
const std::vector<double> kThresholds{0.0005, 0.002, 0.008, 0.032};

struct SceneResult {
  std::map<std::string, std::string> cells;  // row -> cell
};

SceneResult measure(QualityScene& scene, const Options& o) {
  SceneResult r;
  auto& cell = r.cells;
  const med::FrameBuffer ref = reference(scene, o, o.size);
  writePng(o, scene, "reference", ref);

  // Unfiltered: one progressive viewport; samples do not depend on the pass
  // they fall in, so the cumulative time is that of a render to each spp.
  Curve none;
  {
    auto vp = scene.viewport(baseParameters(o, o.fitSpp.front(), "none"));
    double total = 0;
    for (std::uint32_t spp : o.fitSpp) {
      vp->setParameter("spp", std::int64_t{spp});
      Shot s = scene.render(*vp, o.size);
      total += s.seconds;
      none.push_back({spp, total, quality::relMse(s.image.colour, ref.colour)});
      if (spp == 8) writePng(o, scene, "none_8spp", s.image);
    }
  }
  const double a = fitA(none);
  note(fmt::format("{}: unfiltered fit a = {:.4g}", scene.label(), a));

  // Filtered: a fresh viewport per spp, so each time is a render to that spp.
  std::map<std::string, Curve> curves;
  std::map<std::string, std::string> failure;
  double blend8 = NAN;
  for (const auto& f : kFilters) {
    for (std::uint32_t spp : o.timedSpp) {
      try {
        auto vp = scene.viewport(baseParameters(o, spp, f));
        Shot s = scene.render(*vp, o.size, spp == 8 && f == "pixel");
        curves[f].push_back({spp, s.seconds, quality::relMse(s.image.colour, ref.colour)});
        if (spp == 8) {
          writePng(o, scene, f + "_8spp", s.image);
          if (f == "pixel") {
            blend8 = quality::meanRed(s.image.outputs["blend"]);
            writePng(o, scene, "pixel_8spp_blend", s.image, "blend");
          }
        }
      } catch (const std::exception& e) {
        failure[f] = e.what();
        curves.erase(f);
        note(fmt::format("{}: filter={} n/a: {}", scene.label(), f, e.what()));
        break;
      }
    }
  }
  auto at8 = [&](const std::string& f) -> std::optional<Point> {
    if (!curves.count(f)) return std::nullopt;
    for (const auto& p : curves[f])
      if (p.spp == 8) return p;
    return std::nullopt;
  };
  std::optional<double> none8;
  for (const auto& p : none)
    if (p.spp == 8) none8 = p.relMse;

  const auto pixel8 = at8("pixel");
  cell["relmse8"] = pixel8 ? fmt::format("{} (unfiltered {}; mean s {})", num(pixel8->relMse),
                                         none8 ? num(*none8) : "n/a", num(blend8))
                           : "n/a";
  cell["equiv"] = pixel8 ? fmt::format("{} (a = {})", num(a / pixel8->relMse), num(a)) : "n/a";
  for (const auto& f : {"atrous", "radiance", "hybrid"}) {
    const auto p = at8(f);
    cell[std::string("equiv_") + f] = p ? num(a / p->relMse) : "n/a";
  }

  // Equal time: every method's relMSE at the time pixel filtering takes for 8 spp.
  if (pixel8) {
    const double t = pixel8->seconds;
    auto compare = [&](const std::string& f) -> std::string {
      if (!curves.count(f)) return "n/a";
      bool extra = false, extraPixel = false;
      const auto ef = atTime(curves[f], t, &extra);
      const auto ep = atTime(curves["pixel"], t, &extraPixel);
      return fmt::format("{} / {} = {}{}", num(*ef), num(*ep), num(*ef / *ep), extra ? " (extrap.)" : "");
    };
    cell["eq_time"] = fmt::format("{:.3f} s", t);
    cell["eq_none"] = num(*atTime(none, t));
    cell["eq_radiance"] = compare("radiance");
    cell["eq_hybrid"] = compare("hybrid");
    cell["eq_atrous"] = compare("atrous");
  }

  // Threshold: only the blend depends on it, so one viewport re-blends.
  try {
    auto vp = scene.viewport(baseParameters(o, 8, "pixel"));
    std::string sweep;
    for (double t : kThresholds) {
      vp->setParameter("threshold", t);
      Shot s = scene.render(*vp, o.size, true);
      sweep += fmt::format("{}{}: {} (s {})", sweep.empty() ? "" : "; ", num(t),
                           num(quality::relMse(s.image.colour, ref.colour)),
                           num(quality::meanRed(s.image.outputs["blend"])));
    }
    cell["sweep"] = sweep;
  } catch (const std::exception&) {
    cell["sweep"] = "n/a";
  }

  // Consistency: at high spp filtering must fade out (s -> 1).
  {
    const med::FrameBuffer cref = o.consistencySize == o.size ? ref : reference(scene, o, o.consistencySize);
    auto vp = scene.viewport(baseParameters(o, o.consistencySpp, "none"));
    Shot u = scene.render(*vp, o.consistencySize);
    const double eu = quality::relMse(u.image.colour, cref.colour);
    std::string text = fmt::format("unfiltered {}", num(eu));
    for (const auto& f : {"pixel", "atrous", "hybrid"}) {
      try {
        auto params = baseParameters(o, o.consistencySpp, f);
        for (const auto& [name, value] : params.all()) vp->setParameter(name, value);
        Shot s = scene.render(*vp, o.consistencySize, true);
        const double ef = quality::relMse(s.image.colour, cref.colour);
        text += fmt::format("; {} {} ({:+.1f} %, mean s {})", f, num(ef), 100.0 * (ef / eu - 1.0),
                            num(quality::meanRed(s.image.outputs["blend"])));
      } catch (const std::exception&) {
        text += fmt::format("; {} n/a", f);
      }
    }
    cell["consistency"] = text;
  }

  // Overhead over 32 progressive frames, one sample each, as a viewer renders.
  {
    std::string text;
    double unfiltered = 0;
    for (const std::string f : {"none", "pixel", "atrous"}) {
      auto vp = scene.viewport(baseParameters(o, 1, f));
      double total = 0;
      try {
        for (std::int64_t k = 1; k <= 32; ++k) {
          vp->setParameter("spp", k);
          total += scene.render(*vp, o.size).seconds;
        }
      } catch (const std::exception&) {
        text += fmt::format("; {} n/a", f);
        continue;
      }
      if (f == "none") {
        unfiltered = total;
        text = fmt::format("unfiltered {:.2f} s", total);
      } else {
        text += fmt::format("; {} {:.2f} s ({:+.0f} %)", f, total, 100.0 * (total / unfiltered - 1.0));
      }
    }
    cell["overhead"] = text;
  }
  return r;
}

std::string table(const std::vector<QualityScene*>& scenes, const std::vector<SceneResult>& results, const Options& o) {
  struct Row {
    std::string key, label, target;
  };
  const std::vector<Row> rows{
      {"relmse8", "pixel filter, 8 spp: relMSE", "lower than unfiltered"},
      {"equiv", "pixel filter, 8 spp: equivalent spp", ">= 64"},
      {"equiv_atrous", "a-trous, 8 spp: equivalent spp", ">= 64"},
      {"equiv_radiance", "radiance, 8 spp: equivalent spp", ">= 64"},
      {"equiv_hybrid", "hybrid, 8 spp: equivalent spp", ">= 64"},
      {"eq_time", "equal time T = pixel filter's time for 8 spp", ""},
      {"eq_none", "unfiltered relMSE at T", ""},
      {"eq_radiance", "radiance / pixel relMSE at T", "< 1 diffuse?"},
      {"eq_hybrid", "hybrid / pixel relMSE at T", "< 1"},
      {"eq_atrous", "a-trous / cross bilateral relMSE at T", "~1 (cheaper)"},
      {"sweep", "pixel 8 spp: relMSE (mean s) by threshold", ""},
      {"consistency",
       fmt::format("consistency, {} spp at {}x{}: relMSE (vs unfiltered, mean s)", o.consistencySpp, o.consistencySize,
                   o.consistencySize),
       "within 5 %, s > 0.95"},
      {"overhead", "32 progressive 1-spp frames: time (overhead)", "7-18 %"},
  };
  std::ostringstream md;
  md << "| measure |";
  for (auto* s : scenes) md << " " << s->label() << " |";
  md << " target |\n|---|";
  for (std::size_t i = 0; i < scenes.size(); ++i) md << "---|";
  md << "---|\n";
  for (const auto& row : rows) {
    md << "| " << row.label << " |";
    for (const auto& r : results) {
      auto it = r.cells.find(row.key);
      md << " " << (it == r.cells.end() ? "n/a" : it->second) << " |";
    }
    md << " " << row.target << " |\n";
  }
  std::string fit, timed;
  for (auto n : o.fitSpp) fit += (fit.empty() ? "" : ",") + std::to_string(n);
  for (auto n : o.timedSpp) timed += (timed.empty() ? "" : ",") + std::to_string(n);
  md << "\n"
     << o.size << "x" << o.size << " pixels unless stated; reference " << o.refSpp << " spp (seed " << o.refSeed
     << ", maxDepth " << o.maxDepth << ") by the same path tracer; measured renders seed " << o.seed
     << ". relMSE = mean over pixels and RGB of (y^-y)^2/(y^2+0.01), linear HDR.\n"
     << "Equivalent spp = a / relMSE(filtered, 8 spp), a from the unfiltered renders at spp " << fit
     << " (least squares of relMSE*spp = a; the reference's own noise, about a/" << o.refSpp
     << ", caps it).\nEqual time: filtered renders at spp " << timed
     << " on fresh viewports (scene converted once beforehand), wall time of the render call; each method's "
        "relMSE interpolated piecewise linearly in log(time)-log(relMSE) at T; unfiltered times are cumulative over "
        "one progressive viewport.\n";
  if (!o.extra.empty()) {
    md << "Filter parameters set on every filtered render:";
    for (const auto& e : o.extra) md << " " << e;
    md << "\n";
  }
  return md.str();
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"filter_quality: relMSE of the Embree viewport's noise filters against a cached reference"};
  app.add_option("--size", o.size, "image width and height (256)")->check(CLI::Range(16, 4096));
  app.add_option("--ref-spp", o.refSpp, "reference samples per pixel (4096)")->check(CLI::Range(64, 1 << 20));
  app.add_option("--cache", o.cache, "reference cache directory (build/quality-cache)");
  app.add_option("--out", o.out, "also write the markdown table to this file");
  app.add_option("--png", o.pngDir, "write the images (PNG and EXR) into this directory");
  app.add_option("--gltf", o.gltf, "make_cornell.py's cornell.gltf (diffuse and glossy rows)");
  app.add_option("--scene", o.scenes, "only these scene keys: builtin-cornell, cornell-diffuse, cornell-glossy");
  app.add_option("--set", o.extra, "name=value set on every filtered render (e.g. threshold=0.01)");
  app.add_option("--threads", o.threads, "render threads (0: all)");
  app.add_option("--max-depth", o.maxDepth, "maxDepth (8)");
  app.add_option("--consistency-size", o.consistencySize, "image size of the consistency row (128)");
  app.add_option("--consistency-spp", o.consistencySpp, "spp of the consistency row (1024)");
  app.add_flag("--quick", o.quick, "fewer spp points: a few minutes once references are cached");
  CLI11_PARSE(app, argc, argv);
  o.fitSpp = o.quick ? std::vector<std::uint32_t>{4, 8, 16, 32} : std::vector<std::uint32_t>{4, 8, 16, 32, 64};
  o.timedSpp = o.quick ? std::vector<std::uint32_t>{4, 8, 16, 32} : std::vector<std::uint32_t>{4, 8, 16, 32, 64};
  for (const auto& e : o.extra)
    if (e.find('=') == std::string::npos) {
      std::cerr << "--set " << e << ": expected name=value\n";
      return 2;
    }

  try {
    med::ViewportRegistry registry;
    med::registerEmbree(registry);
    struct Spec {
      std::string key, label, source;
      bool glossy;
    };
    std::vector<Spec> specs{{"builtin-cornell", "builtin:cornell", "builtin:cornell", false}};
    if (!o.gltf.empty()) {
      specs.push_back({"cornell-diffuse", "make_cornell (diffuse)", o.gltf, false});
      specs.push_back({"cornell-glossy", "make_cornell, glossy right wall", o.gltf, true});
    }
    std::vector<std::unique_ptr<QualityScene>> scenes;
    std::vector<QualityScene*> shown;
    std::vector<SceneResult> results;
    for (const auto& s : specs) {
      if (!o.scenes.empty() && std::find(o.scenes.begin(), o.scenes.end(), s.key) == o.scenes.end()) continue;
      const auto start = std::chrono::steady_clock::now();
      scenes.push_back(std::make_unique<QualityScene>(s.key, s.label, s.source, s.glossy, registry));
      results.push_back(measure(*scenes.back(), o));
      shown.push_back(scenes.back().get());
      note(fmt::format("{} done in {:.0f} s", s.label,
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()));
    }
    const std::string md = table(shown, results, o);
    std::cout << md;
    if (!o.out.empty()) {
      std::ofstream f(o.out);
      f << md;
      if (!f) throw std::runtime_error(o.out + ": cannot write");
    }
  } catch (const std::exception& e) {
    std::cerr << "filter_quality: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
