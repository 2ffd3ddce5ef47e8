// Persistence of the idle-time estimator: record layout and CRC-32
// (checked against zlib), the Linux file store (write-new, fsync, rename,
// fsync folder), and the worst-case boot when the record is missing,
// truncated, damaged, of another version, or the clock went backwards.
#include "firmware/core/state_store.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <bit>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "firmware/core/idle_estimator.hpp"
#include "firmware/platform/linux/file_state_store.hpp"

namespace mrd::fw {
namespace {
namespace fs = std::filesystem;

PersistedIdleState sample_state() {
  PersistedIdleState s;
  s.equivalent_idle_ms = 1000;          // 1 s
  s.rtc_ms = 1700000000000;             // 1.7e9 s
  s.lifetime_volume = std::int64_t{1} << 37;  // 0.125 m³ in 2^−40 m³
  s.mixing_volume = std::int64_t{1} << 36;    // 0.0625 m³
  s.mixing_cycles = 7;
  s.save_sequence = 42;
  s.flags = kIdleNoSavedState;
  return s;
}

// The standard check value of CRC-32/ISO-HDLC (the zlib / IEEE 802.3 CRC).
TEST(Crc32, CheckValue) {
  const std::string s = "123456789";
  EXPECT_EQ(crc32(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()), 0xCBF43926u);
  EXPECT_EQ(crc32(nullptr, 0), 0u);
}

TEST(Crc32, AgreesWithZlib) {
  std::mt19937 rng(7);
  for (std::size_t len : {1u, 3u, 60u, 64u, 255u, 1000u}) {
    std::vector<std::uint8_t> buf(len);
    for (auto& b : buf) b = static_cast<std::uint8_t>(rng());
    const auto expected = ::crc32(0L, buf.data(), static_cast<uInt>(buf.size()));
    EXPECT_EQ(crc32(buf.data(), buf.size()), static_cast<std::uint32_t>(expected)) << len;
  }
}

TEST(StateRecord, RoundTrip) {
  const PersistedIdleState s = sample_state();
  PersistedIdleState back;
  ASSERT_EQ(decode_state(encode_state(s), back), DecodeStatus::kOk);
  EXPECT_EQ(back.equivalent_idle_ms, s.equivalent_idle_ms);
  EXPECT_EQ(back.rtc_ms, s.rtc_ms);
  EXPECT_EQ(back.lifetime_volume, s.lifetime_volume);
  EXPECT_EQ(back.mixing_volume, s.mixing_volume);
  EXPECT_EQ(back.mixing_cycles, 7u);
  EXPECT_EQ(back.save_sequence, 42u);
  EXPECT_EQ(back.flags, s.flags);
}

// The documented layout, byte by byte where it is easy to write down:
// "MRDI", version 2, size 64, τ = 1000 ms = 0x03E8 little-endian, the
// lifetime volume 2^37 counts (byte 28 = 0x20), and the CRC of bytes 0..59 (computed by zlib) in the last four bytes.
TEST(StateRecord, LayoutAsDocumented) {
  const hal::StateRecord r = encode_state(sample_state());
  EXPECT_EQ(r[0], 'M');
  EXPECT_EQ(r[1], 'R');
  EXPECT_EQ(r[2], 'D');
  EXPECT_EQ(r[3], 'I');
  EXPECT_EQ(r[4], 2);
  EXPECT_EQ(r[5], 0);
  EXPECT_EQ(r[6], 64);
  EXPECT_EQ(r[7], 0);
  EXPECT_EQ(r[8], 0xE8);
  EXPECT_EQ(r[9], 0x03);
  for (int k = 10; k < 16; ++k) EXPECT_EQ(r[k], 0) << k;
  for (int k = 24; k < 32; ++k) EXPECT_EQ(r[k], k == 28 ? 0x20 : 0) << k;
  EXPECT_EQ(r[40], 7);
  EXPECT_EQ(r[44], 42);
  for (int k = 52; k < 60; ++k) EXPECT_EQ(r[k], 0) << k;
  const auto crc = static_cast<std::uint32_t>(::crc32(0L, r.data(), 60));
  EXPECT_EQ(r[60], crc & 0xFF);
  EXPECT_EQ(r[61], (crc >> 8) & 0xFF);
  EXPECT_EQ(r[62], (crc >> 16) & 0xFF);
  EXPECT_EQ(r[63], crc >> 24);
}

// CRC-32 detects every single-bit error; magic and size bits are caught
// even before the CRC is looked at.
TEST(StateRecord, EverySingleBitFlipIsRefused) {
  const hal::StateRecord good = encode_state(sample_state());
  for (std::size_t bit = 0; bit < 8 * hal::kStateRecordSize; ++bit) {
    hal::StateRecord r = good;
    r[bit / 8] = static_cast<std::uint8_t>(r[bit / 8] ^ (1u << (bit % 8)));
    PersistedIdleState out;
    EXPECT_NE(decode_state(r, out), DecodeStatus::kOk) << "bit " << bit;
  }
}

hal::StateRecord with_fixed_crc(hal::StateRecord r) {
  const std::uint32_t c = crc32(r.data(), 60);
  for (int k = 0; k < 4; ++k) r[60 + k] = static_cast<std::uint8_t>(c >> (8 * k));
  return r;
}

/// A version-1 record as the double-only estimator wrote it: τ, stamp,
/// lifetime volume (and half of it as the mixing volume) as binary64, 3 cycles.
hal::StateRecord version1(double idle_s, double rtc_s, double lifetime_m3) {
  hal::StateRecord r{};
  const auto put = [&r](std::size_t at, std::uint64_t v, int bytes) {
    for (int k = 0; k < bytes; ++k) r[at + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(v >> (8 * k));
  };
  put(0, kStateRecordMagic, 4);
  put(4, 1, 2);
  put(6, 64, 2);
  put(8, std::bit_cast<std::uint64_t>(idle_s), 8);
  put(16, std::bit_cast<std::uint64_t>(rtc_s), 8);
  put(24, std::bit_cast<std::uint64_t>(lifetime_m3), 8);
  put(32, std::bit_cast<std::uint64_t>(0.5 * lifetime_m3), 8);
  put(40, 3, 4);
  return with_fixed_crc(r);
}

TEST(StateRecord, RefusalReasons) {
  PersistedIdleState out;
  hal::StateRecord r = encode_state(sample_state());
  r[0] = 'X';
  EXPECT_EQ(decode_state(with_fixed_crc(r), out), DecodeStatus::kBadMagic);

  r = encode_state(sample_state());
  r[4] = 3;  // version 3 with a valid CRC: a record we do not understand
  EXPECT_EQ(decode_state(with_fixed_crc(r), out), DecodeStatus::kBadVersion);

  r = encode_state(sample_state());
  r[6] = 63;
  EXPECT_EQ(decode_state(with_fixed_crc(r), out), DecodeStatus::kBadSize);

  r = encode_state(sample_state());
  r[20] ^= 0x01;
  EXPECT_EQ(decode_state(r, out), DecodeStatus::kBadCrc);

  PersistedIdleState s = sample_state();
  s.lifetime_volume = -1;
  EXPECT_EQ(decode_state(encode_state(s), out), DecodeStatus::kBadValue);
  s = sample_state();
  s.equivalent_idle_ms = ~std::uint64_t{0};
  EXPECT_EQ(decode_state(encode_state(s), out), DecodeStatus::kBadValue);
  EXPECT_EQ(decode_state(version1(std::numeric_limits<double>::quiet_NaN(), 1.7e9, 0.0), out),
            DecodeStatus::kBadValue);
  EXPECT_EQ(decode_state(version1(-1.0, 1.7e9, 0.0), out), DecodeStatus::kBadValue);
  EXPECT_EQ(decode_state(version1(1.0, std::numeric_limits<double>::infinity(), 0.0), out), DecodeStatus::kBadValue);
}

// A version-1 record (doubles, s and m³) still boots: converted to ms and
// 2^−40 m³ counts, rounded to nearest. 86400.0004 s → 86400000 ms;
// 0.5 m³ → 2^39 counts; 1.7e9 s → 1.7e12 ms.
TEST(StateRecord, ReadsVersion1) {
  PersistedIdleState out;
  ASSERT_EQ(decode_state(version1(86400.0004, 1.7e9, 0.5), out), DecodeStatus::kOk);
  EXPECT_EQ(out.equivalent_idle_ms, 86400000u);
  EXPECT_EQ(out.rtc_ms, 1700000000000);
  EXPECT_EQ(out.lifetime_volume, std::int64_t{1} << 39);
  EXPECT_EQ(out.mixing_volume, std::int64_t{1} << 38);
  EXPECT_EQ(out.mixing_cycles, 3u);
}

// ------------------------------------------------------------ FileStateStore

class FileStore : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "mrd-state-XXXXXX").string();
    ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
    path_ = dir_ / "idle_state.bin";
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_, fs::perms::owner_all, ec);
    fs::remove_all(dir_, ec);
  }
  void write_bytes(const std::vector<std::uint8_t>& bytes) const {
    std::ofstream f(path_, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
  std::vector<std::uint8_t> read_bytes() const {
    std::ifstream f(path_, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
  }
  fs::path dir_;
  fs::path path_;
};

TEST_F(FileStore, MissingFileIsMissing) {
  posix::FileStateStore store(path_.string());
  hal::StateRecord r{};
  EXPECT_EQ(store.load(r), hal::StoreStatus::kMissing);
}

TEST_F(FileStore, SaveThenLoadGivesTheSameBytesAndLeavesNoTemporary) {
  posix::FileStateStore store(path_.string());
  const hal::StateRecord rec = encode_state(sample_state());
  ASSERT_EQ(store.save(rec), hal::StoreStatus::kOk);
  EXPECT_EQ(fs::file_size(path_), hal::kStateRecordSize);
  EXPECT_FALSE(fs::exists(store.temp_path()));
  hal::StateRecord back{};
  ASSERT_EQ(store.load(back), hal::StoreStatus::kOk);
  EXPECT_EQ(back, rec);

  PersistedIdleState s = sample_state();
  s.save_sequence = 43;
  ASSERT_EQ(store.save(encode_state(s)), hal::StoreStatus::kOk);
  ASSERT_EQ(store.load(back), hal::StoreStatus::kOk);
  PersistedIdleState out;
  ASSERT_EQ(decode_state(back, out), DecodeStatus::kOk);
  EXPECT_EQ(out.save_sequence, 43u);
}

TEST_F(FileStore, TruncatedOrOverlongFileHasTheWrongSize) {
  posix::FileStateStore store(path_.string());
  const hal::StateRecord rec = encode_state(sample_state());
  hal::StateRecord back{};
  write_bytes(std::vector<std::uint8_t>(rec.begin(), rec.begin() + 40));
  EXPECT_EQ(store.load(back), hal::StoreStatus::kWrongSize);
  write_bytes({});
  EXPECT_EQ(store.load(back), hal::StoreStatus::kWrongSize);
  std::vector<std::uint8_t> longer(rec.begin(), rec.end());
  longer.push_back(0);
  write_bytes(longer);
  EXPECT_EQ(store.load(back), hal::StoreStatus::kWrongSize);
}

// A crash after writing `<path>.new` but before the rename: load() still
// sees the old record, and the next save replaces both.
TEST_F(FileStore, StaleTemporaryFromACrashIsIgnoredAndReplaced) {
  posix::FileStateStore store(path_.string());
  const hal::StateRecord old_rec = encode_state(sample_state());
  ASSERT_EQ(store.save(old_rec), hal::StoreStatus::kOk);
  { std::ofstream(store.temp_path(), std::ios::binary) << "half a rec"; }
  hal::StateRecord back{};
  ASSERT_EQ(store.load(back), hal::StoreStatus::kOk);
  EXPECT_EQ(back, old_rec);
  PersistedIdleState s = sample_state();
  s.save_sequence = 99;
  ASSERT_EQ(store.save(encode_state(s)), hal::StoreStatus::kOk);
  EXPECT_FALSE(fs::exists(store.temp_path()));
  ASSERT_EQ(store.load(back), hal::StoreStatus::kOk);
  EXPECT_EQ(back, encode_state(s));
}

// When the temporary cannot be written the old record stays untouched.
TEST_F(FileStore, FailedSaveKeepsTheOldRecord) {
  posix::FileStateStore store(path_.string());
  const hal::StateRecord old_rec = encode_state(sample_state());
  ASSERT_EQ(store.save(old_rec), hal::StoreStatus::kOk);
  fs::create_directory(store.temp_path());  // open(O_WRONLY) on a folder fails
  PersistedIdleState s = sample_state();
  s.save_sequence = 1000;
  EXPECT_EQ(store.save(encode_state(s)), hal::StoreStatus::kIoError);
  EXPECT_NE(store.last_errno(), 0);
  hal::StateRecord back{};
  ASSERT_EQ(store.load(back), hal::StoreStatus::kOk);
  EXPECT_EQ(back, old_rec);
}

TEST_F(FileStore, UnreadableRecordIsAnIoError) {
  fs::create_directory(path_);  // a folder is refused before any read
  posix::FileStateStore store(path_.string());
  hal::StateRecord back{};
  EXPECT_EQ(store.load(back), hal::StoreStatus::kIoError);
  EXPECT_EQ(store.last_load().problem, posix::FileProblem::kFolder);
}

// A FIFO as the state file: a plain open() would wait for a writer for ever
// (the boot and --print-state hung). The load is refused at once (5 s bound
// here, a writer then releases it) and a save leaves the FIFO in place.
TEST_F(FileStore, AFifoIsRefusedPromptlyAndNeverReplaced) {
  ASSERT_EQ(::mkfifo(path_.c_str(), 0600), 0);
  posix::FileStateStore store(path_.string());
  hal::StateRecord back{};
  auto pending = std::async(std::launch::async, [&] { return store.load(back); });
  if (pending.wait_for(std::chrono::seconds(5)) != std::future_status::ready) {
    ADD_FAILURE() << "load() blocked on the FIFO";
    const int w = ::open(path_.c_str(), O_WRONLY | O_NONBLOCK);
    if (w >= 0) ::close(w);
  }
  EXPECT_EQ(pending.get(), hal::StoreStatus::kIoError);
  EXPECT_EQ(store.last_load().problem, posix::FileProblem::kPipe);
  EXPECT_EQ(store.save(encode_state(sample_state())), hal::StoreStatus::kIoError);
  struct stat st {};
  ASSERT_EQ(::lstat(path_.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the save replaced the FIFO";
  EXPECT_FALSE(fs::exists(store.temp_path()));
}

// A state path that leads to a device (here a link to /dev/null) is neither
// read nor replaced by a save's rename.
TEST_F(FileStore, ADeviceIsRefusedAndNeverReplaced) {
  fs::create_symlink("/dev/null", path_);
  posix::FileStateStore store(path_.string());
  hal::StateRecord back{};
  EXPECT_EQ(store.load(back), hal::StoreStatus::kIoError);
  EXPECT_EQ(store.last_load().problem, posix::FileProblem::kDevice);
  EXPECT_EQ(store.save(encode_state(sample_state())), hal::StoreStatus::kIoError);
  EXPECT_TRUE(fs::is_symlink(path_));
  EXPECT_EQ(fs::read_symlink(path_), "/dev/null");
}

TEST_F(FileStore, BareFileNameUsesTheCurrentFolder) {
  const auto cwd = fs::current_path();
  fs::current_path(dir_);
  posix::FileStateStore store("state.bin");
  const hal::StoreStatus st = store.save(encode_state(sample_state()));
  fs::current_path(cwd);
  EXPECT_EQ(st, hal::StoreStatus::kOk);
  EXPECT_TRUE(fs::exists(dir_ / "state.bin"));
}

// ------------------------------------------- estimator boot over the file store

constexpr double kStampRtcS = 1.7e9;  // an arbitrary wall-clock stamp, s

IdleEstimatorConfig config() { return IdleEstimatorConfig{}; }

class EstimatorBoot : public FileStore {
 protected:
  /// A healthy record: τ = 1 day, saved at kStampRtcS.
  void save_healthy() {
    PersistedIdleState s;
    s.equivalent_idle_ms = 86400000;
    s.rtc_ms = std::llround(kStampRtcS * 1e3);
    s.lifetime_volume = std::int64_t{1} << 39;  // 0.5 m³
    posix::FileStateStore store(path_.string());
    ASSERT_EQ(store.save(encode_state(s)), hal::StoreStatus::kOk);
  }
  IdleBootReport boot(double rtc_s, bool rtc_valid = true) {
    posix::FileStateStore store(path_.string());
    EXPECT_TRUE(est_.init(config()));
    return est_.boot(store, 0, rtc_s, rtc_valid);
  }
  void expect_worst(std::uint32_t cause) const {
    const auto& e = est_.estimate();
    EXPECT_EQ(e.equivalent_idle_s, est_.model().max_settling_time_s());
    EXPECT_EQ(e.sq, 1.0);
    EXPECT_NEAR(e.participant_ratio, 0.100821, 1e-6);  // Eq. 5.6 at SQ = 1 (Table 5.6, by hand)
    EXPECT_TRUE(e.flags & cause) << std::hex << e.flags;
    EXPECT_TRUE(e.flags & kIdleAssumedSettled) << std::hex << e.flags;
    EXPECT_TRUE(est_.save_due());
  }
  IdleEstimator est_;
};

TEST_F(EstimatorBoot, HealthyRecordAddsTheTimeOff) {
  save_healthy();
  const auto rep = boot(kStampRtcS + 2.0 * 86400.0);
  EXPECT_EQ(rep.flags, 0u);
  EXPECT_NEAR(est_.estimate().equivalent_idle_s, 3.0 * 86400.0, 1e-6);  // 1 day stored + 2 days off
  EXPECT_EQ(est_.estimate().lifetime_volume_m3, 0.5);
  EXPECT_FALSE(est_.save_due());
}

TEST_F(EstimatorBoot, MissingFileMeansFullySettled) {
  const auto rep = boot(kStampRtcS);
  EXPECT_EQ(rep.load, hal::StoreStatus::kMissing);
  expect_worst(kIdleNoSavedState);
}

TEST_F(EstimatorBoot, TruncatedFileMeansFullySettled) {
  save_healthy();
  fs::resize_file(path_, 33);
  const auto rep = boot(kStampRtcS + 10.0);
  EXPECT_EQ(rep.load, hal::StoreStatus::kWrongSize);
  expect_worst(kIdleCorruptState);
}

TEST_F(EstimatorBoot, BitFlipMeansFullySettled) {
  save_healthy();
  auto bytes = read_bytes();
  bytes[9] ^= 0x10;  // inside τ: CRC catches it
  write_bytes(bytes);
  const auto rep = boot(kStampRtcS + 10.0);
  EXPECT_EQ(rep.decode, DecodeStatus::kBadCrc);
  expect_worst(kIdleCorruptState);
}

TEST_F(EstimatorBoot, WrongVersionMeansFullySettled) {
  save_healthy();
  auto bytes = read_bytes();
  bytes[4] = 9;
  hal::StateRecord r{};
  std::copy(bytes.begin(), bytes.end(), r.begin());
  r = with_fixed_crc(r);
  write_bytes({r.begin(), r.end()});
  const auto rep = boot(kStampRtcS + 10.0);
  EXPECT_EQ(rep.decode, DecodeStatus::kBadVersion);
  expect_worst(kIdleCorruptState);
}

TEST_F(EstimatorBoot, ClockBehindTheStampMeansFullySettled) {
  save_healthy();
  const auto rep = boot(kStampRtcS - 3600.0);
  EXPECT_EQ(rep.flags & kIdleClockBackwards, kIdleClockBackwards);
  expect_worst(kIdleClockBackwards);
  // The counters of a record that was itself intact are kept.
  EXPECT_EQ(est_.estimate().lifetime_volume_m3, 0.5);
}

// Within the tolerance (2 s by default) a clock behind the stamp is jitter.
TEST_F(EstimatorBoot, ClockJitterWithinToleranceIsAccepted) {
  save_healthy();
  const auto rep = boot(kStampRtcS - 1.0);
  EXPECT_EQ(rep.flags, 0u);
  EXPECT_NEAR(est_.estimate().equivalent_idle_s, 86400.0, 1e-9);
}

TEST_F(EstimatorBoot, InvalidClockAtBootMeansFullySettled) {
  save_healthy();
  boot(kStampRtcS + 100.0, false);
  expect_worst(kIdleClockInvalid);
}

// After a worst-case boot the estimator saves the new state at once, so the
// next boot starts from the present clock rather than the damaged record.
TEST_F(EstimatorBoot, WorstCaseIsPersistedAndTheNextBootIsClean) {
  save_healthy();
  boot(kStampRtcS - 3600.0);
  {
    posix::FileStateStore store(path_.string());
    ASSERT_EQ(est_.save(store), SaveOutcome::kSaved);
  }
  IdleEstimator again;
  ASSERT_TRUE(again.init(config()));
  posix::FileStateStore store(path_.string());
  const auto rep = again.boot(store, 0, kStampRtcS - 3600.0 + 60.0, true);
  EXPECT_EQ(rep.flags, 0u);
  EXPECT_EQ(again.estimate().equivalent_idle_s, again.model().max_settling_time_s());
}

}  // namespace
}  // namespace mrd::fw
