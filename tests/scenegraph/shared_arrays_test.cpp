// One copy of bulk geometry in a process: a scene, the lists it commits and
// the replicas that apply them share a mesh's arrays until someone edits
// them, and the wire carries the same bytes whether a list shares or not.
#include <gtest/gtest.h>

#include <numeric>

#include "tsr/sg/geometry.hpp"
#include "tsr/sg/replica.hpp"
#include "tsr/sg/scene.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

using namespace tsr::sg;

namespace {
std::vector<Vec3> grid(std::size_t n) {
  std::vector<Vec3> p(n);
  for (std::size_t i = 0; i < n; ++i) p[i] = Vec3(float(i % 97), float(i / 97), 0.5f);
  return p;
}
std::vector<std::uint32_t> fan(std::size_t vertices) {
  std::vector<std::uint32_t> idx;
  for (std::uint32_t i = 1; i + 1 < vertices; ++i) idx.insert(idx.end(), {0, i, i + 1});
  return idx;
}

struct Mesh {
  Scene source;
  ContainerId id = kNoContainer;
  Mesh() {
    Geometry& g = source.create<Geometry>("mesh");
    g.setPositions(grid(5000));
    g.setIndices(fan(5000));
    id = g.id();
  }
  Geometry& geometry() { return *source.find<Geometry>(id); }
};

const Geometry& in(const Replica& r, ContainerId id) { return *r.scene().find<Geometry>(id); }
}  // namespace

TEST(SharedArrays, AReplicaHoldsTheScenesArraysNotACopy) {
  Mesh m;
  ChangeListPtr list = m.source.commit();
  // The list carries the arrays by reference: its bytes are the fields'
  // headers, not 60 kB of positions.
  EXPECT_EQ(list->slices().size(), 2u);
  EXPECT_LT(list->values().size(), 200u);
  Replica replica;
  replica.apply(list);
  EXPECT_EQ(in(replica, m.id).positions().data(), m.geometry().positions().data());
  EXPECT_EQ(in(replica, m.id).indices().data(), m.geometry().indices().data());
  EXPECT_EQ(replica.scene().contentHash(), m.source.contentHash());
}

TEST(SharedArrays, AnEditAfterSharingCopiesAndReachesNoOneElse) {
  Mesh m;
  ChangeListPtr first = m.source.commit();
  Replica replica;
  replica.apply(first);
  const Vec3* shared = in(replica, m.id).positions().data();

  std::vector<Vec3> moved{Vec3(7.0f), Vec3(8.0f)};
  m.geometry().updatePositions(10, moved);
  // The scene copied before editing; the replica and the list still hold
  // the elements as committed.
  EXPECT_NE(m.geometry().positions().data(), shared);
  EXPECT_EQ(in(replica, m.id).positions()[10], grid(5000)[10]);
  EXPECT_EQ(in(replica, m.id).positions().data(), shared);

  // A second edit in the same frame edits the scene's own copy in place.
  const Vec3* own = m.geometry().positions().data();
  m.geometry().updatePositions(20, moved);
  EXPECT_EQ(m.geometry().positions().data(), own);

  // The ranged edit reaches the replica, which copies in turn: the first
  // list (in its log) still holds the elements it carried.
  replica.apply(m.source.commit());
  EXPECT_EQ(in(replica, m.id).positions()[10], Vec3(7.0f));
  EXPECT_EQ(in(replica, m.id).positions()[21], Vec3(8.0f));
  EXPECT_EQ(replica.scene().contentHash(), m.source.contentHash());
  auto fresh = std::make_shared<Replica>();
  fresh->apply(first);
  EXPECT_EQ(in(*fresh, m.id).positions()[10], grid(5000)[10]) << "the committed list changed after the edit";
}

TEST(SharedArrays, TheWireCarriesTheSameBytesWithOrWithoutSharing) {
  Mesh m;
  ChangeListPtr list = m.source.commit();
  std::vector<std::uint8_t> bytes = encode(*list);
  EXPECT_GT(bytes.size(), 5000 * sizeof(Vec3)) << "the elements must be written in place";

  // A list read from bytes holds its whole arrays as shared arrays too, and
  // writes the same bytes again.
  ChangeListPtr decoded = decode(bytes);
  EXPECT_EQ(decoded->slices().size(), 2u);
  EXPECT_LT(decoded->values().size(), 200u);
  EXPECT_EQ(encode(*decoded), bytes);

  // A replica of it shares the decoded list's arrays and equals the source.
  Replica replica;
  replica.apply(decoded);
  EXPECT_EQ(static_cast<const void*>(in(replica, m.id).positions().data()),
            static_cast<const void*>(decoded->slices()[0].bytes));
  EXPECT_EQ(replica.scene().contentHash(), m.source.contentHash());

  // The snapshot of that replica, a late joiner's start, is the same bytes
  // as the source's snapshot.
  EXPECT_EQ(encode(*replica.scene().snapshot()), encode(*m.source.snapshot()));
}

TEST(SharedArrays, RangedEditsAndWholeArraysInOneListKeepTheirPlaces) {
  // Several geometries with shared arrays and ranged edits in one list:
  // slices of one entry must not be spliced into its neighbour.
  Scene source;
  std::vector<ContainerId> ids;
  for (int i = 0; i < 4; ++i) {
    Geometry& g = source.create<Geometry>("g" + std::to_string(i));
    g.setPositions(grid(100 + i));
    g.setNormals(std::vector<Vec3>(100 + i, Vec3(0, 0, 1)));
    g.setIndices(fan(100 + i));
    ids.push_back(g.id());
  }
  Replica replica;
  replica.apply(source.commit());
  source.find<Geometry>(ids[0])->updatePositions(3, std::vector<Vec3>{Vec3(1.0f)});
  source.find<Geometry>(ids[1])->setNormals(std::vector<Vec3>(101, Vec3(0, 1, 0)));
  source.find<Geometry>(ids[2])->updateIndices(0, std::vector<std::uint32_t>{2, 1, 0});
  source.find<Geometry>(ids[3])->setUvs(std::vector<Vec2>(103, Vec2(0.5f)));
  ChangeListPtr list = source.commit();
  ChangeListPtr decoded = decode(encode(*list));
  EXPECT_EQ(encode(*decoded), encode(*list));
  Replica viaWire;
  viaWire.apply(decode(encode(*source.snapshot())));
  ASSERT_EQ(viaWire.version(), source.version());
  replica.apply(decoded);
  EXPECT_EQ(replica.scene().contentHash(), source.contentHash());
  EXPECT_EQ(viaWire.scene().contentHash(), source.contentHash());
}
