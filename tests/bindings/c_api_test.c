/* The C API from C: a known shift through the matcher, the mask against the
 * threshold table, and every kind of bad input answered by a status and a
 * message (no crash, no exception). Prints "N passed, N failed". */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include <horopter/horopter.h>

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int passed = 0, failed = 0;

#define CHECK(cond)                                                      \
  do {                                                                   \
    if (cond) {                                                          \
      ++passed;                                                          \
    } else {                                                             \
      ++failed;                                                          \
      fprintf(stderr, "%s:%d: FAILED: %s\n", __FILE__, __LINE__, #cond); \
    }                                                                    \
  } while (0)

/* Random texture; the right view is the left shifted by `shift` pixels. */
static void make_pair(unsigned char* left, unsigned char* right, int w, int h, int shift) {
  unsigned state = 12345u;
  for (int i = 0; i < w * h; ++i) {
    state = state * 1103515245u + 12345u;
    left[i] = (unsigned char)(state >> 16);
  }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      right[y * w + x] = left[y * w + (x + shift < w ? x + shift : w - 1)];
}

static void test_version_and_backends(void) {
  CHECK(strlen(horopter_version()) >= 5);
  /* The library's version is the header's (horopter/version.h, through horopter.h). */
  CHECK(strcmp(horopter_version(), HOROPTER_VERSION_STRING) == 0);
  char numbers[32];
  snprintf(numbers, sizeof numbers, "%d.%d.%d", HOROPTER_VERSION_MAJOR, HOROPTER_VERSION_MINOR,
           HOROPTER_VERSION_PATCH);
  CHECK(strcmp(numbers, HOROPTER_VERSION_STRING) == 0);
  CHECK(HOROPTER_VERSION_NUMBER ==
        HOROPTER_VERSION_MAJOR * 10000 + HOROPTER_VERSION_MINOR * 100 + HOROPTER_VERSION_PATCH);
  const int n = horopter_backend_count();
  CHECK(n >= 1);
  int scalar_found = 0;
  for (int i = 0; i < n; ++i) {
    const char* name = NULL;
    int available = -1;
    CHECK(horopter_backend_info(i, &name, &available) == HOROPTER_OK);
    CHECK(name != NULL && (available == 0 || available == 1));
    if (name && strcmp(name, "scalar") == 0) scalar_found = available;
  }
  CHECK(scalar_found == 1);
  CHECK(horopter_backend_info(n, NULL, NULL) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(horopter_last_error(), "out of range") != NULL);
}

static void test_known_shift(void) {
  enum { W = 96, H = 48, SHIFT = 7 };
  unsigned char* left = malloc(W * H);
  unsigned char* right = malloc(W * H);
  make_pair(left, right, W, H, SHIFT);

  horopter_stereo_params params;
  horopter_stereo_params_default(&params);
  params.num_disparities = 16;
  params.block_size = 5;
  horopter_matcher* matcher = NULL;
  CHECK(horopter_matcher_create(&params, "scalar", 2, &matcher) == HOROPTER_OK);
  CHECK(matcher != NULL);
  CHECK(strcmp(horopter_matcher_backend(matcher), "scalar") == 0);

  horopter_image l = {left, W, H, W, HOROPTER_U8C1};
  horopter_image r = {right, W, H, W, HOROPTER_U8C1};
  CHECK(horopter_matcher_compute(matcher, &l, &r) == HOROPTER_OK);
  horopter_image disparity;
  CHECK(horopter_matcher_disparity(matcher, &disparity) == HOROPTER_OK);
  CHECK(disparity.width == W && disparity.height == H && disparity.type == HOROPTER_S16C1);
  /* Away from the borders every pixel finds the shift: 7 px = 112/16, within
   * the sub-pixel fit's half pixel. */
  int found = 0, total = 0;
  for (int y = 8; y < H - 8; ++y) {
    const int16_t* row = (const int16_t*)((const char*)disparity.data + y * disparity.stride_bytes);
    for (int x = 24; x < W - 8; ++x, ++total)
      found += abs(row[x] - SHIFT * 16) <= 8;
  }
  CHECK(total > 0 && found == total);

  /* Mask: a fixation disparity between 5 and 9 px keeps the 7-px plane only
   * where its column's threshold is <= 112. */
  int16_t thresholds[W];
  horopter_geometry g = {W, (W - 1) / 2.0, (H - 1) / 2.0, 1.0};
  CHECK(horopter_thresholds_from_disparity(&g, g.cx, 5.0, thresholds, W) == HOROPTER_OK);
  CHECK(horopter_matcher_mask(matcher, thresholds, W, &l) == HOROPTER_OK);
  horopter_image mask, segmented;
  CHECK(horopter_matcher_mask_result(matcher, &mask, &segmented) == HOROPTER_OK);
  CHECK(segmented.data != NULL && segmented.type == HOROPTER_U8C1);
  int agree = 1;
  for (int y = 0; y < H; ++y) {
    const int16_t* d = (const int16_t*)((const char*)disparity.data + y * disparity.stride_bytes);
    const unsigned char* m = (const unsigned char*)mask.data + y * mask.stride_bytes;
    const unsigned char* s = (const unsigned char*)segmented.data + y * segmented.stride_bytes;
    for (int x = 0; x < W; ++x) {
      const int inside = d[x] != (params.min_disparity - 1) * 16 && d[x] >= thresholds[x];
      agree &= m[x] == (inside ? 255 : 0);
      agree &= s[x] == (inside ? left[y * W + x] : 0);
    }
  }
  CHECK(agree);
  horopter_matcher_destroy(matcher);
  free(left);
  free(right);
}

/* The last error names `field` as horopter.h spells it, and no C++ member
 * (a lowercase letter followed by a capital: numDisparities, blockSize). */
static int names_c_field(const char* field) {
  const char* message = horopter_last_error();
  for (const char* p = message; p[0] && p[1]; ++p)
    if (p[0] >= 'a' && p[0] <= 'z' && p[1] >= 'A' && p[1] <= 'Z') {
      fprintf(stderr, "C++ name in the message: %s\n", message);
      return 0;
    }
  if (!strstr(message, field)) {
    fprintf(stderr, "'%s' not named in the message: %s\n", field, message);
    return 0;
  }
  return 1;
}

/* Each bad field of horopter_stereo_params is named as the struct spells it. */
static void test_messages_name_c_fields(void) {
  const struct {
    const char* field;
    size_t offset;
    int value;
  } cases[] = {
      {"block_size", offsetof(horopter_stereo_params, block_size), 8},
      {"num_disparities", offsetof(horopter_stereo_params, num_disparities), 20},
      {"min_disparity", offsetof(horopter_stereo_params, min_disparity), 5000},
      {"pre_filter_cap", offsetof(horopter_stereo_params, pre_filter_cap), 0},
      {"pre_filter_size", offsetof(horopter_stereo_params, pre_filter_size), 4},
      {"pre_filter_type", offsetof(horopter_stereo_params, pre_filter_type), 7},
      {"uniqueness_ratio", offsetof(horopter_stereo_params, uniqueness_ratio), -1},
      {"speckle_window_size", offsetof(horopter_stereo_params, speckle_window_size), -1},
      {"median_kernel_size", offsetof(horopter_stereo_params, median_kernel_size), 4},
      {"median_min_valid", offsetof(horopter_stereo_params, median_min_valid), 30},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    horopter_stereo_params params;
    horopter_stereo_params_default(&params);
    *(int*)((char*)&params + cases[i].offset) = cases[i].value;
    horopter_matcher* matcher = NULL;
    CHECK(horopter_matcher_create(&params, "scalar", 1, &matcher) ==
          HOROPTER_ERROR_INVALID_ARGUMENT);
    CHECK(matcher == NULL);
    CHECK(names_c_field(cases[i].field));
  }
}

/* Each prefilter of the struct reaches the matcher: the three give three
 * different maps of one random pair, and the normalized response's window
 * matters. */
static void test_pre_filter_types(void) {
  enum { W = 96, H = 48 };
  static unsigned char left[W * H], right[W * H];
  make_pair(left, right, W, H, 6);
  horopter_image l = {left, W, H, W, HOROPTER_U8C1}, r = {right, W, H, W, HOROPTER_U8C1};
  static int16_t maps[4][W * H];
  const int types[4] = {HOROPTER_PREFILTER_NORMALIZED_RESPONSE, HOROPTER_PREFILTER_XSOBEL,
                        HOROPTER_PREFILTER_NONE, HOROPTER_PREFILTER_NORMALIZED_RESPONSE};
  for (int k = 0; k < 4; ++k) {
    horopter_stereo_params params;
    horopter_stereo_params_default(&params);
    CHECK(params.pre_filter_type == HOROPTER_PREFILTER_XSOBEL && params.pre_filter_size == 9);
    params.num_disparities = 32;
    params.pre_filter_type = types[k];
    if (k == 3) params.pre_filter_size = 21;
    horopter_matcher* matcher = NULL;
    CHECK(horopter_matcher_create(&params, "scalar", 1, &matcher) == HOROPTER_OK);
    CHECK(horopter_matcher_compute(matcher, &l, &r) == HOROPTER_OK);
    horopter_image d;
    CHECK(horopter_matcher_disparity(matcher, &d) == HOROPTER_OK);
    for (int y = 0; y < H; ++y)
      memcpy(maps[k] + y * W, (const char*)d.data + (ptrdiff_t)y * d.stride_bytes, W * 2);
    horopter_matcher_destroy(matcher);
  }
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) CHECK(memcmp(maps[a], maps[b], sizeof maps[a]) != 0);
}

