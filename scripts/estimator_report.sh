#!/usr/bin/env bash
# The estimator's figures (issue 13): every scenario of sil/scenarios/estimator
# flown on the firmware's own attitude estimate from the simulated sensors,
# each target printed with its measured value. A target missed is reported,
# not an error: exit 0 unless a scenario cannot be flown.
#   scripts/estimator_report.sh [OUT_DIR]     (default out/estimator)
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/estimator}"
scripts/setup_venv.sh >/dev/null
cmake --preset host >/dev/null && cmake --build --preset host --target helical_sil_board >/dev/null
set +e
PYTHONPATH=sil .venv/bin/python -m helical_sil batch sil/scenarios/estimator --out "$out" --no-plots
rc=$?
set -e
[ "$rc" -le 1 ] || exit "$rc"
.venv/bin/python - "$out" <<'PY'
import json, pathlib, sys
for m in sorted(pathlib.Path(sys.argv[1]).glob("*/metrics.json")):
    d = json.loads(m.read_text())
    for c in d["pass_criteria"]:
        lim = " ".join(x for x in (f">= {c['min']}" if c["min"] is not None else "",
                                    f"<= {c['max']}" if c["max"] is not None else "") if x)
        v = "n/a" if c["value"] is None else f"{c['value']:.3f}"
        print(f"{'met   ' if c['ok'] else 'MISSED'} {d['scenario']}: {c['segment']}.{c['metric']} = {v} (target {lim})")
PY
