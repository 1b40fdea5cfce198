// The table of backends. A new backend adds one entry here, and the
// conformance test and the benches pick it up from this list.
#include <cstdlib>
#include <string>

#include "horopter/backend.hpp"
#include "horopter/error.hpp"
#include "horopter_mask/horopter_mask.hpp"
#include "median/median.hpp"
#include "occlusion/occlusion.hpp"
#include "prefilter/prefilter.hpp"
#include "sad/sad.hpp"

namespace horopter {

namespace {

Backend makeScalar() {
  Backend b;
  b.name = "scalar";
  b.description = "portable C++ reference (the specification), one thread";
  b.available = true;
  b.kernels.prefilterXSobel = scalar::prefilterXSobel;
  b.kernels.matchBlocks = scalar::matchBlocks;
  b.kernels.leftRightCheck = scalar::leftRightCheck;
  b.kernels.filterSpeckles = scalar::filterSpeckles;
  b.kernels.medianFilter = scalar::medianFilter;
  b.kernels.horopterMask = scalar::horopterMask;
  return b;
}

std::string knownNames() {
  std::string names = "auto";
  for (const Backend* b : registeredBackends())
    names += ", " + b->name;
  return names;
}

}  // namespace

const Backend& scalarBackend() {
  static const Backend scalar = makeScalar();
  return scalar;
}

const std::vector<const Backend*>& registeredBackends() {
  static const std::vector<const Backend*> all = {&scalarBackend()};
  return all;
}

const Backend& findBackend(const std::string& name) {
  std::string wanted = name;
  if (wanted == "auto") {
    const char* forced = std::getenv("HOROPTER_BACKEND");
    if (forced != nullptr && *forced != '\0' && std::string(forced) != "auto") wanted = forced;
  }
  if (wanted == "auto") {
    const Backend* best = &scalarBackend();
    for (const Backend* b : registeredBackends()) {
      if (b->available) best = b;
    }
    return *best;
  }
  for (const Backend* b : registeredBackends()) {
    if (b->name != wanted) continue;
    if (!b->available)
      throw Error("backend '" + wanted +
                  "' is not available on this machine: " + b->unavailableReason);
    return *b;
  }
  throw Error("unknown backend '" + wanted + "': use one of " + knownNames());
}

}  // namespace horopter
