#!/usr/bin/env bash
# Creates .venv at the repo root with the SIL harness's pinned dependencies
# (sil/requirements.lock, from PyPI), the optional Ray backend's
# (sil/requirements-ray.lock: the tests run it), the ground-station link's
# (sil/requirements-mavlink.lock: pymavlink's mavgen and MAVProxy) and the harness itself (sil/,
# editable).
# Idempotent: does nothing when .venv is already in step with the lock file
# and sil/pyproject.toml. Use PYTHON=/path/to/python3.11+ to choose the
# interpreter.
set -euo pipefail
cd "$(dirname "$0")/.."

PY="${PYTHON:-python3}"
VENV=.venv
STAMP="$VENV/.helical_sil_stamp"
want="$(cat sil/requirements.lock sil/requirements-ray.lock sil/requirements-mavlink.lock sil/pyproject.toml | sha256sum | cut -d' ' -f1)"

if [[ -x "$VENV/bin/python" && -f "$STAMP" && "$(cat "$STAMP")" == "$want" ]]; then
    echo "setup_venv: $VENV is up to date"
    exit 0
fi

if ! command -v "$PY" >/dev/null 2>&1; then
    echo "setup_venv: $PY not found; install Python >= 3.11 or set PYTHON=" >&2
    exit 1
fi
if ! "$PY" -c 'import sys; sys.exit(0 if sys.version_info >= (3, 11) else 1)'; then
    echo "setup_venv: $PY is $("$PY" -V 2>&1); the SIL harness needs Python >= 3.11" >&2
    exit 1
fi

if [[ ! -x "$VENV/bin/python" ]]; then
    echo "setup_venv: creating $VENV with $("$PY" -V 2>&1)"
    "$PY" -m venv "$VENV"
fi
echo "setup_venv: installing sil/requirements.lock, sil/requirements-ray.lock and the sil package"
"$VENV/bin/python" -m pip install --quiet --disable-pip-version-check -r sil/requirements.lock \
    -r sil/requirements-ray.lock
# pymavlink and MAVProxy without MAVProxy's GUI dependencies (see the lock file)
"$VENV/bin/python" -m pip install --quiet --disable-pip-version-check --no-deps \
    -r sil/requirements-mavlink.lock
"$VENV/bin/python" -m pip install --quiet --disable-pip-version-check --no-deps -e sil
echo "$want" > "$STAMP"
echo "setup_venv: done ($VENV/bin/python)"
