#pragma once
// Runs one of our executables the way a user would, in a scratch folder,
// and captures exit status, stdout and stderr.
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

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
    const std::string cmd = "cd '" + dir.string() + "' && '" + binary + "' " + args + " > '" + out.string() + "' 2> '" +
                            err.string() + "' < /dev/null";
    const int raw = std::system(cmd.c_str());
    Outcome r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
  }

  // The peak resident kilobytes of one run (output discarded), from wait4.
  // A fresh process starts from this test's own footprint, so compare runs.
  static long peakKilobytes(const std::string& binary, const std::vector<std::string>& args) {
    std::vector<std::string> all{binary};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
      const int null = open("/dev/null", O_WRONLY);
      dup2(null, STDOUT_FILENO);
      dup2(null, STDERR_FILENO);
      execv(argv[0], argv.data());
      _exit(127);
    }
    int status = 0;
    rusage usage{};
    if (pid < 0 || wait4(pid, &status, 0, &usage) != pid) return -1;
    return usage.ru_maxrss;
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

  // Found by mutating real files: a glTF camera at z = -1e20, finite, which
  // passed every check and aborted Embree ("Assertion 'ray.valid()' failed").
  std::filesystem::path writeFarCameraGltf(const std::string& name = "far.gltf") {
    auto path = dir / name;
    std::ofstream(path) << R"({"asset": {"version": "2.0"},
      "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
      "nodes": [{"camera": 0, "translation": [0, 0, -1e20]}], "scenes": [{"nodes": [0]}]})";
    return path;
  }

  std::filesystem::path dir;
};

}  // namespace tsr::test
