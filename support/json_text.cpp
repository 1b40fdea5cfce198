// See json_text.hpp.
#include "json_text.hpp"

#include <cmath>

namespace horopter::detail {

Json jsonNumber(double v, int decimals) {
  if (!std::isfinite(v)) return nullptr;
  if (decimals < 0) return v;
  const double scale = std::pow(10.0, decimals);
  const double rounded = std::round(v * scale) / scale;
  return std::isfinite(rounded) ? rounded : v;  // a huge v: as is
}

std::string jsonText(const Json& document) {
  return document.dump(-1, ' ', false, Json::error_handler_t::replace);
}

}  // namespace horopter::detail
