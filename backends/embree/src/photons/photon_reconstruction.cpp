// PhotonSequence::reconstruct: the validity test of Myszkowski et al. 2001
// (eq. 1) bounds each element's temporal window, then the space-time
// bilateral filter of Weber et al. 2004 (eq. 2) runs inside it.
#include "photons/photon_sequence_state.hpp"
#include "tsr/embree/error.hpp"
#include "tsr/embree/rng.hpp"
#include "tsr/embree/sampling.hpp"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/enumerable_thread_specific.h>
#include <oneapi/tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include <atomic>
#include <cmath>
#include <string>
#include <tuple>

namespace tsr::embree {

namespace {

std::atomic<std::uint64_t> nextFieldUid{1};

// Corner values: area-weighted means over the elements at each corner that
// lie within the crease angle of this one, so the lookup is continuous
// across element borders on smooth surfaces.
std::vector<glm::vec3> cornerValues(const ElementSet& set, const ElementGeometry& geo,
                                    const std::vector<glm::vec3>& value, float cosCrease, tbb::task_arena& arena) {
  const std::size_t elements = value.size();
  std::vector<glm::vec3> corner(3 * elements);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, elements, 1024),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t e = r.begin(); e != r.end(); ++e) {
                          for (int k = 0; k < 3; ++k) {
                            const std::uint32_t v = set.corners[3 * e + k];
                            glm::vec3 sum(0.0f);
                            float area = 0.0f;
                            for (std::uint32_t i = set.vertexStart[v]; i < set.vertexStart[v + 1]; ++i) {
                              const std::uint32_t p = set.vertexElements[i];
                              if (glm::dot(geo.normal[p], geo.normal[e]) < cosCrease) continue;
                              sum += geo.area[p] * value[p];
                              area += geo.area[p];
                            }
                            corner[3 * e + k] = area > 0.0f ? sum / area : value[e];
                          }
                        }
                      });
  });
  return corner;
}

// The buffered frames around t0, oldest first, as the reconstruction reads
// them: counts and energies of the chosen photons, with prefix sums over time.
struct Window {
  std::size_t frames = 0, centre = 0, elements = 0;
  std::vector<std::uint32_t> count;     // [k * elements + e]
  std::vector<glm::vec3> energyPrefix;  // [k * elements + e]: frames < k; k in [0, frames]
  std::vector<std::uint32_t> countPrefix;

  std::uint32_t n(std::size_t k, std::size_t e) const { return count[k * elements + e]; }
  // Energy and photons of element e over frames [a, b].
  glm::vec3 energy(std::size_t a, std::size_t b, std::size_t e) const {
    return energyPrefix[(b + 1) * elements + e] - energyPrefix[a * elements + e];
  }
  std::uint32_t photons(std::size_t a, std::size_t b, std::size_t e) const {
    return countPrefix[(b + 1) * elements + e] - countPrefix[a * elements + e];
  }
};

// 002 eq. 1 outward from the centre, on the photon counts per frame `n` of
// one support: mu over the three frames around t0, x over the three frames
// ending at the tested one (so a step is caught at the first frame after
// it); at least `minSide` frames each way.
std::pair<std::size_t, std::size_t> validExtent(const std::vector<float>& n, std::size_t centre, float k,
                                                std::size_t minSide) {
  const std::ptrdiff_t c = std::ptrdiff_t(centre), last = std::ptrdiff_t(n.size()) - 1;
  auto mean = [&](std::ptrdiff_t a, std::ptrdiff_t b) {
    a = std::max<std::ptrdiff_t>(a, 0);
    b = std::min(b, last);
    float sum = 0.0f;
    for (std::ptrdiff_t i = a; i <= b; ++i) sum += n[std::size_t(i)];
    return sum / float(b - a + 1);
  };
  const float mu = mean(c - 1, c + 1);
  const float sigma = mu > 0.0f ? std::sqrt(mu) : 1.0f;
  auto valid = [&](float x) { return x >= mu - k * sigma && x <= mu + k * sigma; };
  std::size_t back = 0, fwd = 0;
  while (back < centre) {
    const std::ptrdiff_t d = c - std::ptrdiff_t(back) - 1;
    if (back >= minSide && !valid(mean(d, d + 2))) break;
    ++back;
  }
  while (centre + fwd + 1 < n.size()) {
    const std::ptrdiff_t d = c + std::ptrdiff_t(fwd) + 1;
    if (fwd >= minSide && !valid(mean(d - 2, d))) break;
    ++fwd;
  }
  return {back, fwd};
}

