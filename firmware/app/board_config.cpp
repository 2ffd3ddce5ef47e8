#include "firmware/app/board_config.hpp"

#include <set>
#include <sstream>
#include <string_view>
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

}  // namespace

MixingTaskConfig BoardConfig::mixing_task_config() const noexcept {
  MixingTaskConfig t;
  t.estimator.period_s = period_s();
  t.estimator.dead_band_m = dead_band_m;
  t.estimator.save_interval_s = save_every_s;
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
        key != "mixing")
      fail(origin, v.source(), key, "unknown table (expected board, control, can, gpio, realtime, state, mixing)");
  }
  BoardConfig c;
  read_board(root, origin, c);
  read_control(root, origin, c);
  read_can(root, origin, c);
  read_gpio(root, origin, c);
  read_realtime(root, origin, c);
  read_state(root, origin, c, check_state_path);
  read_mixing(root, origin, c);
  return c;
}

}  // namespace mrd::app
