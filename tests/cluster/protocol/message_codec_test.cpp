// The message codec: every message round-trips, every truncation and
// random corruption ends in a typed ProtocolError (never another exception,
// never a crash), and frame headers are checked before any payload.
#include <cmath>
#include <limits>
#include <random>
#include <type_traits>

#include <gtest/gtest.h>

#include <cmath>

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
  v.apertureRadius = 0.05f;  // a lens travels with the view
  v.focusDistance = 2.5f;
  v.shutterOpen = 0.25f;  // so do the shutter and the camera's motion
  v.shutterClose = 0.75f;
  v.cameraToWorldAtEnd = v.cameraToWorld;
  (*v.cameraToWorldAtEnd)[3].x = 1.5f;
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

// A sample of each message type with every field away from its default, for
// the tests generated from the message list. A type without one here is
// tested with M{}; FieldsAwayFromDefault says when that is not enough.
Hello sample(std::type_identity<Hello>) {
  Hello h;
  h.version = 7;
  h.clientNonce[0] = 9;
  h.clientName = "client";
  return h;
}
Challenge sample(std::type_identity<Challenge>) {
  Challenge c;
  c.nodeNonce[31] = 1;
  c.nodeProof[0] = 2;
  return c;
}
Auth sample(std::type_identity<Auth>) {
  Auth a;
  a.clientProof[5] = 3;
  return a;
}
Welcome sample(std::type_identity<Welcome>) { return {"n1", 4, {"embree", "vulkan"}}; }
Reject sample(std::type_identity<Reject>) { return {"no"}; }
Snapshot sample(std::type_identity<Snapshot>) { return {{'T', 'S', 'R', 'C'}}; }
Changes sample(std::type_identity<Changes>) { return {{1, 2, 3}}; }
Applied sample(std::type_identity<Applied>) { return {41}; }
SetViewports sample(std::type_identity<SetViewports>) {
  SetViewports sv = sampleViewports();
  sv.viewports[0].background = 13;
  sv.window = WindowPlacement{-1920, 40, 1280, 720, true};
  return sv;
}
RenderRequest sample(std::type_identity<RenderRequest>) {
  RenderRequest r = sampleRequest();
  r.jobs[0].outputs = {"albedo", "normal"};
  r.jobs[0].resolve = false;
  return r;
}
RenderTile sample(std::type_identity<RenderTile>) {
  return {5, 1, {0, 0, 2, 2}, 0.5, Compression::Zstd, std::vector<std::uint8_t>(80, 7), {"albedo"}, 16, 123456, 0.25};
}
FrameDone sample(std::type_identity<FrameDone>) { return {5, 0.125}; }
Swap sample(std::type_identity<Swap>) { return {5}; }
HashQuery sample(std::type_identity<HashQuery>) { return {2}; }
HashReply sample(std::type_identity<HashReply>) { return {2, 9, 0xdeadbeefcafef00dull}; }
Heartbeat sample(std::type_identity<Heartbeat>) { return {300}; }
HeartbeatAck sample(std::type_identity<HeartbeatAck>) { return {300}; }
ErrorReport sample(std::type_identity<ErrorReport>) { return {ErrorReport::Kind::UnknownBackend, "bad"}; }
Prepare sample(std::type_identity<Prepare>) { return {12, {1, 2, 3, 4}}; }

template <class M>
M sampleOf() {
  if constexpr (requires { sample(std::type_identity<M>{}); })
    return sample(std::type_identity<M>{});
  else
    return M{};
}

template <class M>
std::vector<std::uint8_t> payloadOf(const M& m) {
  std::vector<std::uint8_t> bytes;
  sg::ByteWriter w(bytes);
  writeFields(w, m);
  return bytes;
}

// One encoded sample of every message type, for the generic tests.
std::vector<Frame> everyMessage() {
  std::vector<Frame> frames;
  Messages::forEach([&]<class M>() { frames.push_back(makeFrame(sampleOf<M>())); });
  return frames;
}