// Weber eq. 5: the five frames nearest k inside [lo, hi].
std::pair<std::size_t, std::size_t> fiveFrames(std::size_t k, std::size_t lo, std::size_t hi) {
  const std::size_t span = std::min<std::size_t>(5, hi - lo + 1);
  std::size_t a = k >= lo + 2 ? k - 2 : lo;
  if (a + span - 1 > hi) a = hi + 1 - span;
  return {a, a + span - 1};
}

// The window's counts and energies of the half-set's photons, oldest frame
// first, with their prefix sums. A half-set's energy counts twice: it
// stands for all photons.
template <class Slot>
Window windowOf(const std::vector<const Slot*>& slots, std::size_t centre, std::size_t elements, PhotonHalf half) {
  Window w;
  w.elements = elements;
  w.centre = centre;
  w.frames = slots.size();
  w.count.resize(w.frames * elements);
  w.countPrefix.assign((w.frames + 1) * elements, 0);
  w.energyPrefix.assign((w.frames + 1) * elements, glm::vec3(0.0f));
  const float scale = half == PhotonHalf::All ? 1.0f : 2.0f;
  for (std::size_t k = 0; k < w.frames; ++k) {
    for (std::size_t e = 0; e < elements; ++e) {
      const std::uint32_t* c = &slots[k]->count[2 * e];
      const glm::vec3* en = &slots[k]->energy[2 * e];
      std::uint32_t n = half == PhotonHalf::All ? c[0] + c[1] : half == PhotonHalf::Even ? c[0] : c[1];
      glm::vec3 energy = half == PhotonHalf::All ? en[0] + en[1] : scale * (half == PhotonHalf::Even ? en[0] : en[1]);
      w.count[k * elements + e] = n;
      w.countPrefix[(k + 1) * elements + e] = w.countPrefix[k * elements + e] + n;
      w.energyPrefix[(k + 1) * elements + e] = w.energyPrefix[k * elements + e] + energy;
    }
  }
  return w;
}

// Weber eq. 5 over frames [a, b] for element e: its energy per frame and area.
glm::vec3 irradianceOver(const Window& w, const ElementGeometry& geo, std::size_t a, std::size_t b, std::size_t e) {
  const float area = geo.area[e];
  return area > 0.0f ? w.energy(a, b, e) / (float(b - a + 1) * area) : glm::vec3(0.0f);
}

// Eq. 5 over the whole window, the common case, computed once.
std::vector<glm::vec3> wholeWindowIrradiance(const Window& w, const ElementGeometry& geo) {
  std::vector<glm::vec3> whole(w.frames * w.elements);
  for (std::size_t k = 0; k < w.frames; ++k)
    for (std::size_t e = 0; e < w.elements; ++e) {
      const auto [a, b] = fiveFrames(k, 0, w.frames - 1);
      whole[k * w.elements + e] = irradianceOver(w, geo, a, b, e);
    }
  return whole;
}

// The frames around the centre between which no source's power steps. A
// light whose power steps between two frames (switched, dimmed at once)
// changes every element it reaches: the window of every element ends
// there. The emitted power is known exactly, so unlike the counts' test
// this needs no noise margin; gradual changes below `step` pass.
template <class Slot>
std::pair<std::size_t, std::size_t> steadyEmission(const std::vector<const Slot*>& slots, std::size_t centre,
                                                   float step) {
  auto jump = [&](std::size_t a, std::size_t b) {
    const auto& pa = slots[a]->sourcePower;
    const auto& pb = slots[b]->sourcePower;
    if (pa.size() != pb.size()) return true;
    for (std::size_t i = 0; i < pa.size(); ++i) {
      const float la = luminance(pa[i]), lb = luminance(pb[i]);
      if (std::abs(la - lb) > step * std::max(la, lb)) return true;
    }
    return false;
  };
  std::pair<std::size_t, std::size_t> steady{centre, centre};
  while (steady.first > 0 && !jump(steady.first - 1, steady.first)) --steady.first;
  while (steady.second + 1 < slots.size() && !jump(steady.second, steady.second + 1)) ++steady.second;
  return steady;
}

