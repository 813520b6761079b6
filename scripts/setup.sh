#!/usr/bin/env bash
# Install netshape, idempotently:
#   - Debian packages (compiler, CMake, Eigen, CGAL, doctest) via apt-get, only if missing;
#   - a virtual environment in .venv (or the active one, or NETSHAPE_PYTHON) with netshape built from
#     this checkout by pip (scikit-build-core), plus the optional extras named as arguments:
#       scripts/setup.sh              netshape and its run-time dependencies (what `netshape demo` needs)
#       scripts/setup.sh test         + the test extra (pytest, hypothesis, geomdl, sympy, stub generator)
#       scripts/setup.sh test bench   + the benchmark peers (gcodeparser, pygcode, toppra)
# Safe to run any number of times; a second run only rebuilds what changed. Works from an empty pip
# cache: the tools that sdist-only dependencies need to build (setuptools, wheel) are installed first.
set -euo pipefail
cd "$(dirname "$0")/.."

extras=""
for e in "$@"; do
  case "$e" in
    test|bench) extras="${extras:+$extras,}$e" ;;
    *) echo "netshape setup: unknown extra '$e' (expected: test, bench)" >&2; exit 2 ;;
  esac
done

APT_PACKAGES=(build-essential cmake ninja-build pkg-config libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev
              python3-dev python3-venv)
[ -n "$extras" ] && APT_PACKAGES+=(doctest-dev)
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
PIP=("$PY" -m pip install -q --disable-pip-version-check)
"${PIP[@]}" --upgrade pip >/dev/null
# Build tools first: scikit-build-core and pybind11 build netshape itself (below, without isolation so
# build/ keeps its CMake tree between runs); setuptools and wheel build any dependency that PyPI ships
# only as an sdist (e.g. euclid3, which pygcode in the bench extra needs).
"${PIP[@]}" "scikit-build-core>=0.10" "pybind11>=2.12" "setuptools>=64" wheel
echo "netshape setup: building netshape${extras:+ with [$extras]} (the first build compiles the C++ core, a few minutes)"
"${PIP[@]}" --no-build-isolation ".${extras:+[$extras]}"
echo "netshape setup: installed into $("$PY" -c 'import sys; print(sys.prefix)')"
