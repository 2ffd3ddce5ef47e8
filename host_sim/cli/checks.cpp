#include <cmath>
#include <sstream>

#include "cli/command.hpp"
#include "report/output_dir.hpp"

namespace mrd::cli {

void require_finite_at_least(const std::string& option, double value, double min_inclusive) {
  if (!std::isfinite(value)) {
    throw report::UsageError(option + ": expected a finite number, got " + (std::isnan(value) ? "NaN" : "infinity"));
  }
  if (value < min_inclusive) {
    std::ostringstream os;
    os << option << ": expected a number >= " << min_inclusive << ", got " << value;
    throw report::UsageError(os.str());
  }
}

}  // namespace mrd::cli
