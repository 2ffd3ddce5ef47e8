#pragma once
/// The virtual RTHS benchmark's published set-up (Silva et al. 2020) and the
/// conversions from mrd's building and record files.
///
/// Reference structure: three storeys, the condensed stiffness matrix
/// (buildings/silva-2020-3dof.toml), four cases of lumped mass per floor and
/// damping ratio: 1000 kg at 5 %, 1100 kg at 4 %, 1300 kg at 3 %, 1000 kg at
/// 3 %. The damping is Rayleigh's, the ratio exact in modes 1 and 2 (the
/// benchmark states a ratio, not the form of C; mode 3 gets a little more).

#include <filesystem>
#include <vector>

#include "host_sim/rths/substructure.hpp"
#include "host_sim/structure/building_params.hpp"

namespace mrd::rths {

/// The published condensed stiffness matrix, N/m, row-major.
extern const std::vector<double> kBenchmarkStiffness_n_m;

/// The reference structure of case 1..4. Throws std::invalid_argument otherwise.
structure::BuildingParams benchmark_structure(int case_number);

/// M, C, K of any building (validated first).
StructureMatrices structure_matrices(const structure::BuildingParams& b);

/// A ground-motion file (mrd's record reader: the shared CSV format or PEER
/// .AT2) scaled by `scale` and resampled linearly to `rate_hz`, m/s².
/// Throws io::UsageError naming the file for a bad record.
std::vector<double> benchmark_record(const std::filesystem::path& file, double scale, double rate_hz);

/// The benchmark's ground-motion scale.
inline constexpr double kBenchmarkRecordScale = 0.4;

}  // namespace mrd::rths
