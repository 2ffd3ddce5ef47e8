#include "host_sim/risk/run_journal.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/report/path_ownership.hpp"

namespace mrd::risk {
namespace {

constexpr std::uint32_t kMagic = 0x4a44524d;  // "MRDJ" read little-endian

std::uint32_t crc_of(const unsigned char* b) {
  uLong c = crc32(0L, Z_NULL, 0);
  c = crc32(c, b, 4);
  c = crc32(c, b + 8, kJournalRecordBytes - 8);
  return static_cast<std::uint32_t>(c);
}

bool is_journal_name(const std::filesystem::path& p) {
  const std::string n = p.filename().string();
  return n.rfind("part-", 0) == 0 && p.extension() == ".journal";
}

}  // namespace

void encode_journal_record(std::uint64_t fingerprint, std::uint64_t run, const RunMetrics& m,
                           unsigned char (&out)[kJournalRecordBytes]) {
  const double v[kRunMetricCount] = {m.peak_base_displacement_m, m.peak_damper_force_n, m.peak_floor_accel_m_s2,
                                     m.peak_base_accel_m_s2, m.peak_story_drift_m};
  std::memcpy(out, &kMagic, 4);
  std::memcpy(out + 8, &fingerprint, 8);
  std::memcpy(out + 16, &run, 8);
  std::memcpy(out + 24, v, sizeof v);
  const std::uint32_t crc = crc_of(out);
  std::memcpy(out + 4, &crc, 4);
}

std::optional<JournalRecord> decode_journal_record(const unsigned char* b) {
  std::uint32_t magic = 0, crc = 0;
  std::memcpy(&magic, b, 4);
  std::memcpy(&crc, b + 4, 4);
  if (magic != kMagic || crc != crc_of(b)) return std::nullopt;
  JournalRecord r;
  double v[kRunMetricCount];
  std::memcpy(&r.fingerprint, b + 8, 8);
  std::memcpy(&r.run, b + 16, 8);
  std::memcpy(v, b + 24, sizeof v);
  r.metrics = {v[0], v[1], v[2], v[3], v[4]};
  return r;
}

std::vector<std::optional<RunMetrics>> load_journal(const std::filesystem::path& dir, std::uint64_t fingerprint,
                                                    std::size_t run_count) {
  std::vector<std::optional<RunMetrics>> runs(run_count);
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return runs;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    if (!is_journal_name(entry.path())) continue;
    const std::string bytes = io::read_regular_file(entry.path(), (run_count + 1) * kJournalRecordBytes);
    const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
    for (std::size_t at = 0; at + kJournalRecordBytes <= bytes.size(); at += kJournalRecordBytes) {
      const auto r = decode_journal_record(b + at);
      if (r && r->fingerprint == fingerprint && r->run < run_count) runs[r->run] = r->metrics;
    }
  }
  return runs;
}

void remove_journal(const std::filesystem::path& dir) noexcept {
  if (!report::holds_marker(dir, report::kJournalMarker)) return;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code rm;
    if (is_journal_name(it->path()) && it->is_regular_file(rm) && !it->is_symlink(rm)) {
      std::filesystem::remove(it->path(), rm);
    }
  }
  std::filesystem::remove(dir / report::kJournalMarker, ec);
  std::filesystem::remove(dir, ec);  // only when nothing else is left in it
}

unsigned journal_file_count(const std::filesystem::path& dir) {
  unsigned n = 0;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) n += is_journal_name(entry.path());
  return n;
}

JournalWriter::JournalWriter(const std::filesystem::path& dir, std::uint64_t fingerprint, unsigned attempt, int rank)
    : fingerprint_(fingerprint) {
  report::claim_folder("--journal", dir, report::kJournalMarker);
  path_ = dir / ("part-" + std::to_string(attempt) + "-r" + std::to_string(rank) + ".journal");
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) throw io::UsageError(path_.string() + ": cannot open the study journal: " + std::strerror(errno));
}

JournalWriter::~JournalWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void JournalWriter::append(std::uint64_t run, const RunMetrics& m) {
  unsigned char b[kJournalRecordBytes];
  encode_journal_record(fingerprint_, run, m, b);
  const ssize_t n = ::write(fd_, b, kJournalRecordBytes);
  if (n != static_cast<ssize_t>(kJournalRecordBytes)) {
    throw io::UsageError(path_.string() +
                         ": cannot append to the study journal: " + (n < 0 ? std::strerror(errno) : "short write"));
  }
}

}  // namespace mrd::risk
