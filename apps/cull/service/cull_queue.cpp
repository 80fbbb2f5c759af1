#include "service/cull_queue.hpp"

#include <spdlog/spdlog.h>

namespace tsr::app {

CullQueue::CullQueue(CullService& cull, std::size_t capacity)
    : cull_(cull), capacity_(capacity), worker_([this] { work(); }) {}

CullQueue::~CullQueue() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

bool CullQueue::push(std::shared_ptr<CullJob> job) {
  {
    std::lock_guard lock(mutex_);
    if (waiting_.size() >= capacity_) {
      ++refused_;
      return false;
    }
    job->queued = CullJob::Clock::now();
    waiting_.push_back(std::move(job));
  }
  wake_.notify_one();
  return true;
}

void CullQueue::work() {
  for (;;) {
    std::shared_ptr<CullJob> job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !waiting_.empty(); });
      if (stopping_) return;
      job = std::move(waiting_.front());
      waiting_.pop_front();
      if (job->gone) {
        ++dropped_;
        continue;
      }
      ranking_ = true;
    }
    const auto start = CullJob::Clock::now();
    std::string error;
    CullAnswer answer;
    try {
      answer = cull_.cull(job->query, &job->gone);
    } catch (const std::exception& e) {
      spdlog::error("/v1/cull failed: {}", e.what());
      error = e.what();
    }
    const double ms = std::chrono::duration<double, std::milli>(CullJob::Clock::now() - start).count();
    {
      std::lock_guard lock(mutex_);
      ranking_ = false;
      recentMs_ = answered_ + dropped_ == 0 ? ms : 0.9 * recentMs_ + 0.1 * ms;
      ++(job->gone ? dropped_ : answered_);
    }
    if (!job->gone) job->done(error.empty() ? &answer : nullptr, error);
  }
}

CullQueueStatus CullQueue::status() const {
  std::lock_guard lock(mutex_);
  CullQueueStatus s;
  s.waiting = waiting_.size();
  s.capacity = capacity_;
  s.ranking = ranking_;
  s.answered = answered_;
  s.dropped = dropped_;
  s.refused = refused_;
  s.recentRankingMs = recentMs_;
  if (!waiting_.empty())
    s.oldestWaitMs =
        std::chrono::duration<double, std::milli>(CullJob::Clock::now() - waiting_.front()->queued).count();
  return s;
}

}  // namespace tsr::app
