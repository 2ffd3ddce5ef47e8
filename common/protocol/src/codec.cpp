#include "mrd/protocol/codec.hpp"

#include <array>
#include <cmath>

namespace mrd::protocol {
namespace {

// ---- CRC-8 SAE J1850 --------------------------------------------------------

constexpr std::uint8_t kCrcPoly = 0x1D;
constexpr std::uint8_t kCrcInit = 0xFF;
constexpr std::uint8_t kCrcXorOut = 0xFF;

constexpr std::array<std::uint8_t, 256> make_crc_table() {
  std::array<std::uint8_t, 256> t{};
  for (unsigned i = 0; i < 256; ++i) {
    unsigned c = i;
    for (int b = 0; b < 8; ++b) c = (c & 0x80u) ? ((c << 1) ^ kCrcPoly) : (c << 1);
    t[i] = static_cast<std::uint8_t>(c & 0xFFu);
  }
  return t;
}
constexpr std::array<std::uint8_t, 256> kCrcTable = make_crc_table();

constexpr std::uint8_t crc_update(std::uint8_t crc, std::uint8_t byte) {
  return kCrcTable[static_cast<std::uint8_t>(crc ^ byte)];
}

// ---- Signal scaling (CAN_PROTOCOL.md, "Signals") ----------------------------
// raw = round(value · scale); value = raw / scale. Scales are exact integers
// in double, so both directions are correctly rounded and platform independent.

struct Scaling {
  double scale;     ///< raw counts per SI unit
  double min_si;    ///< documented range
  double max_si;
};

constexpr Scaling kCommandCurrent{1.0e3, -10.0, 10.0};      // 1 mA, ±10 A (§3.2)
constexpr Scaling kDriveCurrent{1.0e3, -30.0, 30.0};        // 1 mA, ±30 A (drive peak)
constexpr Scaling kDisp{1.0e7, -0.5, 0.5};                  // 0.1 µm
constexpr Scaling kForce{10.0, -800.0e3, 800.0e3};          // 0.1 N
constexpr Scaling kAccel{1.0e5, -80.0, 80.0};               // 1e-5 m/s²
constexpr Scaling kMixAmplitude{1.0e5, 0.0, 0.2};           // 0.01 mm
constexpr Scaling kMixFrequency{100.0, 0.0, 2.0};           // 0.01 Hz
constexpr Scaling kMixDuration{1.0, 0.0, 7200.0};           // 1 s
constexpr Scaling kMixElapsed{1.0, 0.0, 65535.0};           // 1 s
constexpr Scaling kFraction{250.0, 0.0, 1.0};             // 0.004 (PR, capacity)
constexpr std::uint32_t kMaxIdleHours = 0xFFFFFF;           // 24 bits of hours: 1914 years
constexpr Scaling kCoilCurrent{1.0e5, -30.0, 30.0};         // 10 µA (a float near 30 A resolves 1.9 µA)

/// "Not available" code of a 24-bit signed signal (J1939 style).
constexpr std::int32_t kInt24NotAvailable = -8388608;

bool raw_in_range(std::int64_t raw, const Scaling& s) noexcept {
  return raw >= std::llround(s.min_si * s.scale) && raw <= std::llround(s.max_si * s.scale);
}

/// The range is checked on the quantized value, so a float just past a limit
/// by its own rounding (0.2f = 0.2000000030) is still sent as the limit.
bool quantize(float value, const Scaling& s, std::int64_t& raw) noexcept {
  const double scaled = static_cast<double>(value) * s.scale;
  if (!std::isfinite(scaled) || std::fabs(scaled) > 1.0e15) return false;
  raw = std::llround(scaled);
  return raw_in_range(raw, s);
}

float to_si(std::int64_t raw, const Scaling& s) noexcept {
  return static_cast<float>(static_cast<double>(raw) / s.scale);
}

// ---- Little-endian field access --------------------------------------------

using Bytes = std::array<std::uint8_t, 8>;

void put_u16(Bytes& d, int at, std::uint32_t v) noexcept {
  d[at] = static_cast<std::uint8_t>(v & 0xFFu);
  d[at + 1] = static_cast<std::uint8_t>((v >> 8) & 0xFFu);
}
void put_u24(Bytes& d, int at, std::uint32_t v) noexcept {
  put_u16(d, at, v);
  d[at + 2] = static_cast<std::uint8_t>((v >> 16) & 0xFFu);
}
void put_u32(Bytes& d, int at, std::uint32_t v) noexcept {
  put_u16(d, at, v);
  put_u16(d, at + 2, v >> 16);
}
std::uint32_t get_u16(const Bytes& d, int at) noexcept {
  return static_cast<std::uint32_t>(d[at]) | (static_cast<std::uint32_t>(d[at + 1]) << 8);
}
std::uint32_t get_u24(const Bytes& d, int at) noexcept {
  return get_u16(d, at) | (static_cast<std::uint32_t>(d[at + 2]) << 16);
}
std::uint32_t get_u32(const Bytes& d, int at) noexcept { return get_u16(d, at) | (get_u16(d, at + 2) << 16); }
std::int64_t get_i16(const Bytes& d, int at) noexcept {
  const std::uint32_t u = get_u16(d, at);
  return (u & 0x8000u) ? static_cast<std::int64_t>(u) - 0x10000 : static_cast<std::int64_t>(u);
}
std::int64_t get_i24(const Bytes& d, int at) noexcept {
  const std::uint32_t u = get_u24(d, at);
  return (u & 0x800000u) ? static_cast<std::int64_t>(u) - 0x1000000 : static_cast<std::int64_t>(u);
}
std::int64_t get_i32(const Bytes& d, int at) noexcept {
  const std::uint32_t u = get_u32(d, at);
  return (u & 0x80000000u) ? static_cast<std::int64_t>(u) - 0x100000000LL : static_cast<std::int64_t>(u);
}
/// Two's complement bits of a signed raw value (callers range-checked it).
std::uint32_t bits(std::int64_t raw) noexcept { return static_cast<std::uint32_t>(raw & 0xFFFFFFFF); }

bool sender_ok(std::uint8_t sender) noexcept { return sender >= 1 && sender <= kMaxNodeId; }

void begin(hal::CanFrame& out, MsgId m, std::uint8_t sender) noexcept {
  out = hal::CanFrame{};
  out.id = can_id(m, sender);
  out.dlc = kFrameDlc;
}

bool finish(hal::CanFrame& out, std::uint8_t counter) noexcept {
  out.data[6] = counter;
  out.data[7] = frame_crc(out.id, out.data);
  return true;
}

DecodeError check_frame(const hal::CanFrame& f, MsgId m, std::uint8_t sender) noexcept {
  if (!sender_ok(sender) || f.extended || f.remote || f.id != can_id(m, sender)) return DecodeError::kWrongId;
  if (f.dlc != kFrameDlc) return DecodeError::kWrongLength;
  if (f.data[7] != frame_crc(f.id, f.data)) return DecodeError::kBadChecksum;
  return DecodeError::kOk;
}

bool mode_ok(std::uint32_t raw) noexcept { return raw <= static_cast<std::uint32_t>(control::ControlMode::kSemiActive); }

// Optional 24-bit signal: out-of-range values may not be sent as "not available".
bool put_opt_i24(Bytes& d, int at, bool valid, float value, const Scaling& s) noexcept {
  if (!valid) {
    put_u24(d, at, bits(kInt24NotAvailable));
    return true;
  }
  std::int64_t raw = 0;
  if (!quantize(value, s, raw)) return false;
  put_u24(d, at, bits(raw));
  return true;
}

bool get_opt_i24(const Bytes& d, int at, const Scaling& s, float& value, bool& valid) noexcept {
  const std::int64_t raw = get_i24(d, at);
  if (raw == kInt24NotAvailable) {
    value = 0.0f;
    valid = false;
    return true;
  }
  if (!raw_in_range(raw, s)) return false;
  value = to_si(raw, s);
  valid = true;
  return true;
}

}  // namespace

const char* decode_error_name(DecodeError e) noexcept {
  switch (e) {
    case DecodeError::kOk: return "ok";
    case DecodeError::kWrongId: return "wrong id";
    case DecodeError::kWrongLength: return "wrong length";
    case DecodeError::kBadChecksum: return "bad checksum";
    case DecodeError::kBadField: return "bad field";
    case DecodeError::kOutOfRange: return "out of range";
  }
  return "unknown";
}

std::uint8_t crc8_j1850(std::span<const std::uint8_t> bytes) noexcept {
  std::uint8_t crc = kCrcInit;
  for (std::uint8_t b : bytes) crc = crc_update(crc, b);
  return static_cast<std::uint8_t>(crc ^ kCrcXorOut);
}

std::uint8_t frame_crc(std::uint32_t id, const std::array<std::uint8_t, 8>& data) noexcept {
  std::uint8_t crc = kCrcInit;
  crc = crc_update(crc, static_cast<std::uint8_t>(id & 0xFFu));
  crc = crc_update(crc, static_cast<std::uint8_t>((id >> 8) & 0xFFu));
  for (int i = 0; i < 7; ++i) crc = crc_update(crc, data[i]);
  return static_cast<std::uint8_t>(crc ^ kCrcXorOut);
}

// ---- CurrentCommand: b0-1 i16 current 1 mA, b2 bit0 enable, b3 mode, b4-5 0

bool encode(const CurrentCommand& m, std::uint8_t sender, hal::CanFrame& out) noexcept {
  std::int64_t raw = 0;
  if (!sender_ok(sender) || !quantize(m.current_a, kCommandCurrent, raw) || !mode_ok(static_cast<std::uint32_t>(m.mode)))
    return false;
  begin(out, MsgId::kCurrentCommand, sender);
  put_u16(out.data, 0, bits(raw));
  out.data[2] = m.enable ? 1 : 0;
  out.data[3] = static_cast<std::uint8_t>(m.mode);
  return finish(out, m.counter);
}

DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, CurrentCommand& out) noexcept {
  if (const DecodeError e = check_frame(f, MsgId::kCurrentCommand, sender); e != DecodeError::kOk) return e;
  const auto& d = f.data;
  if ((d[2] & 0xFEu) != 0 || !mode_ok(d[3]) || d[4] != 0 || d[5] != 0) return DecodeError::kBadField;
  const std::int64_t raw = get_i16(d, 0);
  if (!raw_in_range(raw, kCommandCurrent)) return DecodeError::kOutOfRange;
  out.current_a = to_si(raw, kCommandCurrent);
  out.enable = (d[2] & 0x01u) != 0;
  out.mode = static_cast<control::ControlMode>(d[3]);
  out.counter = d[6];
  return DecodeError::kOk;
}

