#pragma once
/// Column-oriented tables of sampled signals, written as CSV.

#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace mrd::report {

/// A table with one column per signal and one row per sample. Column names
/// carry their unit as a suffix (`time_s`, `force_n`, `accel_m_s2`).
///
/// Misuse (a row of the wrong length, an unknown column name, a bad name in
/// the constructor) is a programming error and throws from the std::logic_error
/// family; bad user input never reaches this class.
class TimeSeries {
 public:
  /// Throws std::invalid_argument when the list is empty, a name is empty or
  /// repeated, or a name contains a comma, quote or control character (it
  /// could not be written as a plain CSV header).
  explicit TimeSeries(std::vector<std::string> column_names_with_units);

  void reserve(std::size_t rows);

  /// Appends one sample per column, in column order. Throws
  /// std::invalid_argument when the count differs from columns(); the table is
  /// unchanged then.
  void add_row(std::initializer_list<double> values);
  void add_row(std::span<const double> values);

  [[nodiscard]] std::size_t rows() const noexcept;
  [[nodiscard]] std::size_t columns() const noexcept { return names_.size(); }
  [[nodiscard]] const std::vector<std::string>& column_names() const noexcept { return names_; }
  [[nodiscard]] bool has_column(std::string_view name) const noexcept;

  /// Throws std::out_of_range naming the column when there is none.
  [[nodiscard]] const std::vector<double>& column(std::string_view name) const;
  /// Throws std::out_of_range when index >= columns().
  [[nodiscard]] const std::vector<double>& column(std::size_t index) const;

  /// Header line with the column names, then one line per row with values in
  /// `%.*g` form, comma-separated, `\n` line ends (also after the last row).
  /// NaN is written as `nan`, infinities as `inf` / `-inf`. The output does
  /// not depend on the C locale. Throws std::invalid_argument unless
  /// 1 <= significant_digits <= 17.
  [[nodiscard]] std::string to_csv(int significant_digits = 9) const;

 private:
  [[nodiscard]] std::size_t index_of(std::string_view name) const;

  std::vector<std::string> names_;
  std::vector<std::vector<double>> data_;
};

/// Rows 0, stride, 2·stride, … of `series` (the last row is not forced in).
/// Meant for thinning 1 kHz records before plotting. Throws
/// std::invalid_argument when stride is 0.
[[nodiscard]] TimeSeries decimate(const TimeSeries& series, std::size_t stride);

/// Writes series.to_csv(significant_digits) to `path` through
/// write_file_atomically. Throws UsageError when the file cannot be written.
void write_csv(const TimeSeries& series, const std::filesystem::path& path, int significant_digits = 9);

}  // namespace mrd::report
