// Replicas follow a source through change lists and snapshots, and refuse
// lists that do not fit without changing anything.
#include <gtest/gtest.h>

#include "random_edits.hpp"
#include "tsr/sg/scene.hpp"

using namespace tsr::sg;
using tsr::sg::test::RandomEditor;

TEST(Replica, RandomEditSequencesKeepReplicasIdentical) {
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    Scene source, replica;
    RandomEditor edit(source, seed);
    for (int frame = 0; frame < 40; ++frame) {
      for (int i = 0; i < 8; ++i) edit.editOne();
      replica.apply(*source.commit());
      ASSERT_EQ(replica.contentHash(), source.contentHash()) << "seed " << seed << " frame " << frame;
      ASSERT_EQ(replica.version(), source.version());
    }
  }
}

TEST(Replica, SnapshotRebuildsTheSceneInAnEmptyReplica) {
  Scene source;
  RandomEditor edit(source, 7);
  for (int i = 0; i < 300; ++i) edit.editOne();
  source.commit();
  auto snap = source.snapshot();
  EXPECT_TRUE(snap->isSnapshot());
  EXPECT_TRUE(snap->changes().empty());
  EXPECT_EQ(snap->creations().size(), source.size());
  Scene late;
  late.apply(*snap);
  EXPECT_EQ(late.contentHash(), source.contentHash());
  EXPECT_EQ(late.version(), source.version());
  // And it follows the deltas from there.
  for (int i = 0; i < 50; ++i) edit.editOne();
  late.apply(*source.commit());
  EXPECT_EQ(late.contentHash(), source.contentHash());
}

TEST(Replica, SnapshotNeedsCommittedStateAndAnEmptyReplica) {
  Scene source;
  source.create<Group>();
  EXPECT_THROW(source.snapshot(), SceneError);
  source.commit();
  Scene replica;
  replica.apply(*source.snapshot());
  EXPECT_THROW(replica.apply(*source.snapshot()), ApplyError);
}

TEST(Replica, ContentHashSeesEveryField) {
  Scene a, b;
  a.create<SurfaceMaterial>().setIor(1.5f);
  b.create<SurfaceMaterial>().setIor(1.5f);
  EXPECT_EQ(a.contentHash(), b.contentHash());
  b.find<SurfaceMaterial>(1)->setIor(1.33f);
  EXPECT_NE(a.contentHash(), b.contentHash());
  b.find<SurfaceMaterial>(1)->setIor(1.5f);
  b.find<SurfaceMaterial>(1)->setName("x");
  EXPECT_NE(a.contentHash(), b.contentHash());
}

namespace {
// A replica at version 1 holding a group, a transform and a geometry.
struct Diverged {
  Scene source, replica;
  Group* group;
  Transform* transform;
  Geometry* mesh;
  Diverged() {
    group = &source.create<Group>();
    transform = &source.create<Transform>();
    mesh = &source.create<Geometry>();
    group->addChild(transform->id());
    transform->addChild(mesh->id());
    replica.apply(*source.commit());
  }
  void expectRejected(const ChangeList& list, const char* why) {
    std::uint64_t hash = replica.contentHash();
    std::uint64_t version = replica.version();
    EXPECT_THROW(replica.apply(list), ApplyError) << why;
    EXPECT_EQ(replica.contentHash(), hash) << why;
    EXPECT_EQ(replica.version(), version) << why;
    EXPECT_FALSE(replica.hasPendingChanges()) << why;
  }
};
}  // namespace

TEST(Replica, WrongVersionIsRejected) {
  Diverged d;
  d.transform->setMatrix(Mat4(2.0f));
  auto v2 = d.source.commit();
  d.transform->setMatrix(Mat4(3.0f));
  auto v3 = d.source.commit();
  d.expectRejected(*v3, "skips version 2");
  d.replica.apply(*v2);
  d.expectRejected(*v2, "applied twice");
  d.replica.apply(*v3);
  EXPECT_EQ(d.replica.contentHash(), d.source.contentHash());
}

TEST(Replica, ListsNamingMissingOrMistypedContainersAreRejected) {
  Diverged d;
  Scene elsewhere;  // containers with ids the replica does not hold
  for (int i = 0; i < 5; ++i) elsewhere.create<Transform>();
  {
    ChangeList::Builder b(ChangeList::Kind::Delta, 2);
    b.addChange(*elsewhere.find(5), fieldBit(Transform::Matrix), {});
    d.expectRejected(*b.finish(), "changes a missing container");
  }
  {
    ChangeList::Builder b(ChangeList::Kind::Delta, 2);
    b.addChange(*elsewhere.find(3), fieldBit(Transform::Matrix), {});  // id 3 is a Geometry in the replica
    d.expectRejected(*b.finish(), "changes a container as the wrong type");
  }
  {
    ChangeList::Builder b(ChangeList::Kind::Delta, 2);
    b.addCreation(*elsewhere.find(2));  // id 2 exists in the replica
    d.expectRejected(*b.finish(), "creates an existing id");
  }
  {
    ChangeList::Builder b(ChangeList::Kind::Delta, 2);
    b.addDestruction(99, ContainerType::Group);
    d.expectRejected(*b.finish(), "destroys a missing container");
  }
  {
    ChangeList::Builder b(ChangeList::Kind::Delta, 2);
    b.addDestruction(d.mesh->id(), ContainerType::Geometry);
    d.expectRejected(*b.finish(), "destroys a container that is still a child");
  }
  {
    Scene g;
    auto& parent = g.create<Group>();
    for (int i = 0; i < 40; ++i) g.create<Group>();
    parent.addChild(40);
    ChangeList::Builder b(ChangeList::Kind::Delta, 2);
    b.addChange(parent, fieldBit(Group::Children), {});  // group 1 names child 40, missing
    d.expectRejected(*b.finish(), "names a missing child");
  }
}

TEST(Replica, ListsThatWouldMakeACycleAreRejected) {
  Diverged d;
  // In the replica, 1 -> 2 -> 3 (group, transform, mesh). A list that makes
  // transform 2 a parent of group 1 closes a cycle.
  Scene crafted;
  crafted.create<Group>();
  auto& t = crafted.create<Transform>();
  t.addChild(1);
  ChangeList::Builder b(ChangeList::Kind::Delta, 2);
  b.addChange(t, fieldBit(Transform::Children), {});
  d.expectRejected(*b.finish(), "cycle");
}

TEST(Replica, ALocallyEditedReplicaRefusesLists) {
  Diverged d;
  d.transform->setMatrix(Mat4(2.0f));
  auto list = d.source.commit();
  d.replica.find<Transform>(2)->setName("local");
  EXPECT_THROW(d.replica.apply(*list), ApplyError);
}
