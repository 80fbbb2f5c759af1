// The message codec: every message round-trips, every truncation and
// random corruption ends in a typed ProtocolError (never another exception,
// never a crash), and frame headers are checked before any payload.
#include <random>

#include <gtest/gtest.h>

#include "tsr/cluster/frame_header.hpp"
#include "tsr/cluster/messages.hpp"
#include "tsr/cluster/protocol_error.hpp"

namespace tsr::cluster {
namespace {

using Kind = ProtocolError::Kind;

Message unframe(const Frame& frame) {
  std::span<const std::uint8_t> bytes(*frame);
  FrameHeader h = decodeFrameHeader(bytes.first(kFrameHeaderBytes));
  EXPECT_EQ(h.length, bytes.size() - kFrameHeaderBytes);
  return {h.type, std::vector<std::uint8_t>(bytes.begin() + kFrameHeaderBytes, bytes.end())};
}

med::View sampleView() {
  med::View v;
  v.cameraToWorld[3] = glm::vec4(1, 2, 3, 1);
  v.left = -0.5f;
  v.right = 0.7f;
  v.bottom = -0.4f;
  v.top = 0.4f;
  v.width = 64;
  v.height = 48;
  v.region = {0, 0, 64, 48};
  return v;
}

RenderRequest sampleRequest() {
  RenderRequest r;
  r.frame = 77;
  r.compression = Compression::Zstd;
  r.jobs.push_back({1, sampleView(), {{0, 0, 16, 16}, {16, 32, 64, 48}}});
  r.sequenceFrame = 1234;
  return r;
}

SetViewports sampleViewports() {
  SetViewports sv;
  ViewportSpec v;
  v.id = 3;
  v.backend = "embree";
  v.root = 12;
  v.parameters.set("spp", std::int64_t{4});
  v.parameters.set("flag", true);
  v.parameters.set("t", 0.25);
  v.parameters.set("mode", std::string("fast"));
  sv.viewports.push_back(v);
  return sv;
}

// One encoded sample of every message type, for the generic tests.
std::vector<Frame> everyMessage() {
  Hello h;
  h.clientNonce[0] = 9;
  h.clientName = "client";
  RenderTile tile{5, 1, {0, 0, 2, 2}, 0.5, Compression::None, std::vector<std::uint8_t>(80, 7)};
  return {makeFrame(h),
          makeFrame(Challenge{}),
          makeFrame(Auth{}),
          makeFrame(Welcome{"n1", 4, {"embree", "vulkan"}}),
          makeFrame(Reject{"no"}),
          makeFrame(Applied{41}),
          makeFrame(sampleViewports()),
          makeFrame(sampleRequest()),
          makeFrame(tile),
          makeFrame(FrameDone{5, 0.125}),
          makeFrame(Swap{5}),
          makeFrame(HashQuery{2}),
          makeFrame(HashReply{2, 9, 0xdeadbeefcafef00dull}),
          makeFrame(Heartbeat{300}),
          makeFrame(HeartbeatAck{300}),
          makeFrame(ErrorReport{"bad"}),
          makeFrame(Bye{}),
          makeFrame(Prepare{12, {1, 2, 3, 4}})};
}

// Parses a message of any type; what the node and client do on receipt.
void parseAny(const Message& m) {
  switch (m.type) {
    case MessageType::Hello:
      parse<Hello>(m);
      break;
    case MessageType::Challenge:
      parse<Challenge>(m);
      break;
    case MessageType::Auth:
      parse<Auth>(m);
      break;
    case MessageType::Welcome:
      parse<Welcome>(m);
      break;
    case MessageType::Reject:
      parse<Reject>(m);
      break;
    case MessageType::Applied:
      parse<Applied>(m);
      break;
    case MessageType::SetViewports:
      parse<SetViewports>(m);
      break;
    case MessageType::RenderRequest:
      parse<RenderRequest>(m);
      break;
    case MessageType::RenderTile:
      parse<RenderTile>(m);
      break;
    case MessageType::FrameDone:
      parse<FrameDone>(m);
      break;
    case MessageType::Swap:
      parse<Swap>(m);
      break;
    case MessageType::HashQuery:
      parse<HashQuery>(m);
      break;
    case MessageType::HashReply:
      parse<HashReply>(m);
      break;
    case MessageType::Heartbeat:
      parse<Heartbeat>(m);
      break;
    case MessageType::HeartbeatAck:
      parse<HeartbeatAck>(m);
      break;
    case MessageType::Error:
      parse<ErrorReport>(m);
      break;
    case MessageType::Bye:
      parse<Bye>(m);
      break;
    case MessageType::Prepare:
      parse<Prepare>(m);
      break;
    default:
      break;
  }
}

TEST(MessageCodec, RoundTripsCarryEveryField) {
  RenderRequest r = parse<RenderRequest>(unframe(makeFrame(sampleRequest())));
  RenderRequest want = sampleRequest();
  EXPECT_EQ(r.frame, want.frame);
  EXPECT_EQ(r.compression, want.compression);
  EXPECT_EQ(r.jobs, want.jobs);
  EXPECT_EQ(r.sequenceFrame, 1234);
  RenderRequest none = sampleRequest();
  none.sequenceFrame = -1;
  EXPECT_EQ(parse<RenderRequest>(unframe(makeFrame(none))).sequenceFrame, -1);
  Prepare p = parse<Prepare>(unframe(makeFrame(Prepare{12, {1, 2, 3, 4}})));
  EXPECT_EQ(p.frame, 12);
  EXPECT_EQ(p.changes, (std::vector<std::uint8_t>{1, 2, 3, 4}));
  EXPECT_THROW(parse<Prepare>(unframe(makeFrame(Prepare{std::int64_t{1} << 50, {}}))), ProtocolError);

  SetViewports sv = parse<SetViewports>(unframe(makeFrame(sampleViewports())));
  EXPECT_EQ(sv.viewports, sampleViewports().viewports);
  EXPECT_FALSE(sv.window.has_value());
  SetViewports placed = sampleViewports();
  placed.window = WindowPlacement{-1920, 40, 1280, 0, true};
  EXPECT_EQ(parse<SetViewports>(unframe(makeFrame(placed))).window, placed.window);
  placed.window->x = -(1 << 20);  // beyond any desktop
  EXPECT_THROW(parse<SetViewports>(unframe(makeFrame(placed))), ProtocolError);

  Welcome w = parse<Welcome>(unframe(makeFrame(Welcome{"n1", 4, {"embree", "vulkan"}})));
  EXPECT_EQ(w.nodeName, "n1");
  EXPECT_EQ(w.threads, 4u);
  EXPECT_EQ(w.backends, (std::vector<std::string>{"embree", "vulkan"}));

  HashReply h = parse<HashReply>(unframe(makeFrame(HashReply{2, 9, 0xdeadbeefcafef00dull})));
  EXPECT_EQ(h.hash, 0xdeadbeefcafef00dull);
  EXPECT_EQ(h.version, 9u);

  RenderTile t =
      parse<RenderTile>(unframe(makeFrame(RenderTile{5, 1, {1, 2, 3, 4}, 0.5, Compression::Lz4, {1, 2, 3}})));
  EXPECT_EQ(t.rect, (med::PixelRect{1, 2, 3, 4}));
  EXPECT_EQ(t.seconds, 0.5);
  EXPECT_EQ(t.compression, Compression::Lz4);
  EXPECT_EQ(t.pixels, (std::vector<std::uint8_t>{1, 2, 3}));
}

TEST(MessageCodec, EveryMessageRoundTrips) {
  for (const Frame& f : everyMessage()) {
    Message m = unframe(f);
    EXPECT_NO_THROW(parseAny(m)) << name(m.type);
  }
}

TEST(MessageCodec, EveryTruncationIsAMalformedError) {
  for (const Frame& f : everyMessage()) {
    Message whole = unframe(f);
    // RenderTile's pixels and Prepare's change list run to the end: a shorter
    // one is caught by the pixel decoder or the change list's.
    if (whole.type == MessageType::RenderTile || whole.type == MessageType::Prepare || whole.payload.empty()) continue;
    for (std::size_t n = 0; n < whole.payload.size(); ++n) {
      Message cut{whole.type, std::vector<std::uint8_t>(whole.payload.begin(), whole.payload.begin() + n)};
      try {
        parseAny(cut);
        ADD_FAILURE() << name(whole.type) << " cut to " << n << " bytes decoded";
      } catch (const ProtocolError& e) {
        EXPECT_EQ(e.kind(), Kind::Malformed) << e.what();
      }
    }
  }
}

TEST(MessageCodec, TrailingBytesAreRejected) {
  Message m = unframe(makeFrame(Swap{3}));
  m.payload.push_back(0);
  EXPECT_THROW(parse<Swap>(m), ProtocolError);
}

TEST(MessageCodec, RandomCorruptionOnlyEverGivesTypedErrors) {
  std::mt19937 rng(1234);
  std::size_t rejected = 0, total = 0;
  for (const Frame& f : everyMessage()) {
    Message whole = unframe(f);
    if (whole.payload.empty()) continue;
    for (int round = 0; round < 300; ++round) {
      Message bad = whole;
      int flips = 1 + static_cast<int>(rng() % 4);
      for (int k = 0; k < flips; ++k)
        bad.payload[rng() % bad.payload.size()] ^= static_cast<std::uint8_t>(1 + rng() % 255);
      ++total;
      try {
        parseAny(bad);
      } catch (const ProtocolError& e) {
        EXPECT_EQ(e.kind(), Kind::Malformed);
        ++rejected;
      }  // any other exception type fails the test by escaping
    }
  }
  EXPECT_GT(rejected, total / 10) << "corruption should usually be detected";
}

TEST(MessageCodec, ValidationRejectsNonsenseValues) {
  RenderRequest r = sampleRequest();
  r.jobs[0].rects.push_back({10, 10, 10, 20});  // empty rectangle
  EXPECT_THROW(parse<RenderRequest>(unframe(makeFrame(r))), ProtocolError);
  r = sampleRequest();
  r.jobs[0].rects.push_back({0, 0, 65, 48});  // outside the image
  EXPECT_THROW(parse<RenderRequest>(unframe(makeFrame(r))), ProtocolError);
  r = sampleRequest();
  r.jobs[0].view.nearPlane = -1;  // degenerate view
  EXPECT_THROW(parse<RenderRequest>(unframe(makeFrame(r))), ProtocolError);
  // Found by mutating recorded traffic: a finite eye at -2.7e38 aborted the
  // node in Embree. Views must stay within sg::kMaxCoordinate.
  for (float eye : {-2.7e38f, 1e20f, 1.1e12f}) {
    r = sampleRequest();
    r.jobs[0].view.cameraToWorld[3][2] = eye;
    try {
      parse<RenderRequest>(unframe(makeFrame(r)));
      ADD_FAILURE() << "eye " << eye << " accepted";
    } catch (const ProtocolError& e) {
      EXPECT_EQ(e.kind(), ProtocolError::Kind::Malformed);
      EXPECT_NE(std::string(e.what()).find("beyond the coordinate limit"), std::string::npos) << e.what();
    }
  }
  r = sampleRequest();
  r.jobs[0].view.top = 2e12f;
  EXPECT_THROW(parse<RenderRequest>(unframe(makeFrame(r))), ProtocolError);
  r = sampleRequest();
  r.jobs[0].view.farPlane = 1e30f;  // an infinite projection, as glTF says: fine
  EXPECT_NO_THROW(parse<RenderRequest>(unframe(makeFrame(r))));
  r = sampleRequest();
  r.jobs[0].view.width = r.jobs[0].view.height = 8192;  // a valid image, but one tile of 64 M pixels is too much
  r.jobs[0].view.region = {0, 0, 8192, 8192};
  r.jobs[0].rects = {{0, 0, 8192, 8192}};
  EXPECT_THROW(parse<RenderRequest>(unframe(makeFrame(r))), ProtocolError);
  // A wall node keeping its pixels sends a tile without them, and only without them.
  RenderTile kept = parse<RenderTile>(unframe(makeFrame(RenderTile{5, 1, {1, 2, 3, 4}, 0.5, Compression::Kept, {}})));
  EXPECT_EQ(kept.compression, Compression::Kept);
  EXPECT_TRUE(kept.pixels.empty());
  EXPECT_THROW(parse<RenderTile>(unframe(makeFrame(RenderTile{5, 1, {1, 2, 3, 4}, 0.5, Compression::Kept, {1}}))),
               ProtocolError);
  EXPECT_THROW(parse<RenderTile>(unframe(makeFrame(RenderTile{5, 1, {1, 2, 3, 4}, 0.5, Compression(4), {}}))),
               ProtocolError);
  SetViewports sv = sampleViewports();
  sv.viewports.push_back(sv.viewports[0]);  // the same id twice
  EXPECT_THROW(parse<SetViewports>(unframe(makeFrame(sv))), ProtocolError);
}

TEST(FrameHeader, ChecksMagicVersionTypeAndSize) {
  auto header = [](std::uint8_t version, std::uint8_t type, std::uint32_t length) {
    std::vector<std::uint8_t> h;
    writeFrameHeader(h, {version, static_cast<MessageType>(type), length});
    return h;
  };
  auto kindOf = [](const std::vector<std::uint8_t>& h) {
    try {
      decodeFrameHeader(h);
    } catch (const ProtocolError& e) {
      return e.kind();
    }
    return Kind::Closed;  // stands for "accepted"
  };
  EXPECT_EQ(kindOf(header(kProtocolVersion, 1, 100)), Kind::Closed);
  auto bad = header(kProtocolVersion, 1, 100);
  bad[0] = 'X';
  EXPECT_EQ(kindOf(bad), Kind::BadMagic);
  EXPECT_EQ(kindOf(header(kProtocolVersion + 1, 1, 100)), Kind::VersionMismatch);
  EXPECT_EQ(kindOf(header(kProtocolVersion, 0, 0)), Kind::UnknownType);
  EXPECT_EQ(kindOf(header(kProtocolVersion, 200, 0)), Kind::UnknownType);
  EXPECT_EQ(kindOf(header(kProtocolVersion, static_cast<std::uint8_t>(MessageType::Hello), 1u << 20)), Kind::Oversized);
  EXPECT_EQ(kindOf(header(kProtocolVersion, static_cast<std::uint8_t>(MessageType::Snapshot), 0xffffffffu)),
            Kind::Oversized);
}

TEST(FrameHeader, EveryTypeHasABoundedSpec) {
  for (int t = 0; t < 256; ++t)
    if (const MessageSpec* s = findSpec(static_cast<std::uint8_t>(t))) {
      EXPECT_EQ(static_cast<int>(s->type), t);
      EXPECT_LE(s->maxPayload, std::size_t{1} << 30) << s->name;
    }
}

}  // namespace
}  // namespace tsr::cluster