// Ring neighbourhoods of an element: BFS layers over shared corners, not
// across creases. One a thread: its visit stamps span every element.
class RingSearch {
 public:
  std::vector<std::uint32_t> members;  // the element first, ring by ring
  std::vector<std::uint32_t> ringEnd;  // members of rings [0, r] end at ringEnd[r]

  // Rings around q until they hold `want` photons over frames [lo, hi],
  // plus one ring, at most maxRings + 1. Returns the number of rings.
  std::size_t grow(const ElementSet& set, const ElementGeometry& geo, const Window& w, std::uint32_t maxRings,
                   float cosCrease, std::size_t q, std::size_t lo, std::size_t hi, float want) {
    if (stamp_.size() != w.elements) stamp_.assign(w.elements, 0), current_ = 0;
    if (++current_ == 0) std::fill(stamp_.begin(), stamp_.end(), 0), current_ = 1;
    members.assign(1, std::uint32_t(q));
    ringEnd.assign(1, 1);
    stamp_[q] = current_;
    float photons = float(w.photons(lo, hi, q));
    std::size_t rings = 0, extra = 0;
    while (rings < maxRings + 1) {
      if (photons >= want || rings == maxRings) {
        if (extra == 1) break;
        extra = 1;
      }
      const std::size_t from = rings == 0 ? 0 : ringEnd[rings - 1], to = ringEnd[rings];
      for (std::size_t m = from; m < to; ++m) {
        const std::uint32_t* c = &set.corners[3 * std::size_t(members[m])];
        for (int k = 0; k < 3; ++k) {
          for (std::uint32_t i = set.vertexStart[c[k]]; i < set.vertexStart[c[k] + 1]; ++i) {
            const std::uint32_t p = set.vertexElements[i];
            if (stamp_[p] == current_) continue;
            stamp_[p] = current_;
            if (glm::dot(geo.normal[p], geo.normal[q]) < cosCrease) continue;
            members.push_back(p);
            photons += float(w.photons(lo, hi, p));
          }
        }
      }
      if (members.size() == to) break;  // nothing more to reach
      ringEnd.push_back(std::uint32_t(members.size()));
      ++rings;
      if (extra == 1) break;
    }
    return rings;
  }

 private:
  std::vector<std::uint32_t> stamp_;
  std::uint32_t current_ = 0;
};

// What filtering one element needs, shared by all elements of a
// reconstruction; run(q) writes element q's window, rings and value into
// `out`, `filtered` and `cut`. Each q is one task's, so the tasks share the
// filter without writing the same entry.
struct ElementFilter {
  const ElementSet& set;
  const ElementGeometry& geo;
  const Window& w;
  const std::vector<glm::vec3>& wholeWindow;
  const PhotonSettings& cfg;
  std::pair<std::size_t, std::size_t> emission;
  float cosCrease, target, quantum;
  std::size_t minSide;
  Reconstruction& out;
  std::vector<glm::vec3>& filtered;
  std::vector<std::uint8_t>& cut;

  struct Scratch {
    RingSearch rings;
    std::vector<float> supportCounts;  // photons per frame over the support
  };

  void run(std::size_t q, Scratch& sc) const {
    const auto [lo, hi, wholeRings] = temporalExtent(q, sc);
    const std::size_t rings = (lo == 0 && hi + 1 == w.frames)
                                  ? wholeRings
                                  : sc.rings.grow(set, geo, w, cfg.maxRings, cosCrease, q, lo, hi, target);
    out.rings[q] = std::uint8_t(rings);
    float ringRadius = 0.0f;
    if (rings > 0)
      for (std::size_t m = sc.rings.ringEnd[rings - 1]; m < sc.rings.members.size(); ++m)
        ringRadius = std::max(ringRadius, glm::length(geo.centroid[sc.rings.members[m]] - geo.centroid[q]));
    filtered[q] = bilateral(q, lo, hi, 0.5f * ringRadius, sc.rings.members);
  }

