// OpenCL C 1.2 x-Sobel prefilter: bit-exact with the scalar reference
// (prefilter_scalar.cpp states the semantics).
//
// Strategy
//   One work-item per output pixel; global size (width rounded up to the
//   work-group width, rows of the range). Rows outside the image reflect
//   without repeating the edge (reflect-101); columns 0 and width-1 give 0.
//   Integer arithmetic only. Either output may be switched off with its flag
//   (the host then passes any buffer and does not read it back).

int prefilter_reflect101(int y, int height) {
  if (height == 1) return 0;
  if (y < 0) return -y;
  if (y >= height) return 2 * height - 2 - y;
  return y;
}

__kernel void prefilter_xsobel(__global const uchar* src, int srcStride, int width, int height,
                               int cap, int rowBegin, int rowEnd, __global uchar* filtered,
                               __global uchar* texture, int outStride, int wantFiltered,
                               int wantTexture) {
  const int x = get_global_id(0);
  const int y = rowBegin + (int)get_global_id(1);
  if (x >= width || y >= rowEnd) return;
  int sobel = 0;
  if (x > 0 && x < width - 1) {
    __global const uchar* above = src + prefilter_reflect101(y - 1, height) * srcStride;
    __global const uchar* here = src + y * srcStride;
    __global const uchar* below = src + prefilter_reflect101(y + 1, height) * srcStride;
    sobel = ((int)above[x + 1] - (int)above[x - 1]) + 2 * ((int)here[x + 1] - (int)here[x - 1]) +
            ((int)below[x + 1] - (int)below[x - 1]);
  }
  const int clipped = clamp(sobel, -cap, cap);
  if (wantFiltered) filtered[y * outStride + x] = (uchar)(clipped + cap);
  if (wantTexture) texture[y * outStride + x] = (uchar)abs(clipped);
}

// The normalized-response prefilter (cv::StereoBM's prefilterNorm), bit-exact
// with prefilter_normalized_scalar.cpp, which states the semantics. One
// work-item per output pixel sums its size x size window directly (size^2
// reads: cheap at OpenCV's default 9, slow at the largest windows; the sum is
// an exact integer whatever the order). Borders replicate the edge.
int prefilter_clamp_to(int v, int size) {
  return clamp(v, 0, size - 1);
}

__kernel void prefilter_normalized(__global const uchar* src, int srcStride, int width, int height,
                                   int cap, int radius, int centreWeight, int meanWeight,
                                   int rowBegin, int rowEnd, __global uchar* filtered,
                                   __global uchar* texture, int outStride, int wantFiltered,
                                   int wantTexture) {
  const int x = get_global_id(0);
  const int y = rowBegin + (int)get_global_id(1);
  if (x >= width || y >= rowEnd) return;
  int sum = 0;
  for (int dy = -radius; dy <= radius; ++dy) {
    __global const uchar* row = src + prefilter_clamp_to(y + dy, height) * srcStride;
    for (int dx = -radius; dx <= radius; ++dx)
      sum += (int)row[prefilter_clamp_to(x + dx, width)];
  }
  __global const uchar* here = src + y * srcStride;
  const int cross = 4 * (int)here[x] + (int)here[prefilter_clamp_to(x - 1, width)] +
                    (int)here[prefilter_clamp_to(x + 1, width)] +
                    (int)src[prefilter_clamp_to(y - 1, height) * srcStride + x] +
                    (int)src[prefilter_clamp_to(y + 1, height) * srcStride + x];
  const int v = (cross * centreWeight - sum * meanWeight) >> 10;
  const int clipped = clamp(v, -cap, cap);
  if (wantFiltered) filtered[y * outStride + x] = (uchar)(clipped + cap);
  if (wantTexture) texture[y * outStride + x] = (uchar)abs(clipped);
}
