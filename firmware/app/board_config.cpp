#include "firmware/app/board_config.hpp"

#include <charconv>
#include <cmath>
#include <map>
#include <set>
#include <vector>
#include <sstream>
#include <string_view>
#include <utility>
#include <toml++/toml.h>

namespace mrd::app {
namespace {

[[noreturn]] void fail(const std::string& origin, const toml::source_region& where, const std::string& field,
                       const std::string& problem) {
  throw BoardConfigError(origin + ":" + std::to_string(where.begin.line) + ": " + field + ": " + problem);
}

/// Reads the keys of one table, refusing keys it does not know (typos).
class Table {
 public:
  Table(const toml::table& root, const char* name, const std::string& origin, bool required)
      : origin_(origin), name_(name) {
    const toml::node* n = root.get(name);
    if (!n) {
      if (required) throw BoardConfigError(origin + ":1: [" + name_ + "]: missing table");
      return;
    }
    t_ = n->as_table();
    if (!t_) fail(origin, n->source(), name_, "expected a table [" + name_ + "]");
  }
  bool present() const noexcept { return t_ != nullptr; }

  template <class T>
  bool integer(const char* key, T& out, std::int64_t lo, std::int64_t hi) {
    const toml::node* n = find(key);
    if (!n) return false;
    // value<int64_t>() of a float node converts it (undefined beyond int64's range): integers only.
    const auto v = n->is_integer() ? n->value<std::int64_t>() : std::nullopt;
    if (!v) fail(origin_, n->source(), field(key), "expected an integer");
    if (*v < lo || *v > hi)
      fail(origin_, n->source(), field(key),
           "expected " + std::to_string(lo) + " … " + std::to_string(hi) + ", got " + std::to_string(*v));
    out = static_cast<T>(*v);
    return true;
  }
  /// A number (integer or float) in [lo, hi].
  bool number(const char* key, double& out, double lo, double hi, const char* unit) {
    const toml::node* n = find(key);
    if (!n) return false;
    if (!n->is_number()) fail(origin_, n->source(), field(key), std::string("expected a number, ") + unit);
    const double v = n->is_integer() ? static_cast<double>(*n->value<std::int64_t>()) : *n->value<double>();
    if (!(v >= lo && v <= hi)) {
      std::ostringstream msg;
      msg << "expected " << lo << " … " << hi << " " << unit << ", got " << v;
      fail(origin_, n->source(), field(key), msg.str());
    }
    out = v;
    return true;
  }
  bool boolean(const char* key, bool& out) {
    const toml::node* n = find(key);
    if (!n) return false;
    if (!n->is_boolean()) fail(origin_, n->source(), field(key), "expected true or false");
    out = *n->value<bool>();
    return true;
  }
  bool string(const char* key, std::string& out) {
    const toml::node* n = find(key);
    if (!n) return false;
    if (!n->is_string()) fail(origin_, n->source(), field(key), "expected a string");
    out = *n->value<std::string>();
    return true;
  }
  /// A GPIO line: an offset (integer ≥ 0) or a line name (string).
  bool line(const char* key, GpioLine& out) {
    const toml::node* n = find(key);
    if (!n) return false;
    if (n->is_integer()) {
      const std::int64_t v = *n->value<std::int64_t>();
      if (v < 0 || v > 1023) fail(origin_, n->source(), field(key), "expected a line offset 0 … 1023");
      out.offset = static_cast<int>(v);
    } else if (n->is_string()) {
      out.name = *n->value<std::string>();
      if (out.name.empty()) fail(origin_, n->source(), field(key), "expected a line name or offset");
    } else {
      fail(origin_, n->source(), field(key), "expected a line offset (integer) or a line name (string)");
    }
    return true;
  }
  toml::source_region where(const char* key) const {
    const toml::node* n = t_ ? t_->get(key) : nullptr;
    return n ? n->source() : (t_ ? t_->source() : toml::source_region{});
  }
  /// Refuses keys that were never asked for, saying `problem`.
  void no_unknown_keys(const char* problem = "unknown key") const {
    if (!t_) return;
    for (const auto& [k, v] : *t_) {
      if (!asked_.count(std::string(k.str())))
        fail(origin_, v.source(), field(std::string(k.str()).c_str()), problem);
    }
  }
  std::string field(const char* key) const { return name_ + "." + key; }

