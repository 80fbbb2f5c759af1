#pragma once
// Runs one of our executables the way a user would, in a scratch folder,
// and captures exit status, stdout and stderr.
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace tsr::test {

struct Outcome {
  int status = -1;
  std::string out;
  std::string err;
};

class CommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device rd;
    dir = std::filesystem::temp_directory_path() / ("tsr_cmd_" + std::to_string(rd()));
    std::filesystem::create_directories(dir);
  }
  void TearDown() override { std::filesystem::remove_all(dir); }

  static std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  Outcome runBinary(const std::string& binary, const std::string& args) {
    const auto out = dir / "out.txt", err = dir / "err.txt";
    const std::string cmd = "cd '" + dir.string() + "' && '" + binary + "' " + args + " > '" + out.string() +
                            "' 2> '" + err.string() + "' < /dev/null";
    const int raw = std::system(cmd.c_str());
    Outcome r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
  }

  // Exit status 2 and exactly one line on stderr, "error: ..." naming `about`.
  static void expectOneErrorLine(const Outcome& r, const std::string& about) {
    EXPECT_EQ(r.status, 2);
    ASSERT_FALSE(r.err.empty());
    EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.back(), '\n');
    EXPECT_THAT(r.err, ::testing::HasSubstr(about));
  }

  std::filesystem::path dir;
};

}  // namespace tsr::test
