/// Checks that every subcommand's parsed options get alike, once CLI11 has
/// parsed them: list items (none empty, none twice) and the paths the options
/// name (the command's inputs, which no output may overlap).

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "host_sim/cli/command.hpp"
#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/report/output_transaction.hpp"
#include "host_sim/report/path_ownership.hpp"

namespace mrd::cli {
namespace {

/// Options that name what a command writes, not what it reads.
bool is_output_option(const CLI::Option& opt) { return opt.check_lname("out") || opt.check_lname("journal"); }

/// The option of `sub` that the argument `arg` ("--name" or "--name=value") names, or null.
const CLI::Option* option_named(const CLI::App& sub, std::string_view arg) {
  if (arg.size() < 3 || arg.substr(0, 2) != "--") return nullptr;
  const std::string_view name = arg.substr(0, arg.find('='));
  for (const CLI::Option* opt : sub.get_options()) {
    if (opt->check_name(std::string(name))) return opt;
  }
  return nullptr;
}

/// Refuses a value of a list option with an empty item ("0.1,,0.2", ",0.1",
/// "0.1,"): CLI11 drops such items silently.
void check_no_empty_item(const CLI::Option& opt, std::string_view value) {
  const char d = opt.get_delimiter();
  if (value.find(d) == std::string_view::npos) return;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = value.find(d, start);
    const std::string_view item = io::trim(value.substr(start, end == std::string_view::npos ? value.npos : end - start));
    if (item.empty()) {
      throw io::UsageError(opt.get_name() + ": an empty item in '" + io::excerpt(value, 80) +
                           "'; expected values separated by single '" + std::string(1, d) + "'");
    }
    if (end == std::string_view::npos) return;
    start = end + 1;
  }
}

/// The number `text` is, when it is one as a whole.
bool as_number(const std::string& text, double& value) {
  const std::string_view t = io::trim(text);
  const auto r = std::from_chars(t.data(), t.data() + t.size(), value);
  return r.ec == std::errc() && r.ptr == t.data() + t.size();
}

bool same_item(const std::string& a, const std::string& b) {
  double x = 0.0, y = 0.0;
  if (as_number(a, x) && as_number(b, y)) return x == y;
  return io::trim(a) == io::trim(b);
}

}  // namespace

void check_list_values(const CLI::App& sub, const std::vector<std::string>& args) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const CLI::Option* opt = option_named(sub, args[i]);
    if (!opt || opt->get_delimiter() == '\0') continue;
    const std::size_t eq = args[i].find('=');
    if (eq != std::string::npos) {
      check_no_empty_item(*opt, std::string_view(args[i]).substr(eq + 1));
      continue;
    }
    for (std::size_t j = i + 1; j < args.size() && args[j].rfind("--", 0) != 0; ++j) check_no_empty_item(*opt, args[j]);
  }
  for (const CLI::Option* opt : sub.get_options()) {
    const auto& items = opt->results();
    for (std::size_t i = 0; i < items.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if (same_item(items[i], items[j])) {
          throw io::UsageError(opt->get_name() + ": '" + io::excerpt(items[i], 80) + "' is given twice (as '" +
                               io::excerpt(items[j], 80) + "'); give each value once");
        }
      }
    }
  }
}

std::vector<report::InputPath> input_paths(const CLI::App& sub) {
  std::vector<report::InputPath> inputs;
  for (const CLI::Option* opt : sub.get_options()) {
    if (is_output_option(*opt)) continue;
    for (const std::string& value : opt->results()) {
      if (value.empty()) continue;
      std::error_code ec;
      if (!std::filesystem::exists(std::filesystem::symlink_status(value, ec))) continue;
      inputs.push_back({opt->get_name(), value, report::resolve_path(opt->get_name(), value)});
    }
  }
  return inputs;
}

void check_given_out(const CLI::App& sub) {
  for (const CLI::Option* opt : sub.get_options()) {
    if (opt->check_lname("out") && !opt->results().empty()) report::check_output_folder(opt->results().front());
  }
}

}  // namespace mrd::cli
