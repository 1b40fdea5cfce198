// The FLIR PTU reply parser: lines taken off a receive buffer, each parsed as
// a reply and read as a number and an integer, as the driver does.
#include <cstddef>
#include <cstdint>
#include <string>

#include "horopter/core/error.hpp"
#include "horopter/hardware/ptu_protocol.hpp"

namespace ptu = horopter::hw::ptu;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string buffer(reinterpret_cast<const char*>(data), size);
  while (const auto line = ptu::takeLine(buffer)) {
    try {
      const ptu::Reply reply = ptu::parseReply(*line);
      try {
        (void)ptu::parseNumber(reply);
      } catch (const horopter::Error&) {
      }
      (void)ptu::parseInteger(reply);
    } catch (const horopter::Error&) {
    }
  }
  return 0;
}
