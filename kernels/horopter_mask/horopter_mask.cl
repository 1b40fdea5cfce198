// OpenCL C 1.2 horopter mask: bit-exact with the scalar reference
// (horopter_mask_scalar.cpp states the semantics).
//
// Strategy
//   One work-item per pixel of the row range. The thresholds come from the
//   host as integers (1/16 px, one per column): no float here. `channels` is
//   0 when no segmented image is wanted, else 1 or 3 (interleaved bytes).

__kernel void horopter_mask(__global const short* disparity, int dispStride,
                            __global const short* thresholds, int width, int rowBegin, int rowEnd,
                            short invalid, __global uchar* mask, int maskStride,
                            __global const uchar* image, __global uchar* segmented,
                            int imageStride, int channels) {
  const int x = get_global_id(0);
  const int y = rowBegin + (int)get_global_id(1);
  if (x >= width || y >= rowEnd) return;
  const short d = disparity[y * dispStride + x];
  const int inside = d != invalid && d >= thresholds[x];
  mask[y * maskStride + x] = inside ? (uchar)255 : (uchar)0;
  for (int c = 0; c < channels; ++c) {
    const int at = y * imageStride + x * channels + c;
    segmented[at] = inside ? image[at] : (uchar)0;
  }
}
