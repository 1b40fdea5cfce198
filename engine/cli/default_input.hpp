// The built-in default input: a real stereo pair shipped by Debian's
// opencv-doc package (Middlebury's Aloe), or the same files in ../shared/data.
#pragma once

#include <string>

namespace horopter::cli {

struct StereoPairFiles {
  std::string left, right, groundTruth;
  double groundTruthScale = 1;
};

// The first location that holds the pair: $HOROPTER_DATA/aloe*, opencv-doc's
// examples, then shared/data beside or above the working folder. Throws
// horopter::Error naming the places looked at when none does.
StereoPairFiles defaultStereoPair();

}  // namespace horopter::cli
