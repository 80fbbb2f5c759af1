#pragma once
// Real tessera-node processes for the integration tests: started on a free
// port of 127.0.0.1, their address read from the first stdout line, killed
// (or stopped and continued) on demand, and always reaped.
#include <csignal>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tsr/cluster/node_address.hpp"

extern char** environ;

namespace tsr::cluster::test {

// A program that prints "listening on HOST:PORT" first (tessera-node,
// tessera-cull), started with `args` (the binary first).
class ListeningProcess {
 public:
  explicit ListeningProcess(std::vector<std::string> args) {
    std::vector<char*> argv;
    argv.reserve(args.size() + 1);
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    int out[2];
    if (pipe(out) != 0) throw std::runtime_error("pipe failed");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&actions, out[0]);
    // Nothing else of this process reaches the node: not other nodes' pipes,
    // not client sockets (a node holding one would keep it open after the
    // client closed it, and count it as its own descriptor).
    posix_spawn_file_actions_addclosefrom_np(&actions, STDERR_FILENO + 1);
    int rc = posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(out[1]);
    if (rc != 0) {
      close(out[0]);
      throw std::runtime_error("cannot start " + args[0]);
    }
    stdout_ = out[0];
    std::string line = readLine(10000);
    const std::string prefix = "listening on ";
    if (line.rfind(prefix, 0) != 0) {
      kill();
      throw std::runtime_error(args[0] + " did not report its address, said: '" + line + "'");
    }
    address_ = parseNodeAddress(line.substr(prefix.size()));
  }
  ~ListeningProcess() {
    kill();
    if (stdout_ >= 0) close(stdout_);
  }
  ListeningProcess(const ListeningProcess&) = delete;
  ListeningProcess& operator=(const ListeningProcess&) = delete;

  const NodeAddress& address() const { return address_; }
  std::string text() const { return address_.text(); }
  bool alive() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }

  void kill() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);  // kills a stopped process too; SIGCONT first would let it run on
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }
  void pause() { ::kill(pid_, SIGSTOP); }
  void resume() { ::kill(pid_, SIGCONT); }
  // SIGTERM and wait; true when it exited cleanly with status 0.
  bool terminate() {
    if (pid_ <= 0) return false;
    ::kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
  }

 private:
  std::string readLine(int timeoutMs) {
    std::string line;
    char c;
    while (true) {
      pollfd p{stdout_, POLLIN, 0};
      if (poll(&p, 1, timeoutMs) <= 0) break;
      if (read(stdout_, &c, 1) != 1 || c == '\n') break;
      line.push_back(c);
    }
    return line;
  }

  pid_t pid_ = -1;
  int stdout_ = -1;
  NodeAddress address_;
};

#ifdef TSR_NODE_BINARY
class NodeProcess : public ListeningProcess {
 public:
  explicit NodeProcess(std::vector<std::string> extraArgs = {}, const std::string& listen = "127.0.0.1:0")
      : ListeningProcess(argsFor(std::move(extraArgs), listen)) {}

 private:
  static std::vector<std::string> argsFor(std::vector<std::string> extraArgs, const std::string& listen) {
    std::vector<std::string> args{TSR_NODE_BINARY, "--listen", listen, "--log-level", "warn"};
    args.insert(args.end(), extraArgs.begin(), extraArgs.end());
    return args;
  }
};

inline std::vector<std::unique_ptr<NodeProcess>> startNodes(std::size_t n, const std::vector<std::string>& args = {}) {
  std::vector<std::unique_ptr<NodeProcess>> out;
  for (std::size_t i = 0; i < n; ++i) out.push_back(std::make_unique<NodeProcess>(args));
  return out;
}

// "A:P,B:Q,...": the nodes' addresses as --nodes takes them.
inline std::string addresses(const std::vector<std::unique_ptr<NodeProcess>>& nodes) {
  std::string out;
  for (const auto& n : nodes) out += (out.empty() ? "" : ",") + n->text();
  return out;
}
#endif  // TSR_NODE_BINARY

// A token file that lives as long as the object.
class TokenFile {
 public:
  explicit TokenFile(const std::string& token) {
    char name[] = "/tmp/tsr-token-XXXXXX";
    int fd = mkstemp(name);
    if (fd < 0) throw std::runtime_error("mkstemp failed");
    path_ = name;
    std::string text = token + "\n";
    if (write(fd, text.data(), text.size()) != static_cast<ssize_t>(text.size()))
      throw std::runtime_error("write failed");
    close(fd);
  }
  ~TokenFile() { unlink(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace tsr::cluster::test
