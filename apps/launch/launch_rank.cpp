#include "launch_rank.hpp"

#include <charconv>

namespace tsr::app {

namespace {

unsigned parseCount(const char* name, const char* text) {
  std::string value(text);
  unsigned parsed = 0;
  auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), parsed);
  if (value.empty() || ec != std::errc() || end != value.data() + value.size())
    throw LaunchError(std::string(name) + "='" + value.substr(0, 32) + "' is not a non-negative whole number");
  return parsed;
}

std::optional<LaunchRank> fromPair(const EnvironmentLookup& lookup, const char* rankName, const char* sizeName,
                                   const char* source) {
  const char* rank = lookup(rankName);
  const char* size = lookup(sizeName);
  if (!rank && !size) return std::nullopt;
  if (!rank || !size)
    throw LaunchError(std::string(rank ? sizeName : rankName) + " is not set although " + (rank ? rankName : sizeName) +
                      " is");
  LaunchRank r;
  r.rank = parseCount(rankName, rank);
  r.size = parseCount(sizeName, size);
  r.source = source;
  validateRank(r);
  return r;
}

}  // namespace

void validateRank(const LaunchRank& r) {
  if (r.size == 0 || r.size > kMaxJobSize)
    throw LaunchError("job size " + std::to_string(r.size) + " (from " + r.source + ") is outside 1.." +
                      std::to_string(kMaxJobSize));
  if (r.rank >= r.size)
    throw LaunchError("rank " + std::to_string(r.rank) + " (from " + r.source + ") is not below the job size " +
                      std::to_string(r.size));
}

std::optional<LaunchRank> rankFromEnvironment(const EnvironmentLookup& lookup) {
  if (auto slurm = fromPair(lookup, "SLURM_PROCID", "SLURM_NTASKS", "slurm")) {
    const char* job = lookup("SLURM_JOB_ID");
    const char* step = lookup("SLURM_STEP_ID");
    if (job) slurm->job = std::string(job) + (step ? "." + std::string(step) : "");
    return slurm;
  }
  if (auto ompi = fromPair(lookup, "OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE", "openmpi")) {
    if (const char* job = lookup("OMPI_MCA_ess_base_jobid")) ompi->job = job;
    return ompi;
  }
  return std::nullopt;
}

}  // namespace tsr::app
