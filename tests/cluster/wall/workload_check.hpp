#pragma once
// The properties of a workload image, checked against the tiles the client
// logged: each tile's pixels carry its node's colour (told apart by
// chromaticity, since brightness says the tile's time), the slowest tile is
// drawn at full brightness, and pixels of no tile are black.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tsr/cluster/workload.hpp"

namespace tsr::cluster::test {

// r, g, b over their sum: what shading by time leaves alone.
inline glm::vec3 chromaticity(const glm::vec3& c) {
  const float sum = c.r + c.g + c.b;
  return sum > 0 ? c / sum : glm::vec3(0.0f);
}

// The node among `nodes` whose colour a pixel shows (nearest chromaticity).
inline std::size_t nodeShown(const glm::vec4& pixel, std::size_t nodes) {
  std::size_t best = TileWork::kNoNode;
  float bestDistance = 1e9f;
  for (std::size_t n = 0; n < nodes; ++n) {
    const glm::vec3 d = chromaticity(glm::vec3(pixel)) - chromaticity(nodeColour(n));
    const float distance = d.x * d.x + d.y * d.y + d.z * d.z;
    if (distance < bestDistance) {
      bestDistance = distance;
      best = n;
    }
  }
  return best;
}

// How many tiles of `tiles` cover each pixel of a width x height frame.
inline std::vector<int> coverage(const std::vector<TileWork>& tiles, std::uint32_t width, std::uint32_t height) {
  std::vector<int> count(std::size_t{width} * height, 0);
  for (const TileWork& t : tiles)
    for (std::uint32_t y = t.rect.y0; y < std::min(t.rect.y1, height); ++y)
      for (std::uint32_t x = t.rect.x0; x < std::min(t.rect.x1, width); ++x) ++count[std::size_t{y} * width + x];
  return count;
}

inline void expectCoveredExactlyOnce(const std::vector<TileWork>& tiles, std::uint32_t width, std::uint32_t height,
                                     const std::string& what) {
  const std::vector<int> count = coverage(tiles, width, height);
  const auto wrong = std::count_if(count.begin(), count.end(), [](int c) { return c != 1; });
  EXPECT_EQ(wrong, 0) << what << ": pixels not covered by exactly one tile";
}

inline void expectWorkloadImageMatches(const std::vector<glm::vec4>& image, std::uint32_t width, std::uint32_t height,
                                       const std::vector<TileWork>& tiles, std::size_t nodes, const std::string& what) {
  ASSERT_EQ(image.size(), std::size_t{width} * height) << what;
  double slowest = 0;
  for (const TileWork& t : tiles) slowest = std::max(slowest, t.renderSeconds());
  std::size_t wrongNode = 0, unevenTile = 0;
  for (const TileWork& t : tiles) {
    ASSERT_NE(t.node, TileWork::kNoNode) << what;
    const glm::vec4 first = image[std::size_t{t.rect.y0} * width + t.rect.x0];
    for (std::uint32_t y = t.rect.y0; y < t.rect.y1; ++y)
      for (std::uint32_t x = t.rect.x0; x < t.rect.x1; ++x) {
        const glm::vec4 p = image[std::size_t{y} * width + x];
        wrongNode += nodeShown(p, nodes) != t.node ? 1 : 0;
        unevenTile += p != first ? 1 : 0;
      }
    if (t.renderSeconds() == slowest) {  // drawn at full brightness: exactly the node's colour
      const glm::vec3 full = nodeColour(t.node);
      EXPECT_NEAR(first.r, full.r, 1e-6) << what;
      EXPECT_NEAR(first.g, full.g, 1e-6) << what;
      EXPECT_NEAR(first.b, full.b, 1e-6) << what;
    }
  }
  EXPECT_EQ(wrongNode, 0u) << what << ": pixels in another node's colour than their tile's";
  EXPECT_EQ(unevenTile, 0u) << what << ": tiles not drawn in one colour";
  const std::vector<int> count = coverage(tiles, width, height);
  std::size_t litOutside = 0;
  for (std::size_t i = 0; i < count.size(); ++i)
    if (count[i] == 0 && glm::vec3(image[i]) != glm::vec3(0.0f)) ++litOutside;
  EXPECT_EQ(litOutside, 0u) << what << ": pixels of no tile not black";
}

}  // namespace tsr::cluster::test
