#include "opencl/tiled_variant.hpp"

#include <cstdlib>
#include <sstream>

#include "horopter/core/error.hpp"

namespace horopter::opencl {

namespace {

TiledVariant named(const char* name, int w, int h, int planes, bool spread, int split, int rows,
                   int block = 0) {
  TiledVariant v;
  v.block = block;
  v.name = name;
  v.groupWidth = w;
  v.groupHeight = h;
  v.passPlanes = planes;
  v.spread = spread;
  v.split = split;
  v.rows = rows;
  return v;
}

[[noreturn]] void bad(const std::string& value, const std::string& why) {
  std::string names;
  for (const TiledVariant& v : tiledVariants())
    names += (names.empty() ? "" : ", ") + v.name;
  throw Error(
      "HOROPTER_OPENCL_TILED='" + value + "' is not a tiled-matcher variant (" + why +
      "): use one of " + names +
      ", or key=value pairs joined by commas (w, h: work-group shape, w*h <= 1024; "
      "planes: 1-8 per pass; spread: 0|1; split: passes per group, 0 for all; rows: 1-16 per "
      "work-item; block: a block size compiled in)");
}

int number(const std::string& value, const std::string& text) {
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < 0 || v > 4096) bad(value, "'" + text + "' is no count");
  return static_cast<int>(v);
}

}  // namespace

std::string TiledVariant::buildOptions() const {
  const TiledVariant base;
  std::string options;
  if (passPlanes != base.passPlanes)
    options += " -DSAD_TILED_PASS_PLANES=" + std::to_string(passPlanes);
  if (spread != base.spread) options += " -DSAD_TILED_SPREAD=" + std::to_string(spread ? 1 : 0);
  if (split != base.split) options += " -DSAD_TILED_SPLIT=" + std::to_string(split);
  if (rows != base.rows) options += " -DSAD_TILED_ROWS=" + std::to_string(rows);
  // The program's own default serves every radius: a block compiled in is
  // always an option (the default variant's too).
  if (block != 0) options += " -DSAD_TILED_RADIUS=" + std::to_string(block / 2);
  return options;
}

TiledVariant TiledVariant::forBlock(int blockSize) const {
  TiledVariant v = *this;
  if (v.block != blockSize) v.block = 0;
  return v;
}

const std::vector<TiledVariant>& tiledVariants() {
  static const std::vector<TiledVariant> list = {
      named("default", 64, 4, 4, true, 1, 4, 9),  // the H200's fastest (tiled_variant.hpp)
      named("first", 32, 8, 4, true, 0, 1),       // the first design, the H200's 0.380 ms
      named("rowwise", 32, 8, 4, false, 0, 1),    // column sums row by row (before 9658be7)
      named("p8", 32, 8, 8, true, 0, 1),
      named("g64x4", 64, 4, 4, true, 0, 1),
      named("split", 32, 8, 4, true, 1, 1),  // one pass per group: planes across groups
      named("rows4", 32, 8, 4, true, 0, 4),  // 32 x 32 tiles, sums sliding down 4 rows
      named("rows4-split", 32, 8, 4, true, 1, 4),
      named("rows8-split", 32, 4, 4, true, 1, 8),  // 32 x 32 tiles of 128 work-items
  };
  return list;
}

TiledVariant parseTiledVariant(const std::string& value) {
  if (value.empty()) return tiledVariants().front();
  for (const TiledVariant& v : tiledVariants())
    if (v.name == value) return v;
  if (value.find('=') == std::string::npos) bad(value, "no such name");
  TiledVariant v;
  v.name = value;
  std::stringstream in(value);
  std::string item;
  while (std::getline(in, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) bad(value, "'" + item + "' is not key=value");
    const std::string key = item.substr(0, eq);
    const int n = number(value, item.substr(eq + 1));
    if (key == "w")
      v.groupWidth = n;
    else if (key == "h")
      v.groupHeight = n;
    else if (key == "planes")
      v.passPlanes = n;
    else if (key == "spread")
      v.spread = n != 0;
    else if (key == "split")
      v.split = n;
    else if (key == "rows")
      v.rows = n;
    else if (key == "block")
      v.block = n;
    else
      bad(value, "unknown key '" + key + "'");
  }
  if (v.groupWidth < 1 || v.groupHeight < 1 || v.groupWidth * v.groupHeight > 1024)
    bad(value, "the work-group must have 1 to 1024 work-items");
  if (v.passPlanes < 1 || v.passPlanes > 8) bad(value, "planes must be 1 to 8");
  if (v.rows < 1 || v.rows > 16) bad(value, "rows must be 1 to 16");
  if (v.block != 0 && (v.block % 2 == 0 || v.block > 255)) bad(value, "block must be odd, <= 255");
  return v;
}

TiledVariant tiledVariant() {
  const char* env = std::getenv("HOROPTER_OPENCL_TILED");
  return parseTiledVariant(env != nullptr ? env : "");
}

}  // namespace horopter::opencl
