// The row families; main() registers them all before running.
#pragma once

namespace horopter::bench {

// disparity/...: ours, prefilter + matching + left-right check, and
// opencv_stereobm/...: cv::StereoBM at the same settings.
void registerDisparityRows();

// prefilter/, sad/, lr_check/, speckle/, median/, horopter_mask/: one kernel each.
void registerKernelRows();

// frontend/...: StereoFrontend, the whole per-frame chain.
void registerFrontendRows();

// frontend/.../scene and .../zone: the front end on the synthetic scene's
// frame, full range and zone-limited.
void registerZoneRows();

}  // namespace horopter::bench
