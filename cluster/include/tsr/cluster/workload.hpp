#pragma once
// Who rendered what of a cluster frame and what it cost (Schwenk, figure
// 5.8: one image per server showing its part of the frame). The client
// records every tile it placed (ClusterFrame::tiles); here they are added up
// per node, with the balance of the frame, and drawn as the `workload`
// image: each pixel in its node's colour, darker the quicker its tile was.
#include <algorithm>
#include <cstdint>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "tsr/med/view.hpp"

namespace tsr::cluster {

// The named output (an AOV) a ClusterWindow draws itself rather than asking
// the nodes for: cooperative and (mono) tiled modes.
inline constexpr std::string_view kWorkloadOutput = "workload";

// One rectangle of a frame as the client placed it.
struct TileWork {
  static constexpr std::size_t kNoNode = ~std::size_t{0};
  med::PixelRect rect;         // in the frame's pixels
  std::size_t node = kNoNode;  // config order; kNoNode: given up (a wall screen shown offline)
  double seconds = 0;          // the node's time rendering it (RenderTile::seconds)
  std::uint32_t samples = 0;   // samples per pixel it holds after the frame
  std::uint64_t rays = 0;      // rays cast rendering it
  double syncSeconds = 0;      // of `seconds`, catching the node's back-end up with the scene's changes

  // What the tile itself cost: its seconds without the catching up that
  // the frame's first tile on a node pays for all of them.
  double renderSeconds() const { return std::max(0.0, seconds - syncSeconds); }
};

// One node's share of a frame.
struct NodeWork {
  std::size_t tiles = 0;
  std::uint64_t pixels = 0;
  std::uint64_t samples = 0;  // pixel samples its tiles hold: the sum of pixels x samples per pixel
  std::uint64_t rays = 0;
  double seconds = 0;      // the sum of its tiles' times, catching up included
  double syncSeconds = 0;  // of which catching up with the scene's changes
  double busySeconds = 0;  // its whole requests, encoding and sending included (FrameDone)
};

struct FrameWorkload {
  std::vector<NodeWork> nodes;  // config order
  // The slowest taking part node's render seconds over their mean: 1 is
  // perfectly even, N (of N nodes) one node doing everything. 1 without
  // nodes or time.
  double balance = 1.0;
};

// Adds up `tiles` per node. `busySeconds` per node (config order, may be
// shorter); `participants`: the nodes that could take work in the frame
// (those online when it was planned), over which the balance is taken — a
// node left without tiles counts with 0 s.
FrameWorkload summarizeWorkload(const std::vector<TileWork>& tiles, const std::vector<double>& busySeconds,
                                const std::vector<std::size_t>& participants, std::size_t nodeCount);

// A node's colour in linear RGB: eight hues told apart by people with the
// common colour-vision deficiencies too (Okabe and Ito); nodes 8 to 15 get
// them again lighter, 16 to 23 darker, and so on (beyond eight nodes a hue
// no longer names one node alone). Black belongs to no node.
glm::vec3 nodeColour(std::size_t node);
// How bright a tile of `seconds` is drawn in a frame whose slowest tile took
// `slowest`: from 0.2 (no time) to 1 (the slowest), linearly.
float workloadShade(double seconds, double slowest);

// The workload image of a width x height frame (row by row, alpha 1):
// every tile's pixels in nodeColour(node) x workloadShade(its
// renderSeconds(), the frame's slowest such), so the scene's uneven cost
// shows rather than which tile happened to catch its node up; pixels of no
// tile, or of a given-up one, black.
std::vector<glm::vec4> drawWorkload(const std::vector<TileWork>& tiles, std::uint32_t width, std::uint32_t height);

}  // namespace tsr::cluster
