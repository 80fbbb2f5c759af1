#pragma once
// Which process of a launched job this is: its rank, the job size and a job
// name, as the launcher's environment tells them. Rank 0 runs the client,
// the others run render nodes.
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

namespace tsr::app {

class LaunchError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LaunchRank {
  unsigned rank = 0;
  unsigned size = 1;
  std::string job;     // names the rendezvous of this job; empty when the launcher gives none
  std::string source;  // "slurm", "openmpi" or "command line", for messages
};

using EnvironmentLookup = std::function<const char*(const char*)>;

// SLURM_PROCID/SLURM_NTASKS first (job SLURM_JOB_ID.SLURM_STEP_ID), then
// OMPI_COMM_WORLD_RANK/OMPI_COMM_WORLD_SIZE (job OMPI_MCA_ess_base_jobid).
// Empty when neither pair is set; throws LaunchError for a value that is
// not a number, a size of 0 or above kMaxJobSize, or a rank outside the job.
std::optional<LaunchRank> rankFromEnvironment(const EnvironmentLookup& lookup);

// The same checks for --rank/--size given by hand (ssh, hostfiles).
void validateRank(const LaunchRank& rank);

inline constexpr unsigned kMaxJobSize = 4096;

}  // namespace tsr::app
