// The Segway RMP decoders: USB frames taken off a receive buffer (the USB
// link), each CAN frame decoded as status, motor status and motion, as the
// driver and the simulator do.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "horopter/core/error.hpp"
#include "horopter/hardware/rmp_protocol.hpp"

namespace rmp = horopter::hw::rmp;

namespace {

void decode(const horopter::hw::CanFrame& frame, rmp::Status& status) {
  const rmp::Scaling scaling = rmp::scalingRmp200();
  try {
    (void)rmp::decodeStatusFrame(frame, scaling, status);
  } catch (const horopter::Error&) {
  }
  (void)rmp::decodeMotorStatus(frame);
  try {
    (void)rmp::countsToVelocity(rmp::decodeMotion(frame), scaling);
  } catch (const horopter::Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rmp::Status status;
  // The USB link's framing.
  std::span<const std::uint8_t> buffer(data, size);
  while (!buffer.empty()) {
    const rmp::UsbParse r = rmp::parseUsbFromRmp(buffer);
    if (r.consumed > buffer.size()) std::abort();
    if (r.outcome == rmp::UsbOutcome::kFrame) decode(r.frame, status);
    if (r.consumed == 0) break;
    buffer = buffer.subspan(r.consumed);
  }
  // The same bytes as raw CAN frames (SocketCAN): 2-byte id, length, 8 data bytes.
  for (std::size_t i = 0; i + 11 <= size; i += 11) {
    horopter::hw::CanFrame frame;
    frame.id = static_cast<std::uint32_t>(data[i] | (data[i + 1] << 8)) & 0x7FF;
    frame.length = data[i + 2];
    for (std::size_t k = 0; k < 8; ++k)
      frame.data[k] = data[i + 3 + k];
    decode(frame, status);
  }
  return 0;
}
