#!/usr/bin/env bash
# The two set-up commands of the README:
#   bash scripts/opal.sh run    install what is missing, build, run the main job
#   bash scripts/opal.sh test   install what is missing, build, run every test
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${OPAL_BUILD_DIR:-$root/build}"
mode="${1:-}"
case "$mode" in
  run | test) ;;
  *)
    echo "usage: bash scripts/opal.sh run|test" >&2
    exit 2
    ;;
esac

bash "$root/scripts/install-dependencies.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" -j2

if [[ "$mode" == run ]]; then
  # The main job: render the default preset (the paper's figure 12).
  mkdir -p "$build/output"
  "$build/bin/opal-render" --preset fig12 -o "$build/output/opal-fig12.png" -o "$build/output/opal-fig12.exr"
else
  # Open MPI refuses to run as root unless told (the MPI tests set this too).
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  # Two tests at a time: much of a test is one thread (a process's start, the
  # device's set-up, the sanitized host code), so the second core would idle.
  # The plain build runs what only it can: pvpython, pvbatch, MPI and the GUI.
  ctest --test-dir "$build" --output-on-failure -LE cxx -j2
  # The C++ tests and the programs (label cxx) run once, in the second
  # configuration: their checks and ASan + UBSan's together. Run in both, they
  # were 1830 of the plain run's 2940 test-seconds, the same checks twice.
  sanitize="${build}-sanitize"
  cmake -S "$root" -B "$sanitize" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DOPAL_SANITIZE=ON
  cmake --build "$sanitize" -j2 --target opal-cxx-tests
  ctest --test-dir "$sanitize" --output-on-failure -L cxx -j2
  # The fuzz targets (libFuzzer, clang): kept regression inputs, then a bounded run each.
  fuzz="${build}-fuzz"
  cmake -S "$root/fuzz" -B "$fuzz" -DCMAKE_CXX_COMPILER=clang++
  cmake --build "$fuzz" -j2
  ctest --test-dir "$fuzz" --output-on-failure -j2
fi
