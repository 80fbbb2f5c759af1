#pragma once
// Console output that also keeps each run's "rays/s" counter by benchmark
// name, for a bench's main to print ratios measured in the same run.
#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace tsr::bench {

class RaysPerSecond : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      const auto it = run.counters.find("rays/s");
      if (run.run_type == Run::RT_Iteration && it != run.counters.end()) rates[run.benchmark_name()] = it->second.value;
    }
    ConsoleReporter::ReportRuns(runs);
  }
  // The rate of the first run whose name starts with `prefix`, 0 if none.
  double of(std::string_view prefix) const {
    for (const auto& [name, rate] : rates)
      if (name.starts_with(prefix)) return rate;
    return 0.0;
  }
  std::map<std::string, double> rates;
};

}  // namespace tsr::bench
