#include "tsr/cov/ranking.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <unordered_map>

namespace tsr::cov {

namespace {
using Histogram = std::unordered_map<ObjectId, std::uint64_t>;

// Neighbouring pixels mostly show the same object: count runs and touch
// the hash map once per run, not once per pixel.
void countRuns(std::span<const ObjectId> ids, Histogram& into) {
  std::size_t i = 0;
  while (i < ids.size()) {
    const ObjectId id = ids[i];
    std::size_t end = i + 1;
    while (end < ids.size() && ids[end] == id) ++end;
    into[id] += end - i;
    i = end;
  }
}
}  // namespace

std::vector<Coverage> rank(std::span<const ObjectId> ids) {
  tbb::enumerable_thread_specific<Histogram> perThread;
  constexpr std::size_t kChunk = 1 << 14;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ids.size(), kChunk),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      countRuns(ids.subspan(r.begin(), r.size()), perThread.local());
                    });
  Histogram total;
  for (const Histogram& h : perThread)
    for (const auto& [id, n] : h) total[id] += n;
  total.erase(kBackground);

  std::vector<Coverage> ranked;
  ranked.reserve(total.size());
  const double all = static_cast<double>(ids.size());
  for (const auto& [id, n] : total) ranked.push_back({id, n, static_cast<double>(n) / all});
  std::sort(ranked.begin(), ranked.end(), [](const Coverage& a, const Coverage& b) {
    return a.pixels != b.pixels ? a.pixels > b.pixels : a.id < b.id;
  });
  return ranked;
}

std::vector<Coverage> rank(const IdBuffer& buffer) { return rank(std::span<const ObjectId>(buffer.ids)); }

std::uint64_t backgroundPixels(std::span<const ObjectId> ids) {
  return static_cast<std::uint64_t>(std::count(ids.begin(), ids.end(), kBackground));
}

}  // namespace tsr::cov
