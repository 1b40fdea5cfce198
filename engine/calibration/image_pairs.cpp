#include "calibration/image_pairs.hpp"

#include <glob.h>

#include <filesystem>
#include <map>

#include "horopter/core/error.hpp"

namespace horopter {

namespace {

std::vector<std::string> expand(const std::string& pattern, const char* side) {
  glob_t g{};
  const int rc = ::glob(pattern.c_str(), 0, nullptr, &g);
  std::vector<std::string> files;
  if (rc == 0)
    for (std::size_t i = 0; i < g.gl_pathc; ++i)
      files.emplace_back(g.gl_pathv[i]);
  globfree(&g);
  if (files.empty())
    throw Error(std::string("no file matches --") + side + " '" + pattern +
                "': quote the pattern so the shell passes it on, e.g. --" + side + " 'DIR/" + side +
                "*.jpg'");
  return files;  // glob sorts
}

// The part of `path` that the wildcards of `pattern` matched: the path without
// the pattern's literal prefix (up to the first wildcard) and suffix (after
// the last one).
std::string wildcardPart(const std::string& pattern, const std::string& path) {
  const std::size_t first = pattern.find_first_of("*?[");
  if (first == std::string::npos) return {};
  const std::size_t last = pattern.find_last_of("*?]");
  const std::size_t suffix = pattern.size() - last - 1;
  if (path.size() < first + suffix) return path;
  return path.substr(first, path.size() - first - suffix);
}

std::string baseName(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

}  // namespace

PairedFiles pairImageFiles(const std::string& leftPattern, const std::string& rightPattern) {
  const std::vector<std::string> left = expand(leftPattern, "left");
  const std::vector<std::string> right = expand(rightPattern, "right");
  std::map<std::string, std::string> rightByKey;
  for (const std::string& r : right)
    rightByKey[wildcardPart(rightPattern, r)] = r;
  PairedFiles out;
  for (const std::string& l : left) {
    const auto it = rightByKey.find(wildcardPart(leftPattern, l));
    if (it == rightByKey.end()) {
      out.unpaired.push_back(l);
      continue;
    }
    out.pairs.push_back({l, it->second, baseName(l) + " + " + baseName(it->second)});
    rightByKey.erase(it);
  }
  for (const auto& [key, r] : rightByKey)
    out.unpaired.push_back(r);
  if (out.pairs.empty())
    throw Error("no left file of '" + leftPattern + "' has a right partner in '" + rightPattern +
                "': pairs are matched by the part the wildcards stand for (left07 with right07)");
  return out;
}

}  // namespace horopter