static void test_bad_input(void) {
  horopter_stereo_params params;
  horopter_stereo_params_default(&params);
  horopter_matcher* matcher = NULL;

  params.block_size = 8;
  CHECK(horopter_matcher_create(&params, "scalar", 1, &matcher) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(matcher == NULL);
  CHECK(names_c_field("block_size"));
  horopter_stereo_params_default(&params);

  CHECK(horopter_matcher_create(&params, "no-such-backend", 1, &matcher) ==
        HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(strlen(horopter_last_error()) > 0);
  CHECK(horopter_matcher_create(&params, NULL, -1, &matcher) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(horopter_last_error(), "thread count") != NULL);
  CHECK(horopter_matcher_create(&params, NULL, 257, &matcher) == HOROPTER_ERROR_INVALID_ARGUMENT);
  /* NULL and 0: the library's defaults (auto backend, every hardware thread). */
  CHECK(horopter_matcher_create(&params, NULL, 0, &matcher) == HOROPTER_OK);
  CHECK(strlen(horopter_matcher_backend(matcher)) > 0);
  horopter_matcher_destroy(matcher);
  matcher = NULL;
  CHECK(horopter_matcher_create(NULL, NULL, 1, &matcher) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(horopter_last_error(), "params is NULL") != NULL);

  CHECK(horopter_matcher_create(&params, NULL, 1, &matcher) == HOROPTER_OK);
  horopter_image out;
  CHECK(horopter_matcher_disparity(matcher, &out) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(horopter_last_error(), "was not called") != NULL);

  unsigned char pixels[96 * 32] = {0};
  horopter_image a = {pixels, 96, 32, 96, HOROPTER_U8C1};
  horopter_image narrow = {pixels, 32, 32, 32, HOROPTER_U8C1};
  horopter_image wrong_type = {pixels, 32, 32, 96, HOROPTER_S16C1};
  horopter_image bad_stride = {pixels, 96, 32, 10, HOROPTER_U8C1};
  horopter_image null_data = {NULL, 96, 32, 96, HOROPTER_U8C1};
  horopter_image bad_enum = {pixels, 96, 32, 96, (horopter_pixel_type)7};
  CHECK(horopter_matcher_compute(matcher, &a, &narrow) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(horopter_matcher_compute(matcher, &a, &wrong_type) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(horopter_last_error(), "S16C1") != NULL);
  CHECK(horopter_matcher_compute(matcher, &a, &bad_stride) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(horopter_matcher_compute(matcher, &null_data, &a) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(horopter_matcher_compute(matcher, &bad_enum, &a) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(horopter_matcher_compute(matcher, NULL, &a) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(horopter_matcher_compute(NULL, &a, &a) == HOROPTER_ERROR_INVALID_ARGUMENT);

  unsigned char small[64 * 32] = {0};
  horopter_image too_small = {small, 64, 32, 64, HOROPTER_U8C1};
  CHECK(horopter_matcher_compute(matcher, &too_small, &too_small) ==
        HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(horopter_last_error(), "reduce num_disparities") != NULL);
  CHECK(names_c_field("num_disparities"));
  CHECK(horopter_matcher_compute(matcher, &a, &a) == HOROPTER_OK);
  int16_t table[96] = {0};
  CHECK(horopter_matcher_mask(matcher, table, 10, NULL) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(horopter_matcher_mask(matcher, table, 96, NULL) == HOROPTER_OK);
  horopter_image mask, segmented;
  CHECK(horopter_matcher_mask_result(matcher, &mask, &segmented) == HOROPTER_OK);
  CHECK(segmented.data == NULL);
  /* A failed call leaves no result behind that could pass for its own. */
  CHECK(horopter_matcher_mask(matcher, table, 10, NULL) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(horopter_matcher_mask_result(matcher, &mask, &segmented) ==
        HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(horopter_last_error(), "last call failed") != NULL);
  CHECK(horopter_matcher_compute(matcher, &a, &narrow) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(horopter_matcher_disparity(matcher, &out) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(horopter_matcher_mask(matcher, table, 96, NULL) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(horopter_matcher_compute(matcher, &a, &a) == HOROPTER_OK);
  CHECK(horopter_matcher_disparity(matcher, &out) == HOROPTER_OK);
  horopter_matcher_destroy(matcher);
  horopter_matcher_destroy(NULL);

  horopter_geometry g = {100, 50, 30, 0.1};
  CHECK(horopter_thresholds_at_distance(&g, -1.0, table, 64) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(horopter_thresholds_at_distance(&g, 1.0, table, 0) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(horopter_thresholds_at_distance(&g, 1.0, table, 64) == HOROPTER_OK);
  CHECK(table[32] > 0);
  CHECK(horopter_thresholds_from_disparity(NULL, 0, 1, table, 64) ==
        HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(horopter_geometry_from_calibration("/no/such/calib.yml", &g) == HOROPTER_ERROR_FAILED);
  CHECK(strstr(horopter_last_error(), "/no/such/calib.yml") != NULL);
  CHECK(strcmp(horopter_status_name(HOROPTER_ERROR_FAILED), "failed") == 0);
}

/* Stops the run after `*(int*)user` frames. */
static int stop_after(const horopter_frame_result* frame, void* user) {
  const int* limit = (const int*)user;
  return frame->index + 1 >= *limit;
}

/* A binary PGM (P5) file; 0 on failure. */
static int write_pgm(const char* path, const unsigned char* pixels, int w, int h) {
  FILE* f = fopen(path, "wb");
  if (!f) return 0;
  const int ok = fprintf(f, "P5\n%d %d\n255\n", w, h) > 0 &&
                 fwrite(pixels, 1, (size_t)w * h, f) == (size_t)w * h;
  return fclose(f) == 0 && ok;
}

/* The whole pipeline on a folder of pairs: frames arrive in order with their
 * disparity, a callback can stop the run, and a bad configuration is a
 * status with a message. */
static void test_run(void) {
  enum { W = 96, H = 64, PAIRS = 12 };
  char dir[] = "/tmp/horopter_c_run_XXXXXX";
  CHECK(mkdtemp(dir) != NULL);
  static unsigned char left[W * H], right[W * H];
  make_pair(left, right, W, H, 5);
  for (int i = 0; i < PAIRS; ++i) {
    char path[128];
    snprintf(path, sizeof path, "%s/left_%02d.pgm", dir, i);
    CHECK(write_pgm(path, left, W, H));
    snprintf(path, sizeof path, "%s/right_%02d.pgm", dir, i);
    CHECK(write_pgm(path, right, W, H));
  }
  char source[160];
  snprintf(source, sizeof source, "dir:%s", dir);

  horopter_run_config config;
  horopter_run_config_default(&config);
  CHECK(horopter_run(&config, NULL, NULL, NULL) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(horopter_last_error(), "source") != NULL);
  config.source = source;
  config.detect = "off";
  config.stereo.num_disparities = 16;
  config.stereo.block_size = 5;
  config.in_flight = 2;
  horopter_run_summary whole;
  CHECK(horopter_run(&config, NULL, NULL, &whole) == HOROPTER_OK);
  CHECK(whole.frames == PAIRS);
  CHECK(whole.digest != 0);
  int limit = 4;
  horopter_run_summary stopped;
  CHECK(horopter_run(&config, stop_after, &limit, &stopped) == HOROPTER_OK);
  /* Capture stops; the frame being captured and those in flight still finish. */
  CHECK(stopped.frames >= 4 && stopped.frames <= 4 + config.in_flight);

  horopter_run_config bad = config;
  bad.detect = "everywhere";
  CHECK(horopter_run(&bad, NULL, NULL, NULL) == HOROPTER_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(horopter_last_error(), "everywhere") != NULL);
  bad = config;
  bad.in_flight = 0;
  CHECK(horopter_run(&bad, NULL, NULL, NULL) == HOROPTER_ERROR_INVALID_ARGUMENT);
  bad = config;
  bad.focal_px = -1;
  CHECK(horopter_run(&bad, NULL, NULL, NULL) == HOROPTER_ERROR_INVALID_ARGUMENT);
  bad = config;
  bad.source = "synthetic";
  CHECK(horopter_run(&bad, NULL, NULL, NULL) != HOROPTER_OK);
  CHECK(strstr(horopter_last_error(), "simulator") != NULL);
  bad = config;
  bad.source = "dir:/no/such/folder";
  CHECK(horopter_run(&bad, NULL, NULL, NULL) != HOROPTER_OK);
  CHECK(strlen(horopter_last_error()) > 0);
  CHECK(horopter_run(NULL, NULL, NULL, NULL) == HOROPTER_ERROR_INVALID_ARGUMENT);

  for (int i = 0; i < PAIRS; ++i) {
    char path[128];
    snprintf(path, sizeof path, "%s/left_%02d.pgm", dir, i);
    remove(path);
    snprintf(path, sizeof path, "%s/right_%02d.pgm", dir, i);
    remove(path);
  }
  rmdir(dir);
}

int main(void) {
  test_version_and_backends();
  test_known_shift();
  test_bad_input();
  test_messages_name_c_fields();
  test_pre_filter_types();
  test_run();
  printf("%d passed, %d failed\n", passed, failed);
  return failed == 0 ? 0 : 1;
}