// ---- DriveStatus: b0-1 measured, b2-3 set point (i16, 1 mA), b4 faults, b5 state

bool encode(const DriveStatus& m, std::uint8_t sender, hal::CanFrame& out) noexcept {
  std::int64_t meas = 0, set = 0;
  if (!sender_ok(sender) || !quantize(m.measured_current_a, kDriveCurrent, meas) ||
      !quantize(m.setpoint_a, kDriveCurrent, set) || (m.faults & ~drive_fault::kAll) != 0 ||
      m.state > DriveState::kFault)
    return false;
  begin(out, MsgId::kDriveStatus, sender);
  put_u16(out.data, 0, bits(meas));
  put_u16(out.data, 2, bits(set));
  out.data[4] = m.faults;
  out.data[5] = static_cast<std::uint8_t>(m.state);
  return finish(out, m.counter);
}

DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, DriveStatus& out) noexcept {
  if (const DecodeError e = check_frame(f, MsgId::kDriveStatus, sender); e != DecodeError::kOk) return e;
  const auto& d = f.data;
  if ((d[4] & ~drive_fault::kAll) != 0 || d[5] > static_cast<std::uint8_t>(DriveState::kFault))
    return DecodeError::kBadField;
  const std::int64_t meas = get_i16(d, 0), set = get_i16(d, 2);
  if (!raw_in_range(meas, kDriveCurrent) || !raw_in_range(set, kDriveCurrent)) return DecodeError::kOutOfRange;
  out.measured_current_a = to_si(meas, kDriveCurrent);
  out.setpoint_a = to_si(set, kDriveCurrent);
  out.faults = d[4];
  out.state = static_cast<DriveState>(d[5]);
  out.counter = d[6];
  return DecodeError::kOk;
}

