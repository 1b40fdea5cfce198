#include "default_input.hpp"

#include <cstdlib>
#include <filesystem>
#include <vector>

#include "horopter/core/error.hpp"

namespace horopter::cli {

StereoPairFiles defaultStereoPair() {
  std::vector<std::string> folders;
  if (const char* data = std::getenv("HOROPTER_DATA")) folders.emplace_back(data);
  folders.emplace_back("/usr/share/doc/opencv-doc/examples/data");
  folders.emplace_back("../shared/data/middlebury/aloe");
  folders.emplace_back("../../shared/data/middlebury/aloe");
  std::string tried;
  for (const auto& folder : folders) {
    const std::string left = folder + "/aloeL.jpg";
    const std::string right = folder + "/aloeR.jpg";
    if (std::filesystem::is_regular_file(left) && std::filesystem::is_regular_file(right))
      return {left, right, folder + "/aloeGT.png", 1.0};
    tried += "\n  " + folder;
  }
  throw Error("the default stereo pair (aloeL.jpg, aloeR.jpg) was not found in:" + tried +
              "\ninstall it with: sudo apt-get install opencv-doc, or set HOROPTER_DATA to a "
              "folder that holds it, or pass LEFT RIGHT to horopter disparity");
}

}  // namespace horopter::cli
