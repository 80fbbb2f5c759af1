// tessera-cull under load and abuse, on 127.0.0.0/8 only, bounded in count
// and time: a crowd of silent and dribbling connections from one address
// gets 429 (never a reset) or is closed at its deadline, while a client
// from another address is answered throughout; and a slow body, an idle
// keep-alive connection and a full per-address share end as the limits
// say. /v1/status counts what happened.
#include <gtest/gtest.h>
#include <sys/socket.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/write.hpp>
#include <nlohmann/json.hpp>

#include "../cluster/node_process.hpp"
#include "cull_http.hpp"

namespace {

namespace asio = boost::asio;
using asio::ip::tcp;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

constexpr int kPerAddress = 8;

// A raw connection from a chosen loopback address, reads bounded by a
// receive timeout so a test fails instead of hanging.
class Raw {
 public:
  Raw(asio::io_context& io, const std::string& from, std::uint16_t port) : socket_(io) {
    socket_.open(tcp::v4());
    socket_.bind({asio::ip::make_address(from), 0});
    socket_.connect({asio::ip::make_address("127.0.0.1"), port});
    timeval timeout{15, 0};
    setsockopt(socket_.native_handle(), SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  }
  void send(const std::string& bytes) {
    boost::system::error_code ec;
    asio::write(socket_, asio::buffer(bytes), ec);
  }
  // Everything the service sends until it closes: the text and how it ended.
  std::pair<std::string, boost::system::error_code> untilClosed() {
    std::string text;
    boost::system::error_code ec;
    char chunk[4096];
    for (;;) {
      const std::size_t n = socket_.read_some(asio::buffer(chunk), ec);
      text.append(chunk, n);
      if (ec) return {text, ec};
    }
  }

 private:
  tcp::socket socket_;
};

tsr::cluster::test::ListeningProcess strictService(const std::vector<std::string>& more = {}) {
  std::vector<std::string> args{TSR_CULL_BINARY,
                                "builtin:cornell",
                                "--listen",
                                "127.0.0.1:0",
                                "--threads",
                                "1",
                                "--previews",
                                "0",
                                "--header-timeout",
                                "1",
                                "--keepalive-timeout",
                                "1",
                                "--transfer-timeout",
                                "1",
                                "--min-rate",
                                "1024",
                                "--max-connections-per-address",
                                std::to_string(kPerAddress)};
  args.insert(args.end(), more.begin(), more.end());
  return tsr::cluster::test::ListeningProcess(args);
}

// A /v1/cull request of the Cornell box at side x side pixels, closing after.
std::string cullRequest(int side) {
  const std::string body = tsr::app::test::cornellView(side, side, 3).dump();
  return "POST /v1/cull HTTP/1.1\r\nHost: x\r\nConnection: close\r\nContent-Length: " + std::to_string(body.size()) +
         "\r\n\r\n" + body;
}

// A client from 127.0.0.2 (plain HTTP/1.1, a connection per request).
unsigned goodRequest(std::uint16_t port, const std::string& target, const std::string& body = {}) {
  asio::io_context io;
  Raw raw(io, "127.0.0.2", port);
  const bool post = !body.empty();
  raw.send(std::string(post ? "POST " : "GET ") + target + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n" +
           (post ? "Content-Length: " + std::to_string(body.size()) + "\r\n" : "") + "\r\n" + body);
  const auto [text, ec] = raw.untilClosed();
  if (text.rfind("HTTP/1.1 ", 0) != 0) return 0;
  return unsigned(std::stoul(text.substr(9, 3)));
}

json status(std::uint16_t port) {
  const auto r = tsr::app::test::request(port, boost::beast::http::verb::get, "/v1/status");
  EXPECT_EQ(r.status, 200u);
  return json::parse(r.body);
}

// /v1/status once `counted` holds, or after 3 s: a closed socket is seen
// by the client a moment before the service's handler counts it.
template <class Predicate>
json statusOnce(std::uint16_t port, Predicate counted) {
  const auto until = Clock::now() + std::chrono::seconds(3);
  json s = status(port);
  while (!counted(s) && Clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    s = status(port);
  }
  return s;
}

TEST(CullLimits, ACrowdFromOneAddressIsRefusedOrTimedOutWhileAnotherAddressIsServed) {
  auto service = strictService();
  const std::uint16_t port = service.address().port;
  constexpr int kCrowd = 150;
  asio::io_context io;
  std::vector<std::unique_ptr<Raw>> crowd;
  for (int i = 0; i < kCrowd; ++i) {
    crowd.push_back(std::make_unique<Raw>(io, "127.0.0.3", port));
    if (i % 2) crowd.back()->send("GET / HTTP/1.1\r\n");  // half start a request and stall
  }
  // While the crowd holds on, the other address is answered, a cull included.
  const std::string view = tsr::app::test::cornellView(32, 32, 3).dump();
  for (int round = 0; round < 3; ++round) {
    EXPECT_EQ(goodRequest(port, "/v1/scene"), 200u) << round;
    EXPECT_EQ(goodRequest(port, "/v1/cull", view), 200u) << round;
  }
  // Each of the crowd ends: the ones over its share with a 429 read in
  // full, the admitted ones closed at the header deadline (1 s), none reset.
  int refused = 0, closed = 0;
  const auto start = Clock::now();
  for (auto& raw : crowd) {
    const auto [text, ec] = raw->untilClosed();
    EXPECT_EQ(ec, asio::error::eof) << ec.message();
    if (text.rfind("HTTP/1.1 429", 0) == 0) {
      EXPECT_NE(text.find("Retry-After: 1"), std::string::npos) << text;
      ++refused;
    } else {
      EXPECT_EQ(text, "");
      ++closed;
    }
  }
  EXPECT_EQ(closed, kPerAddress);
  EXPECT_EQ(refused, kCrowd - kPerAddress);
  // The deadline (1 s from each connection) with a wide margin for a loaded machine.
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(8));
  const json s = statusOnce(port, [](const json& s) { return s["connections"]["timed_out"] >= kPerAddress; });
  EXPECT_GE(s["connections"]["refused"].get<int>(), kCrowd - kPerAddress);
  EXPECT_GE(s["connections"]["timed_out"].get<int>(), kPerAddress) << s;
  EXPECT_EQ(s["cull"]["answered"].get<int>(), 3);
}

TEST(CullLimits, ASlowBodyAndAnIdleKeepAliveConnectionAreClosedAtTheirDeadlines) {
  auto service = strictService();
  const std::uint16_t port = service.address().port;
  asio::io_context io;
  // A 1 KiB body at 1 KiB/s has 1 s + 1 s: sending 10 bytes never finishes it.
  Raw slowBody(io, "127.0.0.1", port);
  slowBody.send("POST /v1/cull HTTP/1.1\r\nHost: x\r\nContent-Length: 1024\r\n\r\n{\"camera\"");
  // One answered request, then silence on a kept-alive connection.
  Raw idle(io, "127.0.0.1", port);
  idle.send("GET /v1/scene HTTP/1.1\r\nHost: x\r\n\r\n");
  const auto start = Clock::now();
  const auto [idleText, idleEnd] = idle.untilClosed();
  EXPECT_EQ(idleText.rfind("HTTP/1.1 200", 0), 0u) << idleText;
  EXPECT_EQ(idleEnd, asio::error::eof);
  const auto [bodyText, bodyEnd] = slowBody.untilClosed();
  EXPECT_EQ(bodyText, "");
  EXPECT_EQ(bodyEnd, asio::error::eof);
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(12));
  const json s = statusOnce(port, [](const json& s) { return s["connections"]["timed_out"] >= 2; });
  EXPECT_GE(s["connections"]["timed_out"].get<int>(), 2) << s;
}

