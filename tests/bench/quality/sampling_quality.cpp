// sampling_quality: what the path tracer's sampling buys, unfiltered, over
// the scene suite: the seen error (whole image and worst 16x16 tile) and
// relMSE against the cached high-spp reference at 1, 4, 8, 16, 64 and 256
// spp, and time per sample, for two or more configurations side by side
// (by default "before": white-noise samples, emitters picked by power and
// free flights alone in media, and "after": the defaults, stratified Sobol
// samples, the light tree and equiangular sampling in media).
// Prints markdown tables (and writes them with --out); --png writes each
// configuration's 8-spp image beside the reference.
//
//   tests/bench/quality/sampling_quality.sh build/default/bin [options]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
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

using namespace tsr;

namespace {

struct Config {
  std::string name;
  std::vector<std::pair<std::string, std::string>> settings;  // parameter name, value
};

// NAME or NAME:param=value+param=value
Config parseConfig(const std::string& text) {
  Config c;
  const std::size_t colon = text.find(':');
  c.name = text.substr(0, colon);
  if (c.name.empty()) throw std::runtime_error("--config " + text + ": a configuration needs a name");
  if (colon == std::string::npos) return c;
  std::stringstream rest(text.substr(colon + 1));
  for (std::string item; std::getline(rest, item, '+');) {
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw std::runtime_error("--config " + text + ": expected param=value, got '" + item + "'");
    c.settings.emplace_back(item.substr(0, eq), item.substr(eq + 1));
  }
  return c;
}

struct Options {
  quality::ReferenceOptions reference;
  std::uint64_t seed = 1;
  std::vector<std::uint32_t> spp{1, 4, 8, 16, 64, 256};
  std::vector<std::string> configs{"before:sampler=independent+lightChoice=power+equiangular=false", "after"};
  std::string suite, out, pngDir;
  std::vector<std::string> scenes;
};

struct Point {
  std::uint32_t spp = 0;
  double seconds = 0;  // cumulative over one progressive viewport
  double relMse = NAN;
  quality::SeenError seen;
  double meanRatio = NAN;  // the image's mean luminance over the reference's
};

struct SceneRow {
  std::string label, kind;
  std::vector<std::vector<Point>> curves;  // per configuration
};

void note(const std::string& s) { std::cerr << "[sampling_quality] " << s << std::endl; }

double meanLuminance(const std::vector<glm::vec4>& image) {
  double sum = 0.0;
  for (const auto& c : image) sum += 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
  return image.empty() ? 0.0 : sum / double(image.size());
}

std::vector<Point> curve(quality::QualityScene& scene, const Options& o, const Config& c, const med::FrameBuffer& ref) {
  med::Parameters p;
  p.set("spp", std::int64_t{1});
  p.set("seed", std::int64_t(o.seed));
  p.set("maxDepth", std::int64_t{o.reference.maxDepth});
  p.set("threads", std::int64_t{o.reference.threads});
  for (const auto& [name, value] : c.settings) p.set(name, med::Parameters::parse(name + "=" + value).second);
  auto vp = scene.viewport(p);
  std::vector<Point> out;
  double total = 0;
  for (std::uint32_t n : o.spp) {
    vp->setParameter("spp", std::int64_t{n});
    const quality::Shot shot = scene.render(*vp, o.reference.size);
    total += shot.seconds;
    Point pt{n, total, quality::relMse(shot.image.colour, ref.colour),
             quality::seenError(shot.image.colour, ref.colour, ref.width, ref.height),
             meanLuminance(shot.image.colour) / meanLuminance(ref.colour)};
    out.push_back(pt);
    if (n == 8 && !o.pngDir.empty())
      med::writeImage(fmt::format("{}/{}_{}_8spp.png", o.pngDir, scene.key(), c.name), shot.image);
  }
  return out;
}

// The seen error (whole) at `seconds`, piecewise linear in log-log.
double seenAtTime(const std::vector<Point>& c, double seconds) {
  if (c.size() < 2) return NAN;
  std::size_t i = 1;
  while (i + 1 < c.size() && c[i].seconds < seconds) ++i;
  const Point &a = c[i - 1], &b = c[i];
  if (!(a.seconds > 0 && b.seconds > a.seconds && a.seen.whole > 0 && b.seen.whole > 0)) return NAN;
  const double t = (std::log(seconds) - std::log(a.seconds)) / (std::log(b.seconds) - std::log(a.seconds));
  return std::exp(std::log(a.seen.whole) + t * (std::log(b.seen.whole) - std::log(a.seen.whole)));
}

const Point* at(const std::vector<Point>& c, std::uint32_t n) {
  for (const auto& p : c)
    if (p.spp == n) return &p;
  return nullptr;
}

std::string num(double v) { return std::isfinite(v) ? fmt::format("{:.3g}", v) : "n/a"; }

double median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::string tables(const std::vector<SceneRow>& rows, const std::vector<Config>& configs, const Options& o) {
  std::ostringstream md;
  md << "### Seen error, whole / worst 16x16 tile, unfiltered\n\n| scene | kind | config |";
  for (auto n : o.spp) md << " " << n << " spp |";
  md << " ms / spp |\n|---|---|---|";
  for (std::size_t i = 0; i <= o.spp.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& r : rows)
    for (std::size_t c = 0; c < configs.size(); ++c) {
      md << "| " << r.label << " | " << r.kind << " | " << configs[c].name << " |";
      for (const auto& p : r.curves[c]) md << " " << num(p.seen.whole) << " / " << num(p.seen.worstTile) << " |";
      const Point& last = r.curves[c].back();
      md << " " << num(1000.0 * last.seconds / last.spp) << " |\n";
    }

  md << "\n### relMSE, unfiltered\n\n| scene | config |";
  for (auto n : o.spp) md << " " << n << " spp |";
  md << "\n|---|---|";
  for (std::size_t i = 0; i < o.spp.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& r : rows)
    for (std::size_t c = 0; c < configs.size(); ++c) {
      md << "| " << r.label << " | " << configs[c].name << " |";
      for (const auto& p : r.curves[c]) md << " " << num(p.relMse) << " |";
      md << "\n";
    }

  if (configs.size() >= 2) {
    const std::string& a = configs.front().name;
    const std::string& b = configs.back().name;
    md << "\n### " << a << " / " << b << ": how many times lower the seen error (whole) is with " << b
       << "\n\nequal spp at 8, 64 and 128 (or the nearest measured), and at equal time: " << b
       << "'s error at the time " << a
       << " takes for 8 spp.\n\n| scene | 8 spp | 64 spp | worst tile, 8 spp | equal time |\n"
       << "|---|---|---|---|---|\n";
    std::vector<double> r8, rTime;
    for (const auto& r : rows) {
      auto ratio = [&](std::uint32_t n, bool tile) {
        const Point *x = at(r.curves.front(), n), *y = at(r.curves.back(), n);
        if (!x || !y) return double(NAN);
        return tile ? double(x->seen.worstTile) / y->seen.worstTile : double(x->seen.whole) / y->seen.whole;
      };
      const Point* before8 = at(r.curves.front(), 8);
      const double equalTime = before8 ? before8->seen.whole / seenAtTime(r.curves.back(), before8->seconds) : NAN;
      r8.push_back(ratio(8, false));
      rTime.push_back(equalTime);
      md << "| " << r.label << " | " << num(ratio(8, false)) << "x | " << num(ratio(64, false)) << "x | "
         << num(ratio(8, true)) << "x | " << num(equalTime) << "x |\n";
    }
    md << "\nMedian over the scenes: " << num(median(r8)) << "x at 8 spp, " << num(median(rTime))
       << "x at equal time.\n";

    md << "\n### Bias check: mean luminance of the " << o.spp.back()
       << "-spp image over the reference's (which the defaults rendered)\n\n| scene |";
    for (const auto& c : configs) md << " " << c.name << " |";
    md << "\n|---|";
    for (std::size_t i = 0; i < configs.size(); ++i) md << "---|";
    md << "\n";
    for (const auto& r : rows) {
      md << "| " << r.label << " |";
      for (const auto& c : r.curves) md << " " << fmt::format("{:.4f}", c.back().meanRatio) << " |";
      md << "\n";
    }
  }
  md << "\nReferences: " << o.reference.spp << " spp, seed " << o.reference.seed << ", " << o.reference.size << "x"
     << o.reference.size << ", depth " << o.reference.maxDepth << "; measured renders seed " << o.seed
     << "; times are one progressive viewport's render calls, cumulative, on this machine.\n";
  for (const auto& c : configs) {
    md << "- " << c.name << ":";
    if (c.settings.empty()) md << " the defaults";
    for (const auto& [n, v] : c.settings) md << " " << n << "=" << v;
    md << "\n";
  }
  return md.str();
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"sampling_quality: unfiltered error against spp and time for sampler configurations, over a suite"};
  app.add_option("--size", o.reference.size, "image width and height")
      ->capture_default_str()
      ->check(CLI::Range(16, 4096));
  app.add_option("--ref-spp", o.reference.spp, "reference samples per pixel")
      ->capture_default_str()
      ->check(CLI::Range(64, 1 << 20));
  app.add_option("--cache", o.reference.cache, "reference cache directory")->capture_default_str();
  app.add_option("--suite", o.suite, "folder of make_suite.py's output (suite.json); builtin:cornell is always in");
  app.add_option("--scene", o.scenes, "only these scene keys (builtin-cornell and the suite's keys)");
  app.add_option("--spp", o.spp, "sample counts measured, increasing")->capture_default_str();
  app.add_option("--config", o.configs, "NAME[:param=value+param=value]; the first is 'before', the last 'after'")
      ->capture_default_str();
  app.add_option("--seed", o.seed, "seed of the measured renders")->capture_default_str();
  app.add_option("--threads", o.reference.threads, "render threads (0: all)");
  app.add_option("--max-depth", o.reference.maxDepth, "maxDepth")->capture_default_str();
  app.add_option("--out", o.out, "also write the markdown tables to this file");
  app.add_option("--png", o.pngDir, "write each configuration's 8-spp image and the reference as PNG here");
  CLI11_PARSE(app, argc, argv);

