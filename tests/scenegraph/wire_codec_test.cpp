// Change lists survive the wire bit for bit, and hostile bytes give typed
// errors, never crashes (this suite also runs under ASan + UBSan).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "random_edits.hpp"
#include "tsr/sg/coordinate_limit.hpp"
#include "tsr/sg/scene.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

using namespace tsr::sg;
using tsr::sg::test::RandomEditor;

namespace {
// Encoded lists of a random session: a snapshot and a run of deltas.
std::vector<std::vector<std::uint8_t>> randomSession(std::uint64_t seed, int frames) {
  Scene source;
  RandomEditor edit(source, seed);
  for (int i = 0; i < 20; ++i) edit.createOne();
  source.commit();
  std::vector<std::vector<std::uint8_t>> out{encode(*source.snapshot())};
  for (int f = 0; f < frames; ++f) {
    for (int i = 0; i < 6; ++i) edit.editOne();
    out.push_back(encode(*source.commit()));
  }
  return out;
}

// Decoding must end in a list or a DecodeError; applying a decoded list to a
// replica must end in success or an ApplyError that leaves it untouched.
// True when the list decoded and applied; refusals must leave the replica as it was.
bool decodeAndApplyHostile(std::span<const std::uint8_t> bytes, Scene& replica) {
  ChangeListPtr list;
  try {
    list = decode(bytes);
  } catch (const DecodeError& e) {
    EXPECT_LE(e.offset(), bytes.size());
    return false;
  }
  std::uint64_t before = replica.contentHash();
  try {
    replica.apply(*list);
    return true;
  } catch (const ApplyError&) {
    EXPECT_EQ(replica.contentHash(), before);
    return false;
  }
}
}  // namespace

TEST(WireCodec, RandomScenesAndEditsRoundTrip) {
  for (std::uint64_t seed = 1; seed <= 25; ++seed) {
    Scene source, viaWire;
    RandomEditor edit(source, seed);
    for (int frame = 0; frame < 30; ++frame) {
      for (int i = 0; i < 10; ++i) edit.editOne();
      auto list = source.commit();
      auto bytes = encode(*list);
      auto decoded = decode(bytes);
      ASSERT_EQ(encode(*decoded), bytes) << "re-encoding is the identity";
      ASSERT_EQ(decoded->fieldChangeCount(), list->fieldChangeCount());
      viaWire.apply(*decoded);
      ASSERT_EQ(viaWire.contentHash(), source.contentHash()) << "seed " << seed << " frame " << frame;
    }
    Scene late;
    late.apply(*decode(encode(*source.snapshot())));
    EXPECT_EQ(late.contentHash(), source.contentHash());
  }
}

TEST(WireCodec, DecodedListKeepsRangesAndReferences) {
  Scene s;
  auto& root = s.create<Group>();
  auto& mesh = s.create<Geometry>();
  mesh.setPositions(std::vector<Vec3>(100, Vec3(1)));
  root.addChild(mesh.id());
  s.commit();
  mesh.updatePositions(10, std::vector<Vec3>(3, Vec3(2)));
  auto decoded = decode(encode(*s.commit()));
  ASSERT_EQ(decoded->changes().size(), 1u);
  const RangedEdit* edit = decoded->changes()[0].rangedEdit(Geometry::Positions);
  ASSERT_NE(edit, nullptr);
  EXPECT_EQ(edit->length, 100u);
  EXPECT_EQ(edit->ranges, (std::vector<ArrayRange>{{10, 13}}));
  auto snap = decode(encode(*s.snapshot()));
  ASSERT_EQ(snap->creations().size(), 2u);
  ASSERT_EQ(snap->creations()[0].references.size(), 1u);
  EXPECT_EQ(snap->creations()[0].references[0].target, mesh.id());
}

TEST(WireCodec, ASingleTransformEditIsSmall) {
  Scene s;
  for (int i = 0; i < 5000; ++i) s.create<Transform>();
  s.commit();
  Mat4 m(1.0f);
  m[3] = Vec4(1, 2, 3, 1);
  s.find<Transform>(4321)->setMatrix(m);
  auto bytes = encode(*s.commit());
  EXPECT_LE(bytes.size(), 96u);
}

TEST(WireCodec, EveryTruncationIsATypedError) {
  auto session = randomSession(11, 6);
  for (const auto& bytes : session) {
    for (std::size_t n = 0; n < bytes.size(); ++n) {
      EXPECT_THROW(decode(std::span(bytes).first(n)), DecodeError) << "prefix of " << n << " bytes";
    }
  }
}

TEST(WireCodec, RandomByteFlipsNeverCrash) {
  std::mt19937_64 rng(5);
  std::size_t applied = 0, pairs = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    auto session = randomSession(seed, 5);
    std::vector<ChangeListPtr> lists;
    for (const auto& bytes : session) lists.push_back(decode(bytes));
    for (std::size_t k = 0; k < session.size(); ++k, ++pairs) {
      for (int trial = 0; trial < 300; ++trial) {
        // A fresh replica that followed the session up to the list being
        // corrupted: one that applied an earlier corrupted list would stop
        // every later trial at the version check.
        Scene replica;
        for (std::size_t j = 0; j < k; ++j) replica.apply(*lists[j]);
        auto bytes = session[k];
        int flips = 1 + static_cast<int>(rng() % 4);
        for (int i = 0; i < flips; ++i) bytes[rng() % bytes.size()] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
        applied += decodeAndApplyHostile(bytes, replica);
      }
    }
  }
  // Flips in values decode and apply; with a shared replica at most one
  // trial per list could.
  EXPECT_GT(applied, pairs) << "corrupted lists must reach apply's checks past the version";
}

