// A snapshot larger than one message travels as parts: each within the
// bound, applied together when the last arrives, the same scene as the
// snapshot whole.
#include <gtest/gtest.h>

#include "tsr/sg/geometry.hpp"
#include "tsr/sg/replica.hpp"
#include "tsr/sg/scene.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

using namespace tsr::sg;

namespace {
// Ten meshes of 1,000 vertices (about 12 kB of positions each) under one group.
void build(Scene& scene) {
  std::vector<ContainerId> kids;
  for (int m = 0; m < 10; ++m) {
    Geometry& g = scene.create<Geometry>("mesh " + std::to_string(m));
    std::vector<Vec3> p(1000);
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = Vec3(float(i), float(m), 0.0f);
    std::vector<std::uint32_t> idx;
    for (std::uint32_t i = 0; i + 2 < 1000; i += 3) idx.insert(idx.end(), {i, i + 1, i + 2});
    g.setPositions(std::move(p));
    g.setIndices(std::move(idx));
    kids.push_back(g.id());
  }
  scene.create<Group>("root").setChildren(kids);
  scene.commit();
}
}  // namespace

TEST(SnapshotParts, EachPartFitsAndTheirReplicaEqualsTheSource) {
  Scene source;
  build(source);
  ChangeListPtr whole = source.snapshot();
  const std::size_t wholeBytes = encode(*whole).size();
  auto parts = splitSnapshot(whole, 40 * 1024);
  ASSERT_GE(parts.size(), 4u);
  Replica replica;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const bool last = i + 1 == parts.size();
    EXPECT_EQ(parts[i]->isSnapshot(), last);
    EXPECT_EQ(parts[i]->isSnapshotPart(), !last);
    auto bytes = encode(*parts[i]);
    EXPECT_LE(bytes.size(), 40u * 1024u);
    replica.apply(decode(bytes));  // through the wire, as a node gets them
    EXPECT_EQ(replica.scene().size(), last ? source.size() : 0u) << "part " << i << " applied alone";
    EXPECT_EQ(replica.awaitingSnapshot(), !last);
  }
  EXPECT_EQ(replica.version(), source.version());
  EXPECT_EQ(replica.scene().contentHash(), source.contentHash());
  // The parts joined are the snapshot, byte for byte.
  EXPECT_EQ(encode(*joinSnapshot(parts)), encode(*whole));
  // A snapshot that fits is its own one part (the estimate allows 30
  // bytes an entry for its id, type, mask and size).
  auto one = splitSnapshot(whole, wholeBytes + 30 * whole->creations().size() + 64);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0], whole);
}

TEST(SnapshotParts, PartsOutOfPlaceAreRefusedAndLeaveTheReplicaAsItWas) {
  Scene source;
  build(source);
  auto parts = splitSnapshot(source.snapshot(), 40 * 1024);
  ASSERT_GE(parts.size(), 3u);

  // The last part without the others: a snapshot of part of the scene,
  // whose group names meshes that will not exist.
  Replica missing;
  EXPECT_THROW(missing.apply(parts.back()), ApplyError);
  EXPECT_EQ(missing.scene().size(), 0u);

  // A part repeated: refused when the last arrives; the parts are dropped.
  Replica repeated;
  repeated.apply(parts[0]);
  repeated.apply(parts[0]);
  EXPECT_THROW(repeated.apply(parts.back()), ApplyError);
  EXPECT_FALSE(repeated.awaitingSnapshot());
  EXPECT_EQ(repeated.scene().size(), 0u);

  // A part to a replica that holds a scene.
  Replica full;
  full.apply(source.snapshot());
  const std::uint64_t hash = full.scene().contentHash();
  EXPECT_THROW(full.apply(parts[0]), ApplyError);
  EXPECT_EQ(full.scene().contentHash(), hash);

  // A part applied to a scene directly, not through a replica.
  Scene direct;
  EXPECT_THROW(direct.apply(*parts[0]), ApplyError);
}

// A part size below the largest container still works: that container goes
// alone in a part as large as it needs, within the message's bound.
TEST(SnapshotParts, AContainerLargerThanAPartGoesAlone) {
  Scene source;
  build(source);
  ChangeListPtr whole = source.snapshot();
  auto parts = splitSnapshot(whole, 4 * 1024, 1 << 20);
  ASSERT_GE(parts.size(), 10u);  // each mesh (about 24 kB) in a part of its own
  for (const auto& part : parts) {
    EXPECT_LE(encode(*part).size(), std::size_t{1} << 20);
    if (encode(*part).size() > 4 * 1024) {
      EXPECT_EQ(part->creations().size(), 1u);
    }
  }
  EXPECT_EQ(encode(*joinSnapshot(parts)), encode(*whole));
}

TEST(SnapshotParts, AContainerLargerThanAMessageIsRefusedByName) {
  Scene source;
  build(source);
  EXPECT_THROW(splitSnapshot(source.snapshot(), 4 * 1024), std::length_error);
  EXPECT_THROW(splitSnapshot(source.snapshot(), 4 * 1024, 8 * 1024), std::length_error);
  EXPECT_THROW(splitSnapshot(source.commit(), 1 << 20), std::invalid_argument);  // a delta
}
