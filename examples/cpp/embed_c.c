/* Embedding the C API: a textured pair with a known 6-pixel shift through
 * the matcher and the horopter mask; every call's status is checked. */
#include <horopter/horopter.h>

#include <stdio.h>
#include <stdlib.h>

#define TRY(call)                                                                              \
  do {                                                                                         \
    horopter_status s_ = (call);                                                               \
    if (s_ != HOROPTER_OK) {                                                                   \
      fprintf(stderr, "%s: %s: %s\n", #call, horopter_status_name(s_), horopter_last_error()); \
      return 1;                                                                                \
    }                                                                                          \
  } while (0)

enum { W = 160, H = 120, SHIFT = 6 };

int main(void) {
  static unsigned char left[W * H], right[W * H];
  unsigned state = 7u;
  for (int i = 0; i < W * H; ++i) {
    state = state * 1103515245u + 12345u;
    left[i] = (unsigned char)(state >> 16);
  }
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      right[y * W + x] = left[y * W + (x + SHIFT < W ? x + SHIFT : W - 1)];

  horopter_stereo_params params;
  horopter_stereo_params_default(&params);
  params.num_disparities = 32;
  horopter_matcher* matcher = NULL;
  TRY(horopter_matcher_create(&params, "auto", 1, &matcher));

  const horopter_image l = {left, W, H, W, HOROPTER_U8C1};
  const horopter_image r = {right, W, H, W, HOROPTER_U8C1};
  TRY(horopter_matcher_compute(matcher, &l, &r));
  horopter_image disparity;
  TRY(horopter_matcher_disparity(matcher, &disparity));

  int16_t thresholds[W];
  const horopter_geometry g = {W, (W - 1) / 2.0, (H - 1) / 2.0, 1.0};
  TRY(horopter_thresholds_from_disparity(&g, g.cx, 4.0, thresholds, W)); /* fixation at 4 px */
  TRY(horopter_matcher_mask(matcher, thresholds, W, NULL));
  horopter_image mask;
  TRY(horopter_matcher_mask_result(matcher, &mask, NULL));

  long inside = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      inside += ((const unsigned char*)mask.data)[y * mask.stride_bytes + x] != 0;
  const int16_t centre =
      ((const int16_t*)((const char*)disparity.data + (H / 2) * disparity.stride_bytes))[W / 2];
  printf("horopter %s, backend %s: centre disparity %.2f px, %.1f%% inside the zone\n",
         horopter_version(), horopter_matcher_backend(matcher), centre / 16.0,
         100.0 * inside / (W * H));
  horopter_matcher_destroy(matcher);
  /* The plane at 6 px is nearer than the fixation at 4 px: mostly inside. */
  return (centre > 5 * 16 && centre < 7 * 16 && inside > W * H / 2) ? 0 : 1;
}
