// libFuzzer target for the CAN decoder. Any frame (id, flags, DLC 0..15,
// bytes) goes to every decoder with every sender node id. Properties:
//  - no crash, no undefined behaviour, no read outside the frame;
//  - a frame a decoder accepts re-encodes to the very same identifier and
//    bytes (the codec is a bijection on valid frames), so nothing the decoder
//    lets through can be misread;
//  - the counter check never accepts a repeat of the last accepted counter.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "mrd/protocol/codec.hpp"

namespace {

using namespace mrd;

void require(bool ok) {
  if (!ok) __builtin_trap();
}

template <class M>
void round_trip(const hal::CanFrame& f, std::uint8_t sender) {
  M m{};
  if (protocol::decode(f, sender, m) != protocol::DecodeError::kOk) return;
  hal::CanFrame g;
  require(protocol::encode(m, sender, g));
  require(g.id == f.id && g.dlc == f.dlc && !g.extended && !g.remote);
  require(std::memcmp(g.data.data(), f.data.data(), 8) == 0);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return 0;
  hal::CanFrame f;
  f.id = static_cast<std::uint32_t>(data[0] | (data[1] << 8)) & 0x7FFu;
  f.extended = (data[2] & 0x01u) != 0;
  f.remote = (data[2] & 0x02u) != 0;
  f.dlc = static_cast<std::uint8_t>(data[2] >> 4);  // 0..15: lengths a bad peer could claim
  const std::size_t n = size - 3 < 8 ? size - 3 : 8;
  std::memcpy(f.data.data(), data + 3, n);
  // Half the inputs get a correct CRC so that the fuzzer reaches the field checks.
  if ((data[2] & 0x04u) != 0) f.data[7] = protocol::frame_crc(f.id, f.data);

  for (std::uint8_t sender = 0; sender <= 16; ++sender) {
    round_trip<protocol::CurrentCommand>(f, sender);
    round_trip<protocol::DriveStatus>(f, sender);
    round_trip<protocol::DaqMotion>(f, sender);
    round_trip<protocol::DaqAccel>(f, sender);
    round_trip<protocol::MixingCommand>(f, sender);
    round_trip<protocol::MixingStatus>(f, sender);
    round_trip<protocol::ControllerStatus>(f, sender);
    round_trip<protocol::SimCoilState>(f, sender);
    round_trip<protocol::SimCoilDrive>(f, sender);
  }

  protocol::CounterCheck c;
  for (std::size_t i = 0; i < size; ++i) {
    const std::uint8_t last = c.last();
    const bool synced = c.synced();
    const protocol::CounterVerdict v = c.check(data[i]);
    if (synced && data[i] == last) require(v == protocol::CounterVerdict::kRepeated);
  }
  return 0;
}