 private:
  const toml::node* find(const char* key) {
    asked_.insert(key);
    return t_ ? t_->get(key) : nullptr;
  }
  std::string origin_, name_;
  const toml::table* t_ = nullptr;
  std::set<std::string> asked_;
};

void read_board(const toml::table& root, const std::string& origin, BoardConfig& c) {
  Table board(root, "board", origin, true);
  if (!board.string("name", c.name) || c.name.empty())
    fail(origin, board.where("name"), "board.name", "missing board name");
  board.string("description", c.description);
  board.no_unknown_keys();
}

void read_control(const toml::table& root, const std::string& origin, BoardConfig& c) {
  Table control(root, "control", origin, true);
  control.integer("period_us", c.period_us, 100, 100000);
  std::string mode;
  if (control.string("mode", mode)) {
    const auto m = control::parse_mode_name(mode);
    if (!m)
      fail(origin, control.where("mode"), "control.mode",
           "expected passive-off, passive-on or semi-active, got '" + mode + "'");
    c.mode = *m;
  }
  std::string numeric = "float";
  if (control.string("numeric", numeric) && numeric != "float" && numeric != "fixed")
    fail(origin, control.where("numeric"), "control.numeric", "expected float or fixed, got '" + numeric + "'");
  c.fixed_point = numeric == "fixed";
  control.integer("sensor_timeout_ticks", c.sensor_timeout_ticks, 1, 100000);
  control.integer("drive_status_timeout_ticks", c.drive_status_timeout_ticks, 1, 100000);
  control.integer("heartbeat_period_ticks", c.heartbeat_period_ticks, 1, 100000);
  control.no_unknown_keys();
}

void read_can(const toml::table& root, const std::string& origin, BoardConfig& c) {
  Table can(root, "can", origin, true);
  can.string("interface", c.can_interface);
  can.integer("controller_node", c.nodes.controller, 1, protocol::kMaxNodeId);
  can.integer("drive_node", c.nodes.drive, 1, protocol::kMaxNodeId);
  can.integer("daq_node", c.nodes.daq, 1, protocol::kMaxNodeId);
  can.integer("actuator_node", c.nodes.actuator, 1, protocol::kMaxNodeId);
  can.no_unknown_keys();
  const std::set<int> ids{c.nodes.controller, c.nodes.drive, c.nodes.daq, c.nodes.actuator};
  if (ids.size() != 4) fail(origin, can.where("controller_node"), "can", "node ids must be four different numbers");
}

/// [gpio] is required: the chip and its lines, or `fitted = false` alone.
void read_gpio(const toml::table& root, const std::string& origin, BoardConfig& c) {
  if (!root.get("gpio"))
    throw BoardConfigError(origin + ":1: [gpio]: missing table (the chip and its lines, or fitted = false "
                           "for a board without GPIO)");
  Table gpio(root, "gpio", origin, true);
  c.gpio_fitted = true;
  gpio.boolean("fitted", c.gpio_fitted);
  if (!c.gpio_fitted) {
    gpio.no_unknown_keys("not allowed with fitted = false (a board without GPIO has no lines)");
    return;
  }
  if (!gpio.string("chip", c.gpio_chip) || c.gpio_chip.empty())
    fail(origin, gpio.where("chip"), "gpio.chip", "missing GPIO chip (e.g. \"gpiochip0\")");
  if (!gpio.line("drive_enable", c.drive_enable))
    fail(origin, gpio.where("drive_enable"), "gpio.drive_enable", "missing line");
  if (!gpio.line("drive_fault", c.drive_fault))
    fail(origin, gpio.where("drive_fault"), "gpio.drive_fault", "missing line");
  gpio.line("maintenance_due", c.maintenance_due);
  gpio.boolean("drive_enable_active_low", c.drive_enable.active_low);
  gpio.boolean("drive_fault_active_low", c.drive_fault.active_low);
  gpio.boolean("maintenance_due_active_low", c.maintenance_due.active_low);
  gpio.no_unknown_keys();
}

void read_realtime(const toml::table& root, const std::string& origin, BoardConfig& c) {
  Table rt(root, "realtime", origin, false);
  rt.integer("sched_fifo_priority", c.sched_fifo_priority, 0, 99);
  rt.boolean("lock_memory", c.lock_memory);
  rt.integer("cpu", c.cpu, -1, 1023);
  rt.no_unknown_keys();
}

void read_state(const toml::table& root, const std::string& origin, BoardConfig& c, StatePathCheck check_path) {
  Table st(root, "state", origin, false);
  if (st.string("path", c.state_path)) {
    if (c.state_path.find('\0') != std::string::npos)
      fail(origin, st.where("path"), "state.path", "expected a file path without a NUL character");
    if (c.state_path.empty() || c.state_path.front() != '/' || c.state_path.back() == '/')
      fail(origin, st.where("path"), "state.path", "expected an absolute file path, got '" + c.state_path + "'");
    if (check_path) {
      if (const std::string problem = check_path(c.state_path); !problem.empty())
        fail(origin, st.where("path"), "state.path", c.state_path + ": " + problem);
    }
  }
  st.number("save_every_s", c.save_every_s, 0.001, 86400.0, "s");
  st.no_unknown_keys();
}

void read_mixing(const toml::table& root, const std::string& origin, BoardConfig& c) {
  Table mx(root, "mixing", origin, false);
  fw::MixingSchedulerConfig& m = c.mixing;
  mx.boolean("actuator_fitted", m.actuator_fitted);
  mx.number("capacity_threshold", m.capacity_threshold, 0.05, 0.999, "(fraction of a fully mixed damper's force)");
  mx.number("lead_time_s", m.lead_time_s, 0.0, 30.0 * 86400.0, "s");
  mx.number("maintenance_lead_time_s", m.maintenance_lead_time_s, 0.0, 365.0 * 86400.0, "s");
  mx.number("max_amplitude_m", m.max_amplitude_m, 1e-3, 0.2, "m");
  mx.number("max_velocity_m_s", m.max_velocity_m_s, 1e-3, 2.0, "m/s");
  mx.number("preferred_frequency_hz", m.preferred_frequency_hz, 0.01, 2.0, "Hz");
  mx.integer("max_cycles", m.max_cycles, 1, 1000);
  mx.number("start_timeout_s", m.start_timeout_s, 0.1, 3600.0, "s");
  mx.number("confirm_hold_s", m.confirm_hold_s, 0.0, 86400.0, "s");
  mx.number("holdoff_s", m.holdoff_s, 0.0, 86400.0, "s");
  mx.integer("max_attempts", m.max_attempts, 1, 100);
  mx.number("dead_band_m", c.dead_band_m, 0.0, 0.01, "m");
  mx.no_unknown_keys();
}


/// One number of a table and the field it fills.
struct NumberKey {
  const char* key;
  double* out;
  double lo, hi;
  const char* unit;
};

/// [controller]: fw::ControllerConfig's fields by name, over
/// default_controller_config([control] mode, period). Ranges here only keep
/// numbers finite and signs right; what the core needs of them together is
/// fw::validate_config's, checked after (check_controller).
void read_controller(const toml::table& root, const std::string& origin, BoardConfig& c,
                     std::map<std::string, int>& lines) {
  fw::ControllerConfig& k = c.controller;
  k = fw::default_controller_config(c.mode, c.period_s());
  Table t(root, "controller", origin, false);
  const NumberKey numbers[] = {
      {"stiffness_n_m", &k.stiffness_n_m, 1.0, 1.0e10, "N/m"},
      {"loss_factor", &k.loss_factor, 1e-6, 10.0, ""},
      {"filter_freq_rad_s", &k.filter_freq_rad_s, 1e-4, 1e5, "rad/s"},
      {"desired_force_limit_n", &k.desired_force_limit_n, 1.0, 1e8, "N"},
      {"velocity_cutoff_hz", &k.velocity_cutoff_hz, 1e-3, 1e5, "Hz"},
      {"velocity_on_m_s", &k.velocity_on_m_s, 0.0, 10.0, "m/s"},
      {"velocity_off_m_s", &k.velocity_off_m_s, 0.0, 10.0, "m/s"},
      {"nominal_current_a", &k.nominal_current_a, 1e-3, 100.0, "A"},
      {"rated_current_a", &k.rated_current_a, 1e-3, 100.0, "A"},
      {"overdrive_current_a", &k.overdrive_current_a, 1e-3, 100.0, "A"},
      {"backdrive_current_a", &k.backdrive_current_a, -100.0, -1e-3, "A"},
      {"current_band_a", &k.current_band_a, 1e-6, 100.0, "A"},
      {"force_deadband_n", &k.force_deadband_n, 0.0, 1e8, "N"},
      {"target_dwell_s", &k.target_dwell_s, 0.0, 60.0, "s"},
      {"rest_release_s", &k.rest_release_s, 0.0, 60.0, "s"},
      {"coil_thermal_time_constant_s", &k.coil_thermal_time_constant_s, 1e-3, 1e6, "s"},
      {"coil_derate_fraction", &k.coil_derate_fraction, 1e-3, 0.999, ""},
      {"command_limit_a", &k.command_limit_a, 1e-3, 100.0, "A"},
      {"drive_continuous_limit_a", &k.drive_continuous_limit_a, 1e-3, 1000.0, "A"},
      {"drive_peak_limit_a", &k.drive_peak_limit_a, 1e-3, 1000.0, "A"},
      {"disp_limit_m", &k.disp_limit_m, 1e-5, 10.0, "m"},
      {"force_limit_n", &k.force_limit_n, 1.0, 1e8, "N"},
      {"accel_limit_m_s2", &k.accel_limit_m_s2, 1e-3, 1e4, "m/s²"},
      {"coil_current_limit_a", &k.coil_current_limit_a, 1e-3, 1000.0, "A"},
      {"shaking_threshold_m_s2", &k.shaking_threshold_m_s2, 1e-6, 1e3, "m/s²"},
      {"fallback_current_a", &k.fallback_current_a, 0.0, 100.0, "A"},
  };
  for (const NumberKey& n : numbers) {
    if (t.number(n.key, *n.out, n.lo, n.hi, n.unit)) lines[n.key] = static_cast<int>(t.where(n.key).begin.line);
  }
  const auto ticks = [&](const char* key, std::uint32_t& out, std::int64_t lo) {
    if (t.integer(key, out, lo, 10000000)) lines[key] = static_cast<int>(t.where(key).begin.line);
  };
  ticks("drive_reenable_delay_ticks", k.drive_reenable_delay_ticks, 0);
  ticks("stuck_ticks", k.stuck_ticks, 2);
  ticks("max_input_age_ticks", k.max_input_age_ticks, 0);
  ticks("fault_hold_ticks", k.fault_hold_ticks, 0);
  t.no_unknown_keys();
  if (t.present()) lines[""] = static_cast<int>(t.where("").begin.line);
}

/// The keys fw::validate_config's error `e` concerns, and what it asks of them.
struct ConfigRule {
  std::vector<const char*> keys;
  const char* rule;
};

ConfigRule rule_of(fw::ConfigError e) {
  switch (e) {
    case fw::ConfigError::kPeriod: return {{}, "the period must lie in [10 µs, 100 ms]"};
    case fw::ConfigError::kStiffness: return {{"stiffness_n_m"}, "k must be > 0"};
    case fw::ConfigError::kLossFactor: return {{"loss_factor"}, "η must lie in (0, 10]"};
    case fw::ConfigError::kFilterFrequency:
      return {{"filter_freq_rad_s"}, "ω_f must lie in (0, π/T): below the Nyquist frequency of the control period"};
    case fw::ConfigError::kForceLimit: return {{"desired_force_limit_n"}, "the desired-force limit must be > 0"};
    case fw::ConfigError::kVelocityFilter:
      return {{"velocity_cutoff_hz", "velocity_on_m_s", "velocity_off_m_s"},
              "f_v must lie in (0, 1/(2T)) and 0 ≤ v_off ≤ v_on"};
    case fw::ConfigError::kCurrentLevels:
      return {{"nominal_current_a", "rated_current_a", "overdrive_current_a", "backdrive_current_a", "current_band_a",
               "fallback_current_a", "command_limit_a", "drive_continuous_limit_a", "drive_peak_limit_a"},
              "0 < I_nom ≤ I_od ≤ I_cmd ≤ I_cont ≤ I_peak, 0 < I_r ≤ I_od, −I_cmd ≤ I_bd < 0, 0 < I_band < I_r, "
              "0 ≤ I_fallback ≤ I_cmd"};
    case fw::ConfigError::kDeadband:
      return {{"force_deadband_n", "target_dwell_s", "rest_release_s"},
              "F_db ≥ 0, dwell and rest release in [0, 60] s"};
    case fw::ConfigError::kThermal:
      return {{"coil_thermal_time_constant_s", "coil_derate_fraction"}, "τ > 0 and the derate fraction in (0, 1)"};
    case fw::ConfigError::kSensorLimits:
      return {{"disp_limit_m", "force_limit_n", "accel_limit_m_s2", "coil_current_limit_a", "shaking_threshold_m_s2",
               "stuck_ticks"},
              "the input guard's limits must be > 0 and stuck_ticks ≥ 2"};
    case fw::ConfigError::kFixedPointRange:
      return {{"stiffness_n_m", "loss_factor", "desired_force_limit_n", "force_limit_n", "force_deadband_n",
               "disp_limit_m", "velocity_on_m_s", "rated_current_a", "command_limit_a", "coil_derate_fraction",
               "coil_thermal_time_constant_s", "coil_current_limit_a", "drive_peak_limit_a"},
              "a constant does not fit the fixed-point build's formats (firmware/core/numeric_formats.hpp)"};
    default: return {{}, "refused"};
  }
}

/// fw::validate_config for the board's build, as the core will check it at
/// boot: refused here with the line of the first key concerned.
void check_controller(const std::string& origin, const BoardConfig& c, const std::map<std::string, int>& lines) {
  const fw::ConfigError e = c.fixed_point ? fw::validate_config<num::Fixed32Policy>(c.controller)
                                          : fw::validate_config<num::Float32Policy>(c.controller);
  if (e == fw::ConfigError::kNone) return;
  const ConfigRule r = rule_of(e);
  std::string field = "controller";
  int line = lines.count("") ? lines.at("") : 1;
  for (const char* k : r.keys) {
    if (const auto it = lines.find(k); it != lines.end()) {
      field = std::string("controller.") + k;
      line = it->second;
      break;
    }
  }
  if (e == fw::ConfigError::kPeriod) field = "control.period_us";
  std::string keys;
  for (const char* k : r.keys) keys += (keys.empty() ? "" : ", ") + std::string(k);
  std::string rule = r.rule;
  if (e == fw::ConfigError::kFixedPointRange) {
    if (const char* misfit = fw::fixed_point_misfit<num::Fixed32Policy>(c.controller)) rule += ": " + std::string(misfit);
  }
  throw BoardConfigError(origin + ":" + std::to_string(line) + ": " + field + ": the control core (" +
                         (c.fixed_point ? "fixed" : "float") + " build) refuses these values: " + rule +
                         (keys.empty() ? "" : " (keys: " + keys + ")"));
}

/// [damper]: what the controller's estimator and a simulation of this board
/// take from the damper (names of physics::MrDamperParams and Table 4.1).
void read_damper(const toml::table& root, const std::string& origin, BoardConfig& c) {
  Table t(root, "damper", origin, false);
  if (!t.present()) return;
  physics::MrDamperParams& d = c.damper;
  physics::SettlingParams& g = c.settling;
  if (t.string("name", c.damper_name) && c.damper_name.empty())
    fail(origin, t.where("name"), "damper.name", "expected a name");
  std::string law = "bingham";
  if (t.string("law", law)) {
    if (law == "bingham") d.law = physics::ForceLaw::kBingham;
    else if (law == "bingham_tanh") d.law = physics::ForceLaw::kBinghamTanh;
    else if (law == "bouc_wen") d.law = physics::ForceLaw::kBoucWen;
    else fail(origin, t.where("law"), "damper.law", "expected bingham, bingham_tanh or bouc_wen, got '" + law + "'");
  }
  const NumberKey numbers[] = {
      {"fc_a_n", &d.bingham.fc_a_n, 0.0, 1e8, "N"},
      {"fc_b_n", &d.bingham.fc_b_n, 1e-3, 1e8, "N"},
      {"fc_c_per_a", &d.bingham.fc_c_per_a, 1e-6, 1e3, "1/A"},
      {"c0_a_ns_m", &d.bingham.c0_a_ns_m, 0.0, 1e10, "N·s/m"},
      {"c0_b_ns_m", &d.bingham.c0_b_ns_m, 0.0, 1e10, "N·s/m"},
      {"c0_c_per_a", &d.bingham.c0_c_per_a, 0.0, 1e3, "1/A"},
      {"v_tf_m_s", &d.bingham.v_tf_m_s, 1e-6, 1.0, "m/s"},
      {"bouc_wen_yield_disp_m", &d.bouc_wen.yield_disp_m, 0.0, 1.0, "m"},
      {"bouc_wen_stiffness_n_m", &d.bouc_wen.stiffness_n_m, 0.0, 1e10, "N/m"},
      // A calibrated law's bends (physics::LawShape): absent, the thesis's law.
      {"yield_current_exponent", &d.shape.yield_current_exponent, 0.01, 10.0, ""},
      {"viscous_current_exponent", &d.shape.viscous_current_exponent, 0.01, 10.0, ""},
      {"viscous_exponent", &d.shape.viscous_exponent, 0.01, 10.0, ""},
      {"viscous_ref_m_s", &d.shape.viscous_ref_m_s, 0.0, 100.0, "m/s"},
      {"bingham_stiffness_n_m", &d.shape.stiffness_n_m, 0.0, 1e10, "N/m"},
      {"transition_time_s", &d.shape.transition_time_s, 0.0, 0.1, "s"},
      {"lost_motion_m_per_n", &d.shape.lost_motion_m_per_n, 0.0, 1.0, "m/N"},
      {"lost_motion_share", &d.shape.lost_motion_share, 0.0, 1.0, ""},
      {"lost_motion_band_m_s", &d.shape.lost_motion_band_m_s, 0.0, 100.0, "m/s"},
      {"tau_slow_s", &d.coil.tau_slow_s, 1e-9, 100.0, "s"},
      {"tau_fast_s", &d.coil.tau_fast_s, 1e-9, 100.0, "s"},
      {"weight_slow", &d.coil.weight_slow, 0.0, 1.0, ""},
      {"weight_fast", &d.coil.weight_fast, 0.0, 1.0, ""},
      {"rated_current_a", &d.rating.current_a, 1e-3, 100.0, "A"},
      // The coil's heating (physics::CoilHeatParams): absent, the thesis coil's.
      {"coil_resistance_ohm", &d.coil_heat.resistance_ohm, 1e-3, 1e4, "Ω"},
      {"coil_thermal_resistance_k_w", &d.coil_heat.thermal_resistance_k_w, 1e-3, 1e3, "K/W"},
      {"coil_thermal_time_constant_s", &d.coil_heat.time_constant_s, 1.0, 1e5, "s"},
      {"rated_force_n", &d.rating.force_n, 1.0, 1e8, "N"},
      {"stroke_m", &d.rating.stroke_m, 1e-4, 10.0, "m"},
      {"max_velocity_m_s", &d.rating.velocity_m_s, 1e-4, 100.0, "m/s"},
      {"flow_area_m2", &d.pr.flow_area_m2, 1e-9, 100.0, "m²"},
      {"volume_unit_m3", &d.pr.volume_unit_m3, 1e-12, 100.0, "m³"},
      {"inner_diameter_m", &g.inner_diameter_m, 1e-4, 10.0, "m"},
      {"shaft_radius_m", &g.shaft_radius_m, 0.0, 5.0, "m"},
      {"fluid_length_m", &g.fluid_length_m, 1e-4, 100.0, "m"},
      {"fluid_volume_m3", &g.fluid_volume_m3, 1e-9, 100.0, "m³"},
  };
  for (const NumberKey& n : numbers) t.number(n.key, *n.out, n.lo, n.hi, n.unit);
  // The coil's inductance through its two points (physics::coil_inductance): absent, the thesis coil's.
  double l1_h = d.coil_inductance.inductance_1a_h, l2_h = d.coil_inductance.inductance_2a_h;
  const bool l1 = t.number("coil_inductance_1a_h", l1_h, 1e-6, 1e3, "H");
  const bool l2 = t.number("coil_inductance_2a_h", l2_h, 1e-6, 1e3, "H");
  t.no_unknown_keys();
  if (l1 != l2) {
    const char* missing = l1 ? "coil_inductance_2a_h" : "coil_inductance_1a_h";
    fail(origin, t.where(l1 ? "coil_inductance_1a_h" : "coil_inductance_2a_h"), std::string("damper.") + missing,
         "missing key: L(i) is set by the two points coil_inductance_1a_h and coil_inductance_2a_h");
  }
  if (l2_h > l1_h)
    fail(origin, t.where("coil_inductance_2a_h"), "damper.coil_inductance_2a_h",
         "expected at most coil_inductance_1a_h: the iron saturates, the inductance does not grow with the current");
  if (l1) d.coil_inductance = physics::coil_inductance(l1_h, l2_h);
  if (std::fabs(d.coil.weight_slow + d.coil.weight_fast - 1.0) > 1e-9)
    fail(origin, t.where("weight_slow"), "damper.weight_slow", "the coil's two weights must sum to 1");
  if (!(2.0 * g.shaft_radius_m < g.inner_diameter_m))
    fail(origin, t.where("shaft_radius_m"), "damper.shaft_radius_m", "the shaft must be narrower than the bore");
  if (d.law == physics::ForceLaw::kBoucWen && !(d.bouc_wen.yield_disp_m > 0.0))
    fail(origin, t.where("bouc_wen_yield_disp_m"), "damper.bouc_wen_yield_disp_m",
         "the bouc_wen law needs a yield displacement > 0 m");
  if (d.shape.viscous_exponent != 1.0 && !(d.shape.viscous_ref_m_s > 0.0))
    fail(origin, t.where("viscous_exponent"), "damper.viscous_exponent",
         "a viscous exponent needs viscous_ref_m_s > 0 m/s (the velocity at which c0 is the slope)");
  if (d.law == physics::ForceLaw::kBoucWen) {
    const std::pair<const char*, bool> bingham_only[] = {{"viscous_exponent", d.shape.viscous_exponent != 1.0},
                                                         {"bingham_stiffness_n_m", d.shape.stiffness_n_m != 0.0},
                                                         {"transition_time_s", d.shape.transition_time_s != 0.0}};
    for (const auto& [key, set] : bingham_only)
      if (set)
        fail(origin, t.where(key), std::string("damper.") + key,
             "acts on the bingham and bingham_tanh laws only (the bouc_wen law's spring is bouc_wen_stiffness_n_m)");
  }
}

/// [fluid]: Table 5.3's particles and carrier, an optional measured maximum
/// settling time that replaces Eq. 5.4, and Table 5.6's participant ratio.
void read_fluid(const toml::table& root, const std::string& origin, BoardConfig& c) {
  Table t(root, "fluid", origin, false);
  if (!t.present()) return;
  physics::SettlingParams& f = c.settling;
  physics::ParticipantRatioParams& pr = c.damper.pr;
  if (t.string("name", c.fluid_name) && c.fluid_name.empty())
    fail(origin, t.where("name"), "fluid.name", "expected a name");
  const NumberKey numbers[] = {
      {"particle_diameter_m", &f.particle_diameter_m, 1e-8, 1e-3, "m"},
      {"solid_density_kg_m3", &f.solid_density_kg_m3, 100.0, 30000.0, "kg/m³"},
      {"liquid_density_kg_m3", &f.liquid_density_kg_m3, 100.0, 30000.0, "kg/m³"},
      {"viscosity_pa_s", &f.viscosity_pa_s, 1e-5, 1e4, "Pa·s"},
      {"solid_fraction", &f.solid_fraction, 1e-4, 0.74, "(volume fraction; 0.74 is the densest packing)"},
      {"hindered_exponent", &f.hindered_exponent, 0.0, 20.0, ""},
      {"max_settling_time_s", &f.measured_max_settling_time_s, 1.0, 1e12, "s (a measured maximum settling time)"},
      {"a_initial", &pr.a_initial, 0.0, 10.0, ""},
      {"b_initial", &pr.b_initial, 0.0, 10.0, ""},
      {"c_initial", &pr.c_initial, 0.0, 1e3, ""},
      {"a_final", &pr.a_final, 0.0, 10.0, ""},
      {"b_final", &pr.b_final, 0.0, 10.0, ""},
      {"c_final", &pr.c_final, 0.0, 1e3, ""},
      {"a_rise", &pr.a_rise, 0.0, 1e4, ""},
      {"b_rise", &pr.b_rise, 0.0, 1e4, ""},
      {"c_rise", &pr.c_rise, 0.0, 1e3, ""},
  };
  for (const NumberKey& n : numbers) t.number(n.key, *n.out, n.lo, n.hi, n.unit);
  t.no_unknown_keys();
  if (!(f.solid_density_kg_m3 > f.liquid_density_kg_m3))
    fail(origin, t.where("solid_density_kg_m3"), "fluid.solid_density_kg_m3",
         "the particles must be denser than the carrier liquid (else nothing settles, Eq. 5.1)");
}

}  // namespace

MixingTaskConfig BoardConfig::mixing_task_config() const noexcept {
  MixingTaskConfig t;
  t.estimator.period_s = period_s();
  t.estimator.dead_band_m = dead_band_m;
  t.estimator.save_interval_s = save_every_s;
  t.estimator.model.settling = settling;
  t.estimator.model.pr = damper.pr;
  t.estimator.model.bingham = damper.bingham;
  t.estimator.model.nominal_current_a = damper.rating.current_a;
  t.scheduler = mixing;
  return t;
}

ControlTaskConfig BoardConfig::task_config() const noexcept {
  ControlTaskConfig c;
  c.nodes = nodes;
  c.mode = mode;
  c.sensor_timeout_ticks = sensor_timeout_ticks;
  c.drive_status_timeout_ticks = drive_status_timeout_ticks;
  c.heartbeat_period_ticks = heartbeat_period_ticks;
  return c;
}

namespace {

bool is_bare_key_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
}

/// Refuses, with the line, what toml++ 3 mishandles (undefined behaviour in a
/// release build): a table header whose name does not start with a key
/// character or a quote ("[/gpio]"), and a non-ASCII character outside a
/// comment (toml++'s whitespace test reaches an unreachable branch for some,
/// e.g. U+00B5), and arrays, inline tables and multi-line strings, which
/// board files do not use (toml++ asserts on some malformed ones, and a
/// string spanning lines would hide what follows from these checks). Board files are ASCII but for
/// comments, so a line that starts with '[' is a table header. Strings are
/// single-line, so a line's quotes and comment are found on the line itself.
void check_toml_input(const std::string& text, const std::string& origin) {
  std::size_t line_no = 0;
  for (std::size_t pos = 0; pos <= text.size();) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const std::string_view line(text.data() + pos, end - pos);
    pos = end + 1;
    ++line_no;
    const auto fail_at = [&](const std::string& what) {
      throw BoardConfigError(origin + ":" + std::to_string(line_no) + ": " + what);
    };
    std::size_t k = line.find_first_not_of(" \t\r");
    const bool header = k != std::string_view::npos && line[k] == '[';
    enum class In { kCode, kBasic, kLiteral };  // outside strings, in "...", in '...'
    In in = In::kCode;
    bool in_header_brackets = header;
    for (std::size_t j = 0; j < line.size(); ++j) {
      const char c = line[j];
      if (static_cast<unsigned char>(c) >= 0x80 && in != In::kCode) fail_at("non-ASCII character outside a comment");
      if (in == In::kBasic) {
        if (c == '\\') {
          ++j;  // an escape: the next character cannot end the string
          if (j < line.size() && static_cast<unsigned char>(line[j]) >= 0x80) {
            fail_at("non-ASCII character outside a comment");
          }
        } else if (c == '"') {
          in = In::kCode;
        }
        continue;
      }
      if (in == In::kLiteral) {
        if (c == '\'') in = In::kCode;
        continue;
      }
      if (c == '#') break;  // a comment: anything may follow
      if (static_cast<unsigned char>(c) >= 0x80) fail_at("non-ASCII character outside a comment");
      if (line.substr(j).starts_with("\"\"\"") || line.substr(j).starts_with("'''")) {
        fail_at("multi-line strings are not used in board files");
      }
      if (c == '"') in = In::kBasic;
      if (c == '\'') in = In::kLiteral;
      if (in_header_brackets && c != '[' && c != ' ' && c != '\t') in_header_brackets = false;
      if (!header && (c == '[' || c == '{')) fail_at("arrays and inline tables are not used in board files");
      if (header && !in_header_brackets && c == '{') fail_at("table header: unexpected '{'");
    }
    if (!header) continue;
    // As toml++ reads a header: '[', blanks, an optional second '[' and blanks, then the name.
    const auto skip_blanks = [&] {
      while (k < line.size() && (line[k] == ' ' || line[k] == '\t')) ++k;
    };
    ++k;
    skip_blanks();
    if (k < line.size() && line[k] == '[') {
      ++k;
      skip_blanks();
    }
    const char n = k < line.size() ? line[k] : '\0';
    if (!(n == ']' || is_bare_key_char(n) || n == '"' || n == '\'')) {
      fail_at("table header: expected a table name (letters, digits, _ or -) after '['");
    }
  }
}

