// temporal_quality: how much PCA projection of the indirect light over time
// (Meyer & Anderson; tessera-render --temporal pca) and spatio-temporal
// photon density estimation (Weber et al.; --temporal photons) buy on an animation,
// against every frame rendered by the same path tracer at high spp
// (cached). Prints one markdown table (and writes it with --out): relMSE
// per frame and averaged for frame-by-frame rendering and PCA at k spp,
// flicker (tRelMSE) of the indirect light, the equal-quality speedup on the
// beauty image, and whether a light switch stays a one-frame step.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
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
#include "tsr/temporal/pca_denoise.hpp"

using namespace tsr;
using Image = std::vector<glm::vec4>;
using Sequence = std::vector<Image>;

namespace {

struct Options {
  std::string scene = "builtin:animated";
  std::uint32_t size = 96;
  int frames = 16;
  double fps = 4;
  std::uint32_t k = 16;
  std::uint32_t directSpp = 0;  // 0: k (tessera-render's default)
  std::vector<std::uint32_t> fitSpp{4, 8, 16, 32, 64};
  std::uint32_t refSpp = 2048;
  std::uint64_t refSeed = 900001;
  std::uint64_t seed = 1;
  int switchFrame = -1;     // -1: frames / 2; 0: no switch
  float switchFrom = 0.3f;  // light intensity scale before the switch
  int threads = 0;
  std::string cache = "build/quality-cache";
  std::string out, pngDir;
  std::vector<int> modes{2, 1, 3, 5};  // extra rows with a fixed truncation
  bool photons = true;
  std::uint32_t photonsPerFrame = 0;  // 0: the pilot pass chooses
  std::uint32_t photonFrames = 9;
  bool objectPca = true;
  std::uint32_t highSpp = 64;  // 3.2's importance sampling rows (one of fitSpp; 0: none)
  double pan = 0;              // camera moves this many scene units to its right per second
};

float panAt(const Options& o, int frame) { return static_cast<float>(o.pan * frame / o.fps); }

void note(const std::string& s) { std::cerr << "[temporal_quality] " << s << std::endl; }

double since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::string num(double v) {
  if (!std::isfinite(v)) return "n/a";
  if (v != 0 && (std::abs(v) < 1e-3 || std::abs(v) >= 1e5)) return fmt::format("{:.2e}", v);
  return fmt::format("{:.4g}", v);
}

med::Parameters parameters(const Options& o, std::uint32_t spp, std::uint64_t seed) {
  med::Parameters p;
  p.set("spp", std::int64_t{spp});
  p.set("seed", std::int64_t(seed));
  p.set("threads", std::int64_t{o.threads});
  return p;
}

struct Split {
  Image colour, direct, indirect;
  double seconds = 0;
};

Split split(quality::Shot shot) {
  return {std::move(shot.image.colour), std::move(shot.image.outputs["direct"]),
          std::move(shot.image.outputs["indirect"]), shot.seconds};
}

// The frame's reference (colour and indirect), from the cache when there.
Split reference(quality::QualityScene& scene, const Options& o, int frame, float lightScale) {
  namespace fs = std::filesystem;
  const std::string stem = fmt::format(
      "{}_{}x{}_t{:.4f}_light{:.3f}{}_spp{}_seed{}", scene.key(), o.size, o.size, frame / o.fps, lightScale,
      o.pan != 0 ? fmt::format("_pan{:.4f}", panAt(o, frame)) : "", o.refSpp, o.refSeed + std::uint64_t(frame));
  const fs::path colour = fs::path(o.cache) / (stem + ".exr"), indirect = fs::path(o.cache) / (stem + ".indirect.exr");
  if (fs::exists(colour) && fs::exists(indirect)) {
    Split s;
    s.colour = med::readImage(colour.string()).colour;
    s.indirect = med::readImage(indirect.string()).colour;
    if (s.colour.size() != std::size_t{o.size} * o.size)
      throw std::runtime_error(colour.string() + ": wrong size; delete it");
    return s;
  }
  note(fmt::format("rendering reference frame {} ({} spp); cached afterwards", frame, o.refSpp));
  auto vp = scene.viewport(parameters(o, o.refSpp, o.refSeed + std::uint64_t(frame)));
  quality::Shot shot = scene.render(*vp, o.size, false, {"indirect"});
  fs::create_directories(o.cache);
  med::writeImage(colour.string() + ".partial.exr", shot.image);
  med::writeImage(indirect.string() + ".partial.exr", shot.image, "indirect");
  fs::rename(colour.string() + ".partial.exr", colour);
  fs::rename(indirect.string() + ".partial.exr", indirect);
  return split(std::move(shot));
}

temporal::Frame toFrame(const Image& image, std::uint32_t size) {
  temporal::Frame f(size, size);
  for (std::size_t p = 0; p < image.size(); ++p)
    for (int c = 0; c < 3; ++c) f.rgb[p * 3 + std::size_t(c)] = image[p][c];
  return f;
}

Image toImage(const temporal::Frame& f) {
  Image out(f.pixels());
  for (std::size_t p = 0; p < out.size(); ++p)
    out[p] = glm::vec4(std::max(f.rgb[p * 3], 0.0f), std::max(f.rgb[p * 3 + 1], 0.0f), std::max(f.rgb[p * 3 + 2], 0.0f),
                       1.0f);
  return out;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / double(v.size());
}

double meanLuminance(const Image& image) {
  double s = 0;
  for (const auto& p : image) s += 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
  return image.empty() ? 0 : s / double(image.size());
}

struct Method {
  std::string name;
  Sequence beauty, indirect;
  double seconds = 0;  // every cost: renders (direct samples included) and denoising
  std::string modes = "";
};

void writePngs(const Options& o, const std::string& what, const Sequence& frames) {
  if (o.pngDir.empty()) return;
  std::filesystem::create_directories(o.pngDir);
  for (std::size_t t = 0; t < frames.size(); ++t) {
    med::FrameBuffer fb(o.size, o.size);
    fb.colour = frames[t];
    med::writeImage(fmt::format("{}/{}_{:04d}.png", o.pngDir, what, t), fb);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"Temporal noise reduction quality: frame by frame vs PCA projection against high-spp references"};
  app.add_option("--scene", o.scene, "animated scene (builtin:animated or a glTF with animations)");
  app.add_option("--size", o.size, "square image side");
  app.add_option("--frames", o.frames, "frames")->check(CLI::Range(2, 100000));
  app.add_option("--fps", o.fps, "frames per second of animation time");
  app.add_option("--k", o.k, "indirect samples per pixel of the compared methods");
  app.add_option("--direct-spp", o.directSpp, "direct samples with PCA (default: k)");
  app.add_option("--fit-spp", o.fitSpp, "frame-by-frame sample counts for the relMSE = a/spp fit");
  app.add_option("--ref-spp", o.refSpp, "reference samples per pixel");
  app.add_option("--switch-frame", o.switchFrame, "frame at which the lights switch (0: none; default frames/2)");
  app.add_option("--modes", o.modes, "fixed truncations to compare (--temporal-modes)");
  app.add_option("--threads", o.threads, "render threads (0: all)");
  app.add_flag("!--no-photons", o.photons, "leave out the photon method");
  app.add_flag("!--no-object-pca", o.objectPca, "leave out object-space PCA");
  app.add_option("--high-spp", o.highSpp,
                 "3.2's importance sampling rows: the frame-by-frame render blended in (one of --fit-spp; 0: none)");
  app.add_option("--pan", o.pan, "camera moves this many scene units to its right per second (a moving camera)");
  app.add_option("--photons-per-frame", o.photonsPerFrame, "photons per frame (default: the pilot pass chooses)");
  app.add_option("--photon-frames", o.photonFrames, "the photon method's temporal window t_max (odd)");
  app.add_option("--cache", o.cache, "reference cache directory");
  app.add_option("--out", o.out, "also write the table here");
  app.add_option("--png-dir", o.pngDir, "write the frames of each method as PNGs here");
  CLI11_PARSE(app, argc, argv);
  if (o.switchFrame < 0) o.switchFrame = o.frames / 2;
  if (std::find(o.fitSpp.begin(), o.fitSpp.end(), o.k) == o.fitSpp.end()) o.fitSpp.push_back(o.k);
  std::sort(o.fitSpp.begin(), o.fitSpp.end());
  const std::uint32_t directSpp = std::max(o.k, o.directSpp);

  try {
    med::ViewportRegistry registry;
    med::registerEmbree(registry);
    std::string key = o.scene;
    std::replace_if(
        key.begin(), key.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
    quality::QualityScene scene(key, o.scene, o.scene, false, registry);

    Sequence refColour, refIndirect;
    std::map<std::uint32_t, Method> byFrame;  // frame by frame at each spp
    Sequence kDirect, kIndirect;              // the k-spp renders PCA starts from
    double kSeconds = 0;
    std::map<std::uint32_t, std::unique_ptr<med::Viewport>> viewports;
    for (auto spp : o.fitSpp) viewports[spp] = scene.viewport(parameters(o, spp, o.seed));
    auto directViewport = scene.viewport(parameters(o, directSpp, o.seed));
    for (int t = 0; t < o.frames; ++t) {
      const float light = (o.switchFrame > 0 && t < o.switchFrame) ? o.switchFrom : 1.0f;
      scene.pose(static_cast<float>(t / o.fps), light, panAt(o, t));
      Split ref = reference(scene, o, t, light);
      refColour.push_back(std::move(ref.colour));
      refIndirect.push_back(std::move(ref.indirect));
      for (auto spp : o.fitSpp) {
        // tessera-render --temporal's seeding: one seed per frame.
        viewports[spp]->setParameter("seed", std::int64_t(o.seed + std::uint64_t(t)));
        Split s = split(scene.render(*viewports[spp], o.size, false, {"direct", "indirect"}));
        Method& m = byFrame[spp];
        m.name = fmt::format("frame by frame, {} spp", spp);
        m.beauty.push_back(s.colour);
        m.indirect.push_back(s.indirect);
        m.seconds += s.seconds;
        if (spp == o.k) {
          kDirect.push_back(std::move(s.direct));
          kIndirect.push_back(std::move(s.indirect));
          kSeconds += s.seconds;
        }
      }
      if (directSpp > o.k) {
        // Direct light continues the k-spp accumulation to directSpp: only
        // the samples past k cost extra (as tessera-render does it).
        directViewport->setParameter("seed", std::int64_t(o.seed + std::uint64_t(t)));
        Split d = split(scene.render(*directViewport, o.size, false, {"direct"}));
        kDirect.back() = std::move(d.direct);
        kSeconds += d.seconds * double(directSpp - o.k) / directSpp;
      }
      note(fmt::format("frame {} of {}", t + 1, o.frames));
    }

    std::vector<Method> methods;
    for (auto& [spp, m] : byFrame) methods.push_back(m);
    // highSpp > 0: 3.2's importance sampling, blending pixels whose map
    // exceeds mMin towards the frame-by-frame render at highSpp, charged
    // for the share of pixels it covers.
    auto pca = [&](const std::string& name, temporal::PcaSettings settings, std::uint32_t highSpp = 0, float mMin = 0) {
      std::vector<temporal::Frame> stack;
      for (const auto& image : kIndirect) stack.push_back(toFrame(image, o.size));
      const auto start = std::chrono::steady_clock::now();
      const temporal::PcaResult r = temporal::denoise(stack, settings);
      const double denoise = since(start);
      Method m;
      m.name = name;
      m.seconds = kSeconds + denoise;
      m.modes = fmt::format("M = {}, mean map {:.2f}", r.globalModes, r.meanTruncation());
      std::size_t covered = 0;
      for (int t = 0; t < o.frames; ++t) {
        temporal::Frame f = r.frames[std::size_t(t)];
        if (highSpp) {
          const auto need = temporal::needsHighSamples(r.truncation, mMin);
          covered += static_cast<std::size_t>(std::count(need.begin(), need.end(), true));
          f = temporal::blendHighSamples(f, toFrame(byFrame.at(highSpp).indirect[std::size_t(t)], o.size), r.truncation,
                                         mMin, float(r.availableModes));
        }
        m.indirect.push_back(toImage(f));
        Image beauty = kDirect[std::size_t(t)];
        for (std::size_t p = 0; p < beauty.size(); ++p)
          beauty[p] = glm::vec4(glm::vec3(beauty[p]) + glm::vec3(m.indirect.back()[p]), 1.0f);
        m.beauty.push_back(std::move(beauty));
      }
      if (highSpp) {
        const double share = double(covered) / double(std::size_t{o.size} * o.size * std::size_t(o.frames));
        m.seconds += share * byFrame.at(highSpp).seconds;
        m.modes += fmt::format(", {:.0f}% of pixels at {} spp", 100 * share, highSpp);
      }
      note(fmt::format("{}: {} ({:.3f} s denoising)", name, m.modes, denoise));
      return m;
    };
    const std::string kName =
        fmt::format("{} spp{}", o.k, directSpp > o.k ? fmt::format(", direct {} spp", directSpp) : "");
    temporal::PcaSettings perPixel, global;
    global.perPixel = false;
    methods.push_back(pca("PCA, per-pixel map, " + kName, perPixel));
    if (o.highSpp && byFrame.count(o.highSpp))
      for (float mMin : {4.0f, 8.0f})
        methods.push_back(pca(fmt::format("PCA, per-pixel map, m > {} at {} spp (3.2), {}", mMin, o.highSpp, kName),
                              perPixel, o.highSpp, mMin));
    // The per-frame table and the PNGs show the first fixed truncation (with
    // path-traced noise 2.3's rule keeps every mode; see backends/temporal/README.md), else
    // the global one.
    std::size_t pcaIndex = methods.size();
    methods.push_back(pca("PCA, global M, " + kName, global));
    if (!o.modes.empty()) pcaIndex = methods.size();
    for (int m : o.modes) {
      temporal::PcaSettings fixed;
      fixed.fixedModes = m;
      methods.push_back(pca(fmt::format("PCA, M = {}, {}", m, kName), fixed));
    }

    // A method whose viewport looks ahead (photons, object-space PCA): direct
    // light at k spp per pixel, indirect from photons; every cost (pilot and
    // photon passes, denoising, direct samples) is timed.
    auto ahead = [&](const std::string& temporal, const std::vector<std::pair<std::string, std::int64_t>>& settings,
                     const std::string& name) {
      med::Parameters p = parameters(o, o.k, o.seed);
      p.set("temporal", temporal);
      p.set("photonsPerFrame", std::int64_t{o.photonsPerFrame});
      for (const auto& [key, value] : settings) p.set(key, value);
      auto vp = scene.viewport(p);
      note(name + ": tracing and rendering the sequence");
      auto shots =
          scene.renderAhead(*vp, o.size, o.frames,
                            [&](int t) {
                              scene.pose(static_cast<float>(t / o.fps),
                                         (o.switchFrame > 0 && t < o.switchFrame) ? o.switchFrom : 1.0f, panAt(o, t));
                            },
                            {"direct", "indirect"});
      Method m;
      m.name = name;
      for (auto& shot : shots) {
        Split s = split(std::move(shot));
        m.beauty.push_back(std::move(s.colour));
        m.indirect.push_back(std::move(s.indirect));
        m.seconds += s.seconds;
      }
      return m;
    };
    std::size_t photonIndex = 0, objectIndex = 0;
    if (o.photons) {
      photonIndex = methods.size();
      methods.push_back(ahead("photons", {{"photonFrames", o.photonFrames}},
                              fmt::format("photons, t_max {}, direct {} spp", o.photonFrames, o.k)));
    }
    if (o.objectPca) {
      // Object space (3.1): each element's photon irradiance per frame,
      // projected over the whole sequence.
      objectIndex = methods.size();
      methods.push_back(
          ahead("objectPca", {{"pcaWindow", o.frames}}, fmt::format("PCA, object space, direct {} spp", o.k)));
    }

    // Per method: relMSE per frame (beauty and indirect), flicker.
    struct Scores {
      std::vector<double> beauty, indirect;
      double flicker = 0;
    };
    std::vector<Scores> scores;
    for (const auto& m : methods) {
      Scores s;
      for (int t = 0; t < o.frames; ++t) {
        s.beauty.push_back(quality::relMse(m.beauty[std::size_t(t)], refColour[std::size_t(t)]));
        s.indirect.push_back(quality::relMse(m.indirect[std::size_t(t)], refIndirect[std::size_t(t)]));
      }
      s.flicker = quality::temporalRelMse(m.indirect, refIndirect);
      scores.push_back(std::move(s));
    }
    // relMSE = a / spp and time = b * spp over the frame-by-frame runs.
    double a = 0, b = 0;
    for (std::size_t i = 0; i < byFrame.size(); ++i) {
      const auto spp = o.fitSpp[i];
      a += mean(scores[i].beauty) * spp / double(byFrame.size());
      b += methods[i].seconds / spp / double(byFrame.size());
    }

    std::ostringstream table;
    table << fmt::format("## Temporal quality: {} , {} frames at {}x{}, {} fps, light x{} until frame {}\n\n", o.scene,
                         o.frames, o.size, o.size, o.fps, o.switchFrom, o.switchFrame);
    table << fmt::format("reference: {} spp per frame (cached); fit over frame by frame: relMSE = {:.4g}/spp, time = "
                         "{:.4g} s/spp for all frames\n\n",
                         o.refSpp, a, b);
    table << "| method | relMSE beauty | relMSE indirect | tRelMSE indirect | flicker vs frame by frame | time s | "
             "equal-quality speedup | modes |\n";
    table << "|---|---|---|---|---|---|---|---|\n";
    const std::size_t kIndex =
        static_cast<std::size_t>(std::find(o.fitSpp.begin(), o.fitSpp.end(), o.k) - o.fitSpp.begin());
    for (std::size_t i = 0; i < methods.size(); ++i) {
      const double rel = mean(scores[i].beauty);
      const double equalTime = b * (a / rel);  // frame by frame to the same relMSE
      table << fmt::format("| {} | {} | {} | {} | {}x lower | {} | {} | {} |\n", methods[i].name, num(rel),
                           num(mean(scores[i].indirect)), num(scores[i].flicker),
                           num(scores[kIndex].flicker / scores[i].flicker), num(methods[i].seconds),
                           num(equalTime / methods[i].seconds), methods[i].modes);
    }
    table << fmt::format("| reference, {} spp | 0 | 0 | 0 | | | | |\n\n", o.refSpp);

    table << fmt::format("relMSE per frame (beauty / indirect), frame by frame at {} spp vs {}:\n\n", o.k,
                         methods[pcaIndex].name);
    table << "| frame | frame by frame | PCA | photons | mean indirect luminance: reference | frame by frame | PCA | "
             "photons "
             "|\n|---|---|---|---|---|---|---|---|\n";
    for (int t = 0; t < o.frames; ++t) {
      const auto u = std::size_t(t);
      const bool ph = o.photons;
      table << fmt::format(
          "| {}{} | {} / {} | {} / {} | {} / {} | {} | {} | {} | {} |\n", t, t == o.switchFrame ? " (switch)" : "",
          num(scores[kIndex].beauty[u]), num(scores[kIndex].indirect[u]), num(scores[pcaIndex].beauty[u]),
          num(scores[pcaIndex].indirect[u]), ph ? num(scores[photonIndex].beauty[u]) : "",
          ph ? num(scores[photonIndex].indirect[u]) : "", num(meanLuminance(refIndirect[u])),
          num(meanLuminance(methods[kIndex].indirect[u])), num(meanLuminance(methods[pcaIndex].indirect[u])),
          ph ? num(meanLuminance(methods[photonIndex].indirect[u])) : "");
    }
    if (o.switchFrame > 0 && o.switchFrame < o.frames) {
      const auto s = std::size_t(o.switchFrame);
      auto step = [&](const Sequence& seq) { return meanLuminance(seq[s]) - meanLuminance(seq[s - 1]); };
      auto before = [&](const Sequence& seq) {
        return meanLuminance(seq[s - 1]) / meanLuminance(refIndirect[s - 1]) - 1;
      };
      table << fmt::format(
          "\nlight switch at frame {}: indirect step (mean luminance) reference {}, PCA {} ({:.0f}% of it); the frame "
          "before the switch is off by {:.1f}% (PCA) vs {:.1f}% (frame by frame)\n",
          s, num(step(refIndirect)), num(step(methods[pcaIndex].indirect)),
          100 * step(methods[pcaIndex].indirect) / step(refIndirect), 100 * before(methods[pcaIndex].indirect),
          100 * before(methods[kIndex].indirect));
      auto switchLine = [&](const char* name, std::size_t index) {
        table << fmt::format("light switch, {}: indirect step {} ({:.0f}% of the reference's); the frame before "
                             "is off by {:.1f}%\n",
                             name, num(step(methods[index].indirect)),
                             100 * step(methods[index].indirect) / step(refIndirect),
                             100 * before(methods[index].indirect));
      };
      if (o.photons) switchLine("photons", photonIndex);
      if (o.objectPca) switchLine("object-space PCA", objectIndex);
    }
    std::cout << table.str();
    if (!o.out.empty()) {
      std::filesystem::path out(o.out);
      if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
      std::ofstream(out) << table.str();
    }
    writePngs(o, "reference", refColour);
    writePngs(o, fmt::format("frame_by_frame_{}spp", o.k), methods[kIndex].beauty);
    writePngs(o, "pca", methods[pcaIndex].beauty);
    writePngs(o, "reference_indirect", refIndirect);
    writePngs(o, fmt::format("frame_by_frame_{}spp_indirect", o.k), methods[kIndex].indirect);
    writePngs(o, "pca_indirect", methods[pcaIndex].indirect);
    if (o.photons) {
      writePngs(o, "photons", methods[photonIndex].beauty);
      writePngs(o, "photons_indirect", methods[photonIndex].indirect);
    }
    if (o.objectPca) {
      writePngs(o, "pca_object", methods[objectIndex].beauty);
      writePngs(o, "pca_object_indirect", methods[objectIndex].indirect);
    }
  } catch (const std::exception& e) {
    std::cerr << "temporal_quality: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
