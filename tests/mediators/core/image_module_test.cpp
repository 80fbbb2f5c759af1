// OpenImageIO (and the ~250 libraries it brings) is loaded the first time
// a program touches an image, not when it starts (tsr/imageio/image_codec.hpp).
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tsr/imageio/image_codec.hpp"
#include "tsr/med/image_file.hpp"

namespace {

bool openImageIOMapped() {
  std::ifstream maps("/proc/self/maps");
  for (std::string line; std::getline(maps, line);)
    if (line.find("libOpenImageIO.so") != std::string::npos) return true;
  return false;
}

TEST(ImageModule, OpenImageIOIsLoadedByTheFirstImageAndNotBefore) {
  // A fresh process (the threadsafe style re-runs this test alone), so
  // other tests of this program that wrote images do not count.
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        const bool before = openImageIOMapped();
        tsr::med::FrameBuffer fb(4, 2);
        const bool encoded = !tsr::med::encodePng(fb).empty();
        const bool after = openImageIOMapped();
        std::exit(!before && encoded && after && !tsr::imageio::modulePath().empty() ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(ImageModule, ItsErrorsAreTyped) {
  const std::vector<std::uint8_t> notAnImage{1, 2, 3, 4, 5, 6, 7, 8};
  EXPECT_THROW(tsr::imageio::decode(notAnImage, "memory.png", 1 << 20), tsr::imageio::CodecError);
  tsr::imageio::Layout layout;
  layout.width = 2, layout.height = 2, layout.channels = 3;
  const std::vector<std::byte> tooFew(5);
  EXPECT_THROW(tsr::imageio::encode("x.png", layout, tooFew), tsr::imageio::CodecError)
      << "pixels that do not fill the layout are refused, not read past";
}

}  // namespace
