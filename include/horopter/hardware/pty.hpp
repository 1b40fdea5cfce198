// A pseudo-terminal pair (openpty): the simulated device holds the master,
// the real driver opens the slave's path through SerialPort, so every byte
// crosses a real tty exactly as with a USB-serial adapter.
#pragma once

#include "horopter/core/export.hpp"

#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace horopter::hw {

class HOROPTER_API PseudoTerminal {
 public:
  PseudoTerminal();  // throws horopter::Error if no pty can be made
  ~PseudoTerminal();
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;

  const std::string& slavePath() const { return slavePath_; }
  // The device side. read() returns empty on timeout and after close.
  void write(std::span<const std::uint8_t> bytes);
  std::vector<std::uint8_t> read(std::size_t maxBytes, std::chrono::milliseconds timeout);
  // Hangs up the master: the driver's next read or write fails (a pulled cable).
  void closeMaster();
  bool masterOpen() const { return master_ >= 0; }

 private:
  int master_ = -1;
  int slave_ = -1;  // kept open so the pty survives between driver opens
  std::string slavePath_;
};

}  // namespace horopter::hw
