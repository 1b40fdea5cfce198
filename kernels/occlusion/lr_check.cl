// OpenCL C 1.2 left-right consistency check: bit-exact with the scalar
// reference (lr_check_scalar.cpp states the semantics).
//
// Strategy
//   One work-item per pixel of the row range, in place on the disparity map:
//   each pixel reads only itself and the right view's winner map, so there
//   is no race. The rounding (d + 8) >> 4 is a floor division written out,
//   so it does not depend on how a compiler shifts negative numbers.

int lr_floor_div16(int v) {
  int q = v / 16;
  if (v % 16 < 0) q -= 1;
  return q;
}

__kernel void lr_check(__global short* disparity, __global const short* winnerRight, int stride,
                       int width, int rowBegin, int rowEnd, int maxDiff, short invalid,
                       int noWinner) {
  const int x = get_global_id(0);
  const int y = rowBegin + (int)get_global_id(1);
  if (x >= width || y >= rowEnd) return;
  __global short* d = disparity + y * stride;
  const int v = d[x];
  if (v == invalid) return;
  const int dl = lr_floor_div16(v + 8);
  const int xr = x - dl;
  if (xr < 0 || xr >= width) return;
  const int wr = winnerRight[y * stride + xr];
  if (wr == noWinner) return;
  if (abs(dl - wr) > maxDiff) d[x] = invalid;
}
