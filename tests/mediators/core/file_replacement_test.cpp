#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "tsr/med/file_replacement.hpp"
#include "tsr/med/image_file.hpp"

namespace {

namespace fs = std::filesystem;
using namespace tsr::med;

class FileReplacement : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("tsr_replace_" + std::to_string(std::random_device{}()));
    fs::create_directories(dir);
    target = (dir / "out.png").string();
    std::ofstream(target) << "old";
  }
  void TearDown() override { fs::remove_all(dir); }
  std::string contents() const {
    std::ifstream in(target, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::size_t entries() const { return std::distance(fs::directory_iterator(dir), fs::directory_iterator()); }
  fs::path dir;
  std::string target;
};

TEST_F(FileReplacement, TemporaryKeepsTheExtensionBesideTheTarget) {
  const fs::path temporary = temporaryPathFor(target);
  EXPECT_EQ(temporary.parent_path(), dir);
  EXPECT_EQ(temporary.extension(), ".png");
  EXPECT_NE(temporary.filename(), "out.png");
}

TEST_F(FileReplacement, AWriterThatFailsHalfwayLeavesTheOldFileAndNoTemporary) {
  EXPECT_THROW(replaceFile(target,
                           [](const std::string& temporary) {
                             std::ofstream(temporary) << "half of a new";
                             throw std::runtime_error("disk full");
                           }),
               std::runtime_error);
  EXPECT_EQ(contents(), "old");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(FileReplacement, ASuccessfulWriteReplacesTheFile) {
  replaceTextFile(target, "new");
  EXPECT_EQ(contents(), "new");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(FileReplacement, AnImageThatCannotBeWrittenLeavesTheOldOne) {
  FrameBuffer fb(2, 2);
  EXPECT_THROW(writeImage(target, fb, "no-such-output"), ImageFileError);
  EXPECT_EQ(contents(), "old");
  writeImage(target, fb);
  EXPECT_EQ(readImage(target).width, 2u);
  EXPECT_EQ(entries(), 1u);
}

}  // namespace
