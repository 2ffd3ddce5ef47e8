// SocketCAN error frames → bus state (the pure mapping; the socket itself is
// exercised on a real kernel by the emulated-board test).
#include <gtest/gtest.h>

#include <linux/can/error.h>

#include "firmware/platform/linux/socketcan_bus.hpp"

namespace mrd::posix {
namespace {

using hal::BusState;

TEST(SocketCanErrors, BusOffWins) {
  EXPECT_EQ(bus_state_after_error(CAN_ERR_BUSOFF | CAN_ERR_CRTL, CAN_ERR_CRTL_TX_WARNING, BusState::kActive),
            BusState::kBusOff);
}

TEST(SocketCanErrors, ControllerLevels) {
  EXPECT_EQ(bus_state_after_error(CAN_ERR_CRTL, CAN_ERR_CRTL_RX_WARNING, BusState::kActive), BusState::kWarning);
  EXPECT_EQ(bus_state_after_error(CAN_ERR_CRTL, CAN_ERR_CRTL_TX_PASSIVE, BusState::kWarning), BusState::kPassive);
  EXPECT_EQ(bus_state_after_error(CAN_ERR_CRTL, CAN_ERR_CRTL_ACTIVE, BusState::kPassive), BusState::kActive);
}

TEST(SocketCanErrors, RestartReturnsToActive) {
  EXPECT_EQ(bus_state_after_error(CAN_ERR_RESTARTED, 0, BusState::kBusOff), BusState::kActive);
}

TEST(SocketCanErrors, OtherErrorsKeepTheState) {
  EXPECT_EQ(bus_state_after_error(CAN_ERR_PROT, 0, BusState::kPassive), BusState::kPassive);
  EXPECT_EQ(bus_state_after_error(CAN_ERR_CRTL, CAN_ERR_CRTL_RX_OVERFLOW, BusState::kWarning), BusState::kWarning);
}

TEST(SocketCanBus, NamesTheInterfaceWhenItCannotOpen) {
  // The build machine has no CAN interface called this (and often no PF_CAN at all).
  try {
    SocketCanBus bus("mrd-nonexistent0", {});
    FAIL() << "opened a nonexistent interface";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("CAN interface 'mrd-nonexistent0'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mrd::posix
