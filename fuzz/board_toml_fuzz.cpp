// libFuzzer target for the board file parser (TOML). Properties:
//  - no crash, no undefined behaviour; every refusal is a BoardConfigError
//    whose message starts with the file's name;
//  - an accepted board has a control period > 0.
#include <cstddef>
#include <cstdint>
#include <string>

#include "firmware/app/board_config.hpp"

namespace {

void require(bool ok) {
  if (!ok) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const mrd::app::BoardConfig c = mrd::app::parse_board_config(text, "fuzz.toml");
    require(c.period_us > 0);
  } catch (const mrd::app::BoardConfigError& e) {
    require(std::string(e.what()).rfind("fuzz.toml:", 0) == 0);
  }
  return 0;
}