/// [drive]: the current drive, every key given; the controller's command
/// range, continuous and peak currents within the drive's.
void read_drive(const toml::table& root, const std::string& origin, BoardConfig& c,
                const std::map<std::string, int>& controller_lines) {
  Table t(root, "drive", origin, false);
  if (!t.present()) return;
  BoardDrive d;
  if (!t.string("name", d.name) || d.name.empty()) fail(origin, t.where("name"), "drive.name", "expected a name");
  const NumberKey numbers[] = {
      {"bus_v", &d.bus_v, 1.0, 1000.0, "V"},
      {"command_range_v", &d.command_range_v, 0.1, 100.0, "V"},
      {"volts_per_amp", &d.volts_per_amp, 1e-3, 1e3, "V/A"},
      {"continuous_current_a", &d.continuous_current_a, 1e-3, 1e3, "A"},
      {"peak_current_a", &d.peak_current_a, 1e-3, 1e3, "A"},
      {"peak_time_s", &d.peak_time_s, 0.0, 3600.0, "s"},
      {"loop_bandwidth_rad_s", &d.loop_bandwidth_rad_s, 1.0, 1e6, "rad/s"},
      {"loop_period_s", &d.loop_period_s, 1e-7, 1e-2, "s"},
  };
  for (const NumberKey& n : numbers)
    if (!t.number(n.key, *n.out, n.lo, n.hi, n.unit))
      fail(origin, t.where(n.key), std::string("drive.") + n.key, "missing key");
  t.no_unknown_keys();
  if (d.peak_current_a < d.continuous_current_a)
    fail(origin, t.where("peak_current_a"), "drive.peak_current_a",
         "expected at least continuous_current_a: a drive's peak is what it gives above its continuous rating");
  // The controller commands within the drive it drives.
  const fw::ControllerConfig& k = c.controller;
  const struct {
    const char* key;
    double controller, drive;
    const char* drive_key;
    const char* what;
  } limits[] = {{"command_limit_a", k.command_limit_a, d.command_limit_a(), "command_range_v",
                 "command range (command_range_v / volts_per_amp)"},
                {"drive_continuous_limit_a", k.drive_continuous_limit_a, d.continuous_current_a, "continuous_current_a",
                 "continuous current"},
                {"drive_peak_limit_a", k.drive_peak_limit_a, d.peak_current_a, "peak_current_a", "peak current"}};
  for (const auto& l : limits) {
    if (l.controller <= l.drive) continue;
    // The controller's key where the file gives it, else the drive's (the controller's default is exceeded).
    const auto at = controller_lines.find(l.key);
    const int line = at != controller_lines.end() ? at->second : static_cast<int>(t.where(l.drive_key).begin.line);
    std::ostringstream msg;
    msg << origin << ":" << line << ": controller." << l.key << ": " << l.controller << " A exceeds the [drive]'s "
        << l.what << " of " << l.drive << " A";
    throw BoardConfigError(msg.str());
  }
  c.drive = d;
}

}  // namespace