// Parses a message of any type; what the node and client do on receipt.
void parseAny(const Message& m) {
  Messages::visit(m.type, [&]<class M>() { parse<M>(m); });
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
  RenderTile counted{5, 1, {1, 2, 3, 4}, 0.5, Compression::Lz4, {1, 2, 3}, {}, 64, std::uint64_t{1} << 40, 0.125};
  t = parse<RenderTile>(unframe(makeFrame(counted)));
  EXPECT_EQ(t.samples, 64u);
  EXPECT_EQ(t.rays, std::uint64_t{1} << 40);
  EXPECT_EQ(t.syncSeconds, 0.125);
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
    // Pixels and change lists run to the end: a shorter one is caught by the
    // pixel decoder or the change list's.
    if (whole.type == RenderTile::kType || whole.type == Prepare::kType || whole.type == Snapshot::kType ||
        whole.type == Changes::kType || whole.payload.empty())
      continue;
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
  for (const auto& [aperture, focus] : {std::pair{-0.1f, 1.0f}, std::pair{0.1f, 0.0f}, std::pair{NAN, 1.0f}}) {
    r = sampleRequest();
    r.jobs[0].view.apertureRadius = aperture;  // a lens no camera has
    r.jobs[0].view.focusDistance = focus;
    EXPECT_THROW(parse<RenderRequest>(unframe(makeFrame(r))), ProtocolError) << aperture << " " << focus;
  }
  for (const auto& [open, close] : {std::pair{-0.1f, 0.5f}, std::pair{0.6f, 0.5f}, std::pair{0.0f, NAN}}) {
    r = sampleRequest();
    r.jobs[0].view.shutterOpen = open;  // a shutter outside the frame interval
    r.jobs[0].view.shutterClose = close;
    EXPECT_THROW(parse<RenderRequest>(unframe(makeFrame(r))), ProtocolError) << open << " " << close;
  }
  r = sampleRequest();
  (*r.jobs[0].view.cameraToWorldAtEnd)[3].y = NAN;  // a camera moving to nowhere
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
  // A tile's work figures stay within what a render can hold and JSON carries exactly.
  RenderTile tooMany{5, 1, {1, 2, 3, 4}, 0.5, Compression::Lz4, {1}, {}, kMaxTileSamples + 1, 0};
  EXPECT_THROW(parse<RenderTile>(unframe(makeFrame(tooMany))), ProtocolError);
  tooMany.samples = kMaxTileSamples;
  EXPECT_NO_THROW(parse<RenderTile>(unframe(makeFrame(tooMany))));
  tooMany.rays = kMaxTileRays + 1;
  EXPECT_THROW(parse<RenderTile>(unframe(makeFrame(tooMany))), ProtocolError);
  // Times are finite (a NaN would pass a "not negative" test and poison the sums).
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity(), -1.0}) {
    RenderTile t{5, 1, {1, 2, 3, 4}, bad, Compression::Lz4, {1}};
    EXPECT_THROW(parse<RenderTile>(unframe(makeFrame(t))), ProtocolError) << bad;
    t.seconds = 1;
    t.syncSeconds = bad;
    EXPECT_THROW(parse<RenderTile>(unframe(makeFrame(t))), ProtocolError) << bad;
  }
  SetViewports sv = sampleViewports();
  sv.viewports.push_back(sv.viewports[0]);  // the same id twice
  EXPECT_THROW(parse<SetViewports>(unframe(makeFrame(sv))), ProtocolError);
}

TEST(MessageList, SamplesSetEveryField) {
  Messages::forEach([]<class M>() {
    [[maybe_unused]] const M s = sampleOf<M>(), fresh{};
    auto check = [&](const auto& f) { EXPECT_FALSE(s.*f.member == fresh.*f.member) << M::kSpec.name << "." << f.name; };
    std::apply([&](const auto&... f) { (check(f), ...); }, M::fields());
  });
}

