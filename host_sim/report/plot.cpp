#include "host_sim/report/plot.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <system_error>

#include "host_sim/io/text.hpp"
#include "host_sim/report/time_series.hpp"

extern char** environ;

namespace mrd::report {
namespace fs = std::filesystem;

namespace {

constexpr std::array<std::string_view, 8> kStyles = {"lines",  "points",  "linespoints", "steps",
                                                      "fsteps", "histeps", "impulses",    "dots"};

// Okabe–Ito colours: distinguishable for colour-blind readers and in greyscale print.
constexpr std::array<std::string_view, 7> kColours = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                                      "#E69F00", "#56B4E9", "#000000"};

constexpr std::array<unsigned char, 8> kPngSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

// Longest stderr tail kept from gnuplot for the failure reason.
constexpr std::size_t kMaxStderrBytes = 16 * 1024;

void validate_size(int width_px, int height_px) {
  const auto ok = [](int v) { return v >= kMinPlotSidePx && v <= kMaxPlotSidePx; };
  if (!ok(width_px) || !ok(height_px)) {
    throw std::invalid_argument("plot size " + std::to_string(width_px) + "x" + std::to_string(height_px) +
                                " px is outside " + std::to_string(kMinPlotSidePx) + ".." +
                                std::to_string(kMaxPlotSidePx));
  }
}

void validate_panel(const PlotSpec& spec) {
  for (const auto& s : spec.series) {
    if (s.x.size() != s.y.size()) {
      throw std::invalid_argument("plot series '" + s.label + "' has " + std::to_string(s.x.size()) +
                                  " x values but " + std::to_string(s.y.size()) + " y values");
    }
    if (std::find(kStyles.begin(), kStyles.end(), s.style) == kStyles.end()) {
      throw std::invalid_argument("plot series '" + s.label + "' has unknown style '" + s.style + "'");
    }
  }
}

bool has_finite_point(const Series& s) {
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) return true;
  }
  return false;
}

void append_value(std::string& out, double v) {
  if (!std::isfinite(v)) {
    out += "NaN";
    return;
  }
  std::array<char, 48> buf{};
  // Ten significant digits keep millisecond steps distinct over more than a day.
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, 10);
  if (res.ec != std::errc{}) throw std::logic_error("to_chars failed for a finite double");
  out.append(buf.data(), res.ptr);
}

std::string block_name(std::size_t panel, std::size_t series) {
  return "$mrd_p" + std::to_string(panel) + "_s" + std::to_string(series);
}

void append_point(std::string& out, double x, double y) {
  append_value(out, x);
  out += ' ';
  append_value(out, y);
  out += '\n';
}

bool x_never_decreases(const Series& s) {
  double prev = -std::numeric_limits<double>::infinity();
  for (const double x : s.x) {
    if (!std::isfinite(x)) continue;
    if (x < prev) return false;
    prev = x;
  }
  return true;
}

// Writes a line series with x never decreasing as at most four points per
// x bucket (first, lowest, highest, last, in their original order). With
// buckets narrower than a pixel column the drawn line covers the same pixels
// as the full series. Non-finite samples still break the line.
void append_bucketed(std::string& out, const Series& s, double x0, double bucket_width) {
  bool open = false;
  bool gap_pending = false;
  long long bucket = 0;
  std::array<std::size_t, 4> idx{};  // first, lowest, highest, last
  const auto flush = [&] {
    if (!open) return;
    std::array<std::size_t, 4> sorted = idx;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t k = 0; k < sorted.size(); ++k) {
      if (k == 0 || sorted[k] != sorted[k - 1]) append_point(out, s.x[sorted[k]], s.y[sorted[k]]);
    }
    open = false;
  };
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    const double x = s.x[i];
    const double y = s.y[i];
    if (!std::isfinite(x) || !std::isfinite(y)) {
      flush();
      gap_pending = true;
      continue;
    }
    const auto b = static_cast<long long>(std::floor((x - x0) / bucket_width));
    if (open && b != bucket) flush();
    if (!open) {
      if (gap_pending) out += "NaN NaN\n";
      gap_pending = false;
      open = true;
      bucket = b;
      idx = {i, i, i, i};
      continue;
    }
    idx[3] = i;
    if (y < s.y[idx[1]]) idx[1] = i;
    if (y > s.y[idx[2]]) idx[2] = i;
  }
  flush();
}

