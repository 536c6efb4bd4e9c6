#!/usr/bin/env bash
# Setup and the whole test suite: installs dependencies, builds with warnings as errors, runs
# every CTest test (unit, verification, and the benchmark smoke tests they gate), then builds
# with AddressSanitizer and UndefinedBehaviorSanitizer and runs the unit tests again, then
# builds the libFuzzer targets with clang and runs each for 60 s (docs/fuzzing.md), failing on
# any crash, leak, hang or sanitizer report.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DNSB_WARNINGS_AS_ERRORS=ON >/dev/null
cmake --build build -j "$jobs"
ctest --test-dir build --output-on-failure -j "$jobs"

if [[ "${NSB_SKIP_SANITIZERS:-0}" != "1" ]]; then
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DNSB_SANITIZE=ON -DNSB_WARNINGS_AS_ERRORS=ON \
    -DNSB_BUILD_BENCHMARKS=OFF >/dev/null
  cmake --build build-asan -j "$jobs" --target nsb_unit_tests
  ctest --test-dir build-asan --output-on-failure -j "$jobs" -L unit
fi

if [[ "${NSB_SKIP_FUZZ:-0}" != "1" ]]; then
  bash fuzz/run.sh "${NSB_FUZZ_SECONDS:-60}"
fi
