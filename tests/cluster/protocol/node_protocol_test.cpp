// Real tessera-node processes on 127.0.0.1: authentication, version check,
// hostile bytes, and replicas that follow the client's scene frame by frame.
#include <sys/resource.h>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "../../apps/command_runner.hpp"
#include "cluster_test_util.hpp"
#include "protocol/raw_client.hpp"
#include "tsr/cluster/auth.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/cluster/handshake.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

namespace tsr::cluster::test {
namespace {

using namespace std::chrono_literals;
using Outcome = RawClient::Outcome;

// Publishes one animated frame and returns its version.
std::uint64_t step(ClusterWindow& w, AnimatedScene& s, int frame) {
  s.pose(frame);
  auto delta = s.scene.commit();
  w.publish(s.scene, delta);
  return delta->version();
}

void expectReplicasMatch(ClusterWindow& w, const sg::Scene& scene, std::size_t expectedNodes) {
  ASSERT_TRUE(w.waitApplied(scene.version(), 20s));
  auto hashes = w.replicaHashes(20s);
  ASSERT_EQ(hashes.size(), expectedNodes);
  for (const auto& h : hashes) {
    EXPECT_EQ(h.version, scene.version()) << "node " << h.node;
    EXPECT_EQ(h.hash, scene.contentHash()) << "node " << h.node;
  }
}

TEST(NodeProcess, ReportsItsAddressAndStopsOnSigterm) {
  NodeProcess node;
  EXPECT_EQ(node.address().host, "127.0.0.1");
  EXPECT_NE(node.address().port, 0);
  EXPECT_TRUE(node.terminate());
}

// Without a token any client may connect: only loopback, unless --insecure.
// Only the refusal is tested: no traffic goes to a non-loopback address.
class NodeStartup : public tsr::test::CommandTest {};

TEST_F(NodeStartup, NoTokenOnANonLoopbackAddressIsRefused) {
  for (const char* address : {"0.0.0.0:0", "0.0.0.0"}) {
    const tsr::test::Outcome r = runBinary(TSR_NODE_BINARY, std::string("--listen ") + address);
    expectOneErrorLine(r, "refusing to listen on 0.0.0.0");
    EXPECT_THAT(r.err, ::testing::HasSubstr("--token-file"));
    EXPECT_THAT(r.err, ::testing::HasSubstr("--insecure"));
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST(NodeAuth, WrongTokenIsRejected) {
  TokenFile right("right token"), wrong("wrong token");
  auto nodes = startNodes(1, {"--token-file", right.path()});
  ClusterWindow w(configFor(ClusterMode::Cooperative, nodes), {readTokenFile(wrong.path())});
  EXPECT_EQ(w.connect(5s), 0u);
  EXPECT_NE(w.status()[0].lastError, "");

  ClusterWindow ok(configFor(ClusterMode::Cooperative, nodes), {readTokenFile(right.path())});
  EXPECT_EQ(ok.connect(5s), 1u);
}

TEST(NodeAuth, ForgedProofGetsRejectAndHangUp) {
  TokenFile token("secret");
  auto nodes = startNodes(1, {"--token-file", token.path()});
  RawClient raw(nodes[0]->address());
  ClientHandshake hs("not the secret", "raw");
  ASSERT_TRUE(raw.send(hs.hello()));
  Message m;
  ASSERT_EQ(raw.read(m), Outcome::Message);
  EXPECT_EQ(m.type, Challenge::kType);
  ASSERT_TRUE(raw.send(makeFrame(Auth{})));  // a guess
  ASSERT_EQ(raw.read(m), Outcome::Message);
  EXPECT_EQ(m.type, Reject::kType);
  EXPECT_EQ(raw.waitClosed(), Outcome::Closed);
}

TEST(NodeAuth, OtherProtocolVersionIsRejectedWithAReason) {
  auto nodes = startNodes(1);
  RawClient raw(nodes[0]->address());
  Frame hello = makeFrame(Hello{});
  auto bytes = *hello;
  bytes[4] = kProtocolVersion + 1;  // the header's version byte
  bytes[kFrameHeaderBytes] = kProtocolVersion + 1;
  ASSERT_TRUE(raw.send(bytes));
  Message m;
  ASSERT_EQ(raw.read(m), Outcome::Message);
  ASSERT_EQ(m.type, Reject::kType);
  EXPECT_NE(parse<Reject>(m).reason.find("version"), std::string::npos);
  EXPECT_EQ(raw.waitClosed(), Outcome::Closed);
}

class HostileInput : public ::testing::Test {
 protected:
  void SetUp() override {
    nodes = startNodes(1);
    window = std::make_unique<ClusterWindow>(configFor(ClusterMode::Cooperative, nodes));
    ASSERT_EQ(window->connect(5s), 1u);
    for (int f = 0; f < 3; ++f) step(*window, scene, f);
  }
  // The honest client is served as before.
  void expectHonestClientUnharmed() {
    for (int f = 3; f < 8; ++f) step(*window, scene, f);
    expectReplicasMatch(*window, scene.scene, 1);
  }
  std::vector<std::unique_ptr<NodeProcess>> nodes;
  AnimatedScene scene;
  std::unique_ptr<ClusterWindow> window;
};

TEST_F(HostileInput, RandomBytesCloseThatConnectionOnly) {
  std::mt19937 rng(7);
  for (int attempt = 0; attempt < 5; ++attempt) {
    RawClient raw(nodes[0]->address());
    std::vector<std::uint8_t> junk(4096);
    for (auto& b : junk) b = static_cast<std::uint8_t>(rng());
    raw.send(junk);
    EXPECT_EQ(raw.waitClosed(), Outcome::Closed);
  }
  expectHonestClientUnharmed();
}

TEST_F(HostileInput, OversizedFrameClosesBeforeThePayload) {
  RawClient raw(nodes[0]->address());
  std::vector<std::uint8_t> header;
  writeFrameHeader(header, {kProtocolVersion, Hello::kType, 1u << 30});
  raw.send(header);  // no payload follows: the node must not wait for it
  EXPECT_EQ(raw.waitClosed(), Outcome::Closed);
  expectHonestClientUnharmed();
}

TEST_F(HostileInput, OversizedAfterAuthenticationCloses) {
  RawClient raw(nodes[0]->address());
  ClientHandshake hs("", "raw");
  raw.send(hs.hello());
  Message m;
  ASSERT_EQ(raw.read(m), Outcome::Message);
  raw.send(hs.onChallenge(m));
  ASSERT_EQ(raw.read(m), Outcome::Message);
  ASSERT_EQ(m.type, Welcome::kType);
  std::vector<std::uint8_t> header;
  writeFrameHeader(header, {kProtocolVersion, RenderRequest::kType, 64u << 20});
  raw.send(header);
  EXPECT_EQ(raw.waitClosed(), Outcome::Closed);
  expectHonestClientUnharmed();
}

TEST_F(HostileInput, BulkBeforeAuthenticationCloses) {
  RawClient raw(nodes[0]->address());
  raw.send(frameFromPayload(Snapshot::kType, std::vector<std::uint8_t>(64, 1)));
  EXPECT_EQ(raw.waitClosed(), Outcome::Closed);
  expectHonestClientUnharmed();
}

TEST_F(HostileInput, CorruptChangeListClosesThatClientOnly) {
  RawClient raw(nodes[0]->address());
  ClientHandshake hs("", "raw");
  raw.send(hs.hello());
  Message m;
  ASSERT_EQ(raw.read(m), Outcome::Message);
  raw.send(hs.onChallenge(m));
  ASSERT_EQ(raw.read(m), Outcome::Message);
  raw.send(frameFromPayload(Snapshot::kType, std::vector<std::uint8_t>{'T', 'S', 'R', 'C', 1, 1, 50, 0, 0, 0, 9}));
  ASSERT_EQ(raw.read(m), Outcome::Message);
  ASSERT_EQ(m.type, ErrorReport::kType);
  EXPECT_EQ(parse<ErrorReport>(m).kind, ErrorReport::Kind::SceneRejected);
  EXPECT_EQ(raw.waitClosed(), Outcome::Closed);
  expectHonestClientUnharmed();
}

// A flood of connections beyond the node's file-descriptor limit makes its
// accepts fail; once the flood is gone it takes clients again (an accept
// error used to end its accept loop for good).
TEST(NodeFlood, AcceptsAgainAfterRunningOutOfDescriptors) {
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_NOFILE, &saved), 0);
  rlimit low = saved;
  low.rlim_cur = 64;  // inherited by the node: enough to run, far fewer than the flood
  ASSERT_EQ(setrlimit(RLIMIT_NOFILE, &low), 0);
  std::unique_ptr<NodeProcess> node;
  try {
    node = std::make_unique<NodeProcess>();
  } catch (...) {
    setrlimit(RLIMIT_NOFILE, &saved);
    throw;
  }
  ASSERT_EQ(setrlimit(RLIMIT_NOFILE, &saved), 0);
  {
    std::vector<std::unique_ptr<RawClient>> flood;
    for (int i = 0; i < 200; ++i) flood.push_back(std::make_unique<RawClient>(node->address()));
    std::this_thread::sleep_for(500ms);  // the node runs out of descriptors meanwhile
  }
  std::vector<std::unique_ptr<NodeProcess>> nodes;
  nodes.push_back(std::move(node));
  ClusterWindow w(configFor(ClusterMode::Cooperative, nodes));
  ASSERT_EQ(w.connect(10s), 1u);
  AnimatedScene s;
  for (int f = 0; f < 3; ++f) step(w, s, f);
  expectReplicasMatch(w, s.scene, 1);
}

TEST(Replication, HundredAnimatedFramesLeaveEveryReplicaEqual) {
  auto nodes = startNodes(3);
  ClusterWindow w(configFor(ClusterMode::Cooperative, nodes));
  ASSERT_EQ(w.connect(5s), 3u);
  AnimatedScene s;
  ASSERT_FALSE(s.imported.animations.empty());
  for (int f = 0; f < 100; ++f) step(w, s, f);
  expectReplicasMatch(w, s.scene, 3);
}

TEST(Replication, LateJoinerCatchesUpFromASnapshot) {
  auto nodes = startNodes(2);
  ClusterWindow w(configFor(ClusterMode::Cooperative, nodes));
  ASSERT_EQ(w.connect(5s), 2u);
  AnimatedScene s;
  for (int f = 0; f < 20; ++f) step(w, s, f);
  NodeProcess late;
  w.addNode({late.address(), "embree", {}});
  // The joiner connects in the background; it is in from the first publish after.
  for (int f = 20; f < 40 && w.onlineNodes() < 3; ++f) {
    step(w, s, f);
    std::this_thread::sleep_for(20ms);
  }
  for (int f = 40; f < 45; ++f) step(w, s, f);
  expectReplicasMatch(w, s.scene, 3);
}

// A scene whose snapshot exceeds a message goes to each node in parts (here
// parts of 64 KiB instead of 1 GiB): nodes at the start and one that joins
// late hold the client's scene.
TEST(Replication, ASnapshotLargerThanAMessageArrivesInParts) {
  auto nodes = startNodes(2);
  ClusterConfig config = configFor(ClusterMode::Cooperative, nodes);
  config.snapshotPartBytes = 64 * 1024;
  ClusterWindow w(config);
  ASSERT_EQ(w.connect(5s), 2u);
  AnimatedScene s("builtin:plant:20000");
  s.scene.commit();
  ASSERT_GT(sg::encode(*s.scene.snapshot()).size(), 5u * 64 * 1024) << "the test wants many parts";
  for (int f = 0; f < 3; ++f) step(w, s, f);
  expectReplicasMatch(w, s.scene, 2);

  NodeProcess late;
  w.addNode({late.address(), "embree", {}});
  for (int f = 3; f < 40 && w.onlineNodes() < 3; ++f) {
    step(w, s, f);
    std::this_thread::sleep_for(20ms);
  }
  step(w, s, 40);
  expectReplicasMatch(w, s.scene, 3);
}

TEST(Replication, RestartedNodeRejoinsWithTheCurrentScene) {
  auto nodes = startNodes(2);
  ClusterWindow w(configFor(ClusterMode::Cooperative, nodes));
  ASSERT_EQ(w.connect(5s), 2u);
  AnimatedScene s;
  for (int f = 0; f < 10; ++f) step(w, s, f);
  std::string address = nodes[1]->text();
  nodes[1]->kill();
  for (int f = 10; f < 20; ++f) step(w, s, f);
  nodes[1] = std::make_unique<NodeProcess>(std::vector<std::string>{}, address);
  auto until = std::chrono::steady_clock::now() + 10s;
  int f = 20;
  while (std::chrono::steady_clock::now() < until &&
         !(w.status()[1].state == NodeState::Synced && w.status()[1].appliedVersion == s.scene.version())) {
    step(w, s, f++);
    w.waitApplied(s.scene.version(), 100ms);
  }
  expectReplicasMatch(w, s.scene, 2);
}

// The client decides by an ErrorReport's kind, never by its text: a frame
// that no node can render as asked fails at once with the node's reason
// (instead of the work moving on until every node was lost), and the kind
// stays in the node's status.
ErrorReport::Kind frameFailureKind(const med::Parameters& parameters, const std::string& backend,
                                   const std::string& expectedInError) {
  auto nodes = startNodes(1);
  ClusterConfig config = configFor(ClusterMode::Cooperative, nodes, parameters);
  config.nodes[0].backend = backend;
  ClusterWindow w(config);
  EXPECT_EQ(w.connect(5s), 1u);
  AnimatedScene s;
  step(w, s, 0);
  EXPECT_TRUE(w.waitApplied(s.scene.version(), 20s));
  med::View view;
  view.width = 16;
  view.height = 12;
  view.region = {0, 0, 16, 12};
  try {
    w.render(view);
    ADD_FAILURE() << "the frame rendered";
  } catch (const ClusterError& e) {
    EXPECT_NE(std::string(e.what()).find(expectedInError), std::string::npos) << e.what();
  }
  const NodeStatus status = w.status()[0];
  if (!status.lastReport) {
    ADD_FAILURE() << "no ErrorReport seen; last error: " << status.lastError;
    return ErrorReport::Kind::ProtocolViolation;
  }
  return status.lastReport->kind;
}

TEST(NodeErrors, ClientSeesAnUnknownBackendByItsKind) {
  EXPECT_EQ(frameFailureKind({}, "nosuch", "back-end 'nosuch'"), ErrorReport::Kind::UnknownBackend);
}

TEST(NodeErrors, ClientSeesARefusedParameterByItsKind) {
  med::Parameters bad;
  bad.set("filter", std::string("bogus"));
  EXPECT_EQ(frameFailureKind(bad, "embree", "bogus"), ErrorReport::Kind::InvalidParameter);
}

// Over the wire as on the command line: a node refuses a parameter its
// back-end does not take, naming the valid ones.
TEST(NodeErrors, ANodeRefusesAnUnknownParameterNamingTheValidOnes) {
  med::Parameters typo;
  typo.set("sigmaSS", 4.0);
  EXPECT_EQ(frameFailureKind(typo, "embree", "did you mean sigmaS?"), ErrorReport::Kind::InvalidParameter);
}

// An unknown back-end is said when the viewports arrive; the session goes on.
TEST(NodeErrors, UnknownBackendIsReportedAndTheSessionGoesOn) {
  auto nodes = startNodes(1);
  RawClient raw(nodes[0]->address());
  ClientHandshake hs("", "raw");
  ASSERT_TRUE(raw.send(hs.hello()));
  Message m;
  ASSERT_EQ(raw.read(m), Outcome::Message);
  ASSERT_TRUE(raw.send(hs.onChallenge(m)));
  ASSERT_EQ(raw.read(m), Outcome::Message);
  ASSERT_EQ(m.type, Welcome::kType);
  ASSERT_TRUE(raw.send(makeFrame(SetViewports{{{0, "nosuch", 1, 2, {}}}})));
  ASSERT_EQ(raw.read(m), Outcome::Message);
  ASSERT_EQ(m.type, ErrorReport::kType);
  EXPECT_EQ(parse<ErrorReport>(m).kind, ErrorReport::Kind::UnknownBackend);
  ASSERT_TRUE(raw.send(makeFrame(HashQuery{7})));
  ASSERT_EQ(raw.read(m), Outcome::Message);
  ASSERT_EQ(m.type, HashReply::kType);
  EXPECT_EQ(parse<HashReply>(m).token, 7u);
}

}  // namespace
}  // namespace tsr::cluster::test
