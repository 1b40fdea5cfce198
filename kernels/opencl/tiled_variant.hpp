// Tuning variants of the tiled matcher's cost kernel (sad_tiled.cl's
// sad_costs): the work-group's shape, the planes per pass, how the column
// sums spread over the group, how many passes one group takes, and how many
// rows a work-item's column sums slide down. All give
// the same costs, bit for bit; only the speed differs. Picked at run time by
// HOROPTER_OPENCL_TILED (unset or empty: the default variant), for sweeps on
// a GPU (scripts/device/sweep_tiled.sh).
#pragma once

#include <string>
#include <vector>

namespace horopter::opencl {

struct TiledVariant {
  std::string name = "default";
  int groupWidth = 32;  // work-items: columns of a tile
  int groupHeight = 8;  // and rows (fewer where the device allows less)
  int passPlanes = 4;   // planes one pass sums (SAD_TILED_PASS_PLANES)
  bool spread = true;   // column sums spread over the group (SAD_TILED_SPREAD)
  int split = 0;        // passes per group, 0: all (SAD_TILED_SPLIT)
  int rows = 1;         // rows per work-item, sliding sums (SAD_TILED_ROWS)
  int block = 0;        // a block size compiled in (SAD_TILED_RADIUS), 0: any;
                        // other block sizes take the variant without it

  // The -D build options of sad_tiled.cl; "" for the default variant's
  // values (the program every kernel comes from).
  std::string buildOptions() const;
  // This variant for a block size: without `block` where it differs.
  TiledVariant forBlock(int blockSize) const;
};

// The named variants, the default first.
const std::vector<TiledVariant>& tiledVariants();

// HOROPTER_OPENCL_TILED: a variant's name, or a comma-separated list of
// key=value over the default (w, h, planes, spread, split, rows,
// block), e.g. "w=64,h=4,split=1". Anything else is a horopter::Error naming the value.
TiledVariant tiledVariant();
TiledVariant parseTiledVariant(const std::string& value);

}  // namespace horopter::opencl
