#pragma once
/// PNG plots drawn by gnuplot (run as a child process).
///
/// Plots are a convenience next to the CSV files: when gnuplot is missing or
/// fails, plot_png returns a result with ok == false and a one-line reason,
/// and the caller reports it and carries on. Nothing is left in the target
/// folder then: the image is drawn into a hidden temporary file and renamed
/// into place only after gnuplot succeeded.
///
/// Terminal: `pngcairo` (antialiased, present in Debian's gnuplot-nox) when
/// the installed gnuplot has it, else the libgd `png` terminal. The choice is
/// made by the gnuplot script itself, so no extra process is started.
///
/// gnuplot runs without a shell, with the target folder as its working folder
/// and the script (data inline as datablocks) on its standard input; it reads
/// no ~/.gnuplot. Uses Linux/glibc calls (memfd_create, posix_spawn with
/// chdir).

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace mrd::report {

class TimeSeries;

/// One curve. x and y have the same length; NaN or infinite samples are
/// not drawn (a line is broken there). Series without a single finite point
/// are left out of the plot and its key.
struct Series {
  std::string label;
  std::vector<double> x;
  std::vector<double> y;
  /// One of: lines, points, linespoints, steps, fsteps, histeps, impulses, dots.
  std::string style = "lines";
};

/// One panel. Labels are drawn literally (no gnuplot markup), so put units in
/// them: "time [s]", "force [N]".
struct PlotSpec {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<Series> series;
  int width_px = 1000;
  int height_px = 600;
  bool key = true;
  /// Room added above the data for the key, as a share of the y range
  /// (0: none; the key then sits over the data's top right corner).
  double key_headroom = 0.0;
};

/// Panels laid out in a grid, filled row by row; with columns == 1 they are
/// stacked with aligned plot areas (displacement / force / acceleration over
/// time). The panels' own sizes are ignored.
struct MultiPlot {
  std::string title;
  std::vector<PlotSpec> panels;
  int columns = 1;
  int width_px = 1000;
  int height_px = 900;
};

enum class PngTerminal {
  automatic,  ///< pngcairo when available, else png
  cairo,      ///< pngcairo only (gnuplot fails when it lacks it)
  gd,         ///< the libgd png terminal
};

struct PlotOptions {
  /// A bare name is looked up on PATH; anything with a slash is a path
  /// (relative to the current folder).
  std::filesystem::path gnuplot = "gnuplot";
  /// gnuplot is killed when it runs longer; the result is then not ok.
  std::chrono::milliseconds timeout{60'000};
  PngTerminal terminal = PngTerminal::automatic;
  /// A `lines` series whose x never decreases (a time series) and that has
  /// more than four points per pixel column is handed to gnuplot as the first,
  /// lowest, highest and last point of each pixel column. The image looks the
  /// same and a 60 s record at 1 kHz draws several times faster. Other series
  /// (x going back and forth, points, steps) are always passed in full.
  bool thin_long_lines = true;
};

struct PlotResult {
  bool ok = false;
  /// Why no PNG was written; empty when ok.
  std::string reason;
  explicit operator bool() const noexcept { return ok; }
};

/// Smallest and largest accepted image side, in pixels.
inline constexpr int kMinPlotSidePx = 100;
inline constexpr int kMaxPlotSidePx = 10'000;

/// Draws `spec` into the PNG file `png`, replacing an existing file only on
/// success. The folder must exist. Throws std::invalid_argument for a
/// malformed spec (x/y length mismatch, unknown style, size outside
/// [kMinPlotSidePx, kMaxPlotSidePx]); everything else is reported in the result.
[[nodiscard]] PlotResult plot_png(const PlotSpec& spec, const std::filesystem::path& png,
                                  const PlotOptions& options = {});

/// As above for a grid of panels. Also throws std::invalid_argument when there
/// are no panels or columns < 1.
[[nodiscard]] PlotResult plot_png(const MultiPlot& plot, const std::filesystem::path& png,
                                  const PlotOptions& options = {});

/// Series built from two columns of a table, taking every `stride`-th row.
/// Throws std::out_of_range for an unknown column and std::invalid_argument
/// when stride is 0.
[[nodiscard]] Series column_series(const TimeSeries& table, std::string_view x_column, std::string_view y_column,
                                   std::string label, std::size_t stride = 1);

/// `text` as a gnuplot double-quoted string literal that gnuplot reads back
/// as exactly `text`: backslashes and quotes escaped, backquotes (command
/// substitution) written as an octal escape, control characters replaced by
/// spaces.
[[nodiscard]] std::string gnuplot_quote(std::string_view text);

}  // namespace mrd::report
