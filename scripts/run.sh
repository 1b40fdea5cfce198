#!/usr/bin/env bash
# Sets everything up and runs the main job on the built-in default input.
# Extra arguments go to `horopter run` (see build/bin/horopter run --help).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
# Only the CLI and what it links: the tests, the bench and the bindings are
# scripts/test.sh's to build (the same build/ tree, so nothing is built twice).
"$root/scripts/build.sh" horopter
cd "$root"
echo "run: build/bin/horopter run -o out $*"
build/bin/horopter run -o out "$@"