 private:
  // 002's validity test bounds q's window [lo, hi]. It counts the photons of
  // the support the whole window would use, not of q alone: one element
  // sees a few photons a frame, and with sigma = sqrt(mu) a step of several
  // times its level would pass (002 tests the energy of a region large
  // enough to be stable). Also returns the rings of that whole support.
  std::tuple<std::size_t, std::size_t, std::size_t> temporalExtent(std::size_t q, Scratch& sc) const {
    const std::size_t wholeRings = sc.rings.grow(set, geo, w, cfg.maxRings, cosCrease, q, 0, w.frames - 1, target);
    sc.supportCounts.assign(w.frames, 0.0f);
    for (std::uint32_t p : sc.rings.members)
      for (std::size_t k = 0; k < w.frames; ++k) sc.supportCounts[k] += float(w.n(k, p));
    auto [back, fwd] = validExtent(sc.supportCounts, w.centre, cfg.validityK, minSide);
    back = std::min(back, w.centre - emission.first);
    fwd = std::min(fwd, emission.second - w.centre);
    out.backward[q] = std::uint8_t(back);
    out.forward[q] = std::uint8_t(fwd);
    const std::size_t lo = w.centre - back, hi = w.centre + fwd;
    cut[q] = (lo > 0 || hi + 1 < w.frames) ? 1 : 0;
    return {lo, hi, wholeRings};
  }

  // Weber eq. 2 over the support `members` and frames [lo, hi].
  glm::vec3 bilateral(std::size_t q, std::size_t lo, std::size_t hi, float sigmaS,
                      const std::vector<std::uint32_t>& members) const {
    const bool whole = lo == 0 && hi + 1 == w.frames;
    auto irradiance = [&](std::size_t k, std::size_t p) {  // Weber eq. 5
      if (whole) return wholeWindow[k * w.elements + p];
      const auto [a, b] = fiveFrames(k, lo, hi);
      return irradianceOver(w, geo, a, b, p);
    };
    const auto [a0, b0] = fiveFrames(w.centre, lo, hi);
    const float ref = luminance(irradiance(w.centre, q));
    // sigma_I = l * I_t0(q) (§5.1.3), but never below the reference's own
    // Poisson noise, nor, where q saw no photon, below one photon's worth.
    const float n5 = float(w.photons(a0, b0, q));
    const float floorI = geo.area[q] > 0.0f ? quantum / (float(b0 - a0 + 1) * geo.area[q]) : 0.0f;
    const float sigmaI = std::max(cfg.influence, 1.0f / std::sqrt(std::max(n5, 1.0f))) * std::max(ref, floorI);
    const float sigmaT = 0.5f * float(cfg.tMax);
    const float invS = sigmaS > 0.0f ? 1.0f / (2.0f * sigmaS * sigmaS) : 0.0f;
    const float invI = sigmaI > 0.0f ? 1.0f / (2.0f * sigmaI * sigmaI) : 0.0f;
    const float invT = 1.0f / (2.0f * sigmaT * sigmaT);
    float wT[256];
    for (std::size_t k = lo; k <= hi; ++k) {
      const float dt = float(k) - float(w.centre);
      wT[k] = std::exp(-dt * dt * invT);
    }
    glm::vec3 sum(0.0f);
    float weights = 0.0f;
    for (std::uint32_t p : members) {
      const glm::vec3 d = geo.centroid[p] - geo.centroid[q];
      const float wS = std::exp(-glm::dot(d, d) * invS);
      for (std::size_t k = lo; k <= hi; ++k) {
        const glm::vec3 value = irradiance(k, p);
        const float di = luminance(value) - ref;
        const float wgt = wS * wT[k] * (sigmaI > 0.0f ? std::exp(-di * di * invI) : 1.0f);
        sum += wgt * value;
        weights += wgt;
      }
    }
    return weights > 0.0f ? sum / weights : glm::vec3(0.0f);
  }
};

