// Left/right image lists from two glob patterns, paired by the part the
// wildcards matched ('DIR/left*.jpg' + 'DIR/right*.jpg': left07.jpg pairs with
// right07.jpg). Used by `horopter calibrate` and `horopter rectify`.
#pragma once

#include <string>
#include <vector>

namespace horopter {

struct ImagePairFiles {
  std::string left, right;
  std::string name;  // "left07.jpg + right07.jpg"
};

struct PairedFiles {
  std::vector<ImagePairFiles> pairs;  // in the order of the left files
  std::vector<std::string> unpaired;  // files whose partner is missing
};

// A pattern without a wildcard is one file. Throws horopter::Error when a
// pattern matches nothing or no file has a partner.
PairedFiles pairImageFiles(const std::string& leftPattern, const std::string& rightPattern);

}  // namespace horopter
