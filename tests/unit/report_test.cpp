// Time-series tables (CSV) and gnuplot PNG plots.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "host_sim/report/output_dir.hpp"
#include "host_sim/report/plot.hpp"
#include "host_sim/report/summary_json.hpp"
#include "host_sim/report/time_series.hpp"

namespace mrd::report {
namespace {
namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

class ScratchDir {
 public:
  ScratchDir() {
    std::string tmpl = (fs::temp_directory_path() / "mrd-report-test-XXXXXX").string();
    if (::mkdtemp(tmpl.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = tmpl;
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

struct PngInfo {
  bool valid = false;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

std::uint32_t be32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(s[at + i]);
  return v;
}

// Signature, then the IHDR chunk: length 13, type, width, height.
PngInfo read_png_info(const fs::path& p) {
  const std::string bytes = slurp(p);
  PngInfo info;
  static const std::string kSignature("\x89PNG\r\n\x1a\n", 8);
  if (bytes.size() < 33 || bytes.compare(0, 8, kSignature) != 0) return info;
  if (be32(bytes, 8) != 13 || bytes.compare(12, 4, "IHDR") != 0) return info;
  info.valid = true;
  info.width = be32(bytes, 16);
  info.height = be32(bytes, 20);
  return info;
}

bool gnuplot_on_path() {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return false;
  std::stringstream ss(path);
  std::string dir;
  while (std::getline(ss, dir, ':')) {
    const fs::path exe = (dir.empty() ? fs::path(".") : fs::path(dir)) / "gnuplot";
    if (::access(exe.c_str(), X_OK) == 0) return true;
  }
  return false;
}

#define REQUIRE_GNUPLOT()                                                   \
  do {                                                                      \
    if (!gnuplot_on_path()) FAIL() << "gnuplot is not installed (scripts/deps/core.list: gnuplot-nox)"; \
  } while (false)

// Writes an executable shell script standing in for gnuplot.
fs::path fake_gnuplot(const fs::path& dir, const std::string& body) {
  const fs::path p = dir / "fake-gnuplot";
  std::ofstream(p) << "#!/bin/sh\n" << body << "\n";
  fs::permissions(p, fs::perms::owner_all);
  return p;
}

Series sine_series(const std::string& label, std::size_t n, double dt, double amp, double freq_hz) {
  Series s;
  s.label = label;
  s.x.reserve(n);
  s.y.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    s.x.push_back(t);
    s.y.push_back(amp * std::sin(2.0 * 3.141592653589793 * freq_hz * t) * std::exp(-0.2 * t));
  }
  return s;
}

// ---------------------------------------------------------------- TimeSeries

TEST(TimeSeries, CsvExactForTinyTable) {
  TimeSeries ts({"time_s", "force_n"});
  ts.add_row({0.0, 1.5});
  ts.add_row({0.001, -2.25e-7});
  ts.add_row({1.0 / 3.0, kNaN});
  ts.add_row({kInf, -kInf});
  ts.add_row({123456789012.0, -0.0});
  EXPECT_EQ(ts.to_csv(),
            "time_s,force_n\n"
            "0,1.5\n"
            "0.001,-2.25e-07\n"
            "0.333333333,nan\n"
            "inf,-inf\n"
            "1.23456789e+11,-0\n");
}

TEST(TimeSeries, CsvSignificantDigits) {
  TimeSeries ts({"x_m"});
  ts.add_row({1.0 / 3.0});
  ts.add_row({12345.678});
  ts.add_row({0.1});
  ts.add_row({-kNaN});
  EXPECT_EQ(ts.to_csv(3), "x_m\n0.333\n1.23e+04\n0.1\nnan\n");
  EXPECT_EQ(ts.to_csv(17), "x_m\n0.33333333333333331\n12345.678\n0.10000000000000001\nnan\n");
  EXPECT_THROW((void)ts.to_csv(0), std::invalid_argument);
  EXPECT_THROW((void)ts.to_csv(18), std::invalid_argument);
}

TEST(TimeSeries, EmptyTableIsHeaderOnly) {
  const TimeSeries ts({"time_s", "velocity_m_s"});
  EXPECT_EQ(ts.rows(), 0u);
  EXPECT_EQ(ts.to_csv(), "time_s,velocity_m_s\n");
}

TEST(TimeSeries, ColumnAccess) {
  TimeSeries ts({"time_s", "force_n", "current_a"});
  ts.reserve(3);
  ts.add_row({0.0, 10.0, 0.5});
  const std::vector<double> row{0.001, 20.0, 0.75};
  ts.add_row(row);
  EXPECT_EQ(ts.rows(), 2u);
  EXPECT_EQ(ts.columns(), 3u);
  EXPECT_EQ(ts.column("force_n"), (std::vector<double>{10.0, 20.0}));
  EXPECT_EQ(ts.column(2), (std::vector<double>{0.5, 0.75}));
  EXPECT_TRUE(ts.has_column("current_a"));
  EXPECT_FALSE(ts.has_column("current"));
  EXPECT_EQ(ts.column_names(), (std::vector<std::string>{"time_s", "force_n", "current_a"}));
  EXPECT_THROW((void)ts.column("force"), std::out_of_range);
  EXPECT_THROW((void)ts.column(3), std::out_of_range);
}

TEST(TimeSeries, RowLengthMismatchThrowsAndLeavesTableUnchanged) {
  TimeSeries ts({"time_s", "force_n"});
  ts.add_row({0.0, 1.0});
  EXPECT_THROW(ts.add_row({1.0}), std::invalid_argument);
  EXPECT_THROW(ts.add_row({1.0, 2.0, 3.0}), std::invalid_argument);
  EXPECT_THROW(ts.add_row(std::span<const double>{}), std::invalid_argument);
  EXPECT_EQ(ts.rows(), 1u);
  EXPECT_EQ(ts.to_csv(), "time_s,force_n\n0,1\n");
}

TEST(TimeSeries, BadColumnNamesThrow) {
  EXPECT_THROW(TimeSeries({}), std::invalid_argument);
  EXPECT_THROW(TimeSeries({"time_s", ""}), std::invalid_argument);
  EXPECT_THROW(TimeSeries({"time_s", "time_s"}), std::invalid_argument);
  EXPECT_THROW(TimeSeries({"force,n"}), std::invalid_argument);
  EXPECT_THROW(TimeSeries({"force\"n"}), std::invalid_argument);
  EXPECT_THROW(TimeSeries({"force\nn"}), std::invalid_argument);
}

TEST(TimeSeries, DecimateKeepsEveryStrideRow) {
  TimeSeries ts({"time_s", "x_m"});
  for (int i = 0; i < 10; ++i) ts.add_row({i * 0.001, static_cast<double>(i)});
  const TimeSeries d = decimate(ts, 4);
  EXPECT_EQ(d.column_names(), ts.column_names());
  EXPECT_EQ(d.column("x_m"), (std::vector<double>{0.0, 4.0, 8.0}));
  EXPECT_EQ(decimate(ts, 1).to_csv(), ts.to_csv());
  EXPECT_EQ(decimate(ts, 100).rows(), 1u);
  EXPECT_EQ(decimate(TimeSeries({"a"}), 3).rows(), 0u);
  EXPECT_THROW((void)decimate(ts, 0), std::invalid_argument);
}

TEST(TimeSeries, WriteCsvReplacesFileAtomically) {
  ScratchDir dir;
  const fs::path csv = dir.path() / "response.csv";
  std::ofstream(csv) << "old content\n";
  TimeSeries ts({"time_s", "accel_m_s2"});
  ts.add_row({0.0, -9.81});
  ts.add_row({0.001, kNaN});
  write_csv(ts, csv);
  EXPECT_EQ(slurp(csv), "time_s,accel_m_s2\n0,-9.81\n0.001,nan\n");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"response.csv"});
  write_csv(ts, csv, 2);
  EXPECT_EQ(slurp(csv), "time_s,accel_m_s2\n0,-9.8\n0.001,nan\n");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"response.csv"});
}

TEST(TimeSeries, WriteCsvIntoMissingFolderIsUsageError) {
  ScratchDir dir;
  const TimeSeries ts({"time_s"});
  EXPECT_THROW(write_csv(ts, dir.path() / "no-such-folder" / "a.csv"), io::UsageError);
}

TEST(SummaryJson, WritesIndentedJsonWithFinalNewline) {
  ScratchDir dir;
  const fs::path path = write_summary_json(dir.path(), nlohmann::json{{"b_n", 2.5}, {"a", {1, 2}}});
  EXPECT_EQ(path, dir.path() / "summary.json");
  EXPECT_EQ(slurp(path), "{\n  \"a\": [\n    1,\n    2\n  ],\n  \"b_n\": 2.5\n}\n");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"summary.json"});
  EXPECT_THROW((void)write_summary_json(dir.path() / "no-such-folder", nlohmann::json::object()), io::UsageError);
}

