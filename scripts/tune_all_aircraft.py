#!/usr/bin/env python3
"""Every JSBSim model `aircraft list` keeps: a starter file (`aircraft new`),
a tuning (`tune`), and the standard manoeuvres' pass rate on the starter and
on the tuned gains; one table (OUT/table.md, OUT/table.json).

    .venv/bin/python scripts/tune_all_aircraft.py OUT [--trials 20] [--jobs 2]
        [--backend local|ray] [--only MODEL ...]

Slow (minutes per model): a campaign to run and quote, not a test.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "sil"))

from helical_sil.campaigns import tune as tn  # noqa: E402
from helical_sil.config import aircraft as acm  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out")
    ap.add_argument("--trials", type=int, default=20)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--backend", default="local")
    ap.add_argument("--only", nargs="*", default=None)
    a = ap.parse_args()
    out = Path(a.out)
    (out / "aircraft").mkdir(parents=True, exist_ok=True)
    models = [m for m in acm.find_models() if m.fixed_wing]
    if a.only:
        models = [m for m in models if m.name in a.only]
    rows = []
    for i, m in enumerate(models):
        t0 = time.perf_counter()
        row = {"model": m.name}
        try:
            s = acm.starter(m.name)
            f = out / "aircraft" / f"{m.name}.toml"
            f.write_text(acm.starter_toml(s))
            row["trims"] = bool(s["points"])
            row["sas"] = s["sas"]
            r = tn.tune(f, out / "tune" / m.name, a.trials, 1, a.jobs, a.backend, None, None)
            row.update({k: r[k] for k in ("passed_starter", "passed_best", "criteria",
                                          "cost_starter", "cost_best", "error_starter",
                                          "error_best")})
        except Exception as e:  # one model's failure is a row, not the end of the campaign
            row["error"] = f"{type(e).__name__}: {e}"
        row["wall_s"] = round(time.perf_counter() - t0, 1)
        rows.append(row)
        print(f"[{i + 1}/{len(models)}] {m.name}: {row}", file=sys.stderr, flush=True)
        (out / "table.json").write_text(json.dumps(rows, indent=1) + "\n")
    lines = ["| model | trims | own SAS | starter: criteria passed | tuned: criteria passed "
             "| cost starter -> tuned | note |", "| --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        if "error" in r:
            lines.append(f"| {r['model']} | {'yes' if r.get('trims') else 'no'} | | | | | "
                         f"{r['error'][:80]} |")
            continue
        note = r["error_best"] or r["error_starter"]
        lines.append(f"| {r['model']} | {'yes' if r['trims'] else 'no (trim = false)'} | "
                     f"{'yes' if r['sas'] else ''} | {r['passed_starter']}/{r['criteria']} | "
                     f"{r['passed_best']}/{r['criteria']} | {r['cost_starter']:.2f} -> "
                     f"{r['cost_best']:.2f} | {note[:80]} |")
    (out / "table.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
