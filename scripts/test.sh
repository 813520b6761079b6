#!/usr/bin/env bash
# README command 2: install everything, then run every test:
#   1. the C++ unit tests and the C++ examples, built with AddressSanitizer + UndefinedBehaviorSanitizer (ctest);
#   2. the Python suite against the installed package (pytest), which also builds
#      examples/consumer against the installed C++ library.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh test
PY="${NETSHAPE_PYTHON:-${VIRTUAL_ENV:+$VIRTUAL_ENV/bin/python}}"; PY="${PY:-.venv/bin/python}"
PY="$(cd "$(dirname "$PY")" && pwd)/$(basename "$PY")"

JOBS="${NETSHAPE_JOBS:-$(nproc)}"
cmake -S . -B build/sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g -O1" \
  -DNETSHAPE_BUILD_TESTS=ON -DNETSHAPE_BUILD_EXAMPLES=ON -DNETSHAPE_SANITIZE=ON -DPython_EXECUTABLE="$PY" >/dev/null
cmake --build build/sanitize -j "$JOBS"
# pytest is registered in ctest too (label "python"); here it runs once, directly, below.
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build/sanitize -LE python --output-on-failure -j "$JOBS"
# one pytest worker per core; a file stays on one worker, so its module fixtures are built once. Each
# worker keeps NumPy's BLAS to one thread: with a thread pool per worker the cores are oversubscribed and
# OpenBLAS's waiting threads burn the CPU (diagnose of a 4 800-point bundle: 24 s of CPU, 10 s with one).
OPENBLAS_NUM_THREADS="${OPENBLAS_NUM_THREADS:-1}" OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}" "$PY" -m pytest tests/python -q -n "$JOBS" --dist loadfile
