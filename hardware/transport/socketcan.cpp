// SocketCAN raw socket: see include/horopter/hardware/can_transports.hpp.
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "horopter/hardware/can_transports.hpp"

namespace horopter::hw {

SocketCan::SocketCan(const std::string& interfaceName) : name_(interfaceName) {
  if (interfaceName.empty() || interfaceName.size() >= IFNAMSIZ)
    throw Error("CAN interface name '" + interfaceName + "' is empty or too long (e.g. can0)");
  fd_ = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (fd_ < 0)
    throw Error(std::string("cannot open a SocketCAN socket (is the can module loaded?): ") +
                std::strerror(errno));
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, interfaceName.c_str(), IFNAMSIZ - 1);
  if (::ioctl(fd_, SIOCGIFINDEX, &ifr) < 0) {
    const int e = errno;
    ::close(fd_);
    fd_ = -1;
    throw Error("no CAN interface '" + interfaceName + "' (" + std::strerror(e) +
                "): bring it up with `ip link set " + interfaceName +
                " up type can bitrate 500000`, or use --usb or --sim");
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifr.ifr_ifindex;
  if (::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) {
    const int e = errno;
    ::close(fd_);
    fd_ = -1;
    throw Error("cannot bind to CAN interface " + interfaceName + ": " + std::strerror(e));
  }
}

SocketCan::~SocketCan() {
  if (fd_ >= 0) ::close(fd_);
}

void SocketCan::send(const CanFrame& frame) {
  can_frame f{};
  f.can_id = frame.id & CAN_SFF_MASK;
  f.can_dlc = frame.length;
  std::memcpy(f.data, frame.data.data(), 8);
  if (::write(fd_, &f, sizeof f) != static_cast<ssize_t>(sizeof f))
    throw LinkError("CAN send on " + name_ + " failed: " + std::strerror(errno));
}

bool SocketCan::receive(CanFrame& frame, std::chrono::milliseconds timeout) {
  pollfd p{fd_, POLLIN, 0};
  const int r = ::poll(&p, 1, static_cast<int>(timeout.count()));
  if (r < 0 && errno != EINTR) throw LinkError("CAN poll on " + name_ + " failed");
  if (r <= 0) return false;
  can_frame f{};
  const ssize_t n = ::read(fd_, &f, sizeof f);
  if (n != static_cast<ssize_t>(sizeof f))
    throw LinkError("CAN read on " + name_ + " failed: " + std::strerror(errno));
  frame.id = f.can_id & CAN_SFF_MASK;
  frame.length = f.can_dlc > 8 ? 8 : f.can_dlc;
  std::memcpy(frame.data.data(), f.data, 8);
  return true;
}

}  // namespace horopter::hw
