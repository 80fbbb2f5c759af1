#pragma once
// A relay on 127.0.0.1 that forwards one connection at a time to a target
// at a limited rate in both directions, with small socket buffers so the
// kernel does not hide the limit: a slow link for liveness tests.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "tsr/cluster/node_address.hpp"

namespace tsr::cluster::test {

class ThrottledProxy {
 public:
  ThrottledProxy(const NodeAddress& target, std::size_t bytesPerSecond) : target_(target), rate_(bytesPerSecond) {
    listener_ = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    if (bind(listener_, reinterpret_cast<sockaddr*>(&a), len) != 0 || listen(listener_, 4) != 0 ||
        getsockname(listener_, reinterpret_cast<sockaddr*>(&a), &len) != 0)
      throw std::runtime_error("proxy cannot listen");
    port_ = ntohs(a.sin_port);
    thread_ = std::thread([this] { serve(); });
  }
  ~ThrottledProxy() {
    stop_ = true;
    thread_.join();
    close(listener_);
  }
  NodeAddress address() const { return {"127.0.0.1", port_}; }
  std::size_t relayed() const { return relayed_; }

 private:
  static void smallBuffers(int fd) {
    int size = 16 * 1024;
    setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &size, sizeof size);
    setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &size, sizeof size);
  }
  bool waitReadable(int fd) {
    pollfd p{fd, POLLIN, 0};
    while (!stop_) {
      int r = poll(&p, 1, 50);
      if (r > 0) return true;
      if (r < 0) return false;
    }
    return false;
  }
  // One direction, in 4 KiB steps paced to the rate; ends when either side closes.
  void pump(int from, int to) {
    char buffer[4096];
    auto start = std::chrono::steady_clock::now();
    std::size_t moved = 0;
    while (waitReadable(from)) {
      ssize_t n = read(from, buffer, sizeof buffer);
      if (n <= 0) break;
      for (ssize_t off = 0; off < n;) {
        ssize_t w = write(to, buffer + off, static_cast<std::size_t>(n - off));
        if (w <= 0) goto done;
        off += w;
      }
      moved += static_cast<std::size_t>(n);
      relayed_ += static_cast<std::size_t>(n);
      std::this_thread::sleep_until(start + std::chrono::microseconds(moved * 1000000 / rate_));
    }
  done:
    shutdown(to, SHUT_WR);
  }
  void serve() {
    while (waitReadable(listener_)) {
      int client = accept(listener_, nullptr, nullptr);
      if (client < 0) continue;
      smallBuffers(client);
      int node = socket(AF_INET, SOCK_STREAM, 0);
      smallBuffers(node);
      sockaddr_in a{};
      a.sin_family = AF_INET;
      a.sin_port = htons(target_.port);
      inet_pton(AF_INET, target_.host.c_str(), &a.sin_addr);
      if (connect(node, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
        close(client);
        close(node);
        continue;
      }
      std::thread up([&] { pump(client, node); });
      pump(node, client);
      up.join();
      close(client);
      close(node);
    }
  }

  NodeAddress target_;
  std::size_t rate_;
  int listener_ = -1;
  std::uint16_t port_ = 0;
  std::atomic<bool> stop_{false};
  std::atomic<std::size_t> relayed_{0};
  std::thread thread_;
};

}  // namespace tsr::cluster::test