// ---------------------------------------------------------------- plot helpers

TEST(Plot, GnuplotQuote) {
  EXPECT_EQ(gnuplot_quote("force [N]"), R"("force [N]")");
  EXPECT_EQ(gnuplot_quote("it's"), R"("it's")");
  EXPECT_EQ(gnuplot_quote(R"(a\b\ "q")"), R"("a\\b\\ \"q\"")");
  EXPECT_EQ(gnuplot_quote("`rm x`"), R"("\140rm x\140")");
  EXPECT_EQ(gnuplot_quote("two\nlines\t"), R"("two lines ")");
  EXPECT_EQ(gnuplot_quote("m/s\xc2\xb2"), "\"m/s\xc2\xb2\"");
  EXPECT_EQ(gnuplot_quote(""), R"("")");
}

TEST(Plot, ColumnSeries) {
  TimeSeries ts({"time_s", "force_n"});
  for (int i = 0; i < 5; ++i) ts.add_row({i * 0.5, i * 10.0});
  const Series all = column_series(ts, "time_s", "force_n", "force");
  EXPECT_EQ(all.label, "force");
  EXPECT_EQ(all.x, (std::vector<double>{0.0, 0.5, 1.0, 1.5, 2.0}));
  EXPECT_EQ(all.y, (std::vector<double>{0.0, 10.0, 20.0, 30.0, 40.0}));
  const Series thin = column_series(ts, "time_s", "force_n", "force", 2);
  EXPECT_EQ(thin.x, (std::vector<double>{0.0, 1.0, 2.0}));
  EXPECT_THROW((void)column_series(ts, "time_s", "nope", "x"), std::out_of_range);
  EXPECT_THROW((void)column_series(ts, "time_s", "force_n", "x", 0), std::invalid_argument);
}

TEST(Plot, MalformedSpecThrows) {
  ScratchDir dir;
  const fs::path png = dir.path() / "p.png";
  PlotSpec spec;
  spec.series.push_back(Series{"a", {0.0, 1.0}, {0.0}});
  EXPECT_THROW((void)plot_png(spec, png), std::invalid_argument);
  spec.series = {Series{"a", {0.0}, {0.0}, "lines; system 'rm -rf /'"}};
  EXPECT_THROW((void)plot_png(spec, png), std::invalid_argument);
  spec.series = {Series{"a", {0.0}, {0.0}}};
  spec.width_px = 10;
  EXPECT_THROW((void)plot_png(spec, png), std::invalid_argument);
  MultiPlot multi;
  EXPECT_THROW((void)plot_png(multi, png), std::invalid_argument);
  multi.panels.push_back(PlotSpec{});
  multi.columns = 0;
  EXPECT_THROW((void)plot_png(multi, png), std::invalid_argument);
  EXPECT_TRUE(entries(dir.path()).empty());
}

// ---------------------------------------------------------------- script sent to gnuplot

// The script plot_png hands to gnuplot, captured by a stand-in that fails.
std::string captured_script(const PlotSpec& spec, PlotOptions opt = {}) {
  ScratchDir tools;
  ScratchDir dir;
  const fs::path capture = tools.path() / "script.gp";
  opt.gnuplot = fake_gnuplot(tools.path(), "cat > '" + capture.string() + "'\nexit 1");
  const PlotResult r = plot_png(spec, dir.path() / "p.png", opt);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(entries(dir.path()).empty());
  return slurp(capture);
}

// Lines of datablock `name`, each as (x, y); non-numbers read as NaN.
std::vector<std::array<double, 2>> datablock(const std::string& script, const std::string& name) {
  std::vector<std::array<double, 2>> points;
  const std::string head = name + " << EOD\n";
  std::size_t pos = script.find(head);
  if (pos == std::string::npos) return points;
  pos += head.size();
  while (pos < script.size()) {
    const std::size_t end = script.find('\n', pos);
    const std::string line = script.substr(pos, end - pos);
    if (line == "EOD") break;
    std::array<double, 2> p{kNaN, kNaN};
    char* rest = nullptr;
    p[0] = std::strtod(line.c_str(), &rest);
    p[1] = std::strtod(rest, nullptr);
    points.push_back(p);
    pos = end + 1;
  }
  return points;
}

Series noisy_series(std::size_t n) {
  Series s;
  s.label = "noisy";
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * 0.001;
    s.x.push_back(t);
    s.y.push_back(std::sin(7.3 * t) + 0.5 * std::sin(static_cast<double>(i * i % 7919)));
  }
  return s;
}

