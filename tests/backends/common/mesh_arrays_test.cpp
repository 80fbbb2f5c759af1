// The mesh arrays every back-end takes: a vertex edit's checks, and shared
// elements that are held without a copy and copied before an edit.
#include "tsr/backend/shared_elements.hpp"
#include "tsr/backend/vertex_edit.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace tsr::backend {
namespace {

using ::testing::HasSubstr;

TEST(BackendVertexEdit, RangesAndSizesAreChecked) {
  const std::vector<glm::vec3> four(4, glm::vec3(1.0f));
  EXPECT_FALSE((VertexEdit{.positions = four, .first = 1, .count = 3}).invalidReason(4));
  EXPECT_THAT((VertexEdit{.positions = four, .first = 2, .count = 3}).invalidReason(4).value_or(""),
              HasSubstr("[2, 5) exceeds the mesh's 4 vertices"));
  EXPECT_THAT((VertexEdit{.positions = four, .count = 1}).invalidReason(5).value_or(""),
              HasSubstr("4 positions for a mesh of 5 vertices"));
  EXPECT_THAT(
      (VertexEdit{.positions = four, .normals = std::span(four).first(2), .count = 1}).invalidReason(4).value_or(""),
      HasSubstr("2 normals for 4 positions"));
  const VertexEdit edit{.positions = four, .normals = four, .first = 1, .count = 2};
  EXPECT_EQ(edit.changedPositions().data(), four.data() + 1);
  EXPECT_EQ(edit.changedNormals().size(), 2u);
}

TEST(BackendSharedElements, SharedElementsAreHeldWithoutACopyAndCopiedBeforeAnEdit) {
  auto giver = std::make_shared<const std::vector<int>>(std::vector<int>{1, 2, 3});
  SharedElements<int> held(*giver, giver);
  EXPECT_TRUE(held.shared());
  EXPECT_EQ(held.data(), giver->data()) << "no copy";
  SharedElements<int> copy = held;
  EXPECT_EQ(copy.data(), giver->data()) << "a copy of shared elements shares them too";
  held.writable()[1] = 20;
  EXPECT_FALSE(held.shared());
  EXPECT_EQ((*giver)[1], 2) << "the giver never sees the edit";
  EXPECT_EQ(copy[1], 2);
  EXPECT_EQ(held[1], 20);
  const int* own = held.data();
  held.writable()[2] = 30;
  EXPECT_EQ(held.data(), own) << "elements already owned are edited in place";
}

TEST(BackendSharedElements, OwnedElementsAreValues) {
  SharedElements<int> a = std::vector<int>{1, 2, 3};
  EXPECT_FALSE(a.shared());
  SharedElements<int> b = a;
  EXPECT_NE(b.data(), a.data()) << "owned elements are copied with their holder";
  b.writable()[0] = 10;
  EXPECT_EQ(a[0], 1);
  SharedElements<int> moved = std::move(b);
  EXPECT_EQ(moved[0], 10);
  EXPECT_TRUE(b.empty()) << "moved from: empty, not dangling";  // NOLINT(bugprone-use-after-move)
  SharedElements<int>& same = moved;
  moved = same;  // self-assignment keeps the elements
  EXPECT_EQ(moved[0], 10);
  EXPECT_TRUE(SharedElements<int>({}, nullptr).empty());
}

}  // namespace
}  // namespace tsr::backend
