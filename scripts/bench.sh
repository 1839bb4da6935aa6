#!/usr/bin/env bash
# The benchmark of issue 6, in one command: instructions per control step on
# Cortex-M0/M3/M4/M4F (Unicorn), the same law in float and double, host
# ns/step and callgrind, footprint and stack; prints Markdown tables.
#
#   scripts/bench.sh            full run (10 000 steps + edge cases, -O2 and -Os)
#   scripts/bench.sh --quick    CI run (200 steps, -O2): fails only on breakage
#   scripts/bench.sh --help     every option (bench/py/bench.py)
#   scripts/bench.sh --dcm      the attitude estimator (bench/py/bench_dcm.py)
#   scripts/bench.sh --sil      the SIL's speed against JSBSim's bare loop, side by
#                               side; --batch, --tune N add campaign wall times
#                               (bench/py/bench_sil.py --help)
#
# Needs arm-none-eabi-gcc, gcc, python3 (venv) and, for the callgrind figure,
# valgrind. Makes bench/.venv from bench/requirements.lock on first use
# (idempotent: reinstalls only when the lock file changes). Results also go
# to bench/out/ (table.md, profile.md, results.json).
set -euo pipefail
cd "$(dirname "$0")/.."

if [[ ${1:-} == --sil ]]; then # the SIL harness's own venv and board library, no ARM tools
    shift
    [[ -x .venv/bin/python ]] || { echo "bench.sh: no .venv (scripts/setup_venv.sh)" >&2; exit 2; }
    PYTHONPATH="$PWD/sil${PYTHONPATH:+:$PYTHONPATH}" exec .venv/bin/python bench/py/bench_sil.py "$@"
fi

for tool in arm-none-eabi-gcc arm-none-eabi-objdump arm-none-eabi-size arm-none-eabi-addr2line gcc python3; do
    if ! command -v "$tool" >/dev/null 2>&1; then
        echo "bench.sh: $tool not found (Debian: apt-get install gcc-arm-none-eabi binutils-arm-none-eabi gcc python3-venv)" >&2
        exit 2
    fi
done
if ! command -v valgrind >/dev/null 2>&1; then
    echo "bench.sh: valgrind not found: the callgrind column will be '-'" >&2
fi

venv=bench/.venv
lock=bench/requirements.lock
stamp=$venv/.lock.sha256
want=$(sha256sum "$lock" | cut -d' ' -f1)
if [[ ! -x $venv/bin/python || ! -f $stamp || $(cat "$stamp") != "$want" ]]; then
    echo "bench.sh: installing $lock into $venv" >&2
    rm -rf "$venv"
    python3 -m venv "$venv"
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check --require-hashes \
        -r "$lock"
    echo "$want" >"$stamp"
fi

if [[ ${1:-} == --dcm ]]; then # the estimator: bench/py/bench_dcm.py --help
    shift
    exec "$venv/bin/python" bench/py/bench_dcm.py "$@"
fi
exec "$venv/bin/python" bench/py/bench.py "$@"
