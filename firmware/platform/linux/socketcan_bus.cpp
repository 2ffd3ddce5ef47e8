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
#include <string>
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

SocketCanBus::SocketCanBus(const std::string& interface, std::span<const hal::CanFilter> filters)
    : SocketCanBus(interface, filters, false) {}

SocketCanBus::SocketCanBus(const std::string& interface, std::span<const hal::CanFilter> filters, bool can_fd)
    : fd_(can_fd) {
  if (interface.empty() || interface.size() >= IFNAMSIZ) fail(interface, "interface name", EINVAL);
  sock_ = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (sock_ < 0) fail(interface, "socket(PF_CAN, SOCK_RAW, CAN_RAW)", errno);

  std::vector<can_filter> raw;
  raw.reserve(filters.size());
  for (const auto& f : filters) {
    // Standard data frames only: the EFF and RTR flags take part in the match.
    raw.push_back({f.id & CAN_SFF_MASK, (f.mask & CAN_SFF_MASK) | CAN_EFF_FLAG | CAN_RTR_FLAG});
  }
  const auto filter_bytes = static_cast<socklen_t>(raw.size() * sizeof(can_filter));
  const int kOn = 1;
  const can_err_mask_t err_mask = CAN_ERR_CRTL | CAN_ERR_BUSOFF | CAN_ERR_RESTARTED | CAN_ERR_TX_TIMEOUT;
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, interface.c_str(), IFNAMSIZ - 1);
  ifreq mtu_ifr = ifr;  // SIOCGIFMTU writes over the union that holds the index
  sockaddr_can addr{};
  int err = 0;
  const char* what = nullptr;
  if (::setsockopt(sock_, SOL_CAN_RAW, CAN_RAW_FILTER, raw.empty() ? nullptr : raw.data(), filter_bytes) < 0) {
    what = "setsockopt(CAN_RAW_FILTER)";
  } else if (::setsockopt(sock_, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) < 0) {
    what = "setsockopt(CAN_RAW_ERR_FILTER)";
  } else if (::ioctl(sock_, SIOCGIFINDEX, &ifr) < 0) {
    what = "ioctl(SIOCGIFINDEX)";
  } else if (can_fd && ::setsockopt(sock_, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &kOn, sizeof kOn) < 0) {
    what = "setsockopt(CAN_RAW_FD_FRAMES) (a kernel without CAN FD)";
  } else if (can_fd && ::ioctl(sock_, SIOCGIFMTU, &mtu_ifr) < 0) {
    what = "ioctl(SIOCGIFMTU)";
  } else {
    if (can_fd && mtu_ifr.ifr_mtu != static_cast<int>(CANFD_MTU)) {
      const int mtu = mtu_ifr.ifr_mtu;
      ::close(sock_);
      sock_ = -1;
      throw std::runtime_error("CAN interface '" + interface + "': CAN FD asked for, but the interface is classic CAN only (MTU " +
                               std::to_string(mtu) + ", CAN FD needs " + std::to_string(CANFD_MTU) +
                               "): use a CAN FD controller, or for vcan `ip link set " + interface + " mtu 72`");
    }
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifr.ifr_ifindex;
    if (::bind(sock_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) < 0) what = "bind";
  }
  if (what) {
    err = errno;
    ::close(sock_);
    sock_ = -1;
    fail(interface, what, err);
  }
}

SocketCanBus::~SocketCanBus() {
  if (sock_ >= 0) ::close(sock_);
}

hal::CanResult SocketCanBus::send(const hal::CanFrame& frame) noexcept {
  if (frame.dlc > CAN_MAX_DLEN) return hal::CanResult::kError;
  can_frame cf{};
  cf.can_id = frame.extended ? ((frame.id & CAN_EFF_MASK) | CAN_EFF_FLAG) : (frame.id & CAN_SFF_MASK);
  if (frame.remote) cf.can_id |= CAN_RTR_FLAG;
  cf.len = frame.dlc;
  std::memcpy(cf.data, frame.data.data(), frame.dlc);
  const ssize_t n = ::write(sock_, &cf, sizeof cf);
  if (n == static_cast<ssize_t>(sizeof cf)) return hal::CanResult::kOk;
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS)) return hal::CanResult::kWouldBlock;
  if (n < 0 && errno == ENETDOWN) state_ = hal::BusState::kBusOff;
  return hal::CanResult::kError;
}