// Matrices and vertex arrays place what back-ends trace: beyond
// kMaxCoordinate they are refused by setters and by the decoder alike.
TEST(WireCodec, CoordinatesBeyondTheLimitAreRefused) {
  Scene s;
  auto& t = s.create<Transform>();
  auto& c = s.create<Camera>();
  auto& g = s.create<Geometry>();
  Mat4 far(1.0f);
  far[3][2] = -1e20f;
  EXPECT_THROW(t.setMatrix(far), SceneError);
  EXPECT_THROW(c.setPose(far), SceneError);
  EXPECT_THROW(g.setPositions({Vec3(0), Vec3(0, 2e12f, 0)}), SceneError);
  g.setPositions({Vec3(0), Vec3(1, 0, 0), Vec3(0, kMaxCoordinate, 0)});  // the limit itself is fine
  EXPECT_THROW(g.updatePositions(0, std::vector<Vec3>{Vec3(3e38f)}), SceneError);
  c.setFarPlane(1e30f);  // planes are no coordinates: an infinite projection stays allowed
  t.setMatrix(Mat4(2.0f));
  auto bytes = encode(*s.commit());

  // The same values patched into the bytes, as a hostile peer would send them.
  auto patched = [&](float from, float to) {
    auto out = bytes;
    std::uint8_t a[4], b[4];
    std::memcpy(a, &from, 4);
    std::memcpy(b, &to, 4);
    auto it = std::search(out.begin(), out.end(), a, a + 4);
    EXPECT_NE(it, out.end());
    if (it != out.end()) std::copy(b, b + 4, it);
    return out;
  };
  EXPECT_NO_THROW(decode(bytes));
  try {
    decode(patched(2.0f, -2.7e38f));
    ADD_FAILURE() << "matrix entry accepted";
  } catch (const DecodeError& e) {
    EXPECT_NE(std::string(e.what()).find("beyond the coordinate limit"), std::string::npos) << e.what();
  }
  try {
    decode(patched(kMaxCoordinate, 1e20f));
    ADD_FAILURE() << "position accepted";
  } catch (const DecodeError& e) {
    EXPECT_NE(std::string(e.what()).find("beyond 1e12"), std::string::npos) << e.what();
  }
}

TEST(WireCodec, MalformedHeadersAndBodiesAreNamed) {
  Scene s;
  s.create<Transform>();
  auto good = encode(*s.commit());

  auto expectError = [](std::vector<std::uint8_t> bytes, const std::string& reasonPart) {
    try {
      decode(bytes);
      ADD_FAILURE() << "decoded, expected: " << reasonPart;
    } catch (const DecodeError& e) {
      EXPECT_NE(std::string(e.what()).find(reasonPart), std::string::npos) << e.what();
    }
  };
  auto bad = good;
  bad[0] = 'X';
  expectError(bad, "magic");
  bad = good;
  bad[4] = 99;
  expectError(bad, "protocol version 99");
  bad = good;
  bad[6] = 0xff, bad[7] = 0xff, bad[8] = 0xff, bad[9] = 0x7f;
  expectError(bad, "exceeds the limit");
  bad = good;
  bad.push_back(0);
  expectError(bad, "payload bytes");

  DecodeLimits tiny;
  tiny.maxMessageBytes = 8;
  EXPECT_THROW(decode(good, tiny), DecodeError);

  // Hand-built payloads with a valid header.
  auto withPayload = [](std::vector<std::uint8_t> payload) {
    std::vector<std::uint8_t> out = {'T', 'S', 'R', 'C', kWireFormatVersion, 0};
    auto n = static_cast<std::uint32_t>(payload.size());
    out.insert(out.end(), {std::uint8_t(n), std::uint8_t(n >> 8), std::uint8_t(n >> 16), std::uint8_t(n >> 24)});
    out.insert(out.end(), payload.begin(), payload.end());
    return out;
  };
  // version 1, 0 creations, 1 change: id 1, type 77
  expectError(withPayload({1, 0, 1, 0, 1, 77, 1, 0}), "unknown container type 77");
  // type Transform, mask with field 40 set
  expectError(withPayload({1, 0, 1, 0, 1, 2, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x01, 0}), "unknown field");
  // a billion changes announced in a few bytes
  expectError(withPayload({1, 0, 0x80, 0x94, 0xeb, 0xdc, 0x03, 0}), "exceeds");
  // a creation without every field
  expectError(withPayload({1, 1, 0, 0, 1, 2, 1, 1, 0}), "without every field");
  // a change whose values are longer than its fields: name "" plus a stray byte
  expectError(withPayload({1, 0, 1, 0, 1, 2, 1, 2, 0, 9}), "left over");
  // a string longer than what remains
  expectError(withPayload({1, 0, 1, 0, 1, 2, 1, 2, 50, 0}), "exceeds the bytes that remain");
  // ids out of order
  expectError(withPayload({1, 0, 2, 0, 5, 2, 1, 1, 0, 4, 2, 1, 1, 0}), "ascend");
  // an overlong varint
  expectError(withPayload({0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x01}), "varint");
}
