// The region every back-end renders: what is refused, and how a back-end
// throws it as its own error type.
#include "tsr/backend/region.hpp"
#include "tsr/backend/validate.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>

namespace tsr::backend {
namespace {

using ::testing::HasSubstr;

struct BackendError : std::runtime_error {
  explicit BackendError(const std::string& message) : std::runtime_error("backend: " + message) {}
};

TEST(BackendRegion, EmptyOrOutsideRegionsAreRefused) {
  EXPECT_FALSE(Region::full(8, 4).invalidReason());
  EXPECT_FALSE((Region{8, 4, 2, 1, 8, 4}).invalidReason());
  EXPECT_THAT(Region{}.invalidReason().value_or(""), HasSubstr("non-zero"));
  EXPECT_THAT((Region{8, 4, 3, 0, 3, 4}).invalidReason().value_or(""), HasSubstr("empty"));
  EXPECT_THAT((Region{8, 4, 0, 0, 9, 4}).invalidReason().value_or(""), HasSubstr("exceeds image 8x4"));
}

TEST(BackendRegion, ValidateThrowsTheBackendsError) {
  EXPECT_NO_THROW(validate<BackendError>(Region::full(2, 2)));
  try {
    validate<BackendError>(Region{2, 2, 0, 0, 3, 2});
    FAIL() << "no throw";
  } catch (const BackendError& e) {
    EXPECT_THAT(e.what(), HasSubstr("backend: region [0,3)x[0,2) exceeds image 2x2"));
  }
}

TEST(BackendRegion, SizesAreOfTheCrop) {
  const Region r{10, 10, 2, 3, 7, 5};
  EXPECT_EQ(r.regionWidth(), 5u);
  EXPECT_EQ(r.regionHeight(), 2u);
  EXPECT_EQ(r.pixelCount(), 10u);
}

}  // namespace
}  // namespace tsr::backend
