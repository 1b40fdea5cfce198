// A serial port through termios: raw 8-bit bytes, a chosen baud rate and
// parity, reads that wait with poll() up to a timeout. Also opens the slave
// side of a pseudo-terminal (the simulated devices' wire).
#pragma once

#include "horopter/core/export.hpp"

#include <string>

#include "horopter/hardware/transport.hpp"

namespace horopter::hw {

enum class Parity { kNone, kEven, kOdd };

struct HOROPTER_API SerialOptions {
  int baud = 57600;  // 9600 .. 4000000, one of the standard termios rates
  Parity parity = Parity::kNone;
  int stopBits = 1;  // 1 or 2
};

class HOROPTER_API SerialPort final : public ByteTransport {
 public:
  // Throws horopter::Error naming the path and the reason (missing device,
  // permission: "add yourself to the dialout group", unsupported baud).
  SerialPort(const std::string& path, const SerialOptions& options = {});
  ~SerialPort() override;
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  void write(std::span<const std::uint8_t> bytes) override;
  std::vector<std::uint8_t> read(std::size_t maxBytes, std::chrono::milliseconds timeout) override;
  void discardInput() override;
  std::string describe() const override { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

// The termios speed constant for a baud rate; throws for a non-standard rate.
HOROPTER_API unsigned baudConstant(int baud);

}  // namespace horopter::hw
