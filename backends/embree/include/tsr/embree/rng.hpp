#pragma once

#include <glm/vec2.hpp>

#include <cstdint>

namespace tsr::embree {

constexpr std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Counter-based generator: the stream is a pure function of (seed, pixel in
// full-image coordinates, sample index), so an image does not depend on the
// thread count, the tiling or the region that was rendered.
class Rng {
 public:
  // A pixel's key is computed once for all its samples.
  Rng(std::uint64_t pixelKey, std::uint64_t sample) : key_(splitmix64(pixelKey ^ sample)) {}
  static std::uint64_t pixelKey(std::uint64_t seed, std::uint32_t x, std::uint32_t y) {
    return splitmix64(splitmix64(seed) ^ ((std::uint64_t(x) << 32) | y));
  }

  std::uint64_t nextU64() { return splitmix64(key_ ^ (++counter_ * 0xD1B54A32D192ED03ull)); }

  void skip(std::uint64_t numbers) { counter_ += numbers; }

  // Uniform in [0, 1): 24 random bits fit a float mantissa exactly.
  float uniform() { return float(nextU64() >> 40) * 0x1p-24f; }
  glm::vec2 uniform2() {
    float a = uniform();
    return {a, uniform()};
  }

 private:
  std::uint64_t key_;
  std::uint64_t counter_ = 0;
};

}  // namespace tsr::embree