TEST(PlotScript, LongTimeSeriesIsThinnedKeepingExtremes) {
  PlotSpec spec;
  spec.series.push_back(noisy_series(60'000));
  const auto pts = datablock(captured_script(spec), "$mrd_p0_s0");
  ASSERT_FALSE(pts.empty());
  EXPECT_LE(pts.size(), 4u * 1000u);
  EXPECT_GE(pts.size(), 1000u);
  const auto& y = spec.series[0].y;
  double lo = kInf;
  double hi = -kInf;
  for (const auto& p : pts) {
    lo = std::min(lo, p[1]);
    hi = std::max(hi, p[1]);
  }
  EXPECT_NEAR(lo, *std::min_element(y.begin(), y.end()), 1e-9);
  EXPECT_NEAR(hi, *std::max_element(y.begin(), y.end()), 1e-9);
  EXPECT_DOUBLE_EQ(pts.front()[0], 0.0);
  EXPECT_NEAR(pts.back()[0], 59.999, 1e-9);
  for (std::size_t i = 1; i < pts.size(); ++i) ASSERT_LT(pts[i - 1][0], pts[i][0]);
}

TEST(PlotScript, ThinningKeepsGaps) {
  PlotSpec spec;
  spec.series.push_back(noisy_series(60'000));
  for (std::size_t i = 20'000; i < 20'500; ++i) spec.series[0].y[i] = kNaN;
  const auto pts = datablock(captured_script(spec), "$mrd_p0_s0");
  const auto gaps = std::count_if(pts.begin(), pts.end(), [](const auto& p) { return std::isnan(p[1]); });
  EXPECT_EQ(gaps, 1);
  EXPECT_LE(pts.size(), 4u * 1000u + 1u);
}

TEST(PlotScript, OtherSeriesArePassedInFull) {
  PlotSpec spec;
  spec.series.push_back(noisy_series(60'000));
  PlotOptions off;
  off.thin_long_lines = false;
  EXPECT_EQ(datablock(captured_script(spec, off), "$mrd_p0_s0").size(), 60'000u);

  spec.series[0].style = "points";
  EXPECT_EQ(datablock(captured_script(spec), "$mrd_p0_s0").size(), 60'000u);

  // A force–velocity loop: x goes back and forth.
  spec.series[0].style = "lines";
  for (std::size_t i = 0; i < spec.series[0].x.size(); ++i) {
    spec.series[0].x[i] = std::sin(static_cast<double>(i) * 0.01);
  }
  EXPECT_EQ(datablock(captured_script(spec), "$mrd_p0_s0").size(), 60'000u);

  // Short series are never touched.
  spec.series[0] = noisy_series(3000);
  EXPECT_EQ(datablock(captured_script(spec), "$mrd_p0_s0").size(), 3000u);
}

TEST(PlotScript, LabelsCannotRunCommands) {
  PlotSpec spec;
  spec.title = "`rm -rf x` \" ; system 'ls'";
  spec.series.push_back(Series{"a", {0.0, 1.0}, {0.0, 1.0}});
  const std::string script = captured_script(spec);
  EXPECT_NE(script.find(R"(set title "\140rm -rf x\140 \" ; system 'ls'")"), std::string::npos) << script;
  EXPECT_EQ(script.find('`'), std::string::npos);
}

// ---------------------------------------------------------------- plots with gnuplot

TEST(Plot, WritesPngOfRequestedSize) {
  REQUIRE_GNUPLOT();
  ScratchDir dir;
  PlotSpec spec;
  spec.title = "Damper force, sine test 2 Hz";
  spec.x_label = "time [s]";
  spec.y_label = "force [N]";
  spec.series.push_back(sine_series("measured", 2000, 0.001, 800.0, 2.0));
  spec.series.push_back(sine_series("model", 2000, 0.001, 700.0, 2.0));
  spec.series.back().style = "points";
  const fs::path png = dir.path() / "force.png";
  const PlotResult r = plot_png(spec, png);
  ASSERT_TRUE(r.ok) << r.reason;
  EXPECT_TRUE(static_cast<bool>(r));
  EXPECT_TRUE(r.reason.empty());
  const PngInfo info = read_png_info(png);
  ASSERT_TRUE(info.valid);
  EXPECT_EQ(info.width, 1000u);
  EXPECT_EQ(info.height, 600u);
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"force.png"});

  spec.width_px = 640;
  spec.height_px = 480;
  spec.key = false;
  ASSERT_TRUE(plot_png(spec, png).ok);
  const PngInfo smaller = read_png_info(png);
  EXPECT_EQ(smaller.width, 640u);
  EXPECT_EQ(smaller.height, 480u);
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"force.png"});
}

TEST(Plot, GdTerminalAlsoWorks) {
  REQUIRE_GNUPLOT();
  ScratchDir dir;
  PlotSpec spec;
  spec.x_label = "time [s]";
  spec.y_label = "displacement [m]";
  spec.series.push_back(sine_series("x", 500, 0.002, 0.01, 1.0));
  spec.width_px = 700;
  spec.height_px = 400;
  PlotOptions opt;
  opt.terminal = PngTerminal::gd;
  const fs::path png = dir.path() / "gd.png";
  const PlotResult r = plot_png(spec, png, opt);
  ASSERT_TRUE(r.ok) << r.reason;
  const PngInfo info = read_png_info(png);
  ASSERT_TRUE(info.valid);
  EXPECT_EQ(info.width, 700u);
  EXPECT_EQ(info.height, 400u);
}

TEST(Plot, MultiPlotStackedPanels) {
  REQUIRE_GNUPLOT();
  ScratchDir dir;
  MultiPlot mp;
  mp.title = "Response to El Centro, controlled damper";
  mp.width_px = 900;
  mp.height_px = 1000;
  const char* names[] = {"displacement", "force", "acceleration"};
  const char* units[] = {"displacement [m]", "force [N]", "acceleration [m/s²]"};
  for (int i = 0; i < 3; ++i) {
    PlotSpec p;
    p.title = names[i];
    p.x_label = "time [s]";
    p.y_label = units[i];
    p.series.push_back(sine_series("uncontrolled", 3000, 0.001, std::pow(10.0, i), 1.5));
    p.series.push_back(sine_series("controlled", 3000, 0.001, 0.5 * std::pow(10.0, i), 1.5));
    mp.panels.push_back(std::move(p));
  }
  const fs::path png = dir.path() / "response.png";
  const PlotResult r = plot_png(mp, png);
  ASSERT_TRUE(r.ok) << r.reason;
  const PngInfo info = read_png_info(png);
  ASSERT_TRUE(info.valid);
  EXPECT_EQ(info.width, 900u);
  EXPECT_EQ(info.height, 1000u);
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"response.png"});

  mp.columns = 2;
  mp.title.clear();
  ASSERT_TRUE(plot_png(mp, png).ok);
  EXPECT_TRUE(read_png_info(png).valid);
}

TEST(Plot, LabelsWithQuotesAndBackslashes) {
  REQUIRE_GNUPLOT();
  ScratchDir dir;
  PlotSpec spec;
  spec.title = "it's a \"quoted\" title \\ with \\' backslash \\";
  spec.x_label = "'''a' time [s] '''''";
  spec.y_label = "force [N] \\\nnext line \" '''' '\"\" '";
  spec.series.push_back(sine_series("a'b\"c\\d_e^f{g}@h", 100, 0.01, 1.0, 1.0));
  spec.series.push_back(sine_series("", 100, 0.01, 0.5, 1.0));
  spec.series.push_back(sine_series("`touch injected` $(touch injected) @x", 100, 0.01, 0.25, 1.0));
  const fs::path png = dir.path() / "quotes.png";
  const PlotResult r = plot_png(spec, png);
  ASSERT_TRUE(r.ok) << r.reason;
  EXPECT_TRUE(read_png_info(png).valid);
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"quotes.png"});
}

TEST(Plot, OddFolderAndFileNames) {
  REQUIRE_GNUPLOT();
  ScratchDir dir;
  const fs::path sub = dir.path() / "it's a \"folder\"\nwith newline";
  fs::create_directory(sub);
  PlotSpec spec;
  spec.series.push_back(sine_series("x", 50, 0.01, 1.0, 1.0));
  const fs::path png = sub / "plot 'one'.png";
  const PlotResult r = plot_png(spec, png);
  ASSERT_TRUE(r.ok) << r.reason;
  EXPECT_TRUE(read_png_info(png).valid);
  EXPECT_EQ(entries(sub), std::vector<std::string>{"plot 'one'.png"});
}

TEST(Plot, EmptySeriesAndNaN) {
  REQUIRE_GNUPLOT();
  ScratchDir dir;
  PlotSpec spec;
  spec.x_label = "time [s]";
  spec.y_label = "force [N]";
  Series gaps = sine_series("with gaps", 400, 0.01, 1.0, 0.5);
  for (std::size_t i = 100; i < 150; ++i) gaps.y[i] = kNaN;
  gaps.y[200] = kInf;
  gaps.x[300] = -kInf;
  spec.series.push_back(gaps);
  spec.series.push_back(Series{"empty", {}, {}});
  spec.series.push_back(Series{"all nan", {kNaN, 1.0}, {1.0, kNaN}});
  const fs::path png = dir.path() / "gaps.png";
  PlotResult r = plot_png(spec, png);
  ASSERT_TRUE(r.ok) << r.reason;
  EXPECT_TRUE(read_png_info(png).valid);

  // Nothing to draw at all: still a valid image with empty axes.
  spec.series = {Series{"empty", {}, {}}, Series{"nan", {kNaN}, {kNaN}}};
  r = plot_png(spec, png);
  ASSERT_TRUE(r.ok) << r.reason;
  EXPECT_TRUE(read_png_info(png).valid);
  spec.series.clear();
  r = plot_png(spec, png);
  ASSERT_TRUE(r.ok) << r.reason;

  // A single point and a constant signal (degenerate ranges).
  spec.series = {Series{"one", {1.0}, {2.0}, "points"}, Series{"flat", {0.0, 1.0, 2.0}, {5.0, 5.0, 5.0}}};
  r = plot_png(spec, png);
  ASSERT_TRUE(r.ok) << r.reason;

  MultiPlot mp;
  mp.panels = {PlotSpec{}, spec};
  r = plot_png(mp, dir.path() / "multi.png");
  ASSERT_TRUE(r.ok) << r.reason;
  EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{"gaps.png", "multi.png"}));
}

