#!/usr/bin/env bash
# Sets everything up and runs every test. Usage: scripts/test.sh [--sanitize|--thread]
#   (default)    the Release build's whole ctest suite
#   --sanitize   the unit tests built with ASan+UBSan (the slow real-data
#                accuracy runs, labelled `accuracy`, are left to the default run)
#   --thread     ThreadSanitizer (build-tsan/): the tests of the code that shares
#                state between threads, labels pipeline (the scheduler, the
#                stages), frontend (the vision library: front end, thread
#                pool, capture) and hardware (the drivers' worker threads
#                against the simulators), their four test binaries; and the
#                Python module's threaded pytest file. Not the CLI tests.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
jobs="$(nproc 2>/dev/null || echo 2)"
if [ "${1:-}" = "--thread" ]; then
  "$root/scripts/build.sh" --thread horopter_pipeline_tests horopter_app_tests \
    horopter_vision_tests horopter_hardware_tests horopter_python
  # What is suppressed, and why, is in the file; second_deadlock_stack for
  # lock-order reports.
  export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$root/scripts/tsan.supp"
  cd "$root/build-tsan"
  # OpenCV's own threads are oneTBB's (not built with TSan): TSan cannot see
  # TBB hand a cv::parallel_for_ body to a worker, and reports the worker's
  # reads of the caller's stack without a worker stack to suppress by (notes
  # in scripts/tsan.supp). Where a test renders the synthetic scene (cv::
  # parallel_for_ over its textures and rasteriser), it runs on one CPU
  # (taskset): oneTBB, and so OpenCV, then starts no worker; Horopter's own
  # threads are as many as ever (std::thread::hardware_concurrency ignores
  # the affinity mask) and TSan checks them the same way.
  one_cpu=(taskset -c "$(taskset -pc $$ | sed 's/.*: *//; s/[-,].*//')")
  echo "test: ctest (ThreadSanitizer: pipeline, frontend, hardware; no CLI tests)"
  ctest --output-on-failure -j "$jobs" -L "pipeline|frontend|hardware" -LE cli \
    -E "^Capture\.SyntheticRunIsDeterministicAcrossThreadsAndDepth$"
  "${one_cpu[@]}" ctest --output-on-failure \
    -R "^Capture\.SyntheticRunIsDeterministicAcrossThreadsAndDepth$"
  # The Python module built with TSan, its pytest files on the bindings'
  # threads run by the interpreter it was built for (python3, not built with
  # TSan: libtsan is preloaded, and TSan sees the GIL's pthread locks). Each
  # renders the synthetic scene (conftest.py): one CPU, as above.
  # The file whose tests run the bindings' threads: test_threads (Python
  # threads in kernels at once, the GIL released). Left out for CI's 45
  # minutes (the three files took about 250 s here, on one CPU):
  # test_pipeline (the scheduler's stages, which the pipeline label's C++
  # tests run under TSan above) and test_kernels (the front end with two
  # threads, every backend: the frontend label above). Left out: the files on one thread (the
  # arrays, geometry, calibration and file formats, the StereoBM setters,
  # metadata, stubs, examples: each about as slow under TSan as the three
  # above, about 330 s all told on the shared machine), those that run the
  # CLI or the C tool (not built here), and test_eval_cluster (Dask worker
  # processes).
  echo "test: pytest (ThreadSanitizer: the Python module's threads)"
  module_dir="$root/build-tsan/bindings/python"
  # The TSan runtime the module was linked with, loaded first. awk reads
  # all of ldd's output: leaving early made ldd's last write fail (SIGPIPE),
  # ldd exit 1 and, under pipefail, this script stop without a word (CI's
  # run of c478011; 5 of 30 tries here).
  tsan_runtime="$(ldd "$module_dir"/horopter*.so | awk '/libtsan/ && !found { print $3; found = 1 }')"
  [ -n "$tsan_runtime" ] || { echo "test: no libtsan in $module_dir's module" >&2; exit 1; }
  python="$(sed -n 's/^_Python_EXECUTABLE:INTERNAL=//p' "$root/build-tsan/CMakeCache.txt")"
  # --capture=sys: a TSan report (written to file descriptor 2 as the
  # process stops) is not swallowed by pytest's capture.
  (cd "$root/bindings/python/tests" &&
    "${one_cpu[@]}" env PYTHONPATH="$module_dir" PYTHONDONTWRITEBYTECODE=1 \
      HOROPTER_SOURCE_DIR="$root" LD_PRELOAD="$tsan_runtime" "${python:-python3}" -m pytest \
      -q --capture=sys -p no:cacheprovider -rs test_threads.py)
  exit 0
fi
"$root/scripts/build.sh" "$@"
if [ "${1:-}" = "--sanitize" ]; then
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  # PoCL and the ICD loader keep allocations until exit; nothing else is suppressed.
  export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp:print_suppressions=0"
  cd "$root/build-asan"
  echo "test: ctest (sanitizers, without the accuracy label)"
  # Also left out, to keep CI under 45 minutes (41 and 11 s): the replays
  # of closed-loop trials (the detector and tracker code they run is under
  # ASan in the other Detection.*, BodyFace.*, ShirtSkin.* and TrackingTrial.*
  # tests; the two shirts' replays take 10-15 s each in Release) and the help
  # of every command. bindings.install_consumer stays: an -E'd
  # fixture setup is not run for the tests that require it.
  ctest --output-on-failure -j "$jobs" -LE accuracy \
    -E '^(Detection\.(AFaceSizeLearntFromAFalseFaceDoesNotHideTheRealOne|AFalseFaceOnTheShirtIsNoFace|TheSleeveOfASkinColouredShirtIsNoHand)|cli\.help_lists_every_flag)$'
else
  cd "$root/build"
  echo "test: ctest"
  ctest --output-on-failure -j "$jobs"
fi