  try {
    if (o.spp.empty() || !std::is_sorted(o.spp.begin(), o.spp.end()) || o.spp.front() == 0)
      throw std::runtime_error("--spp: give increasing sample counts of at least 1");
    std::vector<Config> configs;
    for (const auto& c : o.configs) configs.push_back(parseConfig(c));
    if (!o.pngDir.empty()) std::filesystem::create_directories(o.pngDir);
    med::ViewportRegistry registry;
    med::registerEmbree(registry);
    std::vector<SceneRow> rows;
    for (const auto& s : quality::suiteScenes(o.suite)) {
      if (!o.scenes.empty() && std::find(o.scenes.begin(), o.scenes.end(), s.key) == o.scenes.end()) continue;
      const auto start = std::chrono::steady_clock::now();
      quality::QualityScene scene(s.key, s.label, s.source, false, registry, s.environment, s.motion);
      const med::FrameBuffer ref = quality::reference(scene, o.reference);
      if (!o.pngDir.empty()) med::writeImage(fmt::format("{}/{}_reference.png", o.pngDir, s.key), ref);
      SceneRow row{s.label, s.kind, {}};
      for (const auto& c : configs) row.curves.push_back(curve(scene, o, c, ref));
      rows.push_back(std::move(row));
      note(fmt::format("{} done in {:.0f} s", s.label,
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()));
    }
    quality::publishTables(tables(rows, configs, o), o.out);
  } catch (const std::exception& e) {
    std::cerr << "sampling_quality: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
