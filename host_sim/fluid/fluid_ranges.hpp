#pragma once
/// Physical ranges of an MR fluid's quantities (Table 5.3, Eq. 5.1–5.4): what
/// a fluid file (fluid_file.hpp) may hold, each with the reason for its ends.
/// The participant-ratio coefficients (Table 5.6) share the damper file's
/// ranges (discrepancy/physical_ranges.hpp).

#include "host_sim/discrepancy/physical_ranges.hpp"

namespace mrd::fluid {

using discrepancy::PhysicalRange;

/// d_p: from 1 nm (the nanoparticles of ferrofluids) to 1 mm, a hundred
/// times the carbonyl iron of MR fluids (1–10 µm; the thesis's 5 µm, §5.1.1).
inline constexpr PhysicalRange kParticleDiameterRange{1e-9, 1e-3, "m", "a diameter"};
/// ρ_s: from 1000 kg/m³ (polymer-coated or hollow particles) to 23000 kg/m³,
/// above osmium, the densest element (iron 7870, Table 5.3).
inline constexpr PhysicalRange kSolidDensityRange{1000.0, 23000.0, "kg/m3", "a density"};
/// ρ_l: from 500 kg/m³, lighter than any carrier oil (hydrocarbons about
/// 800, Table 5.3's 820), to 3000 kg/m³, denser than any carrier liquid
/// (perfluorinated oils about 1900).
inline constexpr PhysicalRange kLiquidDensityRange{500.0, 3000.0, "kg/m3", "a density"};
/// η: from 0.1 mPa·s, below water's 1 mPa·s, to 1 MPa·s, a thixotropic
/// carrier at rest (the thesis's 2 Pa·s, Table 5.3).
inline constexpr PhysicalRange kViscosityRange{1e-4, 1e6, "Pa s", "a viscosity"};
/// χ: a volume fraction of particles, from 0.1 % to 74 %, the densest packing
/// of equal spheres (MR fluids hold 20–50 %; the thesis's 40 %).
inline constexpr PhysicalRange kSolidFractionRange{1e-3, 0.74, "", "a volume fraction"};
/// n of Eq. 5.2 (Richardson–Zaki): from 0 (no hindrance) to 10, twice the
/// 4.65 of creeping flow (Re_p < 0.3, the thesis's) and four times the 2.4 of
/// fast settling.
inline constexpr PhysicalRange kHinderedExponentRange{0.0, 10.0, "", "an exponent"};
/// A measured maximum settling time: from 1 s to 1e11 s (3200 years, beyond
/// the life of any structure; the thesis's model fluid 0.8531 years, fluids in
/// practice decades, §6.5, §7).
inline constexpr PhysicalRange kMaxSettlingTimeRange{1.0, 1e11, "s", "a time"};
/// Eq. 5.1 holds for a particle Reynolds number ρ_l V_t d_p / η below 0.3
/// (thesis §5.1.1): above it the fluid file is read with a warning.
inline constexpr double kMaxStokesReynolds = 0.3;

}  // namespace mrd::fluid