hal::CanResult SocketCanBus::read_frame(hal::CanFdFrame& out) noexcept {
  for (;;) {
    canfd_frame cf{};
    const ssize_t n = ::read(sock_, &cf, sizeof cf);
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK) return hal::CanResult::kWouldBlock;
      if (errno == EINTR) continue;
      ++read_errors_;
      return hal::CanResult::kError;
    }
    const bool is_fd = n == static_cast<ssize_t>(CANFD_MTU);
    if (n != static_cast<ssize_t>(CAN_MTU) && !is_fd) {
      ++read_errors_;
      continue;  // neither a classic nor an FD frame: skip it
    }
    if (cf.can_id & CAN_ERR_FLAG) {
      ++error_frames_;
      state_ = bus_state_after_error(cf.can_id & CAN_ERR_MASK, cf.data[1], state_);
      continue;
    }
    out = hal::CanFdFrame{};
    out.fd = is_fd;
    out.brs = is_fd && (cf.flags & CANFD_BRS) != 0;
    out.extended = (cf.can_id & CAN_EFF_FLAG) != 0;
    out.remote = !is_fd && (cf.can_id & CAN_RTR_FLAG) != 0;
    out.id = cf.can_id & (out.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
    const auto max_len = static_cast<std::uint8_t>(is_fd ? CANFD_MAX_DLEN : CAN_MAX_DLEN);
    out.len = cf.len > max_len ? max_len : cf.len;
    std::memcpy(out.data.data(), cf.data, out.len);
    // A frame received means the controller takes part in traffic again.
    if (state_ == hal::BusState::kBusOff) state_ = hal::BusState::kActive;
    return hal::CanResult::kOk;
  }
}

hal::CanResult SocketCanBus::receive(hal::CanFrame& frame) noexcept {
  for (;;) {
    hal::CanFdFrame f;
    const hal::CanResult r = read_frame(f);
    if (r != hal::CanResult::kOk) return r;
    if (f.fd) {
      ++fd_skipped_;
      continue;
    }
    frame = hal::as_classic(f);
    return hal::CanResult::kOk;
  }
}

hal::CanResult SocketCanBus::receive_fd(hal::CanFdFrame& frame) noexcept { return read_frame(frame); }

hal::CanResult SocketCanBus::send_fd(const hal::CanFdFrame& frame) noexcept {
  if (!frame.fd) {
    if (frame.len > CAN_MAX_DLEN) return hal::CanResult::kError;
    return send(hal::as_classic(frame));
  }
  if (!fd_ || !hal::valid_fd_length(frame.len)) return hal::CanResult::kError;
  canfd_frame cf{};
  cf.can_id = frame.extended ? ((frame.id & CAN_EFF_MASK) | CAN_EFF_FLAG) : (frame.id & CAN_SFF_MASK);
  cf.len = frame.len;
  cf.flags = frame.brs ? CANFD_BRS : 0;
#ifdef CANFD_FDF
  cf.flags |= CANFD_FDF;
#endif
  std::memcpy(cf.data, frame.data.data(), frame.len);
  const ssize_t n = ::write(sock_, &cf, CANFD_MTU);
  if (n == static_cast<ssize_t>(CANFD_MTU)) return hal::CanResult::kOk;
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS)) return hal::CanResult::kWouldBlock;
  if (n < 0 && errno == ENETDOWN) state_ = hal::BusState::kBusOff;
  return hal::CanResult::kError;
}

bool SocketCanBus::wait_readable(std::chrono::nanoseconds timeout) noexcept {
  pollfd p{sock_, POLLIN, 0};
  timespec ts{};
  const auto ns = timeout.count() < 0 ? 0 : timeout.count();
  ts.tv_sec = static_cast<time_t>(ns / 1000000000);
  ts.tv_nsec = static_cast<long>(ns % 1000000000);
  const int r = ::ppoll(&p, 1, &ts, nullptr);
  return r > 0 && (p.revents & POLLIN);
}

}  // namespace mrd::posix
