// The handshake as state machines: both sides prove the token without
// sending it, a wrong token or version is refused, replayed proofs fail.
#include <gtest/gtest.h>

#include "tsr/cluster/auth.hpp"
#include "tsr/cluster/frame_header.hpp"
#include "tsr/cluster/handshake.hpp"
#include "tsr/cluster/protocol_error.hpp"

namespace tsr::cluster {
namespace {

using Kind = ProtocolError::Kind;

Message unframe(const Frame& f) {
  FrameHeader h = decodeFrameHeader(std::span<const std::uint8_t>(*f).first(kFrameHeaderBytes));
  return {h.type, std::vector<std::uint8_t>(f->begin() + kFrameHeaderBytes, f->end())};
}

bool contains(const Frame& f, const std::string& s) {
  return std::search(f->begin(), f->end(), s.begin(), s.end()) != f->end();
}

TEST(Handshake, SameTokenSucceedsWithoutSendingIt) {
  const std::string token = "correct horse battery staple";
  ClientHandshake client(token, "c");
  NodeHandshake node(token, Welcome{"n", 2, {"embree"}});
  Frame hello = client.hello();
  auto challenge = node.onHello(unframe(hello));
  ASSERT_TRUE(challenge.accepted);
  Frame auth = client.onChallenge(unframe(challenge.reply));
  auto welcome = node.onAuth(unframe(auth));
  ASSERT_TRUE(welcome.accepted);
  EXPECT_TRUE(node.done());
  EXPECT_EQ(client.onWelcome(unframe(welcome.reply)).nodeName, "n");
  for (const Frame& f : {hello, challenge.reply, auth, welcome.reply}) EXPECT_FALSE(contains(f, token));
}

TEST(Handshake, WrongClientTokenIsRejected) {
  ClientHandshake client("wrong", "c");
  NodeHandshake node("right", Welcome{"n", 2, {}});
  auto challenge = node.onHello(unframe(client.hello()));
  // The client notices first: the node cannot prove a token the client does not share.
  EXPECT_THROW(
      {
        try {
          client.onChallenge(unframe(challenge.reply));
        } catch (const ProtocolError& e) {
          EXPECT_EQ(e.kind(), Kind::AuthFailed);
          throw;
        }
      },
      ProtocolError);
}

TEST(Handshake, ForgedAuthIsRejectedByTheNode) {
  NodeHandshake node("right", Welcome{"n", 2, {}});
  ClientHandshake honest("right", "c");
  node.onHello(unframe(honest.hello()));
  auto step = node.onAuth(unframe(makeFrame(Auth{})));
  EXPECT_FALSE(step.accepted);
  EXPECT_EQ(unframe(step.reply).type, Reject::kType);
  EXPECT_FALSE(node.done());
}

TEST(Handshake, ProofFromAnotherConnectionDoesNotReplay) {
  const std::string token = "t";
  ClientHandshake client(token, "c");
  NodeHandshake first(token, Welcome{"n", 1, {}});
  Frame hello = client.hello();
  Frame auth = client.onChallenge(unframe(first.onHello(unframe(hello)).reply));
  NodeHandshake second(token, Welcome{"n", 1, {}});  // fresh node nonce
  second.onHello(unframe(hello));
  EXPECT_FALSE(second.onAuth(unframe(auth)).accepted);
}

TEST(Handshake, OtherVersionIsRejectedWithAReason) {
  ClientHandshake client("t", "c", kProtocolVersion + 1);
  NodeHandshake node("t", Welcome{"n", 1, {}});
  auto step = node.onHello(unframe(client.hello()));
  EXPECT_FALSE(step.accepted);
  Message reject = unframe(step.reply);
  ASSERT_EQ(reject.type, Reject::kType);
  EXPECT_NE(parse<Reject>(reject).reason.find("version"), std::string::npos);
}

TEST(Handshake, MessagesOutOfOrderAreProtocolErrors) {
  NodeHandshake node("t", Welcome{"n", 1, {}});
  EXPECT_THROW(node.onAuth(unframe(makeFrame(Auth{}))), ProtocolError);
  ClientHandshake client("t", "c");
  EXPECT_THROW(client.onChallenge(unframe(makeFrame(Welcome{}))), ProtocolError);
}

TEST(Auth, HmacMatchesRfc4231Case2) {
  std::string msg = "what do ya want for nothing?";
  Digest d = hmacSha256("Jefe", std::span(reinterpret_cast<const std::uint8_t*>(msg.data()), msg.size()));
  const char* hex = "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843";
  for (std::size_t i = 0; i < d.size(); ++i) EXPECT_EQ(d[i], std::stoi(std::string(hex + 2 * i, 2), nullptr, 16));
}

}  // namespace
}  // namespace tsr::cluster
