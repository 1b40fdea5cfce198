// The DYNAMIXEL Protocol 2.0 parser as the driver uses it: packets taken off
// the front of a receive buffer until it needs more, each packet's status
// fields read. parsePacket never throws; toStatus throws horopter::Error for
// a packet that is not a status.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "horopter/core/error.hpp"
#include "horopter/hardware/dynamixel_protocol.hpp"

namespace dxl = horopter::hw::dxl;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::span<const std::uint8_t> buffer(data, size);
  while (!buffer.empty()) {
    const dxl::ParseResult r = dxl::parsePacket(buffer);
    if (r.consumed > buffer.size()) std::abort();  // consumed past the end
    if (r.outcome == dxl::ParseOutcome::kPacket) {
      try {
        const dxl::Status s = dxl::toStatus(r.packet);
        (void)dxl::describeError(s.error);
        if (s.data.size() <= 4) (void)dxl::fromLittleEndian(s.data);
      } catch (const horopter::Error&) {
      }
    }
    if (r.consumed == 0) break;  // kNeedMore with nothing to drop
    buffer = buffer.subspan(r.consumed);
  }
  return 0;
}