// `buckets` is the number of x buckets across the panel's x range; 0 turns
// thinning off.
void append_datablocks(std::string& out, const PlotSpec& spec, std::size_t panel, int buckets) {
  double x_min = std::numeric_limits<double>::infinity();
  double x_max = -x_min;
  for (const auto& s : spec.series) {
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        x_min = std::min(x_min, s.x[i]);
        x_max = std::max(x_max, s.x[i]);
      }
    }
  }
  const double bucket_width = buckets > 0 && x_max > x_min ? (x_max - x_min) / buckets : 0.0;
  for (std::size_t k = 0; k < spec.series.size(); ++k) {
    const Series& s = spec.series[k];
    if (!has_finite_point(s)) continue;
    out += block_name(panel, k);
    out += " << EOD\n";
    const bool bucketed = bucket_width > 0.0 && std::isfinite(bucket_width) && s.style == "lines" &&
                      s.x.size() > 4 * static_cast<std::size_t>(buckets) && x_never_decreases(s);
    if (bucketed) {
      append_bucketed(out, s, x_min, bucket_width);
    } else {
      for (std::size_t i = 0; i < s.x.size(); ++i) append_point(out, s.x[i], s.y[i]);
    }
    out += "EOD\n";
  }
}

int font_points(int width_px) { return std::clamp(width_px / 90, 10, 14); }

void append_header(std::string& out, int width_px, int height_px, PngTerminal terminal,
                   const std::string& output_name) {
  const std::string size = std::to_string(width_px) + "," + std::to_string(height_px);
  const std::string font = gnuplot_quote("DejaVu Sans," + std::to_string(font_points(width_px)));
  const std::string cairo = "set terminal pngcairo size " + size + " noenhanced font " + font + " linewidth 1.2\n";
  const std::string gd = "set terminal png size " + size + " noenhanced font " + font + " linewidth 1\n";
  out += "set encoding utf8\n";
  switch (terminal) {
    case PngTerminal::automatic:
      out += "if (strstrt(' ' . GPVAL_TERMINALS . ' ', ' pngcairo ') > 0) {\n  " + cairo + "} else {\n  " + gd + "}\n";
      break;
    case PngTerminal::cairo:
      out += cairo;
      break;
    case PngTerminal::gd:
      out += gd;
      break;
  }
  out += "set output " + gnuplot_quote(output_name) + "\n";
  for (std::size_t i = 0; i < kColours.size(); ++i) {
    out += "set linetype " + std::to_string(i + 1) + " linecolor rgb '" + std::string(kColours[i]) +
           "' linewidth 1.5 pointtype 7 pointsize 0.6\n";
  }
  out += "set linetype cycle " + std::to_string(kColours.size()) + "\n";
  out += "set border linewidth 1\n";
  out += "set grid xtics ytics linetype 1 linecolor rgb '#d9d9d9' linewidth 1 dashtype solid\n";
  out += "set grid back\n";
  out += "set tics scale 0.75\n";
  out += "set key inside top right opaque box linecolor rgb '#9a9a9a' samplen 2.5 spacing 1.1\n";
}

void append_panel(std::string& out, const PlotSpec& spec, std::size_t panel, const std::string& title_font) {
  out += "unset label\n";
  out += "set autoscale\n";
  out += spec.title.empty() ? std::string("unset title\n")
                            : "set title " + gnuplot_quote(spec.title) + " font " + title_font + "\n";
  out += "set xlabel " + gnuplot_quote(spec.x_label) + "\n";
  out += "set ylabel " + gnuplot_quote(spec.y_label) + "\n";
  out += spec.key ? "set key\n" : "unset key\n";
  out += spec.key_headroom > 0.0 ? "set offsets 0, 0, graph " + std::to_string(spec.key_headroom) + ", 0\n"
                                 : std::string("set offsets 0, 0, 0, 0\n");

  std::string plot;
  for (std::size_t k = 0; k < spec.series.size(); ++k) {
    const Series& s = spec.series[k];
    if (!has_finite_point(s)) continue;
    plot += plot.empty() ? "plot " : ", \\\n     ";
    plot += block_name(panel, k) + " using 1:2 with " + s.style + " linetype " + std::to_string(k + 1);
    plot += s.label.empty() ? std::string(" notitle") : " title " + gnuplot_quote(s.label);
  }
  if (plot.empty()) {
    out += "set xrange [0:1]\nset yrange [0:1]\n";
    out += "set label 1 'no data' at graph 0.5, graph 0.5 center\n";
    out += "unset key\n";
    out += "plot NaN notitle\n";
  } else {
    out += plot + "\n";
  }
}

