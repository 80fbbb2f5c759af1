#pragma once
// A plain POSIX socket for talking to a node byte by byte: what an attacker
// or a client of another version would do. Every read has a timeout.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <optional>
#include <stdexcept>
#include <vector>

#include "tsr/cluster/frame_header.hpp"
#include "tsr/cluster/messages.hpp"
#include "tsr/cluster/node_address.hpp"

namespace tsr::cluster::test {

class RawClient {
 public:
  explicit RawClient(const NodeAddress& a, int timeoutMs = 8000) {
    fd_ = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(a.port);
    inet_pton(AF_INET, a.host.c_str(), &addr.sin_addr);
    if (connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) throw std::runtime_error("connect failed");
    timeval tv{timeoutMs / 1000, (timeoutMs % 1000) * 1000};
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  }
  ~RawClient() { close(fd_); }

  // False when the node already hung up.
  bool send(const std::vector<std::uint8_t>& bytes) {
    return ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(bytes.size());
  }
  bool send(const Frame& f) { return send(*f); }

  enum class Outcome { Message, Closed, TimedOut };
  // Reads one frame; Closed on EOF or reset, TimedOut when the node stays silent.
  Outcome read(Message& out) {
    std::vector<std::uint8_t> header(kFrameHeaderBytes);
    Outcome o = readExactly(header);
    if (o != Outcome::Message) return o;
    FrameHeader h = decodeFrameHeader(header);
    out.type = h.type;
    out.payload.resize(h.length);
    return readExactly(out.payload);
  }
  // Reads until the node closes; Message never returned.
  Outcome waitClosed() {
    Message m;
    for (;;) {
      Outcome o = read(m);
      if (o != Outcome::Message) return o;
    }
  }

 private:
  Outcome readExactly(std::vector<std::uint8_t>& buf) {
    std::size_t have = 0;
    while (have < buf.size()) {
      ssize_t n = recv(fd_, buf.data() + have, buf.size() - have, 0);
      if (n == 0) return Outcome::Closed;
      if (n < 0) return (errno == EAGAIN || errno == EWOULDBLOCK) ? Outcome::TimedOut : Outcome::Closed;
      have += static_cast<std::size_t>(n);
    }
    return Outcome::Message;
  }
  int fd_ = -1;
};

}  // namespace tsr::cluster::test
