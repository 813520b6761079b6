#!/usr/bin/env bash
# Developer loop (no install): build the library, the C++ tests and the extension module in place
# (python/netshape/_core*.so) into build/dev, then run what you ask:
#   scripts/dev.sh                 build only
#   scripts/dev.sh ctest           build + C++ tests
#   scripts/dev.sh pytest [ARGS]   build + pytest with PYTHONPATH=python
set -euo pipefail
cd "$(dirname "$0")/.."
PY="${NETSHAPE_PYTHON:-$(command -v python3)}"
if [ ! -f build/dev/build.ninja ]; then
  cmake -S . -B build/dev -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNETSHAPE_BUILD_TESTS=ON \
    -DNETSHAPE_BUILD_PYTHON=ON -DNETSHAPE_PYTHON_INPLACE=ON -DPython_EXECUTABLE="$PY" \
    -Dpybind11_DIR="$("$PY" -c 'import pybind11; print(pybind11.get_cmake_dir())')" >/dev/null
fi
cmake --build build/dev -j "${NETSHAPE_JOBS:-2}"
case "${1:-}" in
  ctest) shift; ctest --test-dir build/dev -LE python --output-on-failure "$@" ;;
  pytest) shift; PYTHONPATH=python "$PY" -m pytest tests/python "$@" ;;
  "") ;;
  *) echo "usage: scripts/dev.sh [ctest|pytest [ARGS]]" >&2; exit 2 ;;
esac
