/* Runs the whole pipeline through the C API and prints its frames' digest,
 * for the parity test (bindings/python/tests/test_pipeline_parity.py), which
 * compares it with `horopter run --json` and the Python module's.
 * Usage: horopter_run_digest FRAMES WIDTH HEIGHT SEED DETECT BACKEND IN_FLIGHT */
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
  if (argc != 8) {
    fprintf(stderr, "usage: %s FRAMES WIDTH HEIGHT SEED DETECT BACKEND IN_FLIGHT\n", argv[0]);
    return 2;
  }
  horopter_run_config config;
  horopter_run_config_default(&config);
  config.frames = atoi(argv[1]);
  config.width = atoi(argv[2]);
  config.height = atoi(argv[3]);
  config.seed = strtoull(argv[4], NULL, 10);
  config.detect = argv[5];
  config.backend = argv[6];
  config.in_flight = atoi(argv[7]);
  int64_t next = 0;
  horopter_run_summary summary;
  const horopter_status status = horopter_run(&config, count_frames, &next, &summary);
  if (status != HOROPTER_OK) {
    fprintf(stderr, "horopter_run: %s: %s\n", horopter_status_name(status), horopter_last_error());
    return 1;
  }
  if (next != summary.frames || summary.frames != config.frames) {
    fprintf(stderr, "%" PRId64 " frames seen, %" PRId64 " run, %d asked\n", next, summary.frames,
            config.frames);
    return 1;
  }
  printf("%016" PRIx64 "\n", summary.digest);
  return 0;
}
