#include "host_sim/risk/cluster.hpp"

#include <mpi.h>

#include <cstdlib>
#include <cstring>

namespace mrd::risk {
namespace {

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"}) {
    if (std::getenv(v)) return true;
  }
  return false;
}

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  if (!v) return fallback;
  const int n = std::atoi(v);
  return n > 0 ? n : fallback;
}

}  // namespace

Cluster::Cluster() {
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  mpi_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  local_size_ = env_int("OMPI_COMM_WORLD_LOCAL_SIZE", env_int("SLURM_NTASKS_PER_NODE", 0));
  if (local_size_ <= 0) {
    MPI_Comm node;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
    MPI_Comm_size(node, &local_size_);
    MPI_Comm_free(&node);
  }
}

Cluster::~Cluster() {
  int finalized = 0;
  if (mpi_ && MPI_Finalized(&finalized) == MPI_SUCCESS && !finalized) MPI_Finalize();
}

std::uint64_t Cluster::broadcast(std::uint64_t value) const {
  if (mpi_) MPI_Bcast(&value, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  return value;
}

bool Cluster::any(bool flag) const {
  int v = flag ? 1 : 0, r = v;
  if (mpi_) MPI_Allreduce(&v, &r, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
  return r != 0;
}

std::vector<RunMetrics> Cluster::gather(std::size_t run_count, const std::vector<std::size_t>& runs,
                                        const std::vector<RunMetrics>& metrics) const {
  std::vector<RunMetrics> all;
  if (!mpi_ || size_ == 1) {
    all.resize(run_count);
    for (std::size_t i = 0; i < runs.size(); ++i) all[runs[i]] = metrics[i];
    return all;
  }
  const int n = static_cast<int>(runs.size());
  std::vector<int> counts(rank_ == 0 ? size_ : 0);
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<int> offsets(counts.size()), value_counts(counts.size()), value_offsets(counts.size());
  int total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    offsets[r] = total;
    value_offsets[r] = total * static_cast<int>(kRunMetricCount);
    value_counts[r] = counts[r] * static_cast<int>(kRunMetricCount);
    total += counts[r];
  }
  std::vector<std::uint64_t> local_runs(runs.begin(), runs.end()), all_runs(rank_ == 0 ? total : 0);
  MPI_Gatherv(local_runs.data(), n, MPI_UINT64_T, all_runs.data(), counts.data(), offsets.data(), MPI_UINT64_T, 0,
              MPI_COMM_WORLD);
  static_assert(sizeof(RunMetrics) == kRunMetricCount * sizeof(double));
  std::vector<RunMetrics> all_metrics(rank_ == 0 ? total : 0);
  MPI_Gatherv(metrics.data(), n * static_cast<int>(kRunMetricCount), MPI_DOUBLE, all_metrics.data(),
              value_counts.data(), value_offsets.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  if (rank_ != 0) return all;
  all.resize(run_count);
  for (std::size_t i = 0; i < all_runs.size(); ++i) all[all_runs[i]] = all_metrics[i];
  return all;
}

void Cluster::share(std::vector<std::vector<double>>& data) const {
  if (!mpi_ || size_ == 1) return;
  for (std::size_t i = 0; i < data.size(); ++i) {
    const int owner = static_cast<int>(i % static_cast<std::size_t>(size_));
    std::uint64_t length = data[i].size();
    MPI_Bcast(&length, 1, MPI_UINT64_T, owner, MPI_COMM_WORLD);
    data[i].resize(length);
    MPI_Bcast(data[i].data(), static_cast<int>(length), MPI_DOUBLE, owner, MPI_COMM_WORLD);
  }
}

void Cluster::abort(int code) const {
  if (mpi_) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

}  // namespace mrd::risk
