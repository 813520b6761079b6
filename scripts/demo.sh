#!/usr/bin/env bash
# README command 1: install netshape with its run-time dependencies only, then run the main job on the
# bundled default.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
PY="${NETSHAPE_PYTHON:-${VIRTUAL_ENV:+$VIRTUAL_ENV/bin/python}}"; PY="${PY:-.venv/bin/python}"
"$(dirname "$PY")/netshape" demo "$@"