BoardConfig parse_board_config(const std::string& text, const std::string& origin, StatePathCheck check_state_path) {
  check_toml_input(text, origin);
  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    throw BoardConfigError(origin + ":" + std::to_string(e.source().begin.line) + ": " + std::string(e.description()));
  }
  for (const auto& [k, v] : root) {
    const std::string key(k.str());
    if (key != "board" && key != "control" && key != "can" && key != "gpio" && key != "realtime" && key != "state" &&
        key != "mixing" && key != "controller" && key != "damper" && key != "fluid" && key != "drive")
      fail(origin, v.source(), key,
           "unknown table (expected board, control, can, gpio, realtime, state, mixing, controller, damper, fluid, "
           "drive)");
  }
  BoardConfig c;
  read_board(root, origin, c);
  read_control(root, origin, c);
  read_can(root, origin, c);
  read_gpio(root, origin, c);
  read_realtime(root, origin, c);
  read_state(root, origin, c, check_state_path);
  read_mixing(root, origin, c);
  std::map<std::string, int> controller_lines;
  read_controller(root, origin, c, controller_lines);
  check_controller(origin, c, controller_lines);
  read_damper(root, origin, c);
  read_fluid(root, origin, c);
  read_drive(root, origin, c, controller_lines);
  return c;
}

}  // namespace mrd::app

