// The CAN transports: SocketCAN (Linux can0, can1, ...), the Segway RMP's USB
// framing over a byte stream (/dev/ttyUSB*), and an in-process bus joining a
// driver to a simulated device (virtual CAN interfaces are not available on
// every machine; this one always is).
#pragma once

#include "horopter/core/export.hpp"

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>

#include "horopter/hardware/transport.hpp"

namespace horopter::hw {

class HOROPTER_API SocketCan final : public CanTransport {
 public:
  // Throws horopter::Error when the interface does not exist or is down.
  explicit SocketCan(const std::string& interfaceName);
  ~SocketCan() override;
  SocketCan(const SocketCan&) = delete;
  SocketCan& operator=(const SocketCan&) = delete;
  void send(const CanFrame& frame) override;
  bool receive(CanFrame& frame, std::chrono::milliseconds timeout) override;
  std::string describe() const override { return "socketcan:" + name_; }

 private:
  std::string name_;
  int fd_ = -1;
};

// CAN frames carried in the RMP's 18-byte USB packets over a ByteTransport
// (see rmp_protocol.hpp). Corrupt packets are dropped and counted.
class HOROPTER_API RmpUsbCan final : public CanTransport {
 public:
  explicit RmpUsbCan(std::unique_ptr<ByteTransport> bytes);
  void send(const CanFrame& frame) override;
  bool receive(CanFrame& frame, std::chrono::milliseconds timeout) override;
  std::string describe() const override { return "rmp-usb:" + bytes_->describe(); }
  long corruptPackets() const { return corrupt_; }

 private:
  std::unique_ptr<ByteTransport> bytes_;
  std::vector<std::uint8_t> buffer_;
  long corrupt_ = 0;
};

// Two endpoints of one in-process bus: what one sends the other receives.
// Either side can be cut (disconnect()): both then throw LinkError.
class HOROPTER_API InProcessCanBus {
 public:
  InProcessCanBus();
  CanTransport& hostSide() { return *host_; }
  CanTransport& deviceSide() { return *device_; }
  // Endpoints that can be handed to a driver as unique_ptr (they forward to this bus,
  // which must outlive them).
  std::unique_ptr<CanTransport> takeHostSide();
  void disconnect();
  bool connected() const;

 private:
  struct Shared {
    mutable std::mutex mutex;
    std::condition_variable changed;
    std::deque<CanFrame> toDevice, toHost;
    bool cut = false;
  };
  class Endpoint;
  std::shared_ptr<Shared> shared_;
  std::unique_ptr<CanTransport> host_, device_;
};

}  // namespace horopter::hw
