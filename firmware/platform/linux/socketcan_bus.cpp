#include "firmware/platform/linux/socketcan_bus.hpp"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace mrd::posix {
namespace {

[[noreturn]] void fail(const std::string& interface, const char* what, int err) {
  std::string msg = "CAN interface '" + interface + "': " + what + ": " + std::strerror(err);
  if (err == EAFNOSUPPORT) msg += " (this kernel has no SocketCAN: load the can and can-raw modules)";
  if (err == ENODEV) msg += " (no such interface: see `ip link`)";
  throw std::runtime_error(msg);
}

}  // namespace

hal::BusState bus_state_after_error(std::uint32_t err_class, std::uint8_t crtl, hal::BusState now) noexcept {
  if (err_class & CAN_ERR_BUSOFF) return hal::BusState::kBusOff;
  if (err_class & CAN_ERR_RESTARTED) return hal::BusState::kActive;
  if (err_class & CAN_ERR_CRTL) {
    if (crtl & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) return hal::BusState::kPassive;
    if (crtl & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) return hal::BusState::kWarning;
    if (crtl & CAN_ERR_CRTL_ACTIVE) return hal::BusState::kActive;
  }
  return now;
}

SocketCanBus::SocketCanBus(const std::string& interface, std::span<const hal::CanFilter> filters) {
  if (interface.empty() || interface.size() >= IFNAMSIZ) fail(interface, "interface name", EINVAL);
  fd_ = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd_ < 0) fail(interface, "socket(PF_CAN, SOCK_RAW, CAN_RAW)", errno);

  std::vector<can_filter> raw;
  raw.reserve(filters.size());
  for (const auto& f : filters) {
    // Standard data frames only: the EFF and RTR flags take part in the match.
    raw.push_back({f.id & CAN_SFF_MASK, (f.mask & CAN_SFF_MASK) | CAN_EFF_FLAG | CAN_RTR_FLAG});
  }
  const auto filter_bytes = static_cast<socklen_t>(raw.size() * sizeof(can_filter));
  const can_err_mask_t err_mask = CAN_ERR_CRTL | CAN_ERR_BUSOFF | CAN_ERR_RESTARTED | CAN_ERR_TX_TIMEOUT;
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, interface.c_str(), IFNAMSIZ - 1);
  sockaddr_can addr{};
  int err = 0;
  const char* what = nullptr;
  if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, raw.empty() ? nullptr : raw.data(), filter_bytes) < 0) {
    what = "setsockopt(CAN_RAW_FILTER)";
  } else if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) < 0) {
    what = "setsockopt(CAN_RAW_ERR_FILTER)";
  } else if (::ioctl(fd_, SIOCGIFINDEX, &ifr) < 0) {
    what = "ioctl(SIOCGIFINDEX)";
  } else {
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifr.ifr_ifindex;
    if (::bind(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) < 0) what = "bind";
  }
  if (what) {
    err = errno;
    ::close(fd_);
    fd_ = -1;
    fail(interface, what, err);
  }
}

SocketCanBus::~SocketCanBus() {
  if (fd_ >= 0) ::close(fd_);
}

hal::CanResult SocketCanBus::send(const hal::CanFrame& frame) noexcept {
  if (frame.dlc > CAN_MAX_DLEN) return hal::CanResult::kError;
  can_frame cf{};
  cf.can_id = frame.extended ? ((frame.id & CAN_EFF_MASK) | CAN_EFF_FLAG) : (frame.id & CAN_SFF_MASK);
  if (frame.remote) cf.can_id |= CAN_RTR_FLAG;
  cf.len = frame.dlc;
  std::memcpy(cf.data, frame.data.data(), frame.dlc);
  const ssize_t n = ::write(fd_, &cf, sizeof cf);
  if (n == static_cast<ssize_t>(sizeof cf)) return hal::CanResult::kOk;
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS)) return hal::CanResult::kWouldBlock;
  if (n < 0 && errno == ENETDOWN) state_ = hal::BusState::kBusOff;
  return hal::CanResult::kError;
}

hal::CanResult SocketCanBus::receive(hal::CanFrame& frame) noexcept {
  for (;;) {
    can_frame cf{};
    const ssize_t n = ::read(fd_, &cf, sizeof cf);
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK) return hal::CanResult::kWouldBlock;
      if (errno == EINTR) continue;
      ++read_errors_;
      return hal::CanResult::kError;
    }
    if (n != static_cast<ssize_t>(sizeof cf)) {
      ++read_errors_;
      continue;  // not a classic frame: skip it
    }
    if (cf.can_id & CAN_ERR_FLAG) {
      ++error_frames_;
      state_ = bus_state_after_error(cf.can_id & CAN_ERR_MASK, cf.data[1], state_);
      continue;
    }
    frame = hal::CanFrame{};
    frame.extended = (cf.can_id & CAN_EFF_FLAG) != 0;
    frame.remote = (cf.can_id & CAN_RTR_FLAG) != 0;
    frame.id = cf.can_id & (frame.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
    frame.dlc = cf.len > CAN_MAX_DLEN ? CAN_MAX_DLEN : cf.len;
    std::memcpy(frame.data.data(), cf.data, frame.dlc);
    // A frame received means the controller takes part in traffic again.
    if (state_ == hal::BusState::kBusOff) state_ = hal::BusState::kActive;
    return hal::CanResult::kOk;
  }
}

bool SocketCanBus::wait_readable(std::chrono::nanoseconds timeout) noexcept {
  pollfd p{fd_, POLLIN, 0};
  timespec ts{};
  const auto ns = timeout.count() < 0 ? 0 : timeout.count();
  ts.tv_sec = static_cast<time_t>(ns / 1000000000);
  ts.tv_nsec = static_cast<long>(ns % 1000000000);
  const int r = ::ppoll(&p, 1, &ts, nullptr);
  return r > 0 && (p.revents & POLLIN);
}

}  // namespace mrd::posix
