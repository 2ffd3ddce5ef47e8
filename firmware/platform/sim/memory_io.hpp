#pragma once
/// In-memory discrete lines: outputs record their level and how often they
/// were written; inputs are set by the test (or the in-process board).

#include <array>
#include <cstdint>

#include "mrd/hal/digital_io.hpp"

namespace mrd::sim {

class MemoryIo final : public hal::DigitalIo {
 public:
  bool write(hal::OutputLine line, bool active) noexcept override {
    if (fail_) return false;
    auto& o = outputs_[static_cast<int>(line)];
    if (o.writes > 0 && o.level != active) ++o.changes;
    o.level = active;
    ++o.writes;
    return true;
  }
  bool read(hal::InputLine line, bool& active) noexcept override {
    if (fail_) return false;
    active = inputs_[static_cast<int>(line)];
    return true;
  }

  void set_input(hal::InputLine line, bool active) noexcept { inputs_[static_cast<int>(line)] = active; }
  bool output(hal::OutputLine line) const noexcept { return outputs_[static_cast<int>(line)].level; }
  std::uint64_t writes(hal::OutputLine line) const noexcept { return outputs_[static_cast<int>(line)].writes; }
  std::uint64_t changes(hal::OutputLine line) const noexcept { return outputs_[static_cast<int>(line)].changes; }
  /// Makes every read and write fail, as a removed GPIO chip would.
  void set_failing(bool fail) noexcept { fail_ = fail; }

 private:
  struct Output {
    bool level = false;
    std::uint64_t writes = 0;
    std::uint64_t changes = 0;
  };
  std::array<Output, hal::kOutputLineCount> outputs_{};
  std::array<bool, hal::kInputLineCount> inputs_{};
  bool fail_ = false;
};

}  // namespace mrd::sim
