// Replays every kept fuzz input (the seed corpus and the inputs of past
// findings) through the same bodies the fuzz targets run, in the normal
// build: a fixed finding that comes back fails here, without clang.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "fuzz_targets.hpp"

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> filesIn(const fs::path& dir) {
  std::vector<fs::path> files;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::uint8_t> readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FuzzReplay : public ::testing::TestWithParam<tsr::fuzz::Target> {};

TEST_P(FuzzReplay, RegressionsAndCorpusDecodeOrAreRefused) {
  const fs::path root = TSR_FUZZ_DIR;
  const std::string name(GetParam().name);
  const auto regressions = filesIn(root / "regressions" / name);
  const auto corpus = filesIn(root / "corpus" / name);
  ASSERT_FALSE(corpus.empty()) << "no seed corpus for " << name;
  for (const auto* set : {&regressions, &corpus})
    for (const fs::path& file : *set) {
      SCOPED_TRACE(file.string());
      const auto bytes = readBytes(file);
      EXPECT_NO_THROW(GetParam().run(bytes));
    }
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzReplay, ::testing::ValuesIn(tsr::fuzz::allTargets()),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
