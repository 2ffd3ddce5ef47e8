#pragma once
/// The processes a fragility study runs on: one process (threads only), or
/// the ranks of an MPI job when `mrd` was started by mpirun or srun (detected
/// from the launcher's environment: OMPI_COMM_WORLD_SIZE, PMIX_RANK or
/// PMI_RANK). MPI is initialized only then, so a plain `mrd fragility` never
/// touches MPI.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "host_sim/risk/fragility_plan.hpp"

namespace mrd::risk {

class Cluster {
 public:
  /// Initializes MPI when launched under MPI; finalizes it at destruction.
  Cluster();
  ~Cluster();
  Cluster(const Cluster&) = delete;
  Cluster& operator=(const Cluster&) = delete;

  int rank() const noexcept { return rank_; }
  int size() const noexcept { return size_; }
  bool mpi() const noexcept { return mpi_; }
  /// Ranks on this node (the launcher's local size; 1 without MPI).
  int local_size() const noexcept { return local_size_; }

  /// Rank 0's `value` on every rank.
  std::uint64_t broadcast(std::uint64_t value) const;
  /// Logical OR of `flag` over the ranks.
  bool any(bool flag) const;
  /// Rank 0 receives every rank's (run, metrics) pairs placed by run index
  /// into a vector of `run_count`; other ranks get an empty vector.
  std::vector<RunMetrics> gather(std::size_t run_count, const std::vector<std::size_t>& runs,
                                 const std::vector<RunMetrics>& metrics) const;
  /// Entry i of `data` from rank i mod N on every rank (each rank fills
  /// the entries it owns, then all hold all).
  void share(std::vector<std::vector<double>>& data) const;
  /// Ends every rank of the job with `code` (MPI_Abort); exits without MPI.
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0;
  int size_ = 1;
  int local_size_ = 1;
  bool mpi_ = false;
};

}  // namespace mrd::risk
