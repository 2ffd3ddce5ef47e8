#pragma once
/// The resume store of a fragility study: completed runs appended to journal
/// files in a folder, one fixed 64-byte record per run, so that a killed study
/// (even by SIGKILL) restarts with the runs it had finished.
///
/// Record (little-endian, as the machine writes it):
/// <pre>
///   u32 magic "MRDJ" | u32 CRC-32 (zlib) of the other 60 bytes | u64 study fingerprint
///   | u64 run index | 5 × f64 RunMetrics
/// </pre>
/// Each record is one write() to a file opened O_APPEND, so a kill leaves at
/// most one torn record at the end of a file; it fails the length or CRC check
/// and is ignored. Records of another study (fingerprint) are ignored too.
/// Every process writes its own file, `part-<attempt>-r<rank>.journal`, so no
/// two processes append to one file; the reader takes every `part-*.journal`.
/// Durability: what write() returned survives the death of the process; it is
/// not synced to disk per record (a power loss can lose the last runs, never
/// corrupt the ones kept).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "host_sim/risk/fragility_plan.hpp"

namespace mrd::risk {

inline constexpr std::size_t kJournalRecordBytes = 64;

/// The runs recorded in the journals of `dir` for `fingerprint`, indexed by
/// run (nullopt where none); runs ≥ run_count are ignored. An absent folder
/// gives no runs. Each file is read through io::read_regular_file, at most
/// (run_count + 1) records long (one attempt appends each run once, and a kill
/// tears at most one record); a larger file or one that is not a regular file
/// is an io::UsageError naming it.
std::vector<std::optional<RunMetrics>> load_journal(const std::filesystem::path& dir, std::uint64_t fingerprint,
                                                    std::size_t run_count);

/// Removes the journal folder `dir` once its study's outputs are in place:
/// only when it holds the journal marker (report::kJournalMarker), and only
/// its own files (`part-*.journal`, the marker); the folder goes when nothing
/// else is left in it. Errors are ignored (the outputs are already written).
void remove_journal(const std::filesystem::path& dir) noexcept;

/// Number of `part-*.journal` files in `dir` (the next attempt's number).
unsigned journal_file_count(const std::filesystem::path& dir);

/// One process's journal file, appended to run by run.
class JournalWriter {
 public:
  /// Creates `dir` if needed (with the journal marker; report::claim_folder
  /// refuses a folder of other files) and opens
  /// `part-<attempt>-r<rank>.journal` for appending. Throws io::UsageError
  /// when it cannot.
  JournalWriter(const std::filesystem::path& dir, std::uint64_t fingerprint, unsigned attempt, int rank);
  ~JournalWriter();
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;

  /// Appends one record. Throws io::UsageError when the write fails.
  void append(std::uint64_t run, const RunMetrics& m);

 private:
  int fd_ = -1;
  std::uint64_t fingerprint_;
  std::filesystem::path path_;
};

/// The 64 bytes of a record (exposed for tests).
void encode_journal_record(std::uint64_t fingerprint, std::uint64_t run, const RunMetrics& m,
                           unsigned char (&out)[kJournalRecordBytes]);
/// Decodes a record; nullopt when the magic or CRC is wrong.
struct JournalRecord {
  std::uint64_t fingerprint = 0, run = 0;
  RunMetrics metrics{};
};
std::optional<JournalRecord> decode_journal_record(const unsigned char* bytes);

}  // namespace mrd::risk
