#include "quiet_png.hpp"

#include <cstring>

namespace horopter {

namespace {

bool isPng(const std::vector<std::uint8_t>& bytes) {
  static const std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  return bytes.size() >= 8 && std::memcmp(bytes.data(), kSignature, 8) == 0;
}

}  // namespace

std::vector<std::uint8_t> withoutIccpChunks(std::vector<std::uint8_t> bytes) {
  if (!isPng(bytes)) return bytes;
  // Chunks: 4-byte big-endian length, 4-byte type, data, 4-byte CRC.
  std::vector<std::uint8_t> out(bytes.begin(), bytes.begin() + 8);
  out.reserve(bytes.size());
  std::size_t pos = 8;
  while (pos < bytes.size()) {
    if (bytes.size() - pos < 12) return bytes;  // truncated: let the decoder say so
    const std::size_t length = (std::size_t{bytes[pos]} << 24) |
                               (std::size_t{bytes[pos + 1]} << 16) |
                               (std::size_t{bytes[pos + 2]} << 8) | std::size_t{bytes[pos + 3]};
    if (length > bytes.size() - pos - 12) return bytes;
    const std::size_t end = pos + 12 + length;
    if (std::memcmp(bytes.data() + pos + 4, "iCCP", 4) != 0)
      out.insert(out.end(), bytes.begin() + static_cast<std::ptrdiff_t>(pos),
                 bytes.begin() + static_cast<std::ptrdiff_t>(end));
    pos = end;
  }
  return out;
}

}  // namespace horopter
