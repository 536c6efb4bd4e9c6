#!/usr/bin/env bash
# Setup and the whole test suite: installs dependencies, builds with warnings as errors, runs
# every CTest test (unit, verification, CLI, MPI, and the benchmark and figure tests they
# gate), runs the sweep's thread test under ThreadSanitizer, then builds with clang,
# AddressSanitizer and UndefinedBehaviorSanitizer, runs the unit tests again and runs each
# libFuzzer target for 60 s (docs/fuzzing.md), failing on any crash, leak, hang, data race or
# sanitizer report.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DNSB_WARNINGS_AS_ERRORS=ON >/dev/null
cmake --build build -j "$jobs"
ctest --test-dir build --output-on-failure -j "$jobs"

# ThreadSanitizer on a build of only the sweep's thread test and the libraries it links:
# event-driven bridge runs on two worker threads must share no state (docs/fuzzing.md).
if [[ "${NSB_SKIP_TSAN:-0}" != "1" ]]; then
  cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNSB_TSAN=ON -DNSB_WITH_MPI=OFF \
        -DNSB_BUILD_BENCHMARKS=OFF -DNSB_WITH_SICONOS=OFF -DNSB_PYTHON=OFF >/dev/null
  cmake --build build-tsan -j "$jobs" --target threads_test
  TSAN_OPTIONS="halt_on_error=1" ctest --test-dir build-tsan --output-on-failure \
    -R '^sweep\.threads_test$'
fi

if [[ "${NSB_SKIP_SANITIZERS:-0}" != "1" ]]; then
  # One clang build instruments every library with ASan, UBSan and libFuzzer's coverage
  # (build-fuzz/, docs/fuzzing.md): it runs the unit tests under the sanitizers, then each
  # fuzz target for 60 s.
  bash fuzz/run.sh --configure
  cmake --build build-fuzz -j "$jobs" --target nsb_unit_tests
  ctest --test-dir build-fuzz --output-on-failure -j "$jobs" -L unit
  if [[ "${NSB_SKIP_FUZZ:-0}" != "1" ]]; then
    bash fuzz/run.sh "${NSB_FUZZ_SECONDS:-60}"
  fi
fi
