#!/usr/bin/env bash
# The README's first command: from a fresh clone, set up the venv, build the
# host preset (library, host board, tests), and fly the default scenario (a
# T-37 climbing helical turn, a roll to inverted, an inverted helical turn and
# the roll back). Plots, telemetry and metrics go to the output folder
# (default out/default; or give one: scripts/fly.sh [SCENARIO.toml] [OUT_DIR]).
set -euo pipefail
cd "$(dirname "$0")/.."

SCENARIO="${1:-sil/scenarios/default.toml}"
OUT="${2:-out/$(basename "$SCENARIO" .toml)}"

scripts/setup_venv.sh
cmake --preset host >/dev/null
cmake --build --preset host --target helical_sil_board
status=0
HT_SIL_BOARD_LIB="build/host/boards/sil/libhelical_sil_board.so" \
    .venv/bin/python -m helical_sil run "$SCENARIO" --out "$OUT" || status=$?
if [[ $status -ge 2 ]]; then
    exit $status
fi
echo
echo "fly: plots (attitude, turn_rate, altitude, surfaces, ground_track .png), telemetry.csv"
echo "fly: and metrics.json are in $(cd "$OUT" && pwd)"
exit $status
