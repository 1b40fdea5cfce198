// CAN over the RMP's USB framing: see include/horopter/hardware/can_transports.hpp.
#include "horopter/hardware/can_transports.hpp"
#include "horopter/hardware/rmp_protocol.hpp"

namespace horopter::hw {

RmpUsbCan::RmpUsbCan(std::unique_ptr<ByteTransport> bytes) : bytes_(std::move(bytes)) {}

void RmpUsbCan::send(const CanFrame& frame) {
  const auto packet = rmp::encodeUsbToRmp(frame);
  bytes_->write(packet);
}

bool RmpUsbCan::receive(CanFrame& frame, std::chrono::milliseconds timeout) {
  bool readOnce = false;
  while (true) {
    const rmp::UsbParse r = rmp::parseUsbFromRmp(buffer_);
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(r.consumed));
    if (r.outcome == rmp::UsbOutcome::kCorrupt) {
      ++corrupt_;
      continue;
    }
    if (r.outcome == rmp::UsbOutcome::kFrame) {
      if (r.channel == 0xBB) continue;  // channel B: libsegwayrmp ignores it too
      frame = r.frame;
      return true;
    }
    if (readOnce) return false;
    const auto more = bytes_->read(256, timeout);
    readOnce = true;
    if (more.empty()) return false;
    buffer_.insert(buffer_.end(), more.begin(), more.end());
  }
}

}  // namespace horopter::hw
