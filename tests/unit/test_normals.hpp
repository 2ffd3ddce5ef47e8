#pragma once
// Deterministic standard normals for tests (SplitMix64 + Box–Muller),
// independent of the project's own random generators.
#include <cmath>
#include <cstdint>

#include "mrd/units.hpp"

namespace mrd::test {

class Normals {
 public:
  explicit Normals(std::uint64_t s) : s_(s) {}
  double next() {
    const double u1 = (static_cast<double>(raw() >> 11) + 0.5) * 0x1.0p-53;
    const double u2 = static_cast<double>(raw() >> 11) * 0x1.0p-53;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * units::kPi * u2);
  }

 private:
  std::uint64_t raw() {
    std::uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  std::uint64_t s_;
};

}  // namespace mrd::test
