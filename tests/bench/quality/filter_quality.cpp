// filter_quality: how much the Embree viewport's noise filters buy, over a
// suite of varied scenes (tests/bench/quality/suite), in relMSE and in the
// seen error (seen_error.hpp) against a cached high-spp reference of the
// same path tracer (Schwenk, chapters 3 and 4). Prints markdown tables (and
// writes them with --out): each filter at 8 spp against unfiltered 8 and
// 256 spp, equivalent spp by every measure, radiance and hybrid against
// pixel filtering at equal time, consistency at 1024 spp, and the filter's
// share of a progressive frame. --png writes the images of a contact sheet.
#include <algorithm>
#include <chrono>
#include <cmath>
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
#include <nlohmann/json.hpp>

#include "quality_scene.hpp"
#include "rel_mse.hpp"
#include "seen_error.hpp"
#include "suite_scenes.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/med/viewport.hpp"

using namespace tsr;
using quality::QualityScene;
using quality::SceneSpec;
using quality::SeenError;
using quality::Shot;

namespace {

struct Options {
  std::uint32_t size = 128;
  std::uint32_t refSpp = 8192;
  std::uint64_t refSeed = 900001;  // independent of the measured renders' seed
  std::uint64_t seed = 1;
  std::uint32_t maxDepth = 8;
  int threads = 0;
  std::uint32_t consistencySpp = 1024;
  std::uint32_t overheadSize = 512;
  std::vector<std::string> overheadScenes{"indirect-room", "builtin-cornell"};
  std::string defaultFilter = "pixel";
  std::string cache = "build/quality-cache";
  std::string out;
  std::string pngDir;
  std::string suite;                // folder holding suite.json (make_suite.py's output)
  std::vector<std::string> scenes;  // subset of keys; empty: all
  std::vector<std::string> filters{"pixel", "atrous", "radiance", "hybrid"};
  std::vector<std::string> extra;  // name=value for every filtered render
  bool quick = false;
  bool consistencyAll = false;  // radiance and hybrid too (1024 radiance passes each)
};

// One image against the reference.
struct Score {
  std::uint32_t spp = 0;
  double seconds = 0, relMse = NAN;
  SeenError seen;
};
using Curve = std::vector<Score>;

// filter: a filter name, optionally followed by +name=value settings of
// its own (pixel+filterKernel=separable), so variants sit side by side.
med::Parameters parameters(const Options& o, std::uint32_t spp, const std::string& filter) {
  med::Parameters p;
  p.set("spp", std::int64_t{spp});
  p.set("seed", std::int64_t(o.seed));
  p.set("maxDepth", std::int64_t{o.maxDepth});
  p.set("threads", std::int64_t{o.threads});
  std::size_t plus = filter.find('+');
  p.set("filter", filter.substr(0, plus));
  if (filter != "none")
    for (const auto& a : o.extra) {
      auto [name, value] = med::Parameters::parse(a);
      p.set(name, value);
    }
  while (plus != std::string::npos) {
    const std::size_t next = filter.find('+', plus + 1);
    auto [name, value] = med::Parameters::parse(filter.substr(plus + 1, next - plus - 1));
    p.set(name, value);
    plus = next;
  }
  return p;
}

void note(const std::string& s) { std::cerr << "[filter_quality] " << s << std::endl; }

quality::ReferenceOptions referenceOptions(const Options& o) {
  return {.size = o.size,
          .spp = o.refSpp,
          .seed = o.refSeed,
          .maxDepth = o.maxDepth,
          .threads = o.threads,
          .cache = o.cache,
          .height = 0,
          .pose = {}};
}

Score score(const Shot& shot, const med::FrameBuffer& ref, std::uint32_t spp, double seconds) {
  Score s;
  s.spp = spp;
  s.seconds = seconds;
  s.relMse = quality::relMse(shot.image.colour, ref.colour);
  s.seen = quality::seenError(shot.image.colour, ref.colour, ref.width, ref.height);
  return s;
}

// Interpolates y(x) piecewise linearly in log-log through the curve, the
// end segments extended; pick reads (x, y) from a Score.
template <class Pick>
double logLog(Curve c, double x, Pick pick) {
  std::sort(c.begin(), c.end(), [&](const Score& a, const Score& b) { return pick(a).first < pick(b).first; });
  if (c.size() < 2) return c.empty() ? NAN : pick(c[0]).second;
  std::size_t i = 1;
  while (i + 1 < c.size() && pick(c[i]).first < x) ++i;
  const auto [x0, y0] = pick(c[i - 1]);
  const auto [x1, y1] = pick(c[i]);
  if (!(x0 > 0 && x1 > x0 && y0 > 0 && y1 > 0 && x > 0)) return y1;
  const double t = (std::log(x) - std::log(x0)) / (std::log(x1) - std::log(x0));
  return std::exp(std::log(y0) + t * (std::log(y1) - std::log(y0)));
}

// The spp at which unfiltered rendering reaches error e: log(spp) linear in
// log(error) between the two neighbouring points of the unfiltered curve
// (sorted by spp), the end segments extended.
template <class Measure>
double equivalentSpp(Curve c, double e, Measure measure) {
  std::sort(c.begin(), c.end(), [](const Score& a, const Score& b) { return a.spp < b.spp; });
  if (c.size() < 2 || !(e > 0)) return NAN;
  std::size_t i = 1;
  while (i + 1 < c.size() && measure(c[i]) > e) ++i;
  const double e0 = measure(c[i - 1]), e1 = measure(c[i]);
  if (!(e0 > 0 && e1 > 0 && e0 != e1)) return NAN;
  const double t = (std::log(e) - std::log(e0)) / (std::log(e1) - std::log(e0));
  return std::exp(std::log(double(c[i - 1].spp)) + t * (std::log(double(c[i].spp)) - std::log(double(c[i - 1].spp))));
}

std::string num(double v) {
  if (!std::isfinite(v)) return "n/a";
  if (v != 0 && (std::abs(v) < 1e-3 || std::abs(v) >= 1e5)) return fmt::format("{:.2e}", v);
  return fmt::format("{:.3g}", v);
}

std::string spp(double v) { return std::isfinite(v) ? fmt::format("{:.0f}", v) : "n/a"; }

void writePng(const Options& o, const QualityScene& scene, const std::string& what, const med::FrameBuffer& fb) {
  if (o.pngDir.empty()) return;
  std::filesystem::create_directories(o.pngDir);
  std::string name = what;
  std::replace_if(
      name.begin(), name.end(), [](char c) { return c == '+' || c == '='; }, '-');
  med::writeImage(fmt::format("{}/{}_{}.png", o.pngDir, scene.key(), name), fb);
}

struct SceneResult {
  std::string key, label, kind;
  Curve unfiltered;                             // progressive, 4 .. consistencySpp
  std::map<std::string, Curve> filtered;        // fresh viewports, timed spp points
  std::map<std::string, Score> consistency;     // filter -> score at consistencySpp
  std::map<std::string, std::string> failures;  // filter -> why it is n/a
  std::map<std::string, double> overheadShare;  // filter -> share of a progressive frame
};

std::optional<Score> at(const Curve& c, std::uint32_t n) {
  for (const auto& s : c)
    if (s.spp == n) return s;
  return std::nullopt;
}

void measure(QualityScene& scene, const Options& o, SceneResult& r) {
  const med::FrameBuffer ref = quality::reference(scene, referenceOptions(o));
  writePng(o, scene, "reference", ref);

  // Unfiltered: one progressive viewport; samples do not depend on the pass
  // they fall in, so the cumulative time is that of a render to each spp.
  auto plain = scene.viewport(parameters(o, 4, "none"));
  double total = 0;
  for (std::uint32_t n = 4; n <= o.consistencySpp; n *= 2) {
    plain->setParameter("spp", std::int64_t{n});
    Shot s = scene.render(*plain, o.size);
    total += s.seconds;
    r.unfiltered.push_back(score(s, ref, n, total));
    if (n == 8 || n == 256) writePng(o, scene, fmt::format("none_{}spp", n), s.image);
  }
  // Consistency: pixel filters re-blend the same samples; radiance filters
  // render their own passes.
  for (const auto& f : o.filters) {
    const bool ownPasses = f.starts_with("radiance") || f.starts_with("hybrid");
    if (ownPasses && !o.consistencyAll && f != o.defaultFilter) continue;
    try {
      std::unique_ptr<med::Viewport> fresh;
      med::Viewport* vp = plain.get();
      if (ownPasses) {
        fresh = scene.viewport(parameters(o, o.consistencySpp, f));
        vp = fresh.get();
      } else {
        const med::Parameters wanted = parameters(o, o.consistencySpp, f);
        for (const auto& [name, value] : wanted.all()) vp->setParameter(name, value);
      }
      r.consistency[f] = score(scene.render(*vp, o.size), ref, o.consistencySpp, 0);
    } catch (const std::exception& e) {
      r.failures[f] = e.what();
    }
  }

  // Filtered: a fresh viewport per spp, so each time is a render to that spp.
  const std::vector<std::uint32_t> timed =
      o.quick ? std::vector<std::uint32_t>{8, 16} : std::vector<std::uint32_t>{4, 8, 16, 32};
  for (const auto& f : o.filters) {
    if (r.failures.count(f)) continue;
    try {
      for (std::uint32_t n : timed) {
        auto vp = scene.viewport(parameters(o, n, f));
        Shot s = scene.render(*vp, o.size);
        r.filtered[f].push_back(score(s, ref, n, s.seconds));
        if (n == 8) writePng(o, scene, f + "_8spp", s.image);
      }
    } catch (const std::exception& e) {
      r.failures[f] = e.what();
      r.filtered.erase(f);
      note(fmt::format("{}: filter={} n/a: {}", scene.label(), f, e.what()));
    }
  }
}

// The default filter's share of a progressive frame: 16 frames of one
// sample each at overheadSize, with and without it.
void overhead(QualityScene& scene, const Options& o, SceneResult& r) {
  auto frames = [&](const std::string& f) {
    auto vp = scene.viewport(parameters(o, 1, f));
    double total = 0;
    for (std::int64_t k = 1; k <= 16; ++k) {
      vp->setParameter("spp", k);
      total += scene.render(*vp, o.overheadSize).seconds;
    }
    return total;
  };
  const double none = frames("none");
  for (const auto& f : o.filters)
    if (!r.failures.count(f)) r.overheadShare[f] = 1.0 - none / frames(f);
}

std::string cellSeen(const std::optional<Score>& s) {
  return s ? fmt::format("{} / {}", num(s->seen.whole), num(s->seen.worstTile)) : "n/a";
}

std::string tables(const std::vector<SceneResult>& results, const Options& o) {
  std::ostringstream md;
  const auto whole = [](const Score& s) { return s.seen.whole; };
  const auto tile = [](const Score& s) { return s.seen.worstTile; };
  const auto rel = [](const Score& s) { return s.relMse; };

  md << "### Seen error at 8 spp: whole / worst 16x16 tile\n\n| scene | kind | unfiltered 8 | unfiltered 256 |";
  for (const auto& f : o.filters) md << " " << f << " |";
  md << " " << o.defaultFilter << " 8 spp <= unfiltered 256 spp |\n|---|---|---|---|";
  for (std::size_t i = 0; i <= o.filters.size(); ++i) md << "---|";
  md << "\n";
  int met = 0;
  for (const auto& r : results) {
    md << "| " << r.label << " | " << r.kind << " | " << cellSeen(at(r.unfiltered, 8)) << " | "
       << cellSeen(at(r.unfiltered, 256)) << " |";
    for (const auto& f : o.filters) {
      auto it = r.filtered.find(f);
      md << " " << (it == r.filtered.end() ? "n/a" : cellSeen(at(it->second, 8))) << " |";
    }
    const auto d = r.filtered.count(o.defaultFilter) ? at(r.filtered.at(o.defaultFilter), 8) : std::nullopt;
    const auto u = at(r.unfiltered, 256);
    std::string verdict = "n/a";
    if (d && u) {
      const bool okWhole = d->seen.whole <= u->seen.whole, okTile = d->seen.worstTile <= u->seen.worstTile;
      met += okWhole && okTile;
      verdict = okWhole && okTile ? "yes" : fmt::format("**no** ({}{})", okWhole ? "" : "whole", okTile ? "" : " tile");
    }
    md << " " << verdict << " |\n";
  }
  md << "\n" << o.defaultFilter << " at 8 spp meets both on " << met << " of " << results.size() << " scenes.\n";

  md << "\n### relMSE at 8 spp, and equivalent unfiltered spp by relMSE / seen whole / seen worst tile\n\n"
        "| scene | unfiltered 8 |";
  for (const auto& f : o.filters) md << " " << f << " |";
  md << "\n|---|---|";
  for (std::size_t i = 0; i < o.filters.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& r : results) {
    const auto u8 = at(r.unfiltered, 8);
    md << "| " << r.label << " | " << (u8 ? num(u8->relMse) : "n/a") << " |";
    for (const auto& f : o.filters) {
      auto it = r.filtered.find(f);
      const auto s = it == r.filtered.end() ? std::nullopt : at(it->second, 8);
      if (!s) {
        md << " n/a |";
        continue;
      }
      md << " " << num(s->relMse) << "; " << spp(equivalentSpp(r.unfiltered, s->relMse, rel)) << " / "
         << spp(equivalentSpp(r.unfiltered, s->seen.whole, whole)) << " / "
         << spp(equivalentSpp(r.unfiltered, s->seen.worstTile, tile)) << " |";
    }
    md << "\n";
  }

  md << "\n### Equal time: seen error (whole) of each filter at the time pixel filtering takes for 8 spp\n\n"
        "| scene | kind | time T | unfiltered at T |";
  for (const auto& f : o.filters) md << " " << f << " |";
  md << " best |\n|---|---|---|---|";
  for (std::size_t i = 0; i <= o.filters.size(); ++i) md << "---|";
  md << "\n";
  const auto timeSeen = [&](const Score& s) { return std::pair<double, double>{s.seconds, s.seen.whole}; };
  for (const auto& r : results) {
    auto pit = r.filtered.find("pixel");
    const auto p8 = pit == r.filtered.end() ? std::nullopt : at(pit->second, 8);
    if (!p8) {
      md << "| " << r.label << " | " << r.kind << " | n/a |\n";
      continue;
    }
    const double t = p8->seconds;
    md << "| " << r.label << " | " << r.kind << " | " << fmt::format("{:.3f} s", t) << " | "
       << num(logLog(r.unfiltered, t, timeSeen)) << " |";
    std::string best;
    double bestError = INFINITY;
    for (const auto& f : o.filters) {
      auto it = r.filtered.find(f);
      if (it == r.filtered.end()) {
        md << " n/a |";
        continue;
      }
      // Below its fewest samples' time the curve would be extrapolated
      // into nonsense: the filter cannot show that picture within T.
      double fastest = INFINITY;
      for (const Score& sc : it->second) fastest = std::min(fastest, sc.seconds);
      if (t < fastest) {
        md << " slower |";
        continue;
      }
      const double e = logLog(it->second, t, timeSeen);
      if (e < bestError) bestError = e, best = f;
      md << " " << num(e) << " |";
    }
    md << " " << best << " |\n";
  }

  md << "\n### Consistency at " << o.consistencySpp << " spp: filtered / unfiltered, worst tile and relMSE"
     << " (target: both <= 1.05)\n\n| scene | unfiltered tile; relMSE |";
  for (const auto& f : o.filters) md << " " << f << " |";
  md << "\n|---|---|";
  for (std::size_t i = 0; i < o.filters.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& r : results) {
    const auto u = at(r.unfiltered, o.consistencySpp);
    if (!u) continue;
    md << "| " << r.label << " | " << num(u->seen.worstTile) << "; " << num(u->relMse)
       << fmt::format(" (at {},{})", u->seen.worstX, u->seen.worstY) << " |";
    for (const auto& f : o.filters) {
      auto it = r.consistency.find(f);
      if (it == r.consistency.end()) {
        md << " n/a |";
        continue;
      }
      const double a = it->second.seen.worstTile / u->seen.worstTile, b = it->second.relMse / u->relMse;
      md << " "
         << fmt::format("{:.3f}; {:.3f}{} (worst tile at {},{})", a, b, a <= 1.05 && b <= 1.05 ? "" : " **miss**",
                        it->second.seen.worstX, it->second.seen.worstY)
         << " |";
    }
    md << "\n";
  }

  bool anyOverhead = false;
  for (const auto& r : results) anyOverhead |= !r.overheadShare.empty();
  if (anyOverhead) {
    md << "\n### Filter's share of a progressive frame, 16 frames of 1 spp at " << o.overheadSize << "x"
       << o.overheadSize << " (target for " << o.defaultFilter << ": <= 20 %)\n\n| scene |";
    for (const auto& f : o.filters) md << " " << f << " |";
    md << "\n|---|";
    for (std::size_t i = 0; i < o.filters.size(); ++i) md << "---|";
    md << "\n";
    for (const auto& r : results) {
      if (r.overheadShare.empty()) continue;
      md << "| " << r.label << " |";
      for (const auto& f : o.filters) {
        auto it = r.overheadShare.find(f);
        md << " " << (it == r.overheadShare.end() ? "n/a" : fmt::format("{:.0f} %", 100.0 * it->second)) << " |";
      }
      md << "\n";
    }
  }

  md << "\n"
     << o.size << "x" << o.size << " pixels; reference " << o.refSpp << " spp (seed " << o.refSeed << ", maxDepth "
     << o.maxDepth << ") by the same path tracer; measured renders seed " << o.seed
     << ". relMSE = mean over pixels and RGB of (y^-y)^2/(y^2+0.01), linear HDR. Seen error = RMSE of the displayed "
        "images (clamped, sRGB), each blurred by a radius-2 box twice, over the image / its worst 16x16 tile. "
        "Equivalent spp: the unfiltered spp with the same error, read off the unfiltered curve (4 to "
     << o.consistencySpp
     << " spp, log-log interpolation). Equal time: filters rendered on fresh viewports (scene converted "
        "beforehand), wall time of the render call, interpolated in log-log; unfiltered times cumulative over one "
        "progressive viewport; slower: the filter's fewest timed spp take longer than T.\n";
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
  CLI::App app{"filter_quality: relMSE and seen error of the Embree viewport's noise filters over a scene suite"};
  app.add_option("--size", o.size, "image width and height")->capture_default_str()->check(CLI::Range(16, 4096));
  app.add_option("--ref-spp", o.refSpp, "reference samples per pixel")
      ->capture_default_str()
      ->check(CLI::Range(64, 1 << 20));
  app.add_option("--cache", o.cache, "reference cache directory")->capture_default_str();
  app.add_option("--out", o.out, "also write the markdown tables to this file");
  app.add_option("--png", o.pngDir, "write each scene's images (reference, unfiltered, each filter) as PNG here");
  app.add_option("--suite", o.suite, "folder of make_suite.py's output (suite.json); builtin:cornell is always in");
  app.add_option("--scene", o.scenes, "only these scene keys (builtin-cornell and the suite's keys)");
  app.add_option("--filter", o.filters, "filters to measure; NAME+param=value+... for a variant")
      ->capture_default_str();
  app.add_option("--default-filter", o.defaultFilter, "the filter the targets are judged on")->capture_default_str();
  app.add_option("--set", o.extra, "name=value set on every filtered render (e.g. threshold=0.01)");
  app.add_option("--threads", o.threads, "render threads (0: all)");
  app.add_option("--max-depth", o.maxDepth, "maxDepth")->capture_default_str();
  app.add_option("--consistency-spp", o.consistencySpp, "spp of the consistency columns")->capture_default_str();
  app.add_flag("--consistency-all", o.consistencyAll, "consistency of radiance and hybrid too, not only the default");
  app.add_option("--overhead-size", o.overheadSize, "image size of the overhead table (0: no table)")
      ->capture_default_str();
  app.add_option("--overhead-scene", o.overheadScenes, "scenes of the overhead table")->capture_default_str();
  app.add_flag("--quick", o.quick, "fewer timed spp points");
  CLI11_PARSE(app, argc, argv);
  for (const auto& e : o.extra)
    if (e.find('=') == std::string::npos) {
      std::cerr << "--set " << e << ": expected name=value\n";
      return 2;
    }

  try {
    med::ViewportRegistry registry;
    med::registerEmbree(registry);
    const std::vector<SceneSpec> specs = quality::suiteScenes(o.suite);
    std::vector<SceneResult> results;
    for (const auto& s : specs) {
      if (!o.scenes.empty() && std::find(o.scenes.begin(), o.scenes.end(), s.key) == o.scenes.end()) continue;
      const auto start = std::chrono::steady_clock::now();
      QualityScene scene(s.key, s.label, s.source, false, registry, s.environment, s.motion);
      SceneResult r{s.key, s.label, s.kind, {}, {}, {}, {}, {}};
      measure(scene, o, r);
      if (o.overheadSize > 0 &&
          std::find(o.overheadScenes.begin(), o.overheadScenes.end(), s.key) != o.overheadScenes.end())
        overhead(scene, o, r);
      results.push_back(std::move(r));
      note(fmt::format("{} done in {:.0f} s", s.label,
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()));
    }
    quality::publishTables(tables(results, o), o.out);
  } catch (const std::exception& e) {
    std::cerr << "filter_quality: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
