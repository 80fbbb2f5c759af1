#pragma once
// A one-line progress bar on stderr, drawn only when stderr is a terminal.
#include <cstdio>
#include <string>

#include <unistd.h>

namespace tsr::app {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label, bool enabled = true)
      : label_(std::move(label)), enabled_(enabled && isatty(fileno(stderr))) {}
  ~ProgressBar() { finish(); }

  void update(double fraction) {
    if (!enabled_) return;
    int filled = static_cast<int>(fraction * kWidth + 0.5);
    if (filled == drawn_) return;
    drawn_ = filled;
    std::fprintf(stderr, "\r%s [%s%s] %3d%%", label_.c_str(), std::string(filled, '#').c_str(),
                 std::string(kWidth - filled, ' ').c_str(), static_cast<int>(fraction * 100 + 0.5));
    std::fflush(stderr);
  }
  bool active() const { return enabled_; }
  void finish() {
    if (enabled_ && drawn_ >= 0) std::fputc('\n', stderr);
    drawn_ = -1;
  }

 private:
  static constexpr int kWidth = 40;
  std::string label_;
  bool enabled_;
  int drawn_ = -1;
};

}  // namespace tsr::app