// ---- DaqMotion: b0-2 i24 stroke 0.1 µm, b3-5 i24 force 0.1 N ---------------

bool encode(const DaqMotion& m, std::uint8_t sender, hal::CanFrame& out) noexcept {
  if (!sender_ok(sender)) return false;
  begin(out, MsgId::kDaqMotion, sender);
  if (!put_opt_i24(out.data, 0, m.disp_valid, m.damper_disp_m, kDisp) ||
      !put_opt_i24(out.data, 3, m.force_valid, m.damper_force_n, kForce))
    return false;
  return finish(out, m.counter);
}

DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, DaqMotion& out) noexcept {
  if (const DecodeError e = check_frame(f, MsgId::kDaqMotion, sender); e != DecodeError::kOk) return e;
  DaqMotion m;
  if (!get_opt_i24(f.data, 0, kDisp, m.damper_disp_m, m.disp_valid) ||
      !get_opt_i24(f.data, 3, kForce, m.damper_force_n, m.force_valid))
    return DecodeError::kOutOfRange;
  m.counter = f.data[6];
  out = m;
  return DecodeError::kOk;
}

// ---- DaqAccel: b0-2 i24 ground, b3-5 i24 base, 1e-5 m/s² -------------------

bool encode(const DaqAccel& m, std::uint8_t sender, hal::CanFrame& out) noexcept {
  if (!sender_ok(sender)) return false;
  begin(out, MsgId::kDaqAccel, sender);
  if (!put_opt_i24(out.data, 0, m.ground_valid, m.ground_accel_m_s2, kAccel) ||
      !put_opt_i24(out.data, 3, m.base_valid, m.base_accel_m_s2, kAccel))
    return false;
  return finish(out, m.counter);
}

DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, DaqAccel& out) noexcept {
  if (const DecodeError e = check_frame(f, MsgId::kDaqAccel, sender); e != DecodeError::kOk) return e;
  DaqAccel m;
  if (!get_opt_i24(f.data, 0, kAccel, m.ground_accel_m_s2, m.ground_valid) ||
      !get_opt_i24(f.data, 3, kAccel, m.base_accel_m_s2, m.base_valid))
    return DecodeError::kOutOfRange;
  m.counter = f.data[6];
  out = m;
  return DecodeError::kOk;
}

// ---- MixingCommand: b0 action, b1-2 u16 amplitude, b3 u8 frequency, b4-5 u16 duration

bool encode(const MixingCommand& m, std::uint8_t sender, hal::CanFrame& out) noexcept {
  std::int64_t amp = 0, freq = 0, dur = 0;
  if (!sender_ok(sender) || m.action > MixingAction::kStart || !quantize(m.amplitude_m, kMixAmplitude, amp) ||
      !quantize(m.frequency_hz, kMixFrequency, freq) || !quantize(m.duration_s, kMixDuration, dur))
    return false;
  begin(out, MsgId::kMixingCommand, sender);
  out.data[0] = static_cast<std::uint8_t>(m.action);
  put_u16(out.data, 1, bits(amp));
  out.data[3] = static_cast<std::uint8_t>(freq);
  put_u16(out.data, 4, bits(dur));
  return finish(out, m.counter);
}

DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, MixingCommand& out) noexcept {
  if (const DecodeError e = check_frame(f, MsgId::kMixingCommand, sender); e != DecodeError::kOk) return e;
  const auto& d = f.data;
  if (d[0] > static_cast<std::uint8_t>(MixingAction::kStart)) return DecodeError::kBadField;
  const std::int64_t amp = get_u16(d, 1), freq = d[3], dur = get_u16(d, 4);
  if (!raw_in_range(amp, kMixAmplitude) || !raw_in_range(freq, kMixFrequency) || !raw_in_range(dur, kMixDuration))
    return DecodeError::kOutOfRange;
  out.action = static_cast<MixingAction>(d[0]);
  out.amplitude_m = to_si(amp, kMixAmplitude);
  out.frequency_hz = to_si(freq, kMixFrequency);
  out.duration_s = to_si(dur, kMixDuration);
  out.counter = d[6];
  return DecodeError::kOk;
}

