#!/usr/bin/env bash
# The test command: installs what is missing, builds, runs the whole suite.
#   scripts/test.sh             release build in build/, all tests
#   scripts/test.sh --sanitize  address + undefined-behaviour sanitizer build in build-sanitize/
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if [ "${1:-}" = "--sanitize" ]; then
  "$root/scripts/build.sh" "$root/build-sanitize" -DDARCYDEM_SANITIZE=ON -DDARCYDEM_BUILD_BENCH=OFF \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo
  cd "$root/build-sanitize"
  # One thread: the sanitizers do not see through OpenMP's runtime reliably.
  OMP_NUM_THREADS=1 ctest --output-on-failure -j "$(nproc)"
else
  "$root/scripts/build.sh" "$root/build" -DDARCYDEM_WERROR=ON
  cd "$root/build"
  ctest --output-on-failure -j "$(nproc)"
fi