TEST(Plot, LargeSeriesIsFast) {
  REQUIRE_GNUPLOT();
  ScratchDir dir;
  MultiPlot mp;
  mp.title = "60 s at 1 kHz";
  for (int panel = 0; panel < 3; ++panel) {
    PlotSpec p;
    p.x_label = "time [s]";
    p.y_label = "signal [1]";
    for (int k = 0; k < 2; ++k) p.series.push_back(sine_series("s", 60'000, 0.001, 1.0 + k, 0.7 + panel));
    mp.panels.push_back(std::move(p));
  }
  PlotSpec single;
  single.x_label = "time [s]";
  single.y_label = "force [N]";
  for (int k = 0; k < 4; ++k) single.series.push_back(sine_series("s", 60'000, 0.001, 1.0 + k, 2.0));

  const auto t0 = std::chrono::steady_clock::now();
  const PlotResult r1 = plot_png(single, dir.path() / "single.png");
  const auto t1 = std::chrono::steady_clock::now();
  const PlotResult r2 = plot_png(mp, dir.path() / "multi.png");
  const auto t2 = std::chrono::steady_clock::now();
  ASSERT_TRUE(r1.ok) << r1.reason;
  ASSERT_TRUE(r2.ok) << r2.reason;
  const double single_s = std::chrono::duration<double>(t1 - t0).count();
  const double multi_s = std::chrono::duration<double>(t2 - t1).count();
  std::printf("plot 4 x 60000 points: %.3f s; 3 panels x 2 x 60000 points: %.3f s\n", single_s, multi_s);
  RecordProperty("single_4x60000_s", std::to_string(single_s));
  RecordProperty("multi_3x2x60000_s", std::to_string(multi_s));
  // Generous bound: sanitizer builds and shared CI machines are slow.
  EXPECT_LT(single_s, 5.0);
  EXPECT_LT(multi_s, 5.0);
}

// ---------------------------------------------------------------- failures

TEST(PlotFailure, MissingGnuplotReportsAndLeavesNothing) {
  ScratchDir dir;
  const fs::path png = dir.path() / "p.png";
  PlotSpec spec;
  spec.series.push_back(sine_series("x", 10, 0.1, 1.0, 1.0));
  PlotOptions opt;
  opt.gnuplot = "/nonexistent/gnuplot";
  PlotResult r = plot_png(spec, png, opt);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(static_cast<bool>(r));
  EXPECT_NE(r.reason.find("/nonexistent/gnuplot"), std::string::npos) << r.reason;
  EXPECT_TRUE(entries(dir.path()).empty());

  opt.gnuplot = "mrd-no-such-gnuplot-binary";
  r = plot_png(spec, png, opt);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.reason.find("cannot run gnuplot"), std::string::npos) << r.reason;
  EXPECT_TRUE(entries(dir.path()).empty());
}

TEST(PlotFailure, ExistingPngIsKeptWhenPlottingFails) {
  ScratchDir dir;
  const fs::path png = dir.path() / "p.png";
  std::ofstream(png) << "previous";
  PlotSpec spec;
  PlotOptions opt;
  opt.gnuplot = "/nonexistent/gnuplot";
  EXPECT_FALSE(plot_png(spec, png, opt).ok);
  EXPECT_EQ(slurp(png), "previous");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"p.png"});
}

TEST(PlotFailure, GnuplotErrorExitIsReported) {
  ScratchDir tools;
  ScratchDir dir;
  const fs::path fake = fake_gnuplot(tools.path(), "cat >/dev/null\necho 'line 3: something broke' >&2\nexit 3");
  PlotOptions opt;
  opt.gnuplot = fake;
  PlotSpec spec;
  spec.series.push_back(sine_series("x", 10, 0.1, 1.0, 1.0));
  const PlotResult r = plot_png(spec, dir.path() / "p.png", opt);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.reason.find("exit status 3"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("something broke"), std::string::npos) << r.reason;
  EXPECT_TRUE(entries(dir.path()).empty());
}

TEST(PlotFailure, HalfWrittenOutputIsRemoved) {
  ScratchDir tools;
  ScratchDir dir;
  // Writes a partial file under the temporary name from the script, then fails.
  const fs::path fake = fake_gnuplot(tools.path(),
                                     "out=$(sed -n 's/^set output \"\\(.*\\)\"$/\\1/p')\n"
                                     "printf 'half' > \"$out\"\nkill -9 $$");
  PlotOptions opt;
  opt.gnuplot = fake;
  PlotSpec spec;
  spec.series.push_back(sine_series("x", 10, 0.1, 1.0, 1.0));
  const PlotResult r = plot_png(spec, dir.path() / "p.png", opt);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.reason.find("signal 9"), std::string::npos) << r.reason;
  EXPECT_TRUE(entries(dir.path()).empty());
}

