#!/usr/bin/env bash
# run-all.sh: the whole test suite. Builds and tests the project twice:
# a release build, then an AddressSanitizer + UndefinedBehaviorSanitizer build.
# Both run every test on both headless back ends (EGL surfaceless, OSMesa).
# Both build with -DOIT_WERROR=ON: a compiler warning fails the run.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
jobs=$(nproc)

echo "== release build"
# its own directory: build/ is the README's build and the one bat/run_comparison.sh
# times (Release when it makes it); configuring it here would change its build type
cmake -S . -B build-tests -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DOIT_WERROR=ON >/dev/null
cmake --build build-tests -j "$jobs"
ctest --test-dir build-tests --output-on-failure -j "$jobs"

echo "== sanitizer build (ASan + UBSan)"
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DOIT_SANITIZE=ON -DOIT_WERROR=ON >/dev/null
cmake --build build-sanitize -j "$jobs"
# Leaks inside Mesa's own libraries (llvmpipe, LLVM, the EGL/OSMesa drivers)
# are suppressed, and only those: see tests/lsan.supp.
export LSAN_OPTIONS="suppressions=$root/tests/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir build-sanitize --output-on-failure -j "$jobs"
