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

// The default is the fastest of the 15 variants timed on an NVIDIA H200
// (scripts/device/sweep_tiled.sh, kernels/README.md "On a GPU"): 64 x 4
// work-items, a group per pass, sums sliding down 4 rows, block 9 compiled
// in; 0.199 ms a 640x480/d64/w9 frame against 0.380 ms for the first
// design (32 x 8, every pass in one group, one row per work-item: "first").
// The sad_tiled.cl defaults (SAD_TILED_*) are these values but the block.
struct TiledVariant {
  std::string name = "default";
  int groupWidth = 64;  // work-items: columns of a tile
  int groupHeight = 4;  // and rows (fewer where the device allows less)
  int passPlanes = 4;   // planes one pass sums (SAD_TILED_PASS_PLANES)
  bool spread = true;   // column sums spread over the group (SAD_TILED_SPREAD)
  int split = 1;        // passes per group, 0: all (SAD_TILED_SPLIT)
  int rows = 4;         // rows per work-item, sliding sums (SAD_TILED_ROWS)
  int block = 9;        // a block size compiled in (SAD_TILED_RADIUS), 0: any;
                        // other block sizes take the variant without it

  // The -D build options of sad_tiled.cl; "" for the program's own
  // defaults (the program every kernel comes from): the default variant
  // for any block size but the one it compiles in.
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
