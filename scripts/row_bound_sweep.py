#!/usr/bin/env python3
"""Fly each estimator and law row of params.def at its min and its max, on the
c172p and the T37, straight and in a 10 deg/s level turn (guided: what
fly-by-wire gives the law with the stick centred or held), on the estimate
with the default sensor model, and print a Markdown table of what flies
(issue 33, item 2). docs/row-bounds.md is its output.

"Flies" (each flight, 40 s; the rest of the table at its default):
  - no ground contact and no refused configuration;
  - straight: |bank| <= 30 deg and |altitude - start| <= 100 m over the last 20 s;
  - turn: the mean turn rate over its last 15 s within 10 % of 10 deg/s, and
    |altitude - start| <= 100 m there.
A row a SIL derives (imu_rate_hz, gyro_limit, accel_limit: the sim rate, the
sensor model's full scales) or a scenario choice (pitch_mode) is not flown.

Usage: PYTHONPATH=sil .venv/bin/python scripts/row_bound_sweep.py [--group dcm|law|all]
       [--rows NAME ...] [--aircraft c172p T37] [--at VALUE ...] > docs/row-bounds.md
Exit 0 when every flight flies, 1 when one does not (the table says which),
2 on a bad argument.
"""
from __future__ import annotations

import argparse
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

from helical_sil.config import params
from helical_sil.config.scenario import (ESTIMATOR_KEYS, ESTIMATOR_SPELLINGS, ScenarioError,
                                         load_scenario)
from helical_sil.sim import lockstep

SCENARIOS = Path(__file__).resolve().parents[1] / "sil" / "scenarios"
NOT_FLOWN = {"imu_rate_hz", "gyro_limit", "accel_limit", "pitch_mode"}
DURATION_S = 40.0
TURN_DEG_S = 10.0


def scenario_text(aircraft: str, table: str, key: str, value: float | int, turn: bool) -> str:
    cmds = ('[[command]]\nt_s = 0\nlabel = "straight"\nturn_rate_deg_s = 0\n')
    if turn:
        cmds += f'[[command]]\nt_s = 10\nlabel = "turn"\nturn_rate_deg_s = {TURN_DEG_S}\n'
    return (f'aircraft = "{aircraft}"\nduration_s = {DURATION_S}\nseed = 1\n'
            f'[attitude]\nsource = "estimate"\n[{table}]\n{key} = {value!r}\n{cmds}')


def flies(text: str, board_lib: str | None, turn: bool) -> str:
    """'ok', or why not."""
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "aircraft"
        p.mkdir()
        for f in (SCENARIOS / "aircraft").glob("*.toml"):
            (p / f.name).write_text(f.read_text())
        s = Path(d) / "s.toml"
        s.write_text(text)
        try:
            sc = load_scenario(s)
            res = lockstep.run(sc, board_lib)
        except (ScenarioError, lockstep.SimError) as e:
            return "refused: " + str(e).split(": ", 2)[-1][:60]
        except Exception as e:  # the board refuses a configuration  # noqa: BLE001
            return "refused: " + str(e)[:60]
    if res.end_reason:
        return "lost: " + res.end_reason.split(":")[0]
    t = res.telemetry
    ts, alt0 = t["t_s"], float(t["altitude_m"][0])
    if turn:
        m = ts >= DURATION_S - 15.0
        rate = float(np.mean(t["turn_rate_deg_s"][m]))
        if abs(rate - TURN_DEG_S) > 0.1 * TURN_DEG_S:
            return f"turn {rate:.1f} deg/s"
    else:
        m = ts >= DURATION_S - 20.0
        bank = float(np.max(np.abs(t["phi_deg"][m])))
        if bank > 30.0:
            return f"bank {bank:.0f} deg"
    dalt = float(np.max(np.abs(t["altitude_m"][m] - alt0)))
    if dalt > 100.0:
        return f"altitude {dalt:.0f} m off"
    return "ok"


def rows(group: str, only: list[str]) -> list[tuple[str, str, str, params.Param, float]]:
    """(table, key, label, row, factor): the scenario key of each row flown."""
    out = []
    if group in ("dcm", "all"):
        back = {name: (k, f) for k, (name, f) in ESTIMATOR_KEYS.items()}
        for p in params.ESTIMATOR:
            if p.name in NOT_FLOWN or p.name not in back:
                continue
            k, f = back[p.name]
            out.append(("estimator", k, f"DCM {p.name}", p, 1.0 / f))
    if group in ("law", "all"):
        for p in params.LAW:
            if p.name not in NOT_FLOWN:
                out.append(("gains", p.name, f"LAW {p.name}", p, 1.0))
    return [r for r in out if not only or r[3].name in only]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--group", choices=("dcm", "law", "all"), default="all")
    ap.add_argument("--rows", nargs="*", default=[], help="only these rows (table names)")
    ap.add_argument("--aircraft", nargs="*", default=["c172p", "T37"])
    ap.add_argument("--at", nargs="*", type=float, default=[],
                    help="fly these values (in the table's unit) instead of min and max")
    ap.add_argument("--board-lib", default=None)
    a = ap.parse_args(argv)
    todo = rows(a.group, a.rows)
    if not todo:
        print("row_bound_sweep: no such row", file=sys.stderr)
        return 2
    cols = [f"{ac} {m}" for ac in a.aircraft for m in ("straight", "turn")]
    print("| row | bound | value | " + " | ".join(cols) + " |")
    print("| --- | --- | --- | " + " | ".join("---" for _ in cols) + " |")
    bad = 0
    for table, key, label, p, factor in todo:
        points = [("at", x) for x in a.at] if a.at else [("min", p.min), ("max", p.max)]
        for bound, v in points:
            value: float | int = v * factor
            if not math.isfinite(value):
                continue
            if p.fmt.scale == 1 and factor == 1.0:  # an integer row: an integer key
                value = int(round(value))
            cells = []
            for ac in a.aircraft:
                for turn in (False, True):
                    r = flies(scenario_text(ac, table, key, value, turn), a.board_lib, turn)
                    bad += r != "ok"
                    cells.append(r)
            unit = ESTIMATOR_SPELLINGS.get(p.name, ("", p.unit))[1] if table == "estimator" \
                else p.unit
            print(f"| {label} | {bound} | {value:g} {unit} | " + " | ".join(cells) + " |",
                  flush=True)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