std::string build_script(const std::vector<const PlotSpec*>& panels, const std::string& title, int columns,
                         int width_px, int height_px, PngTerminal terminal, bool thin,
                         const std::string& output_name) {
  std::size_t points = 0;
  for (const PlotSpec* p : panels) {
    for (const auto& s : p->series) points += s.x.size();
  }
  std::string out;
  out.reserve(4096 + points * 24);
  append_header(out, width_px, height_px, terminal, output_name);
  // One bucket per image pixel column is finer than the pixel columns of any plot area.
  for (std::size_t i = 0; i < panels.size(); ++i) append_datablocks(out, *panels[i], i, thin ? width_px : 0);

  const bool multi = panels.size() > 1 || !title.empty();
  if (multi) {
    const auto cols = static_cast<std::size_t>(columns);
    const std::size_t rows = (panels.size() + cols - 1) / cols;
    // Fixed side margins keep the plot areas of stacked panels aligned.
    out += "set lmargin 12\nset rmargin 4\n";
    out += "set multiplot layout " + std::to_string(rows) + "," + std::to_string(cols) + " rowsfirst";
    if (!title.empty()) {
      out += " title " + gnuplot_quote(title) + " font " +
             gnuplot_quote("DejaVu Sans," + std::to_string(font_points(width_px) + 2));
    }
    out += "\n";
  }
  const std::string panel_title_font = gnuplot_quote("DejaVu Sans," + std::to_string(font_points(width_px) + 1));
  for (std::size_t i = 0; i < panels.size(); ++i) append_panel(out, *panels[i], i, panel_title_font);
  if (multi) out += "unset multiplot\n";
  out += "unset output\n";
  return out;
}

class Fd {
 public:
  explicit Fd(int fd = -1) noexcept : fd_(fd) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() { reset(); }
  [[nodiscard]] int get() const noexcept { return fd_; }
  void reset() noexcept {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 private:
  int fd_;
};

class SpawnActions {
 public:
  SpawnActions() noexcept : init_error_(::posix_spawn_file_actions_init(&actions_)) {}
  SpawnActions(const SpawnActions&) = delete;
  SpawnActions& operator=(const SpawnActions&) = delete;
  ~SpawnActions() {
    if (init_error_ == 0) ::posix_spawn_file_actions_destroy(&actions_);
  }
  /// 0, or the error number from initialising.
  [[nodiscard]] int init_error() const noexcept { return init_error_; }
  posix_spawn_file_actions_t* get() noexcept { return &actions_; }