TEST(PlotFailure, SuccessWithoutPngIsReported) {
  ScratchDir tools;
  ScratchDir dir;
  const fs::path fake = fake_gnuplot(tools.path(),
                                     "out=$(sed -n 's/^set output \"\\(.*\\)\"$/\\1/p')\n"
                                     "printf 'not a png' > \"$out\"\nexit 0");
  PlotOptions opt;
  opt.gnuplot = fake;
  const PlotResult r = plot_png(PlotSpec{}, dir.path() / "p.png", opt);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.reason.find("did not write a PNG"), std::string::npos) << r.reason;
  EXPECT_TRUE(entries(dir.path()).empty());
}

TEST(PlotFailure, HangingGnuplotIsStoppedAfterTimeout) {
  ScratchDir tools;
  ScratchDir dir;
  const fs::path fake = fake_gnuplot(tools.path(), "exec sleep 30");
  PlotOptions opt;
  opt.gnuplot = fake;
  opt.timeout = std::chrono::milliseconds(300);
  const auto t0 = std::chrono::steady_clock::now();
  const PlotResult r = plot_png(PlotSpec{}, dir.path() / "p.png", opt);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.reason.find("did not finish"), std::string::npos) << r.reason;
  EXPECT_LT(took, 5.0);
  EXPECT_TRUE(entries(dir.path()).empty());
}

TEST(PlotFailure, MissingFolderIsReported) {
  ScratchDir dir;
  const PlotResult r = plot_png(PlotSpec{}, dir.path() / "missing" / "p.png");
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.reason.find("does not exist"), std::string::npos) << r.reason;
  EXPECT_TRUE(entries(dir.path()).empty());
}

}  // namespace
}  // namespace mrd::report
