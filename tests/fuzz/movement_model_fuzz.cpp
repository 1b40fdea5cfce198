// MovementModel::parse (what MovementModel::load reads) on arbitrary text.
#include <cstddef>
#include <cstdint>
#include <string>

#include "horopter/core/error.hpp"
#include "horopter/movement/movement_classifier.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const horopter::MovementModel model = horopter::MovementModel::parse(text, "fuzz.hmm");
    // A model that parses serializes and parses back.
    (void)horopter::MovementModel::parse(model.serialize(), "fuzz-again.hmm");
  } catch (const horopter::Error&) {
  }
  return 0;
}
