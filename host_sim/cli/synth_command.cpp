#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "host_sim/cli/command.hpp"
#include "host_sim/cli/options.hpp"
#include "host_sim/discrepancy/discrepancy_report.hpp"
#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/discrepancy/baseline_file.hpp"
#include "host_sim/discrepancy/synth.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::cli {
namespace synth_command {
namespace {

constexpr CommandHelp kSynthHelp{
    "synth", "Generate a measured-like damper record with hidden effects",
    R"(Makes a measured-like damper record: the chapter-4 model plus hidden effects (see
'mrd discrepancy --help' for the catalogue) with parameters drawn from physical ranges (or
--params), a random sine or broadband (0.1-2.5 Hz) displacement below the damper's 0.249 m/s
(Table 3.1), a constant or stepped coil-current command, load-cell noise (white 0.2-1 kN plus a
20 ms correlated part 0.1-0.5 kN), LVDT noise (5-20 um) and 16-bit quantization. Parameters are
drawn again until each effect changes the force by at least 4x the noise RMS.

--baseline damper.toml makes the record from that damper instead (any law: bingham, bouc_wen,
spencer), the draws put on it: half ranges, dominant frequencies and velocities inside its
[validity], currents up to its largest, and the force noise, the load cell's range and the
effects' forces (offset, gas spring) scaled by its force scale over the thesis damper's, the LVDT
noise and range and the effects' lengths (free play, pre-yield) by its largest half range over
40 mm.

Files: DIR/measured.csv (time_s, displacement_m, current_cmd_A, force_N; velocity_m_s with
--velocity-column) or DIR/measured.mat with --format mat, and DIR/summary.json, the truth:
  effects, parameters (per effect, with effect_rms_n), input, current, force_noise_rms_n,
  displacement_noise_m, true_gap (normalized RMS gap of the noise-free truth to the baseline),
  draws, seed, duration_s, rate_hz, jitter, samples.)"};

struct SynthCliOptions {
  std::string effects = "random";
  std::string params;
  std::string input = "random";
  std::string current = "random";
  std::string format = "csv";
  std::string baseline;
  double duration_s = 20.0;
  double rate_hz = 1000.0;
  double jitter = 0.0;
  std::uint64_t seed = 1;
  bool velocity_column = false;
  std::string out_dir;
};

std::vector<double> parse_params(const std::string& text) {
  std::vector<double> out;
  std::size_t start = 0;
  while (start <= text.size() && !text.empty()) {
    const std::size_t p = text.find(',', start);
    const std::string item = text.substr(start, p == std::string::npos ? std::string::npos : p - start);
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(v)) {
      throw io::UsageError("--params: not a number: '" + item + "'");
    }
    out.push_back(v);
    if (p == std::string::npos) break;
    start = p + 1;
  }
  return out;
}

/// --params: each within the physical bounds of its effect, as many as the effects take.
void check_params(const discrepancy::SynthSpec& spec) {
  const discrepancy::EffectSet set{spec.effects};
  if (spec.params.size() != set.param_count()) {
    throw io::UsageError("--params: " + set.label() + " takes " + std::to_string(set.param_count()) +
                         " parameters, got " + std::to_string(spec.params.size()));
  }
  std::size_t i = 0;
  for (const auto e : spec.effects) {
    for (const auto& p : discrepancy::effect_info(e).params) {
      if (spec.params[i] < p.lower || spec.params[i] > p.upper) {
        throw io::UsageError("--params: " + std::string(p.name) + " of " + std::string(discrepancy::effect_name(e)) +
                             " outside its physical bounds [" + std::to_string(p.lower) + ", " +
                             std::to_string(p.upper) + "]");
      }
      ++i;
    }
  }
}

