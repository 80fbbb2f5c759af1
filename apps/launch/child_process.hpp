#pragma once
// A program the launcher starts and outlives: argv exactly as given (no
// shell), stdin and stderr shared with the launcher, stdout either shared
// or read line by line (tessera-node announces its address there).
#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace tsr::app {

// Throws LaunchError when `program` (an argv[0]) cannot be started: a path
// that is missing, a folder or not executable, or a name not found on PATH.
// Checked before a rank waits for the others, not after.
void checkStartable(const std::string& program);

class ChildProcess {
 public:
  // Starts argv[0] (searched on PATH when it has no '/'). Throws
  // LaunchError when it cannot be started.
  ChildProcess(const std::vector<std::string>& argv, bool captureStdout);
  ~ChildProcess();  // kills and reaps a child still running
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  // The next stdout line (captured children only); empty when none came
  // within `timeout` or the child closed stdout.
  std::string readLine(std::chrono::milliseconds timeout);
  // Its exit status (128 + signal when killed) once it has exited.
  std::optional<int> poll();
  int wait();
  // SIGTERM, then SIGKILL when it is still there after `grace`.
  int stop(std::chrono::milliseconds grace);

 private:
  static int statusOf(int raw);
  pid_t pid_ = -1;
  int stdout_ = -1;
  std::optional<int> status_;
};

}  // namespace tsr::app
