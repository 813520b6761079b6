#!/usr/bin/env bash
# Install everything netshape needs, idempotently:
#   - Debian packages (compiler, CMake, Eigen, CGAL, doctest) via apt-get, only if missing;
#   - a virtual environment in .venv (or the active one, or NETSHAPE_PYTHON) with netshape and its
#     test and benchmark extras, built from this checkout by pip (scikit-build-core).
# Safe to run any number of times; a second run only rebuilds what changed.
set -euo pipefail
cd "$(dirname "$0")/.."

APT_PACKAGES=(build-essential cmake ninja-build pkg-config libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev
              doctest-dev python3-dev python3-venv)
missing=()
for p in "${APT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  echo "netshape setup: apt-get install ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

PY="${NETSHAPE_PYTHON:-}"
if [ -z "$PY" ]; then
  if [ -n "${VIRTUAL_ENV:-}" ]; then
    PY="$VIRTUAL_ENV/bin/python"
  else
    [ -x .venv/bin/python ] || python3 -m venv .venv
    PY=.venv/bin/python
  fi
fi
"$PY" -m pip install -q --disable-pip-version-check --upgrade pip >/dev/null
"$PY" -m pip install -q --disable-pip-version-check "scikit-build-core>=0.10" "pybind11>=2.12"
# --no-build-isolation: build with the tools just installed; build/ keeps the CMake tree between runs.
"$PY" -m pip install -q --disable-pip-version-check --no-build-isolation ".[test,bench]"
echo "netshape setup: installed into $("$PY" -c 'import sys; print(sys.prefix)')"
