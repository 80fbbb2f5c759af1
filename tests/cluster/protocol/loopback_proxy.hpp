#pragma once
// A TCP proxy on 127.0.0.1 in front of one node, for link faults that tc
// netem would give outside a sandbox: a bandwidth limit per direction, and
// cutting every connection (now, or after a number of bytes towards the
// node, e.g. in the middle of a snapshot). One thread per direction and
// connection; blocking sockets with short timeouts so it stops promptly.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "tsr/cluster/node_address.hpp"

namespace tsr::cluster::test {

class LoopbackProxy {
 public:
  explicit LoopbackProxy(NodeAddress target) : target_(std::move(target)) {
    listener_ = socket(AF_INET, SOCK_STREAM, 0);
    int on = 1;
    setsockopt(listener_, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (bind(listener_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || listen(listener_, 64) != 0)
      throw std::runtime_error("proxy: cannot listen");
    socklen_t len = sizeof addr;
    getsockname(listener_, reinterpret_cast<sockaddr*>(&addr), &len);
    address_ = {"127.0.0.1", ntohs(addr.sin_port)};
    acceptor_ = std::thread([this] { acceptLoop(); });
  }
  ~LoopbackProxy() {
    stopping_ = true;
    acceptor_.join();
    close(listener_);
    std::lock_guard lock(mutex_);
    for (auto& l : links_) l->join();
  }
  LoopbackProxy(const LoopbackProxy&) = delete;
  LoopbackProxy& operator=(const LoopbackProxy&) = delete;

  const NodeAddress& address() const { return address_; }
  // Bytes per second in each direction; 0: unlimited.
  void setRate(std::uint64_t bytesPerSecond) { rate_ = bytesPerSecond; }
  // Socket buffers of this many bytes on connections accepted from now on
  // (0: the kernel's), so that megabytes of kernel buffering do not hide a
  // slow rate from the sender.
  void setSocketBuffers(int bytes) { socketBuffers_ = bytes; }
  // Closes every open connection now.
  void cutAll() { ++cutGeneration_; }
  // Closes the next connection once it has carried this many bytes towards
  // the node (0: never); applies to one connection, then clears itself.
  void cutNextAfter(std::uint64_t bytes) { cutAfter_ = bytes; }
  std::uint64_t cuts() const { return cuts_; }
  std::uint64_t bytesToNode() const { return bytesToNode_; }

 private:
  struct Link {
    int client = -1, node = -1;
    std::thread up, down;
    void join() {
      if (up.joinable()) up.join();
      if (down.joinable()) down.join();
      if (client >= 0) close(client);
      if (node >= 0) close(node);
      client = node = -1;
    }
  };

  void acceptLoop() {
    while (!stopping_) {
      pollfd p{listener_, POLLIN, 0};
      if (poll(&p, 1, 50) <= 0) continue;
      int client = accept(listener_, nullptr, nullptr);
      if (client < 0) continue;
      int node = socket(AF_INET, SOCK_STREAM, 0);
      if (int size = socketBuffers_; size > 0)
        for (int fd : {client, node}) {
          setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &size, sizeof size);
          setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &size, sizeof size);
        }
      sockaddr_in addr{};
      addr.sin_family = AF_INET;
      addr.sin_port = htons(target_.port);
      inet_pton(AF_INET, target_.host.c_str(), &addr.sin_addr);
      if (connect(node, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
        close(node);
        close(client);
        continue;
      }
      auto link = std::make_unique<Link>();
      link->client = client;
      link->node = node;
      const std::uint64_t cutAt = cutAfter_.exchange(0);
      const std::uint64_t generation = cutGeneration_;
      link->up = std::thread([this, client, node, cutAt, generation] { pump(client, node, cutAt, generation, true); });
      link->down = std::thread([this, client, node, generation] { pump(node, client, 0, generation, false); });
      std::lock_guard lock(mutex_);
      links_.push_back(std::move(link));
    }
  }

  // Copies from -> to until either side closes, the proxy stops, or a cut.
  void pump(int from, int to, std::uint64_t cutAt, std::uint64_t generation, bool towardsNode) {
    std::uint8_t buffer[4096];
    std::uint64_t carried = 0;
    // The rate holds from when it was set: bytes carried before do not count.
    std::uint64_t rate = 0, sinceRate = 0;
    auto rateStart = std::chrono::steady_clock::now();
    auto live = [&] { return !stopping_ && cutGeneration_ == generation; };
    while (live()) {
      pollfd p{from, POLLIN, 0};
      if (poll(&p, 1, 20) <= 0) continue;
      std::size_t want = sizeof buffer;
      if (cutAt) want = std::min<std::uint64_t>(want, cutAt - carried);
      const ssize_t n = recv(from, buffer, want, 0);
      if (n <= 0) break;
      if (send(to, buffer, static_cast<std::size_t>(n), MSG_NOSIGNAL) != n) break;
      carried += static_cast<std::uint64_t>(n);
      if (towardsNode) bytesToNode_ += static_cast<std::uint64_t>(n);
      if (cutAt && carried >= cutAt) {
        ++cuts_;
        break;
      }
      if (rate_ != rate) {
        rate = rate_;
        sinceRate = 0;
        rateStart = std::chrono::steady_clock::now();
      }
      sinceRate += static_cast<std::uint64_t>(n);
      if (rate) {  // hold the average at the rate, in short sleeps that notice a stop or a new rate
        const auto due = rateStart + std::chrono::microseconds(sinceRate * 1000000 / rate);
        while (live() && rate_ == rate && std::chrono::steady_clock::now() < due)
          std::this_thread::sleep_for(std::min<std::chrono::steady_clock::duration>(
              due - std::chrono::steady_clock::now(), std::chrono::milliseconds(10)));
      }
    }
    // Either direction ending ends the connection: the other pump sees EOF.
    shutdown(from, SHUT_RDWR);
    shutdown(to, SHUT_RDWR);
  }

  NodeAddress target_;
  NodeAddress address_;
  int listener_ = -1;
  std::atomic<bool> stopping_{false};
  std::atomic<std::uint64_t> rate_{0};
  std::atomic<int> socketBuffers_{0};
  std::atomic<std::uint64_t> cutAfter_{0};
  std::atomic<std::uint64_t> cutGeneration_{0};
  std::atomic<std::uint64_t> cuts_{0};
  std::atomic<std::uint64_t> bytesToNode_{0};
  std::mutex mutex_;
  std::list<std::unique_ptr<Link>> links_;
  std::thread acceptor_;
};

}  // namespace tsr::cluster::test
