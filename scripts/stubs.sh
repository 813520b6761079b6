#!/usr/bin/env bash
# Regenerate the type stubs of the extension (python/netshape/_core/*.pyi) from the built module with
# pybind11-stubgen. Run after changing a binding (tests/python/test_stubs.py fails until you do):
#   scripts/dev.sh && scripts/stubs.sh
set -euo pipefail
cd "$(dirname "$0")/.."
PY="${NETSHAPE_PYTHON:-$(command -v python3)}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
PYTHONPATH=python "$PY" -m pybind11_stubgen netshape._core --exit-code -o "$out"
rm -f python/netshape/_core/*.pyi
cp "$out"/netshape/_core/*.pyi python/netshape/_core/
echo "stubs written to python/netshape/_core/"
