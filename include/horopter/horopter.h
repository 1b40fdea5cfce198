/* The C API of Horopter: the stereo matcher (disparity and horopter mask),
 * the backends, and the threshold table of the zone of interaction.
 *
 * Rules that hold for every function:
 *  - Objects are opaque handles, created by horopter_*_create and released by
 *    horopter_*_destroy (which accepts NULL).
 *  - Every function that can fail returns a horopter_status. On failure,
 *    horopter_last_error() returns a message that says what to fix, naming
 *    the fields of these structs as spelled here (num_disparities); it is
 *    per thread and stays valid until the next failing call on that thread.
 *    No C++ exception ever crosses this interface.
 *  - Images are views over the caller's memory (never copied, never kept
 *    after the call returns): data, width, height, row stride in bytes, pixel
 *    type. Disparities are int16 in 1/16 pixel, as OpenCV's; an invalid pixel
 *    holds (min_disparity - 1) * 16.
 *  - A handle may be used by one thread at a time; different handles may be
 *    used from different threads at once.
 * Link with -lhoropter (pkg-config horopter, or CMake's horopter::horopter). */
#ifndef HOROPTER_HOROPTER_H
#define HOROPTER_HOROPTER_H

#include <stddef.h>
#include <stdint.h>

#include "version.h" /* HOROPTER_VERSION_MAJOR, _MINOR, _PATCH, _STRING, _NUMBER */