 private:
  posix_spawn_file_actions_t actions_{};
  int init_error_;
};

std::string last_message_line(const std::string& text) {
  std::size_t end = text.size();
  while (end > 0) {
    const std::size_t start = text.rfind('\n', end - 1);
    const std::size_t from = start == std::string::npos ? 0 : start + 1;
    std::string line = text.substr(from, end - from);
    const auto first = line.find_first_not_of(" \t\r^");
    if (first != std::string::npos) {
      line = line.substr(first);
      while (!line.empty() && (line.back() == ' ' || line.back() == '\r' || line.back() == '\t')) line.pop_back();
      if (line.size() > 300) line = line.substr(0, 300) + "...";
      return line;
    }
    if (start == std::string::npos) break;
    end = start;
  }
  return {};
}

PlotResult fail(std::string reason) { return PlotResult{false, std::move(reason)}; }

bool write_all(int fd, std::string_view data) {
  while (!data.empty()) {
    const ssize_t n = ::write(fd, data.data(), data.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

int wait_child(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return status;
}

/// Reads `fd` into `text` (keeping its last kMaxStderrBytes) until end of
/// file or a read error, or until `deadline`. False when the deadline came first.
bool read_until_eof(int fd, std::chrono::steady_clock::time_point deadline, std::string& text) {
  std::array<char, 4096> buf{};
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) return false;
    pollfd pfd{fd, POLLIN, 0};
    const int pr = ::poll(&pfd, 1, static_cast<int>(std::min<long long>(left, 1000)));
    if (pr < 0) {
      if (errno == EINTR) continue;
      return true;
    }
    if (pr == 0) continue;
    const ssize_t n = ::read(fd, buf.data(), buf.size());
    if (n < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      return true;
    }
    if (n == 0) return true;
    text.append(buf.data(), static_cast<std::size_t>(n));
    if (text.size() > kMaxStderrBytes) text.erase(0, text.size() - kMaxStderrBytes);
  }
}

// Runs gnuplot on `script` with `dir` as its working folder.
PlotResult run_gnuplot(const std::string& script, const fs::path& dir, const PlotOptions& options) {
  const std::string exe_name = options.gnuplot.string();
  if (exe_name.empty()) return fail("no gnuplot executable configured");
  const bool search_path = exe_name.find('/') == std::string::npos;
  // The child changes folder before exec, so a relative path is resolved here.
  std::string exe = exe_name;
  if (!search_path) {
    std::error_code ec;
    const fs::path abs = fs::absolute(options.gnuplot, ec);
    if (!ec) exe = abs.string();
  }

  Fd script_fd(::memfd_create("mrd-plot-script", MFD_CLOEXEC));
  if (script_fd.get() < 0) return fail("cannot create the gnuplot script buffer: " + io::errno_text(errno));
  if (!write_all(script_fd.get(), script) || ::lseek(script_fd.get(), 0, SEEK_SET) != 0) {
    return fail("cannot write the gnuplot script: " + io::errno_text(errno));
  }

  std::array<int, 2> pipe_fds{-1, -1};
  if (::pipe2(pipe_fds.data(), O_CLOEXEC) != 0) {
    return fail("cannot create a pipe for gnuplot: " + io::errno_text(errno));
  }
  Fd err_read(pipe_fds[0]);
  Fd err_write(pipe_fds[1]);

  SpawnActions actions;
  int rc = actions.init_error();
  if (rc == 0) rc = ::posix_spawn_file_actions_adddup2(actions.get(), script_fd.get(), STDIN_FILENO);
  if (rc == 0) rc = ::posix_spawn_file_actions_addopen(actions.get(), STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  if (rc == 0) rc = ::posix_spawn_file_actions_adddup2(actions.get(), err_write.get(), STDERR_FILENO);
  if (rc == 0) rc = ::posix_spawn_file_actions_addchdir_np(actions.get(), dir.c_str());
  if (rc != 0) return fail("cannot prepare to run gnuplot: " + io::errno_text(rc));

  // -d: ignore the user's ~/.gnuplot so plots look the same everywhere.
  // The script is read as a file so gnuplot stops at the first error.
  std::string arg0 = exe;
  std::string arg_defaults = "-d";
  std::string arg_script = "/dev/stdin";
  std::array<char*, 4> argv{arg0.data(), arg_defaults.data(), arg_script.data(), nullptr};

  pid_t pid = -1;
  rc = search_path ? ::posix_spawnp(&pid, exe.c_str(), actions.get(), nullptr, argv.data(), environ)
                   : ::posix_spawn(&pid, exe.c_str(), actions.get(), nullptr, argv.data(), environ);
  if (rc != 0) return fail("cannot run gnuplot ('" + exe_name + "'): " + io::errno_text(rc));
  err_write.reset();
  script_fd.reset();

  std::string err_text;
  const bool timed_out = !read_until_eof(err_read.get(), std::chrono::steady_clock::now() + options.timeout, err_text);
  if (timed_out) ::kill(pid, SIGKILL);
  const int status = wait_child(pid);

  if (timed_out) {
    return fail("gnuplot did not finish within " + std::to_string(options.timeout.count()) + " ms and was stopped");
  }
  if (status < 0) return fail("cannot wait for gnuplot: " + io::errno_text(errno));
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return PlotResult{true, {}};
  std::string why = WIFEXITED(status) ? "gnuplot failed (exit status " + std::to_string(WEXITSTATUS(status)) + ")"
                                      : "gnuplot was killed by signal " + std::to_string(WTERMSIG(status));
  if (const std::string msg = last_message_line(err_text); !msg.empty()) why += ": " + msg;
  return fail(why);
}

bool starts_with_png_signature(const fs::path& file) {
  // reader policy: not a user's file: the image gnuplot just wrote under this run's own temporary name.
  Fd fd(::open(file.c_str(), O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) return false;
  std::array<unsigned char, kPngSignature.size()> head{};
  std::size_t got = 0;
  while (got < head.size()) {
    const ssize_t n = ::read(fd.get(), head.data() + got, head.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    got += static_cast<std::size_t>(n);
  }
  return head == kPngSignature;
}

PlotResult render(const std::vector<const PlotSpec*>& panels, const std::string& title, int columns, int width_px,
                  int height_px, const fs::path& png, const PlotOptions& options) {
  if (png.filename().empty()) return fail("plot path '" + png.string() + "' names no file");
  const fs::path dir = png.has_parent_path() ? png.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return fail("cannot write plot: folder '" + dir.string() + "' does not exist");

  static std::atomic<unsigned long> counter{0};
  const std::string tmp_name =
      ".mrd-plot-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1)) + ".png.tmp";
  const fs::path tmp = dir / tmp_name;

  const std::string script = build_script(panels, title, columns, width_px, height_px, options.terminal, options.thin_long_lines, tmp_name);
  PlotResult result = run_gnuplot(script, dir, options);
  if (result.ok && !starts_with_png_signature(tmp)) {
    result = fail("gnuplot did not write a PNG image");
  }
  if (result.ok && ::rename(tmp.c_str(), png.c_str()) != 0) {
    result = fail("cannot rename '" + tmp.string() + "' to '" + png.string() + "': " + io::errno_text(errno));
  }
  if (!result.ok) fs::remove(tmp, ec);
  return result;
}

}  // namespace

std::string gnuplot_quote(std::string_view text) {
  std::string out;
  out.reserve(text.size() + 2);
  out += '"';
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\\' || c == '"') {
      out += '\\';
      out += c;
    } else if (c == '`') {
      // gnuplot runs `...` as a shell command even inside double quotes; the
      // octal escape is only decoded after that substitution.
      out += "\\140";
    } else if (u < 0x20 || u == 0x7f) {
      out += ' ';
    } else {
      out += c;
    }
  }
  out += '"';
  return out;
}

PlotResult plot_png(const PlotSpec& spec, const fs::path& png, const PlotOptions& options) {
  validate_size(spec.width_px, spec.height_px);
  validate_panel(spec);
  return render({&spec}, {}, 1, spec.width_px, spec.height_px, png, options);
}

PlotResult plot_png(const MultiPlot& plot, const fs::path& png, const PlotOptions& options) {
  validate_size(plot.width_px, plot.height_px);
  if (plot.panels.empty()) throw std::invalid_argument("multi-panel plot has no panels");
  if (plot.columns < 1) throw std::invalid_argument("multi-panel plot needs at least one column");
  std::vector<const PlotSpec*> panels;
  panels.reserve(plot.panels.size());
  for (const auto& p : plot.panels) {
    validate_panel(p);
    panels.push_back(&p);
  }
  return render(panels, plot.title, plot.columns, plot.width_px, plot.height_px, png, options);
}

Series column_series(const TimeSeries& table, std::string_view x_column, std::string_view y_column, std::string label,
                     std::size_t stride) {
  if (stride == 0) throw std::invalid_argument("column_series: stride must be at least 1");
  const auto& xs = table.column(x_column);
  const auto& ys = table.column(y_column);
  Series s;
  s.label = std::move(label);
  const std::size_t n = xs.size();
  const std::size_t count = n == 0 ? 0 : (n - 1) / stride + 1;
  s.x.reserve(count);
  s.y.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    s.x.push_back(xs[i * stride]);
    s.y.push_back(ys[i * stride]);
  }
  return s;
}

}  // namespace mrd::report
