#pragma once
// The random numbers of one path sample. Each is a pure function of
// (seed, pixel in full-image coordinates, sample index, dimension), so an
// image does not depend on threads, tiles, regions or cluster nodes.
//
// Sobol (the default): every draw is a fresh "dimension set" of Owen-
// scrambled Sobol points (Burley 2020, "Practical Hash-based Owen
// Scrambling"; the design of Cycles' Sobol-Burley): a 1-D draw takes
// Sobol's first dimension (van der Corput), a 2-D draw its first two,
// which form a (0,2)-sequence. The sample index is shuffled by a nested
// uniform scramble and every set is scrambled by its own seed, hashed from
// the pixel and the set's number (padding: sets are independent of one
// another, each stratified on its own). So the first 2^k samples of a
// pixel fall one per elementary interval of every 2-D set it draws, for
// every k: progressive passes of 1, 2, 4, 8 ... samples stay stratified.
//
// Independent: every number is white noise from a counter hash (Rng), the
// sampler before this one, kept for comparison (--param sampler=independent).
//
// Sets are numbered in the order the path draws them (as pbrt-v4's
// samplers count dimensions): camera jitter (2-D), lens (2-D, with an
// aperture), shutter time (1-D, with a shutter); then per segment of the
// path: medium channel and distance (1-D each, in a homogeneous medium; a
// textured one draws as many as its tracking needs), and per scattering
// vertex light choice (1-D), point on the emitter (2-D), environment
// direction (2-D), BSDF direction (2-D), BSDF lobe (1-D), roulette (1-D).
// See backends/embree/README.md, "Sampling".
#include "tsr/embree/rng.hpp"

#include <glm/vec2.hpp>

#include <cstdint>

namespace tsr::embree {

enum class SamplerKind : std::uint8_t { Sobol, Independent };

namespace sobol {

constexpr std::uint32_t reverseBits(std::uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  return __builtin_bswap32(x);  // the bytes in reverse order: one instruction
}

// A random permutation of the bits' values in which each bit is flipped by
// a function of the bits below it only (Laine-Karras style; the operations
// and constants of Vegdahl's improved hash, as Cycles uses them). Applied
// to bit-reversed numbers this is Owen scrambling of a 32-bit fraction:
// reverse(scramble(reverse(x))).
inline std::uint32_t lowToHighScramble(std::uint32_t x, std::uint32_t seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

// Shuffles sample indices so that every aligned block of 2^k indices maps
// to an aligned block of 2^k (Burley's nested uniform scramble). Takes the
// index already bit-reversed: a sample reverses it once for all its sets.
inline std::uint32_t shuffleReversedIndex(std::uint32_t reversedIndex, std::uint32_t seed) {
  return reverseBits(lowToHighScramble(reversedIndex, seed));
}

// Sobol's second dimension (direction numbers of the polynomial x + 1) is
// linear over GF(2) in the index: the XOR of its direction numbers for the
// index's set bits, looked up a byte at a time. Bit reversal is linear too,
// so the table holds the direction numbers reversed, which is the order
// Owen scrambling wants them in: reverse(dimension(i)) without reversing.
struct ReversedSecondDimensionTable {
  std::uint32_t byByte[4][256];
  constexpr ReversedSecondDimensionTable() : byByte{} {
    std::uint32_t v[32] = {};
    v[0] = 1u << 31;
    for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
    for (int b = 0; b < 4; ++b)
      for (std::uint32_t x = 0; x < 256; ++x) {
        std::uint32_t r = 0;
        for (int k = 0; k < 8; ++k)
          if (x & (1u << k)) r ^= v[8 * b + k];
        byByte[b][x] = reverseBits(r);
      }
  }
};
inline constexpr ReversedSecondDimensionTable kReversedSecondDimension{};

inline std::uint32_t reversedSecondDimension(std::uint32_t i) {
  const auto& t = kReversedSecondDimension.byByte;
  return t[0][i & 255u] ^ t[1][(i >> 8) & 255u] ^ t[2][(i >> 16) & 255u] ^ t[3][i >> 24];
}

// 24 bits fit a float mantissa exactly: [0, 1).
inline float toUnit(std::uint32_t x) { return float(x >> 8) * 0x1p-24f; }

// Three 32-bit seeds of one set in one pixel: index shuffle, first and
// second coordinate's scramble.
struct SetSeeds {
  std::uint32_t shuffle, first, second;
  SetSeeds(std::uint64_t pixelKey, std::uint32_t set) {
    const std::uint64_t a = splitmix64(pixelKey ^ (std::uint64_t(set) * 0x9E3779B97F4A7C15ull));
    const std::uint64_t b = splitmix64(a);
    shuffle = std::uint32_t(a), first = std::uint32_t(a >> 32), second = std::uint32_t(b >> 32);
  }
};

// The scrambled Sobol point of set `set` in the pixel `pixelKey` names, at
// the sample whose bit-reversed index is `reversedIndex`; 1-D draws use the
// first coordinate. Sobol's first dimension is the bit-reversed index, so
// scrambling it is reverse(scramble(i)).
inline glm::vec2 point2(std::uint64_t pixelKey, std::uint32_t set, std::uint32_t reversedIndex) {
  const SetSeeds s(pixelKey, set);
  const std::uint32_t i = shuffleReversedIndex(reversedIndex, s.shuffle);
  return {toUnit(reverseBits(lowToHighScramble(i, s.first))),
          toUnit(reverseBits(lowToHighScramble(reversedSecondDimension(i), s.second)))};
}

inline float point1(std::uint64_t pixelKey, std::uint32_t set, std::uint32_t reversedIndex) {
  const SetSeeds s(pixelKey, set);
  return toUnit(reverseBits(lowToHighScramble(shuffleReversedIndex(reversedIndex, s.shuffle), s.first)));
}

}  // namespace sobol

class Sampler {
 public:
  // pixelKey: Rng::pixelKey(seed, x, y) of the full-image pixel.
  Sampler(SamplerKind kind, std::uint64_t pixelKey, std::uint32_t sample)
      : kind_(kind), pixelKey_(pixelKey), reversedSample_(sobol::reverseBits(sample)), rng_(pixelKey, sample) {}

  SamplerKind kind() const { return kind_; }

  float uniform() {
    if (kind_ == SamplerKind::Independent) return rng_.uniform();
    return sobol::point1(pixelKey_, set_++, reversedSample_);
  }
  glm::vec2 uniform2() {
    if (kind_ == SamplerKind::Independent) return rng_.uniform2();
    return sobol::point2(pixelKey_, set_++, reversedSample_);
  }
  // A draw of `numbers` (1 or 2) whose value is not needed: nothing is
  // computed, and every later draw gives what it would have given.
  void skip(std::uint32_t numbers) {
    if (kind_ == SamplerKind::Independent)
      rng_.skip(numbers);
    else
      ++set_;
  }

 private:
  SamplerKind kind_;
  std::uint64_t pixelKey_;
  std::uint32_t reversedSample_;  // the sample index, bit-reversed once for every set
  std::uint32_t set_ = 0;
  Rng rng_;
};

}  // namespace tsr::embree