namespace mrd::app {
namespace {

/// Shortest text that reads back as the same double.
std::string number_text(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  std::string t(buf, r.ptr);
  if (t.find_first_of(".eEn") == std::string::npos) t += ".0";
  return t;
}

/// A basic string; board files are ASCII outside comments, so any other
/// byte (and a control character) becomes '?'.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto u = static_cast<unsigned char>(ch);
    if (u >= 0x80 || u < 0x20) {
      out += '?';
      continue;
    }
    if (ch == '"' || ch == '\\') out += '\\';
    out += ch;
  }
  return out + "\"";
}

class Writer {
 public:
  void table(const char* name) { out_ += std::string(out_.empty() ? "" : "\n") + "[" + name + "]\n"; }
  void num(const char* key, double v) { out_ += std::string(key) + " = " + number_text(v) + "\n"; }
  void integer(const char* key, long long v) { out_ += std::string(key) + " = " + std::to_string(v) + "\n"; }
  void str(const char* key, const std::string& v) { out_ += std::string(key) + " = " + quoted(v) + "\n"; }
  void boolean(const char* key, bool v) { out_ += std::string(key) + " = " + (v ? "true" : "false") + "\n"; }
  void line(const char* key, const GpioLine& l) {
    if (l.offset >= 0) integer(key, l.offset);
    else if (!l.name.empty()) str(key, l.name);
  }
  void comment(const std::string& text) {
    std::size_t pos = 0;
    while (pos <= text.size()) {
      std::size_t end = text.find('\n', pos);
      if (end == std::string::npos) end = text.size();
      out_ += "# " + text.substr(pos, end - pos) + "\n";
      pos = end + 1;
    }
  }
  std::string& text() { return out_; }

