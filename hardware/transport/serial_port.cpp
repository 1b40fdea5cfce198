// termios serial port: see include/horopter/hardware/serial_port.hpp.
#include "horopter/hardware/serial_port.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace horopter::hw {

unsigned baudConstant(int baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    case 460800:
      return B460800;
    case 921600:
      return B921600;
    case 1000000:
      return B1000000;
    case 2000000:
      return B2000000;
    case 3000000:
      return B3000000;
    case 4000000:
      return B4000000;
    default:
      throw Error("baud rate " + std::to_string(baud) +
                  " is not a standard rate: use 9600, 19200, 38400, 57600, 115200, 230400, "
                  "460800, 921600, 1000000, 2000000, 3000000 or 4000000");
  }
}

SerialPort::SerialPort(const std::string& path, const SerialOptions& options) : path_(path) {
  const unsigned speed = baudConstant(options.baud);
  if (options.stopBits != 1 && options.stopBits != 2)
    throw Error("stop bits must be 1 or 2, got " + std::to_string(options.stopBits));
  fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    const int e = errno;
    std::string hint;
    if (e == ENOENT) hint = ": no such device (is it plugged in? try --sim to use the simulator)";
    if (e == EACCES) hint = ": permission denied (add yourself to the dialout group)";
    throw Error("cannot open serial port " + path + hint + " [" + std::strerror(e) + "]");
  }
  termios tio{};
  if (::tcgetattr(fd_, &tio) != 0) {
    const int e = errno;
    ::close(fd_);
    fd_ = -1;
    throw Error(path + " is not a serial port (tcgetattr: " + std::strerror(e) + ")");
  }
  ::cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~(PARENB | PARODD | CSTOPB);
  if (options.parity == Parity::kEven) tio.c_cflag |= PARENB;
  if (options.parity == Parity::kOdd) tio.c_cflag |= PARENB | PARODD;
  if (options.stopBits == 2) tio.c_cflag |= CSTOPB;
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  ::cfsetispeed(&tio, speed);
  ::cfsetospeed(&tio, speed);
  if (::tcsetattr(fd_, TCSANOW, &tio) != 0) {
    const int e = errno;
    ::close(fd_);
    fd_ = -1;
    throw Error("cannot configure " + path + " (tcsetattr: " + std::strerror(e) + ")");
  }
  ::tcflush(fd_, TCIOFLUSH);
}

SerialPort::~SerialPort() {
  if (fd_ >= 0) ::close(fd_);
}

void SerialPort::write(std::span<const std::uint8_t> bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      pollfd p{fd_, POLLOUT, 0};
      if (::poll(&p, 1, 100) <= 0 || (p.revents & (POLLERR | POLLHUP)))
        throw LinkError("write to " + path_ + " stalled or the device went away");
      continue;
    }
    throw LinkError("write to " + path_ + " failed: " + std::strerror(errno));
  }
}

std::vector<std::uint8_t> SerialPort::read(std::size_t maxBytes,
                                           std::chrono::milliseconds timeout) {
  std::vector<std::uint8_t> out;
  pollfd p{fd_, POLLIN, 0};
  int r;
  do {
    r = ::poll(&p, 1, static_cast<int>(timeout.count()));
  } while (r < 0 && errno == EINTR);
  if (r < 0) throw LinkError("poll on " + path_ + " failed: " + std::strerror(errno));
  if (r == 0) return out;
  if ((p.revents & (POLLHUP | POLLERR)) && !(p.revents & POLLIN))
    throw LinkError(path_ + ": the device hung up (disconnected)");
  out.resize(maxBytes);
  const ssize_t n = ::read(fd_, out.data(), maxBytes);
  if (n < 0) {
    if (errno == EAGAIN || errno == EINTR) {
      out.clear();
      return out;
    }
    throw LinkError("read from " + path_ + " failed: " + std::strerror(errno) +
                    " (device disconnected?)");
  }
  if (n == 0) throw LinkError(path_ + ": end of file (device disconnected)");
  out.resize(static_cast<std::size_t>(n));
  return out;
}

void SerialPort::discardInput() {
  ::tcflush(fd_, TCIFLUSH);
}

}  // namespace horopter::hw
