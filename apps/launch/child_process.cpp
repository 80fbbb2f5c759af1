#include "child_process.hpp"

#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <thread>

#include "launch_rank.hpp"

extern char** environ;

namespace tsr::app {

namespace {

bool executableFile(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec) && access(path.c_str(), X_OK) == 0;
}

}  // namespace

void checkStartable(const std::string& program) {
  if (program.empty()) throw LaunchError("an empty program name");
  if (program.find('/') != std::string::npos) {
    std::error_code ec;
    if (!std::filesystem::exists(program, ec)) throw LaunchError(program + ": no such program");
    if (!executableFile(program)) throw LaunchError(program + ": not an executable file");
    return;
  }
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
  for (std::size_t start = 0; start <= dirs.size();) {
    const auto colon = std::min(dirs.find(':', start), dirs.size());
    const std::string dir = dirs.substr(start, colon - start);
    if (executableFile((dir.empty() ? std::string(".") : dir) + "/" + program)) return;
    start = colon + 1;
  }
  throw LaunchError(program + ": no such program on PATH");
}

ChildProcess::ChildProcess(const std::vector<std::string>& args, bool captureStdout) {
  if (args.empty()) throw LaunchError("no command to start");
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  int out[2] = {-1, -1};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (captureStdout) {
    if (pipe(out) != 0) throw LaunchError(std::string("pipe: ") + std::strerror(errno));
    posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&actions, out[0]);
  }
  const int rc = posix_spawnp(&pid_, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (captureStdout) close(out[1]);
  if (rc != 0) {
    if (captureStdout) close(out[0]);
    pid_ = -1;
    throw LaunchError("cannot start " + args[0] + ": " + std::strerror(rc));
  }
  stdout_ = out[0];
}

ChildProcess::~ChildProcess() {
  if (pid_ > 0 && !status_) {
    ::kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  if (stdout_ >= 0) close(stdout_);
}

std::string ChildProcess::readLine(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::string line;
  while (stdout_ >= 0 && line.size() < 4096) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return {};
    pollfd p{stdout_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) return {};
    char c;
    if (read(stdout_, &c, 1) != 1) return {};
    if (c == '\n') return line;
    line.push_back(c);
  }
  return line;
}

int ChildProcess::statusOf(int raw) {
  if (WIFEXITED(raw)) return WEXITSTATUS(raw);
  if (WIFSIGNALED(raw)) return 128 + WTERMSIG(raw);
  return 1;
}

std::optional<int> ChildProcess::poll() {
  if (status_ || pid_ <= 0) return status_;
  int raw = 0;
  if (waitpid(pid_, &raw, WNOHANG) == pid_) status_ = statusOf(raw);
  return status_;
}

int ChildProcess::wait() {
  while (!status_ && pid_ > 0) {
    int raw = 0;
    const pid_t r = waitpid(pid_, &raw, 0);
    if (r == pid_)
      status_ = statusOf(raw);
    else if (r < 0 && errno != EINTR)
      status_ = 1;
  }
  return status_.value_or(1);
}

int ChildProcess::stop(std::chrono::milliseconds grace) {
  if (poll()) return *status_;
  ::kill(pid_, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + grace;
  while (!poll() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (!status_) {
    ::kill(pid_, SIGKILL);
    return wait();
  }
  return *status_;
}

}  // namespace tsr::app
