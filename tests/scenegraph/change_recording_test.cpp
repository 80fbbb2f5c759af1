// How edits become change lists: coalescing, creations, destructions.
#include <gtest/gtest.h>

#include "tsr/sg/scene.hpp"

using namespace tsr::sg;

namespace {
Mat4 translation(float x) {
  Mat4 m(1.0f);
  m[3] = Vec4(x, 0, 0, 1);
  return m;
}
}  // namespace

TEST(ChangeRecording, IdsAreStableAndAscending) {
  Scene s;
  auto& a = s.create<Group>("a");
  auto& b = s.create<Transform>("b");
  EXPECT_EQ(a.id(), 1u);
  EXPECT_EQ(b.id(), 2u);
  EXPECT_EQ(s.find<Transform>(2), &b);
  EXPECT_EQ(s.find<Group>(2), nullptr) << "typed lookup of the wrong type";
  EXPECT_EQ(s.find(99), nullptr);
}

TEST(ChangeRecording, CreationCarriesEveryFieldAndLaterEditsOfTheFrame) {
  Scene s;
  auto& t = s.create<Transform>("t");
  t.setMatrix(translation(1));
  t.setMatrix(translation(2));
  auto list = s.commit();
  ASSERT_EQ(list->creations().size(), 1u);
  EXPECT_TRUE(list->changes().empty()) << "edits in the creating frame ride on the creation";
  EXPECT_EQ(list->creations()[0].mask, t.allFields());
  EXPECT_EQ(list->version(), 1u);
  EXPECT_EQ(s.version(), 1u);

  Scene replica;
  replica.apply(*list);
  EXPECT_EQ(replica.find<Transform>(t.id())->matrix(), translation(2));
}

TEST(ChangeRecording, SettingAFieldManyTimesYieldsOneEntryWithTheLastValue) {
  Scene s;
  auto& t = s.create<Transform>();
  auto& m = s.create<SurfaceMaterial>();
  s.commit();
  for (int i = 0; i < 3; ++i) t.setMatrix(translation(float(i)));
  m.setRoughness(0.1f);
  m.setRoughness(0.9f);
  m.setMetallic(1.0f);
  auto list = s.commit();
  ASSERT_EQ(list->changes().size(), 2u);
  const ChangeEntry& te = list->changes()[0];
  EXPECT_EQ(te.id, t.id());
  EXPECT_EQ(te.mask, fieldBit(Transform::Matrix));
  const ChangeEntry& me = list->changes()[1];
  EXPECT_EQ(me.mask, fieldBit(SurfaceMaterial::Roughness) | fieldBit(SurfaceMaterial::Metallic));
  EXPECT_EQ(list->fieldChangeCount(), 3u);
}

TEST(ChangeRecording, EmptyFrameGivesEmptyListWithNextVersion) {
  Scene s;
  s.create<Group>();
  s.commit();
  auto list = s.commit();
  EXPECT_TRUE(list->empty());
  EXPECT_EQ(list->version(), 2u);
  EXPECT_EQ(list->baseVersion(), 1u);
}

TEST(ChangeRecording, DestroyRemovesFromParentsAndSlotsAsRecordedChanges) {
  Scene s;
  auto& root = s.create<Group>("root");
  auto& t1 = s.create<Transform>("t1");
  auto& t2 = s.create<Transform>("t2");
  auto& mesh = s.create<Geometry>("mesh");
  auto& mat = s.create<SurfaceMaterial>("mat");
  root.addChild(t1.id());
  root.addChild(t2.id());
  t1.addChild(mesh.id());
  t2.addChild(mesh.id());  // instanced
  mesh.setMaterial(mat.id());
  s.commit();

  const ContainerId meshId = mesh.id(), matId = mat.id();
  s.destroy(meshId);
  s.destroy(matId);
  EXPECT_TRUE(t1.children().empty());
  EXPECT_TRUE(t2.children().empty());
  auto list = s.commit();
  ASSERT_EQ(list->destructions().size(), 2u);
  EXPECT_EQ(list->destructions()[0].id, meshId);
  EXPECT_EQ(list->destructions()[1].id, matId);
  ASSERT_EQ(list->changes().size(), 2u) << "both parents lose the child";
  for (const auto& e : list->changes()) EXPECT_EQ(e.mask, fieldBit(Transform::Children));
  EXPECT_EQ(s.find(meshId), nullptr);
}

