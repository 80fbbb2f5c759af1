#include "socket_rendezvous.hpp"

#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <memory>
#include <thread>

#include "launch_rank.hpp"
#include "rendezvous_text.hpp"

namespace tsr::app {

namespace {

using Clock = std::chrono::steady_clock;

struct AddressList {
  addrinfo* list = nullptr;
  ~AddressList() {
    if (list) freeaddrinfo(list);
  }
};

AddressList resolve(const cluster::NodeAddress& address, bool passive) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = passive ? AI_PASSIVE : 0;
  AddressList out;
  const int rc = getaddrinfo(address.host.c_str(), std::to_string(address.port).c_str(), &hints, &out.list);
  if (rc != 0) throw LaunchError("rendezvous address " + address.text() + ": " + gai_strerror(rc));
  return out;
}

}  // namespace

SocketRendezvous::SocketRendezvous(const cluster::NodeAddress& address, bool listen,
                                   std::chrono::milliseconds connectTimeout)
    : address_(address), connectTimeout_(connectTimeout) {
  if (address.port == 0) throw LaunchError("rendezvous address " + address.text() + ": give a port every rank knows");
  if (!listen) return;
  auto addresses = resolve(address, true);
  std::string why = "no address";
  for (addrinfo* a = addresses.list; a; a = a->ai_next) {
    int fd = socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) continue;
    int yes = 1;
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    if (bind(fd, a->ai_addr, a->ai_addrlen) == 0 && ::listen(fd, 128) == 0) {
      listen_ = fd;
      return;
    }
    why = std::strerror(errno);
    close(fd);
  }
  throw LaunchError("cannot listen on " + address.text() + " for the rendezvous: " + why);
}

SocketRendezvous::~SocketRendezvous() {
  for (int fd : nodes_) close(fd);
  if (listen_ >= 0) close(listen_);
  if (link_ >= 0) close(link_);
}

void SocketRendezvous::publish(unsigned rank, const cluster::NodeAddress& address) {
  const auto deadline = Clock::now() + connectTimeout_;
  const std::string line = "rank " + std::to_string(rank) + " " + address.text() + "\n";
  std::string why;
  while (link_ < 0) {
    auto addresses = resolve(address_, false);
    for (addrinfo* a = addresses.list; a && link_ < 0; a = a->ai_next) {
      int fd = socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
      if (fd < 0) continue;
      if (connect(fd, a->ai_addr, a->ai_addrlen) == 0)
        link_ = fd;
      else {
        why = std::strerror(errno);
        close(fd);
      }
    }
    if (link_ >= 0) break;
    if (Clock::now() >= deadline)
      throw LaunchError("rank 0 did not answer at " + address_.text() + " within " +
                        std::to_string(connectTimeout_.count() / 1000) + " s (" + why + ")");
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  if (send(link_, line.data(), line.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(line.size()))
    throw LaunchError("cannot send this node's address to rank 0 at " + address_.text() + ": " + std::strerror(errno));
}

bool SocketRendezvous::done() {
  if (link_ < 0) return true;
  pollfd p{link_, POLLIN, 0};
  // Rank 0 never writes: the link turns readable only when it closes.
  return poll(&p, 1, 0) > 0;
}

std::vector<cluster::NodeAddress> SocketRendezvous::gather(unsigned size, std::chrono::milliseconds timeout,
                                                           const Progress& progress) {
  struct Pending {
    int fd;
    std::string buffer;
  };
  std::vector<Pending> pending;
  auto dropAll = [&] {
    for (auto& p : pending) close(p.fd);
  };
  std::vector<cluster::NodeAddress> addresses(size - 1);
  std::vector<bool> found(size - 1, false);
  unsigned published = 0;
  std::string refused;
  const auto deadline = Clock::now() + timeout;
  if (progress) progress(0, size - 1);
  while (published + 1 < size) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) {
      dropAll();
      throw LaunchError(missingRanksMessage(found, where(), timeout) + refused);
    }
    std::vector<pollfd> fds{{listen_, POLLIN, 0}};
    for (const auto& p : pending) fds.push_back({p.fd, POLLIN, 0});
    if (poll(fds.data(), fds.size(), static_cast<int>(std::min<long long>(left.count(), 200))) <= 0) continue;
    for (std::size_t i = fds.size(); i-- > 1;) {
      if (!(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      Pending& p = pending[i - 1];
      char chunk[kMaxLine];
      const ssize_t n = recv(p.fd, chunk, kMaxLine - p.buffer.size(), 0);
      bool drop = n <= 0;
      if (n > 0) p.buffer.append(chunk, static_cast<std::size_t>(n));
      if (const auto newline = p.buffer.find('\n'); !drop && newline != std::string::npos) {
        const std::string line = p.buffer.substr(0, newline);
        if (const auto r = parseRankLine(line, size); r && !found[r->rank - 1]) {
          found[r->rank - 1] = true;
          addresses[r->rank - 1] = r->address;
          ++published;
          nodes_.push_back(p.fd);  // kept open: closing it tells the node to stop
          pending.erase(pending.begin() + static_cast<std::ptrdiff_t>(i - 1));
          if (progress) progress(published, size - 1);
          continue;
        }
        refused = "; refused '" + line.substr(0, 64) + "'";
        drop = true;
      }
      if (!drop && p.buffer.size() >= kMaxLine) {
        refused = "; refused a line longer than " + std::to_string(kMaxLine) + " bytes";
        drop = true;
      }
      if (drop) {
        close(p.fd);
        pending.erase(pending.begin() + static_cast<std::ptrdiff_t>(i - 1));
      }
    }
    if (fds[0].revents & POLLIN) {
      const int fd = accept4(listen_, nullptr, nullptr, SOCK_CLOEXEC);
      if (fd >= 0 && pending.size() < 4 * kMaxJobSize)
        pending.push_back({fd, {}});
      else if (fd >= 0)
        close(fd);
    }
  }
  dropAll();
  return addresses;
}

void SocketRendezvous::markDone() {
  for (int fd : nodes_) close(fd);
  nodes_.clear();
}

}  // namespace tsr::app