 private:
  std::string out_;
};

const char* law_name(physics::ForceLaw l) {
  switch (l) {
    case physics::ForceLaw::kBinghamTanh: return "bingham_tanh";
    case physics::ForceLaw::kBoucWen: return "bouc_wen";
    default: return "bingham";
  }
}

}  // namespace

std::string board_toml(const BoardConfig& c, const std::string& header) {
  Writer w;
  if (!header.empty()) w.comment(header);
  w.table("board");
  w.str("name", c.name);
  if (!c.description.empty()) w.str("description", c.description);
  w.table("control");
  w.integer("period_us", c.period_us);
  w.str("mode", control::mode_name(c.mode));
  w.str("numeric", c.fixed_point ? "fixed" : "float");
  w.integer("sensor_timeout_ticks", c.sensor_timeout_ticks);
  w.integer("drive_status_timeout_ticks", c.drive_status_timeout_ticks);
  w.integer("heartbeat_period_ticks", c.heartbeat_period_ticks);
  w.table("can");
  w.str("interface", c.can_interface);
  w.integer("controller_node", c.nodes.controller);
  w.integer("drive_node", c.nodes.drive);
  w.integer("daq_node", c.nodes.daq);
  w.integer("actuator_node", c.nodes.actuator);
  w.table("gpio");
  if (!c.gpio_fitted) {
    w.boolean("fitted", false);
  } else {
    w.str("chip", c.gpio_chip);
    w.line("drive_enable", c.drive_enable);
    w.line("drive_fault", c.drive_fault);
    w.line("maintenance_due", c.maintenance_due);
    w.boolean("drive_enable_active_low", c.drive_enable.active_low);
    w.boolean("drive_fault_active_low", c.drive_fault.active_low);
    w.boolean("maintenance_due_active_low", c.maintenance_due.active_low);
  }
  w.table("realtime");
  w.integer("sched_fifo_priority", c.sched_fifo_priority);
  w.boolean("lock_memory", c.lock_memory);
  w.integer("cpu", c.cpu);
  w.table("state");
  w.str("path", c.state_path);
  w.num("save_every_s", c.save_every_s);
  const fw::MixingSchedulerConfig& m = c.mixing;
  w.table("mixing");
  w.boolean("actuator_fitted", m.actuator_fitted);
  w.num("capacity_threshold", m.capacity_threshold);
  w.num("lead_time_s", m.lead_time_s);
  w.num("maintenance_lead_time_s", m.maintenance_lead_time_s);
  w.num("max_amplitude_m", m.max_amplitude_m);
  w.num("max_velocity_m_s", m.max_velocity_m_s);
  w.num("preferred_frequency_hz", m.preferred_frequency_hz);
  w.integer("max_cycles", m.max_cycles);
  w.num("start_timeout_s", m.start_timeout_s);
  w.num("confirm_hold_s", m.confirm_hold_s);
  w.num("holdoff_s", m.holdoff_s);
  w.integer("max_attempts", m.max_attempts);
  w.num("dead_band_m", c.dead_band_m);
  const fw::ControllerConfig& k = c.controller;
  w.table("controller");
  w.num("stiffness_n_m", k.stiffness_n_m);
  w.num("loss_factor", k.loss_factor);
  w.num("filter_freq_rad_s", k.filter_freq_rad_s);
  w.num("desired_force_limit_n", k.desired_force_limit_n);
  w.num("velocity_cutoff_hz", k.velocity_cutoff_hz);
  w.num("velocity_on_m_s", k.velocity_on_m_s);
  w.num("velocity_off_m_s", k.velocity_off_m_s);
  w.num("nominal_current_a", k.nominal_current_a);
  w.num("rated_current_a", k.rated_current_a);
  w.num("overdrive_current_a", k.overdrive_current_a);
  w.num("backdrive_current_a", k.backdrive_current_a);
  w.num("current_band_a", k.current_band_a);
  w.num("force_deadband_n", k.force_deadband_n);
  w.num("target_dwell_s", k.target_dwell_s);
  w.num("rest_release_s", k.rest_release_s);
  w.num("coil_thermal_time_constant_s", k.coil_thermal_time_constant_s);
  w.num("coil_derate_fraction", k.coil_derate_fraction);
  w.num("command_limit_a", k.command_limit_a);
  w.num("drive_continuous_limit_a", k.drive_continuous_limit_a);
  w.num("drive_peak_limit_a", k.drive_peak_limit_a);
  w.integer("drive_reenable_delay_ticks", k.drive_reenable_delay_ticks);
  w.num("disp_limit_m", k.disp_limit_m);
  w.num("force_limit_n", k.force_limit_n);
  w.num("accel_limit_m_s2", k.accel_limit_m_s2);
  w.num("coil_current_limit_a", k.coil_current_limit_a);
  w.integer("stuck_ticks", k.stuck_ticks);
  w.num("shaking_threshold_m_s2", k.shaking_threshold_m_s2);
  w.integer("max_input_age_ticks", k.max_input_age_ticks);
  w.integer("fault_hold_ticks", k.fault_hold_ticks);
  w.num("fallback_current_a", k.fallback_current_a);
  const physics::MrDamperParams& d = c.damper;
  const physics::SettlingParams& g = c.settling;
  w.table("damper");
  w.str("name", c.damper_name);
  w.str("law", law_name(d.law));
  w.num("fc_a_n", d.bingham.fc_a_n);
  w.num("fc_b_n", d.bingham.fc_b_n);
  w.num("fc_c_per_a", d.bingham.fc_c_per_a);
  w.num("c0_a_ns_m", d.bingham.c0_a_ns_m);
  w.num("c0_b_ns_m", d.bingham.c0_b_ns_m);
  w.num("c0_c_per_a", d.bingham.c0_c_per_a);
  w.num("v_tf_m_s", d.bingham.v_tf_m_s);
  if (d.law == physics::ForceLaw::kBoucWen) {
    w.num("bouc_wen_yield_disp_m", d.bouc_wen.yield_disp_m);
    w.num("bouc_wen_stiffness_n_m", d.bouc_wen.stiffness_n_m);
  }
  const physics::LawShape& sh = d.shape;
  if (sh.yield_current_exponent != 1.0) w.num("yield_current_exponent", sh.yield_current_exponent);
  if (sh.viscous_current_exponent != 1.0) w.num("viscous_current_exponent", sh.viscous_current_exponent);
  if (sh.has_viscous_exponent()) {
    w.num("viscous_exponent", sh.viscous_exponent);
    w.num("viscous_ref_m_s", sh.viscous_ref_m_s);
  }
  if (sh.stiffness_n_m != 0.0) w.num("bingham_stiffness_n_m", sh.stiffness_n_m);
  if (sh.transition_time_s != 0.0) w.num("transition_time_s", sh.transition_time_s);
  if (sh.lost_motion_m_per_n != 0.0 || sh.lost_motion_share != 0.0 || sh.lost_motion_band_m_s != 0.0) {
    w.num("lost_motion_m_per_n", sh.lost_motion_m_per_n);
    w.num("lost_motion_share", sh.lost_motion_share);
    w.num("lost_motion_band_m_s", sh.lost_motion_band_m_s);
  }
  w.num("tau_slow_s", d.coil.tau_slow_s);
  w.num("tau_fast_s", d.coil.tau_fast_s);
  w.num("weight_slow", d.coil.weight_slow);
  w.num("weight_fast", d.coil.weight_fast);
  w.num("rated_current_a", d.rating.current_a);
  if (d.coil_heat != physics::CoilHeatParams{}) {
    w.num("coil_resistance_ohm", d.coil_heat.resistance_ohm);
    w.num("coil_thermal_resistance_k_w", d.coil_heat.thermal_resistance_k_w);
    w.num("coil_thermal_time_constant_s", d.coil_heat.time_constant_s);
  }
  if (d.coil_inductance != physics::CoilInductance{}) {
    w.num("coil_inductance_1a_h", d.coil_inductance.inductance_1a_h);
    w.num("coil_inductance_2a_h", d.coil_inductance.inductance_2a_h);
  }
  w.num("rated_force_n", d.rating.force_n);
  w.num("stroke_m", d.rating.stroke_m);
  w.num("max_velocity_m_s", d.rating.velocity_m_s);
  w.num("flow_area_m2", d.pr.flow_area_m2);
  w.num("volume_unit_m3", d.pr.volume_unit_m3);
  w.num("inner_diameter_m", g.inner_diameter_m);
  w.num("shaft_radius_m", g.shaft_radius_m);
  w.num("fluid_length_m", g.fluid_length_m);
  w.num("fluid_volume_m3", g.fluid_volume_m3);
  w.table("fluid");
  w.str("name", c.fluid_name);
  w.num("particle_diameter_m", g.particle_diameter_m);
  w.num("solid_density_kg_m3", g.solid_density_kg_m3);
  w.num("liquid_density_kg_m3", g.liquid_density_kg_m3);
  w.num("viscosity_pa_s", g.viscosity_pa_s);
  w.num("solid_fraction", g.solid_fraction);
  w.num("hindered_exponent", g.hindered_exponent);
  if (g.measured_max_settling_time_s > 0.0) w.num("max_settling_time_s", g.measured_max_settling_time_s);
  w.num("a_initial", d.pr.a_initial);
  w.num("b_initial", d.pr.b_initial);
  w.num("c_initial", d.pr.c_initial);
  w.num("a_final", d.pr.a_final);
  w.num("b_final", d.pr.b_final);
  w.num("c_final", d.pr.c_final);
  w.num("a_rise", d.pr.a_rise);
  w.num("b_rise", d.pr.b_rise);
  w.num("c_rise", d.pr.c_rise);
  if (const std::optional<BoardDrive>& dr = c.drive) {
    w.table("drive");
    w.str("name", dr->name);
    w.num("bus_v", dr->bus_v);
    w.num("command_range_v", dr->command_range_v);
    w.num("volts_per_amp", dr->volts_per_amp);
    w.num("continuous_current_a", dr->continuous_current_a);
    w.num("peak_current_a", dr->peak_current_a);
    w.num("peak_time_s", dr->peak_time_s);
    w.num("loop_bandwidth_rad_s", dr->loop_bandwidth_rad_s);
    w.num("loop_period_s", dr->loop_period_s);
  }
  return w.text();
}

}  // namespace mrd::app
