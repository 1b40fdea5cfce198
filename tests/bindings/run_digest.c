/* Runs the whole pipeline through the C API and prints its frames' digest,
 * for the parity test (bindings/python/tests/test_pipeline_parity.py), which
 * compares it with `horopter run --json` and the Python module's.
 * Usage: horopter_run_digest SOURCE FRAMES DETECT BACKEND IN_FLIGHT FIXATION_DISPARITY */
#include <horopter/horopter.h>

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>

static int count_frames(const horopter_frame_result* frame, void* user) {
  int64_t* next = (int64_t*)user;
  if (frame->index != *next) {
    fprintf(stderr, "frame %" PRId64 " arrived where %" PRId64 " was due\n", frame->index, *next);
    return 1;
  }
  ++*next;
  return 0;
}

int main(int argc, char** argv) {
  if (argc != 7) {
    fprintf(stderr, "usage: %s SOURCE FRAMES DETECT BACKEND IN_FLIGHT FIXATION_DISPARITY\n", argv[0]);
    return 2;
  }
  horopter_run_config config;
  horopter_run_config_default(&config);
  config.source = argv[1];
  config.frames = atoi(argv[2]);
  config.detect = argv[3];
  config.backend = argv[4];
  config.in_flight = atoi(argv[5]);
  config.fixation_disparity_px = atof(argv[6]);
  int64_t next = 0;
  horopter_run_summary summary;
  const horopter_status status = horopter_run(&config, count_frames, &next, &summary);
  if (status != HOROPTER_OK) {
    fprintf(stderr, "horopter_run: %s: %s\n", horopter_status_name(status), horopter_last_error());
    return 1;
  }
  if (next != summary.frames) {
    fprintf(stderr, "%" PRId64 " frames seen, %" PRId64 " run\n", next, summary.frames);
    return 1;
  }
  printf("%016" PRIx64 "\n", summary.digest);
  return 0;
}