// One address over its share of rankings in flight gets 429 while its
// first one is ranked; a ranking whose client left before its turn is
// dropped unranked. (A 1024x1024 ranking takes a good tenth of a second
// here; the second request arrives within a millisecond of the first.)
TEST(CullLimits, AnAddressOverItsShareOfRankingsGets429AndALeftClientsRankingIsDropped) {
  auto service = strictService({"--max-requests-per-address", "1"});
  const std::uint16_t port = service.address().port;
  asio::io_context io;
  {
    Raw first(io, "127.0.0.4", port), second(io, "127.0.0.4", port);
    first.send(cullRequest(1024));
    second.send(cullRequest(1024));
    const auto [a, aEnd] = first.untilClosed();
    const auto [b, bEnd] = second.untilClosed();
    const std::vector<std::string> heads{a.substr(0, 12), b.substr(0, 12)};
    EXPECT_EQ(std::count(heads.begin(), heads.end(), "HTTP/1.1 200"), 1) << a.substr(0, 200) << b.substr(0, 200);
    EXPECT_EQ(std::count(heads.begin(), heads.end(), "HTTP/1.1 429"), 1);
    EXPECT_NE((a + b).find("Retry-After: 1"), std::string::npos);
  }
  {
    Raw stays(io, "127.0.0.5", port);
    auto leaves = std::make_unique<Raw>(io, "127.0.0.6", port);
    stays.send(cullRequest(1024));
    leaves->send(cullRequest(1024));
    leaves.reset();
    EXPECT_EQ(stays.untilClosed().first.substr(0, 12), "HTTP/1.1 200");
  }
  const json s =
      statusOnce(port, [](const json& s) { return s["cull"]["answered"] == 2 && s["cull"]["dropped"] == 1; });
  EXPECT_EQ(s["cull"]["answered"].get<int>(), 2) << s;
  EXPECT_EQ(s["cull"]["dropped"].get<int>(), 1) << s;
  EXPECT_EQ(s["cull"]["refused"].get<int>(), 1) << s;
}

TEST(CullLimits, StatusSaysHowBusyTheServiceIsAndWhatItsLimitsAre) {
  auto service = strictService();
  const json s = status(service.address().port);
  EXPECT_EQ(s["connections"]["per_address"].get<int>(), kPerAddress);
  EXPECT_EQ(s["connections"]["open"].get<int>(), 1) << "the asking connection";
  EXPECT_EQ(s["cull"]["waiting"].get<int>(), 0);
  EXPECT_EQ(s["cull"]["capacity"].get<int>(), 128);
  EXPECT_EQ(s["previews"]["limit"].get<int>(), 0);
}

}  // namespace