// ---- MixingStatus: b0 state, b1-2 u16 elapsed, b3-4 u16 amplitude, b5 faults

bool encode(const MixingStatus& m, std::uint8_t sender, hal::CanFrame& out) noexcept {
  std::int64_t el = 0, amp = 0;
  if (!sender_ok(sender) || m.state > MixingState::kFault || !quantize(m.elapsed_s, kMixElapsed, el) ||
      !quantize(m.amplitude_m, kMixAmplitude, amp) || (m.faults & ~mixing_fault::kAll) != 0)
    return false;
  begin(out, MsgId::kMixingStatus, sender);
  out.data[0] = static_cast<std::uint8_t>(m.state);
  put_u16(out.data, 1, bits(el));
  put_u16(out.data, 3, bits(amp));
  out.data[5] = m.faults;
  return finish(out, m.counter);
}

DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, MixingStatus& out) noexcept {
  if (const DecodeError e = check_frame(f, MsgId::kMixingStatus, sender); e != DecodeError::kOk) return e;
  const auto& d = f.data;
  if (d[0] > static_cast<std::uint8_t>(MixingState::kFault) || (d[5] & ~mixing_fault::kAll) != 0)
    return DecodeError::kBadField;
  const std::int64_t el = get_u16(d, 1), amp = get_u16(d, 3);
  if (!raw_in_range(amp, kMixAmplitude)) return DecodeError::kOutOfRange;
  out.state = static_cast<MixingState>(d[0]);
  out.elapsed_s = to_si(el, kMixElapsed);
  out.amplitude_m = to_si(amp, kMixAmplitude);
  out.faults = d[5];
  out.counter = d[6];
  return DecodeError::kOk;
}

// ---- ControllerStatus: b0 mode, b1 flags, b2-3 overruns, b4-5 rejected frames

bool encode(const ControllerStatus& m, std::uint8_t sender, hal::CanFrame& out) noexcept {
  if (!sender_ok(sender) || !mode_ok(static_cast<std::uint32_t>(m.mode)) || (m.flags & ~controller_flag::kAll) != 0)
    return false;
  begin(out, MsgId::kControllerStatus, sender);
  out.data[0] = static_cast<std::uint8_t>(m.mode);
  out.data[1] = m.flags;
  put_u16(out.data, 2, m.overruns);
  put_u16(out.data, 4, m.rejected_frames);
  return finish(out, m.counter);
}

DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, ControllerStatus& out) noexcept {
  if (const DecodeError e = check_frame(f, MsgId::kControllerStatus, sender); e != DecodeError::kOk) return e;
  const auto& d = f.data;
  if (!mode_ok(d[0]) || (d[1] & ~controller_flag::kAll) != 0) return DecodeError::kBadField;
  out.mode = static_cast<control::ControlMode>(d[0]);
  out.flags = d[1];
  out.overruns = static_cast<std::uint16_t>(get_u16(d, 2));
  out.rejected_frames = static_cast<std::uint16_t>(get_u16(d, 4));
  out.counter = d[6];
  return DecodeError::kOk;
}

// ---- IdleStatus: b0-2 u24 idle hours, b3 u8 PR, b4 u8 capacity, b5 scheduler | flags << 4

bool encode(const IdleStatus& m, std::uint8_t sender, hal::CanFrame& out) noexcept {
  std::int64_t pr = 0, cap = 0;
  if (!sender_ok(sender) || m.equivalent_idle_h > kMaxIdleHours || !quantize(m.participant_ratio, kFraction, pr) ||
      !quantize(m.capacity_fraction, kFraction, cap) || m.scheduler > scheduler_state::kMaintenanceRequired ||
      (m.flags & ~idle_flag::kAll) != 0)
    return false;
  begin(out, MsgId::kIdleStatus, sender);
  put_u24(out.data, 0, m.equivalent_idle_h);
  out.data[3] = static_cast<std::uint8_t>(pr);
  out.data[4] = static_cast<std::uint8_t>(cap);
  out.data[5] = static_cast<std::uint8_t>(m.scheduler | (m.flags << 4));
  return finish(out, m.counter);
}

DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, IdleStatus& out) noexcept {
  if (const DecodeError e = check_frame(f, MsgId::kIdleStatus, sender); e != DecodeError::kOk) return e;
  const auto& d = f.data;
  const std::uint8_t scheduler = d[5] & 0x0Fu;
  const std::uint8_t flags = static_cast<std::uint8_t>(d[5] >> 4);
  if (scheduler > scheduler_state::kMaintenanceRequired || (flags & ~idle_flag::kAll) != 0) return DecodeError::kBadField;
  if (!raw_in_range(d[3], kFraction) || !raw_in_range(d[4], kFraction)) return DecodeError::kOutOfRange;
  out.equivalent_idle_h = get_u24(d, 0);
  out.participant_ratio = to_si(d[3], kFraction);
  out.capacity_fraction = to_si(d[4], kFraction);
  out.scheduler = scheduler;
  out.flags = flags;
  out.counter = d[6];
  return DecodeError::kOk;
}

// ---- SimCoilState: b0-3 i32 coil current 10 µA, b4-5 0 ----------------------

bool encode(const SimCoilState& m, std::uint8_t sender, hal::CanFrame& out) noexcept {
  std::int64_t raw = 0;
  if (!sender_ok(sender) || !quantize(m.coil_current_a, kCoilCurrent, raw)) return false;
  begin(out, MsgId::kSimCoilState, sender);
  put_u32(out.data, 0, bits(raw));
  return finish(out, m.counter);
}

DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, SimCoilState& out) noexcept {
  if (const DecodeError e = check_frame(f, MsgId::kSimCoilState, sender); e != DecodeError::kOk) return e;
  const auto& d = f.data;
  if (d[4] != 0 || d[5] != 0) return DecodeError::kBadField;
  const std::int64_t raw = get_i32(d, 0);
  if (!raw_in_range(raw, kCoilCurrent)) return DecodeError::kOutOfRange;
  out.coil_current_a = to_si(raw, kCoilCurrent);
  out.counter = d[6];
  return DecodeError::kOk;
}

// ---- SimCoilDrive: b0-1 i16 applied current 1 mA, b2 bit0 output on, b3-5 0

bool encode(const SimCoilDrive& m, std::uint8_t sender, hal::CanFrame& out) noexcept {
  std::int64_t raw = 0;
  if (!sender_ok(sender) || !quantize(m.applied_current_a, kDriveCurrent, raw)) return false;
  begin(out, MsgId::kSimCoilDrive, sender);
  put_u16(out.data, 0, bits(raw));
  out.data[2] = m.output_on ? 1 : 0;
  return finish(out, m.counter);
}

DecodeError decode(const hal::CanFrame& f, std::uint8_t sender, SimCoilDrive& out) noexcept {
  if (const DecodeError e = check_frame(f, MsgId::kSimCoilDrive, sender); e != DecodeError::kOk) return e;
  const auto& d = f.data;
  if ((d[2] & 0xFEu) != 0 || d[3] != 0 || d[4] != 0 || d[5] != 0) return DecodeError::kBadField;
  const std::int64_t raw = get_i16(d, 0);
  if (!raw_in_range(raw, kDriveCurrent)) return DecodeError::kOutOfRange;
  out.applied_current_a = to_si(raw, kDriveCurrent);
  out.output_on = (d[2] & 0x01u) != 0;
  out.counter = d[6];
  return DecodeError::kOk;
}

// ---- Rolling counter -------------------------------------------------------

CounterVerdict CounterCheck::check(std::uint8_t counter) noexcept {
  if (!synced_) {
    synced_ = true;
    last_ = counter;
    return CounterVerdict::kSynced;
  }
  const auto ahead = static_cast<std::uint8_t>(counter - last_);
  if (ahead == 0) return CounterVerdict::kRepeated;
  if (ahead > kMaxCounterJump) return CounterVerdict::kStale;
  lost_ += static_cast<std::uint32_t>(ahead - 1);
  last_ = counter;
  return CounterVerdict::kAccepted;
}

}  // namespace mrd::protocol
