// Transports: how bytes and CAN frames reach a device. Protocols (pure
// functions) and drivers (state machines on their own thread) sit on top of
// these two interfaces, so every driver runs unchanged against a real port,
// a pseudo-terminal with a simulated device, or a scripted fake.
#pragma once

#include "horopter/core/export.hpp"

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "horopter/core/error.hpp"

namespace horopter::hw {

// The link itself failed (device unplugged, port closed, interface down):
// distinct from a corrupt or missing reply, which drivers retry.
class HOROPTER_API LinkError : public Error {
 public:
  explicit LinkError(const std::string& what) : Error(what) {}
};

// A byte stream: a serial port, a pseudo-terminal, a scripted fake.
class HOROPTER_API ByteTransport {
 public:
  virtual ~ByteTransport() = default;
  // Writes every byte or throws LinkError.
  virtual void write(std::span<const std::uint8_t> bytes) = 0;
  // Waits at most `timeout` for data and returns what arrived (at most
  // `maxBytes`); empty on timeout. Throws LinkError when the link is gone.
  virtual std::vector<std::uint8_t> read(std::size_t maxBytes,
                                         std::chrono::milliseconds timeout) = 0;
  // Discards input not read yet (stale replies before a new request).
  virtual void discardInput() = 0;
  virtual std::string describe() const = 0;
};

// One classic CAN 2.0A frame (11-bit identifier, up to 8 data bytes).
struct HOROPTER_API CanFrame {
  std::uint32_t id = 0;
  std::uint8_t length = 8;
  std::array<std::uint8_t, 8> data{};
  bool operator==(const CanFrame&) const = default;
};

// A CAN bus endpoint: SocketCAN, the RMP's USB framing on a serial device,
// or an in-process bus shared with a simulated device.
class HOROPTER_API CanTransport {
 public:
  virtual ~CanTransport() = default;
  // Sends one frame or throws LinkError.
  virtual void send(const CanFrame& frame) = 0;
  // Waits at most `timeout` for one frame; false on timeout. Throws LinkError
  // when the link is gone.
  virtual bool receive(CanFrame& frame, std::chrono::milliseconds timeout) = 0;
  virtual std::string describe() const = 0;
};

}  // namespace horopter::hw
