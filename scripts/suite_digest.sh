#!/usr/bin/env bash
# suite_digest.sh [OUT_DIR] - fly the whole SIL suite (sil/scenarios and its
# estimator/ and faults/ folders) and print one SHA-256 per telemetry.csv and
# their digest: two checkouts fly bit for bit alike when the last lines match.
# Used to show a change that must not change a flight (a move, a speed-up)
# changes none; the flights' wall times are not in the telemetry.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-$(mktemp -d)}"
py=.venv/bin/python
[ -x "$py" ] || { echo "suite_digest: no .venv (scripts/setup_venv.sh)" >&2; exit 2; }
"$py" -m helical_sil batch sil/scenarios --out "$out" --no-plots --jobs 2 >"$out.log" 2>&1 || true
for d in estimator faults; do
    "$py" -m helical_sil batch "sil/scenarios/$d" --out "$out/$d" --no-plots --jobs 2 >>"$out.log" 2>&1 || true
done
(cd "$out" && find . -name telemetry.csv -print0 | sort -z | xargs -0 sha256sum) >"$out/telemetry.sha256"
n=$(wc -l <"$out/telemetry.sha256")
echo "suite_digest: $n telemetry files in $out (log $out.log)"
echo "suite_digest: $(sha256sum <"$out/telemetry.sha256" | cut -d' ' -f1)"
