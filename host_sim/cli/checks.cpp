#include <cmath>
#include <sstream>
#include <string>

#include "host_sim/cli/options.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::cli {

void require_finite_at_least(const std::string& option, double value, double min_inclusive) {
  if (!std::isfinite(value)) {
    throw io::UsageError(option + ": expected a finite number, got " + (std::isnan(value) ? "NaN" : "infinity"));
  }
  if (value < min_inclusive) {
    std::ostringstream os;
    os << option << ": expected a number >= " << min_inclusive << ", got " << value;
    throw io::UsageError(os.str());
  }
}

void require_positive(const std::string& option, double value, const std::string& what) {
  require_finite_at_least(option, value, 0.0);
  if (!(value > 0.0)) throw io::UsageError(option + ": expected " + what + " > 0, got " + std::to_string(value));
}

void require_at_most(const std::string& option, double value, double max, const std::string& limit) {
  if (!(value <= max)) throw io::UsageError(option + ": expected at most " + limit);
}

void require_step_s(double step_s, double max_s, const std::string& limit) {
  require_finite_at_least("--step-s", step_s, 1e-6);
  require_at_most("--step-s", step_s, max_s, limit);
}

void require_choice(const std::string& option, const std::string& value, std::initializer_list<const char*> choices) {
  std::string expected;
  std::size_t i = 0;
  for (const char* c : choices) {
    if (value == c) return;
    if (i > 0) expected += i + 1 == choices.size() ? " or " : ", ";
    expected += c;
    ++i;
  }
  throw io::UsageError(option + ": expected " + expected + ", got '" + value + "'");
}

}  // namespace mrd::cli
