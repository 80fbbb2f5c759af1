#pragma once
// What the path tracer is told besides the scene, camera and region.
#include "tsr/embree/sampler.hpp"

#include <cstdint>
#include <initializer_list>

namespace tsr::embree {

// Which estimator handles emitters and the environment. Mis is the normal
// mode; the single-strategy modes exist to validate it (same expectation).
enum class LightSampling { Mis, LightOnly, BsdfOnly };

// How the emitter triangle for a shadow ray is picked: by what each can
// give at the shading point (a light tree), or by power alone.
enum class LightChoice { Tree, Power };

struct RenderSettings {
  std::uint64_t seed = 0;
  std::uint32_t maxDepth = 8;        // scattering events; 1 = direct lighting only
  std::uint32_t rouletteDepth = 3;   // Russian roulette from this many events on
  std::uint32_t samplesPerPass = 1;  // per pixel
  std::uint32_t tileSize = 16;
  int threads = 0;  // 0 = all hardware threads
  LightSampling lightSampling = LightSampling::Mis;
  LightChoice lightChoice = LightChoice::Tree;
  bool equiangular = true;                   // light in homogeneous media also sampled by distance towards the lights
  SamplerKind sampler = SamplerKind::Sobol;  // where each path's random numbers come from (sampler.hpp)
  // A change of the camera or of where instances stand carries up to this
  // many samples a pixel over to the new view (FrameBuffer::reproject)
  // instead of restarting; 0: every change restarts. Other edits restart.
  std::uint32_t historyLimit = 0;
  bool operator==(const RenderSettings&) const = default;
};

// One value of a choice and its name (describeSettings).
template <class E>
struct Named {
  const char* name;
  E value;
};

// The settings a user sets, each said once: its name, its field, its range
// and what it does, the default being the field's. The Embree mediator makes
// its parameters of this list and reads them back into RenderSettings
// through it, so a new setting is its field above, its line here and the
// code that reads it. `v` has integer(name, field, min, max, help),
// flag(name, field, help) and choice(name, field, {Named...}, help).
// What the mediator derives (seed per frame, direct only, the history
// switch), the work's cutting (tile size) and lightSampling (a way to
// validate MIS, for tests) are not listed.
template <class Visitor>
void describeSettings(Visitor& v) {
  using S = RenderSettings;
  v.integer("maxDepth", &S::maxDepth, 0, 1024, "maximum path depth");
  v.integer("rouletteDepth", &S::rouletteDepth, 1, 1024,
            "scattering events after which Russian roulette may end a path (unbiased: fewer means faster, noisier)");
  v.integer("seed", &S::seed, 0, INT64_MAX, "random seed");
  v.choice("sampler", &S::sampler, {{"sobol", SamplerKind::Sobol}, {"independent", SamplerKind::Independent}},
           "path samples: Owen-scrambled Sobol (stratified), or independent white noise");
  v.choice("lightChoice", &S::lightChoice, {{"tree", LightChoice::Tree}, {"power", LightChoice::Power}},
           "emitter picked for a shadow ray: by what it gives at the point (light tree), or by power");
  v.flag("equiangular", &S::equiangular,
         "light scattered in fog also sampled at distances towards the lights (equiangular, with MIS)");
  v.integer("threads", &S::threads, 0, 4096, "render threads (0: all)");
  v.integer("samplesPerPass", &S::samplesPerPass, 1, 4096, "samples per pass (unset: passes grow 1, 2, 4, 8)");
}

// The settings with those that only cut and schedule the work (pass size,
// tile size, threads) set to their defaults: what an accumulated image
// depends on. A field added above counts unless it is named here, so
// forgetting one restarts accumulation too often, never too rarely.
inline RenderSettings imageSettings(RenderSettings s) {
  const RenderSettings defaults;
  s.samplesPerPass = defaults.samplesPerPass;
  s.tileSize = defaults.tileSize;
  s.threads = defaults.threads;
  s.historyLimit = defaults.historyLimit;  // how a restart goes, not what a still view converges to
  return s;
}

}  // namespace tsr::embree
