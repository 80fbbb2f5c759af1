#include "tsr/cluster/workload.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace tsr::cluster {

FrameWorkload summarizeWorkload(const std::vector<TileWork>& tiles, const std::vector<double>& busySeconds,
                                const std::vector<std::size_t>& participants, std::size_t nodeCount) {
  FrameWorkload out;
  out.nodes.resize(nodeCount);
  for (const TileWork& t : tiles) {
    if (t.node >= nodeCount) continue;
    NodeWork& n = out.nodes[t.node];
    const std::uint64_t pixels = std::uint64_t{t.rect.width()} * t.rect.height();
    ++n.tiles;
    n.pixels += pixels;
    n.samples += pixels * t.samples;
    n.rays += t.rays;
    n.seconds += t.seconds;
    n.syncSeconds += t.syncSeconds;
  }
  for (std::size_t i = 0; i < std::min(nodeCount, busySeconds.size()); ++i) out.nodes[i].busySeconds = busySeconds[i];
  double sum = 0, slowest = 0;
  std::size_t counted = 0;
  for (std::size_t i : participants) {
    if (i >= nodeCount) continue;
    sum += out.nodes[i].seconds;
    slowest = std::max(slowest, out.nodes[i].seconds);
    ++counted;
  }
  if (counted > 0 && sum > 0) out.balance = slowest / (sum / static_cast<double>(counted));
  return out;
}

namespace {
float linearFromSrgb(int value) {
  const float c = static_cast<float>(value) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
}  // namespace

glm::vec3 nodeColour(std::size_t node) {
  // Okabe & Ito's palette without its black (kept for "no node"), grey last.
  static constexpr std::array<std::array<int, 3>, 8> kSrgb{{{230, 159, 0},
                                                            {86, 180, 233},
                                                            {0, 158, 115},
                                                            {240, 228, 66},
                                                            {0, 114, 178},
                                                            {213, 94, 0},
                                                            {204, 121, 167},
                                                            {153, 153, 153}}};
  const auto& c = kSrgb[node % kSrgb.size()];
  glm::vec3 colour(linearFromSrgb(c[0]), linearFromSrgb(c[1]), linearFromSrgb(c[2]));
  switch ((node / kSrgb.size()) % 3) {
    case 1:  // the ninth to sixteenth node: lighter
      return 0.5f * colour + glm::vec3(0.5f);
    case 2:  // then darker
      return 0.45f * colour;
    default:
      return colour;
  }
}

float workloadShade(double seconds, double slowest) {
  if (!(slowest > 0) || !std::isfinite(seconds)) return 1.0f;
  return static_cast<float>(0.2 + 0.8 * std::clamp(seconds / slowest, 0.0, 1.0));
}

std::vector<glm::vec4> drawWorkload(const std::vector<TileWork>& tiles, std::uint32_t width, std::uint32_t height) {
  std::vector<glm::vec4> image(std::size_t{width} * height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  double slowest = 0;
  for (const TileWork& t : tiles)
    if (t.node != TileWork::kNoNode) slowest = std::max(slowest, t.renderSeconds());
  for (const TileWork& t : tiles) {
    if (t.node == TileWork::kNoNode) continue;
    const glm::vec4 colour(nodeColour(t.node) * workloadShade(t.renderSeconds(), slowest), 1.0f);
    const std::uint32_t x1 = std::min(t.rect.x1, width), y1 = std::min(t.rect.y1, height);
    for (std::uint32_t y = t.rect.y0; y < y1; ++y)
      std::fill(image.begin() + std::ptrdiff_t(std::size_t{y} * width + t.rect.x0),
                image.begin() + std::ptrdiff_t(std::size_t{y} * width + std::max(x1, t.rect.x0)), colour);
  }
  return image;
}

}  // namespace tsr::cluster
