#pragma once
// The node's one rendering thread: jobs (apply a change list, render a
// request, answer a hash query) run here in the order they arrive, so the
// io thread keeps answering heartbeats while a frame renders.
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

namespace tsr::cluster {

class RenderWorker {
 public:
  RenderWorker();
  ~RenderWorker();  // finishes the running job, drops the rest
  void post(std::function<void()> job);

 private:
  void run();
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> jobs_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace tsr::cluster