/// The record the options ask for; throws io::UsageError for a bad option.
discrepancy::SynthSpec synth_spec(const SynthCliOptions& o) {
  require_finite_at_least("--duration-s", o.duration_s, 2.0);
  require_finite_at_least("--rate-hz", o.rate_hz, 50.0);
  require_finite_at_least("--jitter", o.jitter, 0.0);
  if (o.duration_s * o.rate_hz > 5.0e7) throw io::UsageError("--duration-s: more than 5e7 samples");
  if (o.jitter >= 0.9) throw io::UsageError("--jitter: expected a fraction below 0.9");
  require_choice("--format", o.format, {"csv", "mat"});
  discrepancy::SynthSpec spec;
  spec.seed = o.seed;
  spec.duration_s = o.duration_s;
  spec.rate_hz = o.rate_hz;
  spec.jitter = o.jitter;
  spec.velocity_column = o.velocity_column;
  if (o.input == "sine") spec.input = discrepancy::SynthInput::sine;
  else if (o.input == "broadband") spec.input = discrepancy::SynthInput::broadband;
  else if (o.input != "random") throw io::UsageError("--input: expected sine, broadband or random");
  if (o.current == "constant") spec.current = discrepancy::SynthCurrent::constant;
  else if (o.current == "steps") spec.current = discrepancy::SynthCurrent::steps;
  else if (o.current != "random") throw io::UsageError("--current: expected constant, steps or random");
  spec.effects = o.effects == "random" ? discrepancy::random_effects(o.seed)
                                       : discrepancy::parse_effect_list(o.effects, "--effects");
  if (!o.params.empty()) {
    spec.params = parse_params(o.params);
    check_params(spec);
  }
  if (!o.baseline.empty()) spec.baseline = discrepancy::read_baseline_file(o.baseline).baseline;
  return spec;
}

void add_options(CLI::App& app, SynthCliOptions& o) {
  app.add_option("--effects", o.effects, "Comma-separated effects, none, or random (0-2 drawn by --seed)")
      ->capture_default_str();
  app.add_option("--params", o.params, "Parameters of the effects, comma-separated in their order (SI)");
  app.add_option("--input", o.input, "sine | broadband | random")->capture_default_str();
  app.add_option("--current", o.current, "constant | steps | random")->capture_default_str();
  app.add_option("--duration-s", o.duration_s, "Record length, s")->capture_default_str();
  app.add_option("--rate-hz", o.rate_hz, "Sampling rate, Hz")->capture_default_str();
  app.add_option("--jitter", o.jitter, "Sampling-time jitter as a fraction of the step (non-uniform time)")
      ->capture_default_str();
  add_seed_option(app, o.seed, "Seed of every random draw");
  app.add_flag("--velocity-column", o.velocity_column, "Also write a measured velocity column");
  app.add_option("--format", o.format, "csv | mat")->capture_default_str();
  app.add_option("--baseline", o.baseline,
                 "damper.toml the record is made from (any law; default: the thesis damper)");
  add_out_option(app, o.out_dir, "Folder for measured.csv/.mat and summary.json")->required();
}

void execute(const SynthCliOptions& o) {
  const discrepancy::SynthSpec spec = synth_spec(o);
  const auto out = open_out_dir(o.out_dir);
  const discrepancy::SynthCase c = discrepancy::synthesize(spec);
  const auto format = o.format == "mat" ? discrepancy::RecordFormat::mat : discrepancy::RecordFormat::csv;
  const auto data_path = shown_path(discrepancy::write_synth_outputs(out, c, spec, format));
  const auto summary_path = shown_path(out / "summary.json");
  commit_out_dir();
  std::printf("effects: %s; %s; %s; %zu samples\n", discrepancy::EffectSet{c.effects}.label().c_str(),
              c.input_description.c_str(), c.current_description.c_str(), c.data.size());
  std::printf("wrote %s and %s\n", data_path.c_str(), summary_path.c_str());
}

}  // namespace
}  // namespace synth_command

Command add_synth_command(CLI::App& parent) {
  using namespace synth_command;
  return make_command(parent, kSynthHelp, add_options, execute);
}

}  // namespace mrd::cli