// The share of lit elements whose window was cut short.
float spatialFallback(const Window& w, const std::vector<std::uint8_t>& cut) {
  std::size_t lit = 0, cutLit = 0;
  for (std::size_t e = 0; e < w.elements; ++e) {
    if (w.photons(0, w.frames - 1, e) == 0) continue;
    ++lit;
    cutLit += cut[e];
  }
  return lit ? float(cutLit) / float(lit) : 0.0f;
}

}  // namespace

Reconstruction PhotonSequence::reconstruct(std::int64_t frame, PhotonHalf half) const {
  const State& s = *s_;
  const PhotonSettings& cfg = s.settings;
  const ElementGeometry& geo = s.buffered(frame).geometry;
  const std::size_t elements = s.elements->elementCount();

  std::vector<const State::Slot*> slots;
  std::size_t centre = 0;
  for (std::int64_t f = frame - lookahead(); f <= frame + lookahead(); ++f)
    if (const State::Slot* slot = s.slot(f)) {
      if (f == frame) centre = slots.size();
      slots.push_back(slot);
    }
  const Window w = windowOf(slots, centre, elements, half);
  const std::vector<glm::vec3> wholeWindow = wholeWindowIrradiance(w, geo);

  Reconstruction out;
  out.backward.resize(elements);
  out.forward.resize(elements);
  out.rings.resize(elements);
  std::vector<glm::vec3> filtered(elements, glm::vec3(0.0f));
  std::vector<std::uint8_t> cut(elements, 0);
  const float scale = half == PhotonHalf::All ? 1.0f : 2.0f;
  const ElementFilter filter{.set = *s.elements,
                             .geo = geo,
                             .w = w,
                             .wholeWindow = wholeWindow,
                             .cfg = cfg,
                             .emission = steadyEmission(slots, centre, cfg.emissionStep),
                             .cosCrease = std::cos(cfg.creaseAngle),
                             .target = 1.0f / (cfg.accuracy * cfg.accuracy),  // eq. 4: photons in the support
                             .quantum = scale * s.photonEnergy,               // one photon's energy in this half-set
                             .minSide = (std::max(cfg.minFrames, 1u) - 1) / 2,
                             .out = out,
                             .filtered = filtered,
                             .cut = cut};
  tbb::enumerable_thread_specific<ElementFilter::Scratch> scratch;
  s.arena->execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, elements, 256), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t q = r.begin(); q != r.end(); ++q) filter.run(q, scratch.local());
    });
  });

  out.spatialFallback = spatialFallback(w, cut);
  out.field.corner_ = cornerValues(*s.elements, geo, filtered, filter.cosCrease, *s.arena);
  out.field.elements_ = s.elements;
  out.field.element_ = std::move(filtered);
  out.field.sceneUid_ = s.sceneUid;
  out.field.uid_ = nextFieldUid.fetch_add(1);
  return out;
}

IrradianceField PhotonSequence::field(std::vector<glm::vec3> irradiance) const {
  const State& s = *s_;
  const ElementGeometry& geo = s.buffered(s.last).geometry;
  if (irradiance.size() != s.elements->elementCount())
    throw Error("irradiance for " + std::to_string(irradiance.size()) + " elements, the sequence has " +
                std::to_string(s.elements->elementCount()));
  IrradianceField out;
  out.corner_ = cornerValues(*s.elements, geo, irradiance, std::cos(s.settings.creaseAngle), *s.arena);
  out.elements_ = s.elements;
  out.element_ = std::move(irradiance);
  out.sceneUid_ = s.sceneUid;
  out.uid_ = nextFieldUid.fetch_add(1);
  return out;
}

bool IrradianceField::fits(const Scene& scene) const { return elements_ && elements_->matches(scene.state()); }

glm::vec3 IrradianceField::at(std::uint32_t instance, std::uint32_t prim, float b1, float b2) const {
  if (!elements_) return glm::vec3(0.0f);
  glm::vec3 wgt;
  const std::uint32_t e = elements_->locate(instance, prim, b1, b2, &wgt);
  if (e == kNoElement) return glm::vec3(0.0f);
  const glm::vec3* c = &corner_[3 * std::size_t(e)];
  return wgt.x * c[0] + wgt.y * c[1] + wgt.z * c[2];
}

}  // namespace tsr::embree