TEST(ChangeRecording, DestroyingAReferencedMaterialClearsTheSlot) {
  Scene s;
  auto& mesh = s.create<Geometry>();
  auto& mat = s.create<SimpleMaterial>();
  mesh.setMaterial(mat.id());
  s.commit();
  s.destroy(mat.id());
  EXPECT_EQ(mesh.material(), kNoContainer);
  auto list = s.commit();
  ASSERT_EQ(list->changes().size(), 1u);
  EXPECT_EQ(list->changes()[0].mask, fieldBit(Geometry::Material));
}

TEST(ChangeRecording, CreateAndDestroyInOneFrameLeavesNoTrace) {
  Scene s;
  s.create<Group>();
  s.commit();
  auto& temp = s.create<Transform>();
  temp.setMatrix(translation(3));
  s.destroy(temp.id());
  auto list = s.commit();
  EXPECT_TRUE(list->empty());
}

TEST(ChangeRecording, DestroyedChildrenOfADestroyedNodeSurviveAsRoots) {
  Scene s;
  auto& g = s.create<Group>();
  auto& child = s.create<Transform>();
  g.addChild(child.id());
  EXPECT_EQ(s.roots(), std::vector<ContainerId>{g.id()});
  s.destroy(g.id());
  EXPECT_EQ(s.roots(), std::vector<ContainerId>{child.id()});
}

TEST(ChangeRecording, ReferencesAreChecked) {
  Scene s, other;
  auto& g = s.create<Group>();
  auto& t = s.create<Transform>();
  auto& mesh = s.create<Geometry>();
  auto& img = s.create<Image>();
  auto& bg = s.create<Background>();
  auto& cam = s.create<Camera>();
  EXPECT_THROW(g.addChild(12345), SceneError) << "missing";
  EXPECT_THROW(g.addChild(img.id()), SceneError) << "an image is not a node";
  EXPECT_THROW(g.addChild(bg.id()), SceneError) << "a background is not a node";
  EXPECT_NO_THROW(t.addChild(cam.id())) << "a camera is a node (its parents move it)";
  t.removeChild(cam.id());
  EXPECT_THROW(mesh.setMaterial(img.id()), SceneError) << "an image is not a material";
  EXPECT_THROW(g.addChild(g.id()), SceneError) << "self cycle";
  g.addChild(t.id());
  EXPECT_THROW(t.addChild(g.id()), SceneError) << "two-node cycle";
  EXPECT_EQ(t.children().size(), 0u) << "a rejected edit changes nothing";
  auto& deep = s.create<Group>();
  t.addChild(deep.id());
  EXPECT_THROW(deep.addChild(g.id()), SceneError) << "longer cycle";
  (void)other;
}

TEST(ChangeRecording, NonFiniteValuesAreRejected) {
  Scene s;
  auto& t = s.create<Transform>();
  Mat4 bad(1.0f);
  bad[3][0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(t.setMatrix(bad), SceneError);
  auto& g = s.create<Geometry>();
  EXPECT_THROW(g.setPositions({Vec3(0), Vec3(std::numeric_limits<float>::infinity())}), SceneError);
  EXPECT_THROW(t.setAttachment("x", std::numeric_limits<double>::infinity()), SceneError);
  EXPECT_EQ(t.matrix(), Mat4(1.0f));
}

TEST(ChangeRecording, AttachmentsTravelAndUnknownOnesAreKept) {
  Scene s;
  auto& g = s.create<Geometry>();
  g.setAttachment("embree.maxDepth", std::int64_t{3});
  g.setAttachment("someone.else", std::vector<float>{1, 2, 3});
  s.commit();
  Scene replica;
  replica.apply(*s.snapshot());
  const auto* depth = replica.find(g.id())->attachment("embree.maxDepth");
  ASSERT_NE(depth, nullptr);
  EXPECT_EQ(std::get<std::int64_t>(*depth), 3);
  g.removeAttachment("someone.else");
  auto list = s.commit();
  ASSERT_EQ(list->changes().size(), 1u);
  EXPECT_EQ(list->changes()[0].mask, fieldBit(Container::kAttachments));
  replica.apply(*list);
  EXPECT_EQ(replica.find(g.id())->attachment("someone.else"), nullptr);
  EXPECT_EQ(replica.contentHash(), s.contentHash());
}