TEST(MessageList, EveryTypeRoundTripsToAnEqualMessage) {
  Messages::forEach([]<class M>() {
    const M sent = sampleOf<M>();
    const Frame frame = makeFrame(sent);
    const Message m = unframe(frame);
    EXPECT_EQ(m.type, M::kType);
    try {
      const M got = parse<M>(m);
      EXPECT_TRUE(got == sent) << M::kSpec.name;
      EXPECT_EQ(*makeFrame(got), *frame) << M::kSpec.name << " encodes differently after a round trip";
    } catch (const ProtocolError& e) {
      ADD_FAILURE() << M::kSpec.name << ": " << e.what();
    }
  });
}

TEST(MessageList, EveryTypesDeclaredLimitsAreEnforced) {
  std::size_t types = 0;
  Messages::forEach([&]<class M>() {
    ++types;
    const MessageSpec& s = M::kSpec;
    // The header's lookup is generated from the declarations.
    EXPECT_EQ(findSpec(static_cast<std::uint8_t>(M::kType)), &M::kSpec) << s.name;
    EXPECT_STREQ(name(M::kType), s.name);
    // A header announcing one byte more than the maximum is refused before
    // any payload is read; the maximum itself passes.
    std::vector<std::uint8_t> header;
    writeFrameHeader(header, {kProtocolVersion, M::kType, static_cast<std::uint32_t>(s.maxPayload)});
    EXPECT_NO_THROW(decodeFrameHeader(header)) << s.name;
    header.clear();
    writeFrameHeader(header, {kProtocolVersion, M::kType, static_cast<std::uint32_t>(s.maxPayload + 1)});
    try {
      decodeFrameHeader(header);
      ADD_FAILURE() << s.name << " of maxPayload + 1 bytes accepted";
    } catch (const ProtocolError& e) {
      EXPECT_EQ(e.kind(), Kind::Oversized) << s.name;
    }
    // The sender refuses to frame more than the maximum (the bulk types'
    // gigabyte is not allocated for this).
    if (s.maxPayload <= 64 * kMiB) {
      try {
        frameFromPayload(M::kType, std::vector<std::uint8_t>(s.maxPayload + 1));
        ADD_FAILURE() << s.name << " framed with maxPayload + 1 bytes";
      } catch (const ProtocolError& e) {
        EXPECT_EQ(e.kind(), Kind::Oversized) << s.name;
      }
    }
    EXPECT_LE(payloadOf(sampleOf<M>()).size(), s.maxPayload) << s.name;
  });
  EXPECT_EQ(types, Messages::size);
}

// Protocol 2 changed the Error message on purpose (a kind byte before the
// reason); these are its bytes, so a change to them is never an accident.
// (Protocols 3 to 6 added volumes, a lens, a shutter and the geometry's primitive: only the version byte moved.)
TEST(MessageCodec, ErrorReportBytesArePinned) {
  const Frame f = makeFrame(ErrorReport{ErrorReport::Kind::InvalidParameter, "spp"});
  const std::vector<std::uint8_t> want{'T', 'S', 'R', 'N', 6, 18, 5, 0, 0, 0, 3, 3, 's', 'p', 'p'};
  EXPECT_EQ(*f, want);
  ErrorReport back = parse<ErrorReport>(unframe(f));
  EXPECT_EQ(back.kind, ErrorReport::Kind::InvalidParameter);
  EXPECT_EQ(back.reason, "spp");
  Message unknownKind = unframe(f);
  unknownKind.payload[0] = 6;  // one past the last kind
  try {
    parse<ErrorReport>(unknownKind);
    ADD_FAILURE() << "an unknown error kind decoded";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.kind(), Kind::Malformed);
    EXPECT_NE(std::string(e.what()).find("unknown error kind 6"), std::string::npos) << e.what();
  }
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
  EXPECT_EQ(kindOf(header(kProtocolVersion, static_cast<std::uint8_t>(Hello::kType), 1u << 20)), Kind::Oversized);
  EXPECT_EQ(kindOf(header(kProtocolVersion, static_cast<std::uint8_t>(Snapshot::kType), 0xffffffffu)), Kind::Oversized);
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