#ifdef __cplusplus
extern "C" {
#endif

typedef enum horopter_status {
  HOROPTER_OK = 0,
  HOROPTER_ERROR_INVALID_ARGUMENT = 1, /* a bad parameter, image, size or NULL handle */
  HOROPTER_ERROR_FAILED = 2,           /* a file, device or backend failed */
  HOROPTER_ERROR_OUT_OF_MEMORY = 3,
  HOROPTER_ERROR_INTERNAL = 4 /* an unexpected error: please report it */
} horopter_status;

/* The last failure's message on this thread, "" when none. */
const char* horopter_last_error(void);
/* "ok", "invalid argument", "failed", "out of memory", "internal error". */
const char* horopter_status_name(horopter_status status);
/* The library's version, "MAJOR.MINOR.PATCH": the HOROPTER_VERSION_STRING
 * the library was built with (compare it with the header's to detect a
 * mismatched libhoropter). */
const char* horopter_version(void);

/* ---- Images ------------------------------------------------------------ */

typedef enum horopter_pixel_type {
  HOROPTER_U8C1 = 0, /* 8-bit grey */
  HOROPTER_U8C3 = 1, /* 8-bit, 3 interleaved channels (BGR) */
  HOROPTER_S16C1 = 2 /* signed 16-bit: disparity in 1/16 px */
} horopter_pixel_type;

typedef struct horopter_image {
  void* data;
  int width;
  int height;
  ptrdiff_t stride_bytes; /* >= width * bytes per pixel */
  horopter_pixel_type type;
} horopter_image;

/* ---- Parameters (cv::StereoBM's names and meanings) -------------------- */

/* The prefilter, with OpenCV's values (cv::StereoBM::PREFILTER_*). */
typedef enum horopter_pre_filter_type {
  HOROPTER_PREFILTER_NORMALIZED_RESPONSE = 0, /* pixel less its window's mean, clipped */
  HOROPTER_PREFILTER_XSOBEL = 1,              /* clipped horizontal Sobel (the default) */
  HOROPTER_PREFILTER_NONE = 2                 /* raw intensities (Horopter's own) */
} horopter_pre_filter_type;

typedef struct horopter_stereo_params {
  int min_disparity;       /* smallest disparity searched, px; may be negative */
  int num_disparities;     /* search range, px; a positive multiple of 16 */
  int block_size;          /* odd, 3..255 */
  int pre_filter_type;     /* a horopter_pre_filter_type */
  int pre_filter_size;     /* the normalized response's window: odd, 5..255 */
  int pre_filter_cap;      /* 1..63 */
  int texture_threshold;   /* 0 = off */
  int uniqueness_ratio;    /* percent; 0 = off */
  int disp12_max_diff;     /* px; negative = left-right check off */
  int speckle_window_size; /* 0 = off */
  int speckle_range;       /* in 1/16 px, as cv::StereoBM */
  int median_kernel_size;  /* hole-filling median: 0 (off), 3 or 5 */
  int median_min_valid;    /* valid pixels needed to fill a hole; 0 = more than half the window */
  int left_band;           /* match the left columns the whole range misses where >= this many
                              disparities fit; 0 = off (0..num_disparities) */
} horopter_stereo_params;

/* Fills *params with the library's defaults (those of `horopter disparity`). */
void horopter_stereo_params_default(horopter_stereo_params* params);

/* ---- Backends ---------------------------------------------------------- */

/* How many backends this build knows (available here or not). */
int horopter_backend_count(void);
/* Backend `index` (0..count-1): its name ("scalar", "avx2", "opencl:0:0") and
 * whether it runs on this machine. Either output may be NULL. */
horopter_status horopter_backend_info(int index, const char** name, int* available);

/* ---- The stereo matcher ------------------------------------------------ */

typedef struct horopter_matcher horopter_matcher;

/* backend: "auto", "scalar", "avx2", "opencl", ... (NULL = the library's
 * default, "auto": the best available CPU backend);
 * threads: 1..256, the rows of each kernel split over that many threads, or
 * 0 = the library's default, one per hardware thread. These are the defaults
 * of C++'s StereoFrontend, Python's StereoMatcher and the CLI too
 * (horopter::FrontendDefaults in horopter/vision/frontend.hpp). */
horopter_status horopter_matcher_create(const horopter_stereo_params* params, const char* backend,
                                        int threads, horopter_matcher** matcher);
void horopter_matcher_destroy(horopter_matcher* matcher);
/* The backend the matcher runs (valid while the matcher lives). */
const char* horopter_matcher_backend(const horopter_matcher* matcher);

/* Disparity of a rectified U8C1 pair of one size. */
horopter_status horopter_matcher_compute(horopter_matcher* matcher, const horopter_image* left,
                                         const horopter_image* right);
/* A read-only view of the last disparity (S16C1), owned by the matcher:
 * valid until the next compute or destroy. */
horopter_status horopter_matcher_disparity(const horopter_matcher* matcher, horopter_image* out);

/* Horopter mask of the last disparity: one threshold per column (count =
 * width, 1/16 px; see horopter_thresholds_*). `image` (U8C1 or U8C3 of the
 * disparity's size, or NULL) is copied into the segmented image with the
 * outside of the zone zeroed. */
horopter_status horopter_matcher_mask(horopter_matcher* matcher, const int16_t* thresholds,
                                      int count, const horopter_image* image);
/* Views of the last mask (U8C1, 255 inside) and segmented image (empty, data
 * NULL, when no image was given); either output may be NULL. */
horopter_status horopter_matcher_mask_result(const horopter_matcher* matcher, horopter_image* mask,
                                             horopter_image* segmented);

/* ---- Geometry ---------------------------------------------------------- */

/* A rectified pair: focal length and principal point in pixels, baseline in
 * any length unit (> 0). */
typedef struct horopter_geometry {
  double focal_px;
  double cx;
  double cy;
  double baseline;
} horopter_geometry;

/* The geometry of a calibration file written by `horopter calibrate`. */
horopter_status horopter_geometry_from_calibration(const char* path, horopter_geometry* geometry);

/* The threshold table (out[width], 1/16 px) of the Vieth-Mueller circle
 * through both cameras and a fixation point given by its disparity
 * (disparity_px > 0) at column u of the left image. */
horopter_status horopter_thresholds_from_disparity(const horopter_geometry* geometry, double u,
                                                   double disparity_px, int16_t* out, int width);
/* The same for a fixation straight ahead at `distance` (the baseline's unit). */
horopter_status horopter_thresholds_at_distance(const horopter_geometry* geometry, double distance,
                                                int16_t* out, int width);

/* ---- The whole pipeline (as `horopter run`) ------------------------------ */

/* What to run: the same configuration gives the same frames as `horopter
 * run` and the Python module's Pipeline (horopter_run_summary.digest equals
 * their frames_digest / digest). Start from horopter_run_config_default. */
typedef struct horopter_run_config {
  const char* source;  /* "dir:PATH", "video:L,R", "camera:L,R", "sbs:DEV" (the synthetic
                          scene is the simulator's, not libhoropter's) */
  int frames;          /* > 0: stop after this many; 0: the source's end */
  int width, height;   /* cameras: the requested size, px (0: the driver's) */
  const char* backend; /* "auto", "scalar", "avx2", "opencl", ... */
  int threads;         /* the disparity stage's threads, 1..256 */
  int in_flight;       /* frames in flight, 1..64 */
  int live;            /* 1: live mode (capture never waits; stale frames dropped) */
  const char* detect;  /* "region", "full" or "off" (front end only) */
  horopter_stereo_params stereo;
  /* The zone of a source rectified already: the fixation's disparity on the
   * centre column (0: the middle of the search range) and the focal length
   * (0: the image width), px. */
  double fixation_disparity_px;
  double focal_px;
} horopter_run_config;

/* source NULL (set one), frames 0, the camera's size, backend "auto",
 * 1 thread, 3 in flight, offline, detect "region", stereo defaults
 * (horopter_stereo_params_default) with the run's left band (16, as
 * `horopter run`), fixation and focal length 0 (defaults). */
void horopter_run_config_default(horopter_run_config* config);

/* What the caller sees of each finished frame, in frame order. Positions in
 * the left rectified image, px; a part's `tracked` is 0 where it has no
 * track (its position is then meaningless). */
typedef struct horopter_part {
  int tracked;
  float x, y;
} horopter_part;

typedef struct horopter_frame_result {
  int64_t index;
  int godfather; /* 1: a godfather is elected; the parts below are theirs */
  horopter_part head, left_hand, right_hand;
  horopter_image disparity; /* S16C1 view, valid during the callback only */
  horopter_image mask;      /* U8C1 view (255 inside the zone), valid during the callback only */
} horopter_frame_result;

/* Called on the pipeline's last lane for each finished frame; return 0 to
 * go on, non-zero to stop capture (the frames in flight still finish). */
typedef int (*horopter_frame_callback)(const horopter_frame_result* frame, void* user);

typedef struct horopter_run_summary {
  int64_t frames; /* frames through every stage */
  double seconds; /* wall time */
  double fps;
  uint64_t digest; /* of the frames' outputs, as `horopter run --json`'s frames_digest */
} horopter_run_summary;

/* Runs the pipeline to the source's end (or `frames`, or a stop from the
 * callback). on_frame and summary may be NULL. */
horopter_status horopter_run(const horopter_run_config* config, horopter_frame_callback on_frame,
                             void* user, horopter_run_summary* summary);

#ifdef __cplusplus
}
#endif

#endif /* HOROPTER_HOROPTER_H */
