#include <cmath>
#include <sstream>
#include <string>

#include "host_sim/cli/command.hpp"
#include "host_sim/report/output_dir.hpp"

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

}  // namespace mrd::cli
