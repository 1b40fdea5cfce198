// openpty pair for the simulated devices: see include/horopter/hardware/pty.hpp.
#include "horopter/hardware/pty.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "horopter/core/error.hpp"

namespace horopter::hw {

PseudoTerminal::PseudoTerminal() {
  char name[256] = {};
  termios tio{};
  ::cfmakeraw(&tio);  // raw from the start: no echo, no line editing
  if (::openpty(&master_, &slave_, name, &tio, nullptr) != 0)
    throw Error(std::string("cannot create a pseudo-terminal (openpty): ") + std::strerror(errno));
  slavePath_ = name;
  ::fcntl(master_, F_SETFD, FD_CLOEXEC);
  ::fcntl(slave_, F_SETFD, FD_CLOEXEC);
  ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
}

PseudoTerminal::~PseudoTerminal() {
  closeMaster();
  if (slave_ >= 0) ::close(slave_);
}

void PseudoTerminal::closeMaster() {
  if (master_ >= 0) ::close(master_);
  master_ = -1;
  // Without the master the slave reads EIO; also close our own slave fd so the
  // driver sees a hang-up, not a silent line.
  if (slave_ >= 0) ::close(slave_);
  slave_ = -1;
}

void PseudoTerminal::write(std::span<const std::uint8_t> bytes) {
  std::size_t done = 0;
  while (master_ >= 0 && done < bytes.size()) {
    const ssize_t n = ::write(master_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
    } else if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
      pollfd p{master_, POLLOUT, 0};
      ::poll(&p, 1, 10);
    } else {
      return;  // the driver side is gone; a device just talks into the void
    }
  }
}

std::vector<std::uint8_t> PseudoTerminal::read(std::size_t maxBytes,
                                               std::chrono::milliseconds timeout) {
  std::vector<std::uint8_t> out;
  if (master_ < 0) return out;
  pollfd p{master_, POLLIN, 0};
  if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0 || !(p.revents & POLLIN)) return out;
  out.resize(maxBytes);
  const ssize_t n = ::read(master_, out.data(), maxBytes);
  out.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  return out;
}

}  // namespace horopter::hw
