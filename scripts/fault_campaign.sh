#!/usr/bin/env bash
# The SIL fault campaign (issue 7, item 5) from one command:
#  1. upset recovery: 50 seeded random upsets per aircraft (T37, c172p), the
#     tuned earth-frame pitch method; then the same upsets with the tilt-cross
#     pitch method for comparison;
#  2. the sensor-fault and severe-turbulence scenarios (sil/scenarios/faults),
#     then the seeded ones (turbulence, noise, bias) again with seeds 2..10.
# Results: OUT/upsets/summary.md, OUT/upsets_tiltcross/summary.md,
# OUT/scenarios/summary.md, OUT/seeds/summary.md (and .json). Exit status non-zero if any upset of
# the tuned campaign or any fault scenario fails (the tilt-cross comparison is
# reported, not gated).
#   scripts/fault_campaign.sh [OUT] [COUNT] [SEED]     (default out/faults 50 1)
set -euo pipefail
cd "$(dirname "$0")/.."
OUT="${1:-out/faults}"
COUNT="${2:-50}"
SEED="${3:-1}"
JOBS="${HT_FAULT_JOBS:-$(nproc 2>/dev/null || echo 1)}"

scripts/setup_venv.sh
cmake --preset host >/dev/null
cmake --build --preset host
export HT_SIL_BOARD_LIB="${HT_SIL_BOARD_LIB:-$PWD/build/host/boards/sil/libhelical_sil_board.so}"
export MPLBACKEND=Agg
PY=.venv/bin/python

status=0
echo "== upset recovery: $COUNT per aircraft, seed $SEED, earth-frame pitch (tuned)"
"$PY" -m helical_sil upsets --aircraft T37 c172p --count "$COUNT" --seed "$SEED" \
    --jobs "$JOBS" --out "$OUT/upsets" || status=1
echo "== upset recovery, the same upsets with the tilt-cross pitch method (comparison)"
"$PY" -m helical_sil upsets --aircraft T37 c172p --count "$COUNT" --seed "$SEED" \
    --jobs "$JOBS" --pitch-mode tilt_cross --out "$OUT/upsets_tiltcross" || true
echo "== sensor faults and severe turbulence (sil/scenarios/faults)"
"$PY" -m helical_sil batch sil/scenarios/faults --out "$OUT/scenarios" || status=1
echo "== the seeded ones again with seeds 2..10 (turbulence, noise and spikes, bias)"
"$PY" -m helical_sil batch sil/scenarios/faults --no-plots --out "$OUT/seeds" \
    --only c172p_turbulence_severe t37_turbulence_severe t37_roll_inverted_turbulence_severe \
           c172p_airspeed_noise_spikes t37_airspeed_noise_spikes c172p_gyro_bias t37_gyro_bias \
    --seeds 2 3 4 5 6 7 8 9 10 || status=1
echo "== fault campaign: $([ $status = 0 ] && echo PASS || echo FAIL) (tables: $OUT/*/summary.md)"
exit $status
