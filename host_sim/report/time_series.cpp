#include "host_sim/report/time_series.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <system_error>

#include "host_sim/report/output_dir.hpp"

namespace mrd::report {

namespace {

bool valid_column_name(std::string_view name) {
  if (name.empty()) return false;
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f || c == ',' || c == '"') return false;
  }
  return true;
}

void append_number(std::string& out, double v, int significant_digits) {
  if (std::isnan(v)) {
    out += "nan";
    return;
  }
  if (std::isinf(v)) {
    out += v > 0 ? "inf" : "-inf";
    return;
  }
  std::array<char, 48> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general,
                                 significant_digits);
  if (res.ec != std::errc{}) throw std::logic_error("to_chars failed for a finite double");
  out.append(buf.data(), res.ptr);
}

}  // namespace

TimeSeries::TimeSeries(std::vector<std::string> column_names_with_units)
    : names_(std::move(column_names_with_units)) {
  if (names_.empty()) throw std::invalid_argument("TimeSeries needs at least one column");
  for (std::size_t i = 0; i < names_.size(); ++i) {
    if (!valid_column_name(names_[i])) {
      throw std::invalid_argument("TimeSeries column name '" + names_[i] +
                                  "' is empty or contains a comma, quote or control character");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (names_[j] == names_[i]) throw std::invalid_argument("TimeSeries column '" + names_[i] + "' is repeated");
    }
  }
  data_.resize(names_.size());
}

void TimeSeries::reserve(std::size_t rows) {
  for (auto& c : data_) c.reserve(rows);
}

void TimeSeries::add_row(std::initializer_list<double> values) {
  add_row(std::span<const double>(values.begin(), values.size()));
}

void TimeSeries::add_row(std::span<const double> values) {
  if (values.size() != data_.size()) {
    throw std::invalid_argument("TimeSeries row has " + std::to_string(values.size()) + " values, table has " +
                                std::to_string(data_.size()) + " columns");
  }
  std::size_t done = 0;
  try {
    for (; done < data_.size(); ++done) data_[done].push_back(values[done]);
  } catch (...) {
    for (std::size_t i = 0; i < done; ++i) data_[i].pop_back();
    throw;
  }
}

std::size_t TimeSeries::rows() const noexcept { return data_.front().size(); }

bool TimeSeries::has_column(std::string_view name) const noexcept {
  for (const auto& n : names_) {
    if (n == name) return true;
  }
  return false;
}

std::size_t TimeSeries::index_of(std::string_view name) const {
  for (std::size_t i = 0; i < names_.size(); ++i) {
    if (names_[i] == name) return i;
  }
  throw std::out_of_range("TimeSeries has no column '" + std::string(name) + "'");
}

const std::vector<double>& TimeSeries::column(std::string_view name) const { return data_[index_of(name)]; }

const std::vector<double>& TimeSeries::column(std::size_t index) const {
  if (index >= data_.size()) {
    throw std::out_of_range("TimeSeries column index " + std::to_string(index) + " out of range (" +
                            std::to_string(data_.size()) + " columns)");
  }
  return data_[index];
}

std::string TimeSeries::to_csv(int significant_digits) const {
  if (significant_digits < 1 || significant_digits > 17) {
    throw std::invalid_argument("to_csv: significant_digits must be in 1..17, got " +
                                std::to_string(significant_digits));
  }
  std::string out;
  const std::size_t n_rows = rows();
  // Typical width of a %.9g value plus its separator.
  out.reserve(64 + n_rows * data_.size() * static_cast<std::size_t>(significant_digits + 8));
  for (std::size_t c = 0; c < names_.size(); ++c) {
    if (c > 0) out += ',';
    out += names_[c];
  }
  out += '\n';
  for (std::size_t r = 0; r < n_rows; ++r) {
    for (std::size_t c = 0; c < data_.size(); ++c) {
      if (c > 0) out += ',';
      append_number(out, data_[c][r], significant_digits);
    }
    out += '\n';
  }
  return out;
}

TimeSeries decimate(const TimeSeries& series, std::size_t stride) {
  if (stride == 0) throw std::invalid_argument("decimate: stride must be at least 1");
  TimeSeries out(series.column_names());
  const std::size_t n = series.rows();
  out.reserve(n == 0 ? 0 : (n - 1) / stride + 1);
  std::vector<double> row(series.columns());
  for (std::size_t r = 0; r < n; r += stride) {
    for (std::size_t c = 0; c < row.size(); ++c) row[c] = series.column(c)[r];
    out.add_row(row);
  }
  return out;
}

void write_csv(const TimeSeries& series, const std::filesystem::path& path, int significant_digits) {
  write_file_atomically(path, series.to_csv(significant_digits));
}

}  // namespace mrd::report
