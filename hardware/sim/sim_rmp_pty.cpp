// The simulated RMP behind its USB interface on a pseudo-terminal; see
// include/horopter/hardware/sim_rmp.hpp.
#include "horopter/hardware/sim_rmp.hpp"

#include <vector>

namespace horopter::hw {

namespace {

// The RMP's side of the USB framing: it reads host -> RMP packets from the
// pty's master and writes RMP -> host packets to it (RmpUsbCan, mirrored).
class RmpUsbDeviceSide final : public CanTransport {
 public:
  explicit RmpUsbDeviceSide(PseudoTerminal& pty) : pty_(pty) {}

  void send(const CanFrame& frame) override { pty_.write(rmp::encodeUsbFromRmp(frame)); }

  bool receive(CanFrame& frame, std::chrono::milliseconds timeout) override {
    bool readOnce = false;
    while (true) {
      const rmp::UsbParse r = rmp::parseUsbToRmp(buffer_);
      buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(r.consumed));
      if (r.outcome == rmp::UsbOutcome::kCorrupt) continue;  // a real RMP drops it too
      if (r.outcome == rmp::UsbOutcome::kFrame) {
        frame = r.frame;
        return true;
      }
      if (readOnce) return false;
      const auto more = pty_.read(256, timeout);
      readOnce = true;
      if (more.empty()) return false;
      buffer_.insert(buffer_.end(), more.begin(), more.end());
    }
  }

  std::string describe() const override { return "rmp-usb-device:" + pty_.slavePath(); }

 private:
  PseudoTerminal& pty_;
  std::vector<std::uint8_t> buffer_;
};

}  // namespace

SimRmpOnPty::SimRmpOnPty(SimRmpOptions options)
    : usb_(std::make_unique<RmpUsbDeviceSide>(pty_)),
      rmp_(std::make_unique<SimRmp>(*usb_, options)) {}

// The simulator's thread stops before the transport and the pty it uses go.
SimRmpOnPty::~SimRmpOnPty() {
  rmp_.reset();
}

}  // namespace horopter::hw
