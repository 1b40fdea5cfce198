#!/usr/bin/env python3
"""A rectified stereo pair in; the horopter mask and the segmented image out.

    python3 examples/python/segment.py LEFT RIGHT [-o DIR] [--num-disparities N]
        [--block-size B] [--fixation-disparity D] [--backend NAME]

With no pair given it takes Middlebury's Aloe pair from Debian's opencv-doc.
Writes DIR/mask.png (255 inside the zone of interaction) and DIR/segmented.png
(the left image, black outside the zone). The zone is the inside of the
Vieth-Mueller circle through both cameras and the fixation point, given by its
disparity on the centre column (default: the middle of the search range).
"""
import argparse
import os
import sys

import horopter

ALOE = "/usr/share/doc/opencv-doc/examples/data/aloe{}.jpg"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("left", nargs="?", default=ALOE.format("L"))
    parser.add_argument("right", nargs="?", default=ALOE.format("R"))
    parser.add_argument("-o", "--out", default="out", help="output folder (default out)")
    parser.add_argument("--num-disparities", type=int, default=None,
                        help="search range, a multiple of 16 (default 64; 224 for Aloe)")
    parser.add_argument("--block-size", type=int, default=9)
    parser.add_argument("--fixation-disparity", type=float, default=None,
                        help="px at the centre column (default: middle of the search range)")
    parser.add_argument("--backend", default="auto", help="scalar, avx2, opencl or auto")
    args = parser.parse_args()
    if args.num_disparities is None:
        args.num_disparities = 224 if args.left == ALOE.format("L") else 64

    try:
        colour = horopter.imread(args.left)            # uint8 (H, W, 3), BGR
        left = horopter.imread(args.left, grey=True)    # uint8 (H, W)
        right = horopter.imread(args.right, grey=True)
        matcher = horopter.StereoMatcher(numDisparities=args.num_disparities,
                                         blockSize=args.block_size, backend=args.backend)
        disparity = matcher.compute(left, right)       # int16, 1/16 px

        height, width = left.shape
        geometry = horopter.RectifiedGeometry(focal_px=width, cx=(width - 1) / 2,
                                              baseline=1.0, cy=(height - 1) / 2)
        fixation_px = args.fixation_disparity or args.num_disparities / 2
        fixation = horopter.fixation_from_disparity(geometry, geometry.cx, fixation_px)
        thresholds = horopter.horopter_thresholds(geometry, width, fixation)
        mask, segmented = matcher.compute_mask(thresholds, colour)
    except horopter.Error as error:  # bad input: the message says what to fix
        sys.exit(f"segment.py: {error}")

    os.makedirs(args.out, exist_ok=True)
    horopter.imwrite(os.path.join(args.out, "mask.png"), mask)
    horopter.imwrite(os.path.join(args.out, "segmented.png"), segmented)
    valid = (disparity != matcher.params.invalidDisparity).mean()
    print(f"{width}x{height}, backend {matcher.backend}: {100 * valid:.1f}% valid disparities, "
          f"{100 * (mask > 0).mean():.1f}% inside the zone (fixation {fixation_px:g} px)")
    print(f"wrote {args.out}/mask.png and {args.out}/segmented.png")


if __name__ == "__main__":
    main()
