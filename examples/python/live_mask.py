#!/usr/bin/env python3
"""Two cameras, a recorded video pair or a folder of pairs in; the horopter mask of each frame out.

    python3 examples/python/live_mask.py camera:/dev/video0,/dev/video2 --calib calib.yml
    python3 examples/python/live_mask.py video:left.avi,right.avi --fixation-disparity 24
    python3 examples/python/live_mask.py dir:recorded/ --frames 30 -o masks

Horopter reads the source itself (no cv2 needed): cameras run live (capture
never waits; a frame the pipeline cannot take in time is dropped), files
offline (every frame). Without --calib the pair is taken as rectified already,
with the zone set by the fixation's disparity on the centre column. Each frame
prints the share of its pixels inside the zone of interaction; -o DIR writes
each mask as DIR/mask_NNNNNN.png (255 inside); --show opens a window with the
left image kept inside the zone, when cv2 is installed (Esc stops).
"""
import argparse
import os
import sys

import horopter


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("source", help="camera:LEFT,RIGHT, video:LEFT,RIGHT, dir:FOLDER or sbs:DEV")
    parser.add_argument("--frames", type=int, default=None, help="stop after N frames")
    parser.add_argument("--calib", default="", help="calibration file (horopter calibrate)")
    parser.add_argument("--fixation-disparity", type=float, default=None,
                        help="px on the centre column (default: middle of the search range)")
    parser.add_argument("--num-disparities", type=int, default=64,
                        help="search range, a multiple of 16 (default 64)")
    parser.add_argument("--backend", default="auto", help="scalar, avx2, opencl or auto")
    parser.add_argument("-o", "--out", default=None, help="folder for the masks")
    parser.add_argument("--show", action="store_true", help="a window (needs cv2)")
    args = parser.parse_args()

    cv2 = None
    if args.show:
        try:
            import cv2  # noqa: F811 (optional: only for the window)
        except ImportError:
            sys.exit("live_mask.py: --show needs cv2 (pip install opencv-python)")
    if args.out:
        os.makedirs(args.out, exist_ok=True)
    live = args.source.startswith(("camera:", "sbs:"))
    try:
        pipeline = horopter.Pipeline(args.source, frames=args.frames, backend=args.backend,
                                     live=live, calib=args.calib,
                                     fixation_disparity=args.fixation_disparity,
                                     numDisparities=args.num_disparities)
        with pipeline:
            for frame in pipeline:
                mask = frame["mask"]                       # uint8 (H, W), 255 inside
                inside = 100.0 * (mask > 0).mean()
                print(f"frame {frame['index']}: {inside:.1f}% inside the zone", flush=True)
                if args.out:
                    horopter.imwrite(os.path.join(args.out, f"mask_{frame['index']:06d}.png"),
                                     mask)
                if cv2 is not None:
                    view = frame["left"].copy()
                    view[mask == 0] //= 4                  # dim what lies outside the zone
                    cv2.imshow("horopter", view)
                    if cv2.waitKey(1) == 27:
                        break
    except horopter.Error as error:  # bad input: the message says what to fix
        sys.exit(f"live_mask.py: {error}")
    summary = pipeline.summary
    if summary:
        print(f"{summary['frames']} frames, {summary['fps']:.1f} frames/s")


if __name__ == "__main__":
    main()
