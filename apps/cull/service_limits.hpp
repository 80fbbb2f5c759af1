#pragma once
// What one client may hold of tessera-cull, and how long the service waits
// for it: the limits that keep the many served when a few are slow, idle
// or greedy (the command line sets each; the defaults suit a browser or
// two per address). Over a limit a client gets 429 (its own share used)
// or 503 (the service's), with Retry-After, never a reset.
#include <chrono>
#include <cstddef>
#include <cstdint>

namespace tsr::app {

struct ServiceLimits {
  using Seconds = std::chrono::duration<double>;
  int ioThreads = 2;                  // the network's threads (all connections share them)
  int maxConnections = 4096;          // open at once, from everyone
  int connectionsPerAddress = 16;     // open at once, from one client address
  int requestsPerAddress = 8;         // /v1/cull requests queued or ranked at once, per address
  int previewsPerAddress = 2;         // /v1/preview streams at once, per address
  std::size_t cullQueue = 128;        // /v1/cull requests waiting, from everyone
  Seconds headerTimeout{5.0};         // a new connection's request line and headers
  Seconds keepAliveTimeout{5.0};      // an idle keep-alive connection's next request headers
  Seconds transferTimeout{5.0};       // a body or a response, plus its size at minRate
  std::uint64_t minRate = 16 * 1024;  // bytes per second a body or response must at least move
  Seconds pingTimeout{20.0};          // a preview WebSocket that answers no ping for this long closes
  Seconds lingerTime{1.0};            // after a last reply: reading what the client still sends, then closing
  static constexpr std::size_t kMaxBodyBytes = 64 * 1024;
  static constexpr std::size_t kMaxHeaderBytes = 8 * 1024;

  // The deadline for moving `bytes` of a body or response.
  Seconds transferDeadline(std::uint64_t bytes) const {
    return transferTimeout + Seconds(double(bytes) / double(minRate));
  }
};

}  // namespace tsr::app
