// OpenCL C 1.2 invalid-aware median that fills holes: bit-exact with the
// scalar reference (median_scalar.cpp states the semantics).
//
// Strategy
//   One work-item per output pixel. The k x k window is loaded into private
//   ints; pixels outside the image and invalid pixels become a sentinel
//   larger than any int16 (32768), so they sort to the end and the n valid
//   values occupy ranks 0..n-1. An odd-even transposition network (k*k
//   rounds of branch-free min/max) sorts the window; the lower median is
//   rank (n - 1) / 2, an element of the window, as the reference. Branch-free
//   so that a CPU device can run neighbouring work-items in vector lanes.

#define MEDIAN_SENTINEL 32768

int median_select(int* v, int count, int n) {
  for (int round = 0; round < count; ++round) {
    for (int i = round & 1; i + 1 < count; i += 2) {
      const int a = v[i];
      const int b = v[i + 1];
      v[i] = min(a, b);
      v[i + 1] = max(a, b);
    }
  }
  return v[(n - 1) / 2];
}

__kernel void median_filter(__global const short* src, __global short* dst, int stride, int width,
                            int height, int kernelSize, int minValid, short invalid, int rowBegin,
                            int rowEnd) {
  const int x = get_global_id(0);
  const int y = rowBegin + (int)get_global_id(1);
  if (x >= width || y >= rowEnd) return;
  const int h = kernelSize / 2;
  int window[25];
  int n = 0;
  int count = 0;
  for (int j = -h; j <= h; ++j) {
    for (int i = -h; i <= h; ++i) {
      const int xx = x + i;
      const int yy = y + j;
      int v = MEDIAN_SENTINEL;
      if (xx >= 0 && xx < width && yy >= 0 && yy < height) {
        const short s = src[yy * stride + xx];
        if (s != invalid) v = s;
      }
      n += v != MEDIAN_SENTINEL;
      window[count++] = v;
    }
  }
  const int centreValid = src[y * stride + x] != invalid;
  short out = invalid;
  if (centreValid || n >= minValid) out = (short)median_select(window, count, n);
  dst[y * stride + x] = out;
}
