"""Upset-recovery campaign (issue 7, item 5): random initial attitudes, the
controller commanded to level upright flight.

For each aircraft, ``count`` upsets are drawn from a seeded generator (the
same ``--seed`` gives the same upsets, bit for bit): bank anywhere in
[-180, 180) deg (half of them inverted), pitch in [-80, 80] deg, any heading,
calibrated airspeed from just above the stall to a little above cruise, body rates up to
+-20 deg/s on each axis. The first four upsets of every campaign are fixed
corners (inverted at low speed, 80 deg nose up at low speed, 80 deg nose down
inverted at cruise, knife edge at low speed); the rest are random.

Each upset becomes a scenario file (``OUT/<aircraft>/upset_NNN.toml``, with an
``[upset]`` table) that ``python -m helical_sil run`` flies again on its own:
JSBSim is trimmed at the start altitude and cruise speed (the servo trims,
throttle and pitch trim a pilot would have set before the upset; the harness
carries them over as usual), then re-initialised at the upset state, untrimmed.
From t = 0 the controller is commanded to level, upright, wings-level flight:
turn rate 0, not inverted, the altitude hold at the start altitude and the
airspeed hold at cruise speed (earth-frame pitch).

Recovered = the tilt (DCM bottom row) within 10 deg of the law's target tilt
(metrics.target_tilt: level upright, pitched by the altitude hold's pitch
ratio) from some time on to the end of the run, for at least the last 5 s,
and the lowest point of the run at least ``floor_m`` above the ground
(JSBSim's terrain is at sea level).
"""

from __future__ import annotations

import json
import math
import sys
import time
import zlib
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

from helical_sil.campaigns.backend import map_ordered
from helical_sil.campaigns.runner import progress_bar, run_one
from helical_sil.config.scenario import DEFAULT_AIRCRAFT_DIR, Upset, load_aircraft

# Calibrated airspeed range (m/s) of the upsets: just above the clean stall to
# a little above cruise. c172p: stall about 48 KCAS (24.7 m/s) clean -> 26 m/s;
# cruise 50 m/s TAS at 2500 m is about 44 m/s CAS; the top, 50 m/s CAS, is about
# 56 m/s TAS. T-37: stall about 85 KCAS (44 m/s) -> 46 m/s; cruise 110 m/s TAS
# at 2500 m is about 97 m/s CAS; the top, 110 m/s CAS, is about 124 m/s TAS.
SPEED_RANGE_M_S: dict[str, tuple[float, float]] = {"c172p": (26.0, 50.0), "T37": (46.0, 110.0)}
RATE_MAX_DEG_S = 20.0
PITCH_MAX_DEG = 80.0
DEFAULT_ALTITUDE_M = 2500.0
DEFAULT_DURATION_S = 45.0
DEFAULT_FLOOR_M = 300.0   # ~1000 ft above the ground: the lowest point allowed
RECOVERY_MAX_S = 40.0     # recovered (and held 5 s) by the end of a 45 s run


@dataclass
class UpsetResult:
    index: int
    aircraft: str
    upset: dict[str, float]
    recovered: bool
    recovery_time_s: float | None
    altitude_loss_m: float
    min_altitude_m: float
    tilt_error_end_deg: float | None
    airspeed_min_m_s: float
    airspeed_max_m_s: float
    passed: bool
    scenario: str
    known: bool = False  # listed in --known-failures
    # issue 17: near a vertical fuselage, the law aileron's total variation per
    # second (metrics.near_vertical_metrics; None: the run never came near it)
    near_vertical_s: float | None = None
    aileron_tv_near_vertical_per_s: float | None = None


def parse_known(items: list[str], aircraft: list[str], count: int) -> list[str]:
    """Check --known-failures entries: AIRCRAFT:INDEX of this campaign."""
    out = []
    for it in items:
        ac, sep, idx = it.partition(":")
        if not sep or ac not in aircraft or not idx.isdigit() or int(idx) >= count:
            raise ValueError(f"--known-failures: {it!r} is not AIRCRAFT:INDEX of this campaign "
                             f"(aircraft {', '.join(aircraft)}; index 0..{count - 1})")
        out.append(f"{ac}:{int(idx)}")
    return out


def _stream(aircraft: str) -> int:
    return zlib.crc32(aircraft.encode())


def generate(aircraft: str, count: int, seed: int,
             speed_range: tuple[float, float] | None = None) -> list[Upset]:
    """count upsets for an aircraft, a pure function of (aircraft, count, seed)
    (the first min(count, 4) are the fixed corners)."""
    lo, hi = speed_range or SPEED_RANGE_M_S.get(aircraft, (0.5, 1.0))
    corners = [Upset(180.0, 0.0, 0.0, lo), Upset(0.0, PITCH_MAX_DEG, 90.0, lo),
               Upset(180.0, -PITCH_MAX_DEG, 180.0, hi), Upset(90.0, 0.0, 270.0, lo)]
    out = corners[:count]
    rng = np.random.Generator(np.random.PCG64([seed, _stream(aircraft)]))
    for _ in range(count - len(out)):
        roll, pitch, head, v = (rng.uniform(-180.0, 180.0), rng.uniform(-80.0, 80.0),
                                rng.uniform(0.0, 360.0), rng.uniform(lo, hi))
        p, q, r = rng.uniform(-RATE_MAX_DEG_S, RATE_MAX_DEG_S, size=3)
        out.append(Upset(*(round(float(x), 3) for x in (roll, pitch, head, v, p, q, r))))
    return out


# --- the vertical grid (issue 17, item 4) ---
VERTICAL_PITCH_DEG = (90.0, 85.0, -85.0, -90.0)
VERTICAL_ROLL_DEG = (0.0, 90.0, 180.0, -90.0)
GRIDS = ("random", "vertical", "both")


def vertical_grid(aircraft: str, speed_range: tuple[float, float] | None = None) -> list[Upset]:
    """Near-vertical climbs and dives: pitch +-90 and +-85 deg, each with the
    wings at 0, 90, 180 and -90 deg of roll, at the lowest and the highest
    speed of the campaign, no body rates (32 upsets; heading 0). At +-90 deg
    the fuselage is vertical: sqrt(X^2 + Z^2) = 0, where Eq. 9's roll sign is
    set by noise (the law option vertical_fade)."""
    lo, hi = speed_range or SPEED_RANGE_M_S.get(aircraft, (0.5, 1.0))
    return [Upset(roll, pitch, 0.0, v) for pitch in VERTICAL_PITCH_DEG
            for roll in VERTICAL_ROLL_DEG for v in (lo, hi)]


def upset_list(aircraft: str, count: int, seed: int, grid: str = "random",
               speed_range: tuple[float, float] | None = None) -> list[Upset]:
    """The campaign's upsets: the random ones (count), the vertical grid, or
    both (the random ones first: their indices do not change)."""
    if grid not in GRIDS:
        raise ValueError(f"grid {grid!r}: one of {', '.join(GRIDS)}")
    out = generate(aircraft, count, seed, speed_range) if grid != "vertical" else []
    if grid != "random":
        out += vertical_grid(aircraft, speed_range)
    return out


def overrides_toml(overrides: dict[str, float] | None) -> str:
    """[gains] and [guidance] tables of law / guidance rows (the campaign's --set)."""
    if not overrides:
        return ""
    from helical_sil.campaigns.options import row_of
    law = {k: v for k, v in overrides.items() if row_of(k)[0] == "law"}
    gd = {k: v for k, v in overrides.items() if row_of(k)[0] == "guidance"}
    text = ""
    if law:
        text += "\n[gains]\n" + "".join(f"{k} = {v!r}\n" for k, v in law.items())
    if gd:
        text += "\n[guidance]\n" + "".join(f"{k} = {v!r}\n" for k, v in gd.items())
    return text
# --- end vertical grid ---


def scenario_toml(aircraft: str, up: Upset, index: int, seed: int, altitude_m: float,
                  duration_s: float, floor_m: float, cruise_m_s: float,
                  pitch_mode: str = "earth_frame", attitude: str = "estimate",
                  overrides: dict[str, float] | None = None) -> str:
    """The scenario file of one upset (flown by `run` like any other);
    overrides: law or guidance rows (--set)."""
    return f"""# Upset {index} of the {aircraft} campaign (python -m helical_sil upsets, seed {seed}).
# Trimmed at {altitude_m:g} m / {cruise_m_s:g} m/s, then released untrimmed at [upset];
# commanded to level upright flight on the altitude and airspeed holds.
aircraft = "{aircraft}"
description = "upset {index}: roll {up.roll_deg:g} pitch {up.pitch_deg:g} deg at {up.calibrated_airspeed_m_s:g} m/s CAS"
duration_s = {duration_s:g}
seed = {seed}

[attitude]
source = "{attitude}"
{overrides_toml(overrides)}
[initial]
altitude_m = {altitude_m:g}
airspeed_m_s = {cruise_m_s:g}

[upset]
roll_deg = {up.roll_deg!r}
pitch_deg = {up.pitch_deg!r}
heading_deg = {up.heading_deg!r}
calibrated_airspeed_m_s = {up.calibrated_airspeed_m_s!r}
p_deg_s = {up.p_deg_s!r}
q_deg_s = {up.q_deg_s!r}
r_deg_s = {up.r_deg_s!r}

[[command]]
t_s = 0
label = "recover"
turn_rate_deg_s = 0
altitude_m = {altitude_m:g}
airspeed_m_s = {cruise_m_s:g}
inverted = false
pitch_mode = "{pitch_mode}"

[[pass]]
metric = "recovery_time_s"
max = {RECOVERY_MAX_S:g}

[[pass]]
metric = "min_altitude_m"
min = {floor_m:g}
"""


def _fly(job: tuple[str, str, str | None, bool]) -> dict[str, Any]:
    path, out, board_lib, plots = job
    return run_one(Path(path), Path(out), board_lib, plots=plots)


def _result(i: int, aircraft: str, up: Upset, m: dict[str, Any], path: Path,
            altitude_m: float) -> UpsetResult:
    run = m["run"]
    rec = run.get("recovery_time_s")
    return UpsetResult(
        index=i, aircraft=aircraft, upset=asdict(up), recovered=rec is not None,
        recovery_time_s=rec, altitude_loss_m=max(0.0, altitude_m - run["min_altitude_m"]),
        min_altitude_m=run["min_altitude_m"], tilt_error_end_deg=run.get("tilt_error_end_deg"),
        airspeed_min_m_s=run["airspeed_min_m_s"], airspeed_max_m_s=run["airspeed_max_m_s"],
        passed=bool(m["passed"]), scenario=str(path),
        near_vertical_s=run.get("near_vertical_s"),
        aileron_tv_near_vertical_per_s=run.get("near_vertical_aileron_tv_per_s"))


def summarize(results: list[UpsetResult], altitude_m: float) -> dict[str, Any]:
    """Per-aircraft aggregate: recovered fraction, worst and median recovery
    time, worst altitude loss, lowest altitude."""
    n = len(results)
    times = [r.recovery_time_s for r in results if r.recovery_time_s is not None]
    worst_t = max(results, key=lambda r: math.inf if r.recovery_time_s is None
                  else r.recovery_time_s) if results else None
    worst_h = max(results, key=lambda r: r.altitude_loss_m) if results else None
    return {
        "count": n, "recovered": len(times), "passed": sum(r.passed for r in results),
        "fraction_recovered": len(times) / n if n else 0.0,
        "recovery_time_worst_s": None if len(times) < n else (max(times) if times else None),
        "recovery_time_median_s": float(np.median(times)) if times else None,
        "worst_time_upset": worst_t.index if worst_t else None,
        "recovery_time_worst_recovered_s": max(times) if times else None,
        "altitude_loss_worst_m": worst_h.altitude_loss_m if worst_h else None,
        "altitude_loss_worst_recovered_m": max((r.altitude_loss_m for r in results
                                                if r.recovered), default=None),
        "worst_loss_upset": worst_h.index if worst_h else None,
        "min_altitude_m": min(r.min_altitude_m for r in results) if results else None,
        "start_altitude_m": altitude_m,
        "aileron_tv_near_vertical_worst_per_s": max(
            (r.aileron_tv_near_vertical_per_s for r in results
             if r.aileron_tv_near_vertical_per_s is not None), default=None),
    }


def _fmt(v: float | None, f: str = "{:.1f}") -> str:
    return "-" if v is None else f.format(v)


def summary_table(summaries: dict[str, dict[str, Any]]) -> str:
    heads = ("aircraft", "upsets", "recovered", "fraction", "worst t s", "median t s",
             "worst h loss m", "worst h loss m (recovered)", "lowest h m", "start h m",
             "ail TV/s near vertical (worst)", "result")
    rows = []
    for ac, s in summaries.items():
        rows.append((ac, str(s["count"]), str(s["recovered"]),
                     f"{100.0 * s['fraction_recovered']:.0f} %",
                     _fmt(s["recovery_time_worst_s"]) if s["recovered"] == s["count"] else
                     f"∞ ({_fmt(s['recovery_time_worst_recovered_s'])} recovered)",
                     _fmt(s["recovery_time_median_s"]), _fmt(s["altitude_loss_worst_m"]),
                     _fmt(s["altitude_loss_worst_recovered_m"]),
                     _fmt(s["min_altitude_m"], "{:.0f}"), f"{s['start_altitude_m']:g}",
                     _fmt(s.get("aileron_tv_near_vertical_worst_per_s"), "{:.2f}"),
                     "PASS" if s["passed"] == s["count"] else
                     f"FAIL {s['count'] - s['passed']}" + (f" ({s['known']} known)"
                                                           if s.get("known") else "")))
    return _md(heads, rows)


def detail_table(results: list[UpsetResult]) -> str:
    heads = ("aircraft", "#", "roll°", "pitch°", "CAS m/s", "p,q,r °/s", "t rec s",
             "h loss m", "V min–max m/s", "tilt end°", "near vert s", "ail TV/s",
             "result")
    rows = []
    for r in results:
        u = r.upset
        rows.append((r.aircraft, str(r.index), f"{u['roll_deg']:.0f}", f"{u['pitch_deg']:.0f}",
                     f"{u['calibrated_airspeed_m_s']:.0f}",
                     f"{u['p_deg_s']:.0f},{u['q_deg_s']:.0f},{u['r_deg_s']:.0f}",
                     _fmt(r.recovery_time_s, "{:.2f}"), _fmt(r.altitude_loss_m),
                     f"{r.airspeed_min_m_s:.0f}–{r.airspeed_max_m_s:.0f}",
                     _fmt(r.tilt_error_end_deg), _fmt(r.near_vertical_s, "{:.2f}"),
                     _fmt(r.aileron_tv_near_vertical_per_s, "{:.2f}"),
                     "PASS" if r.passed else ("FAIL (known)" if r.known else "FAIL")))
    return _md(heads, rows)


def _md(heads: tuple[str, ...], rows: list[tuple[str, ...]]) -> str:
    widths = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h)
              for i, h in enumerate(heads)]
    line = "| " + " | ".join(h.ljust(w) for h, w in zip(heads, widths)) + " |"
    sep = "|" + "|".join("-" * (w + 2) for w in widths) + "|"
    body = ["| " + " | ".join(c.ljust(w) for c, w in zip(r, widths)) + " |" for r in rows]
    return "\n".join([line, sep, *body])


def run_campaign(aircraft: list[str], count: int, seed: int, out: Path,
                 board_lib: str | None, altitude_m: float = DEFAULT_ALTITUDE_M,
                 duration_s: float = DEFAULT_DURATION_S, floor_m: float = DEFAULT_FLOOR_M,
                 jobs: int = 1, plots: bool = False,
                 known_failures: list[str] | None = None,
                 pitch_mode: str = "earth_frame", attitude: str = "estimate",
                 backend: str = "local", address: str | None = None, grid: str = "random",
                 overrides: dict[str, float] | None = None) -> tuple[int, str]:
    """Write the scenario files, fly them, write summary.md / summary.json.
    known_failures ("AIRCRAFT:INDEX") are upsets that fail on a known library
    defect: still failures in every table and fraction, but they do not count
    against the exit status; one of them passing does (strict: remove it).
    Returns (number of unexpected results, the summary table)."""
    jobs_list: list[tuple[str, str, str | None, bool]] = []
    meta: list[tuple[int, str, Upset, Path]] = []
    for ac in aircraft:
        a = load_aircraft(ac, [DEFAULT_AIRCRAFT_DIR], Path("upsets"), "--aircraft")
        d = out / ac
        d.mkdir(parents=True, exist_ok=True)
        for i, up in enumerate(upset_list(ac, count, seed, grid)):
            p = d / f"upset_{i:03d}.toml"
            p.write_text(scenario_toml(ac, up, i, seed, altitude_m, duration_s, floor_m,
                                       a.airspeed_m_s, pitch_mode, attitude, overrides))
            jobs_list.append((str(p), str(d / f"upset_{i:03d}"), board_lib, plots))
            meta.append((i, ac, up, p))
    n = len(jobs_list)
    results: list[UpsetResult] = []
    t0 = time.perf_counter()
    progress_bar(0, n, "upsets", t0)
    # local processes or Ray (backend.py): the results in the upsets' order
    ms = map_ordered(_fly, jobs_list, jobs=jobs, backend=backend, address=address,
                     progress=lambda k, _m: progress_bar(k, n, f"upsets ({backend})", t0))
    known_set = set(known_failures or ())
    for (i, ac, up, p), m in zip(meta, ms):
        results.append(_result(i, ac, up, m, p, altitude_m))
        results[-1].known = f"{ac}:{i}" in known_set
    summaries = {ac: summarize([r for r in results if r.aircraft == ac], altitude_m)
                 for ac in aircraft}
    for ac, sm in summaries.items():
        sm["known"] = sum(1 for r in results if r.aircraft == ac and r.known and not r.passed)
    table = summary_table(summaries)
    failed = [r for r in results if not r.passed and not r.known]
    xpass = [r for r in results if r.passed and r.known]
    known = [r for r in results if not r.passed and r.known]
    per = len(results) // max(1, len(aircraft))
    extra = "" if not overrides else ", " + ", ".join(f"{k} = {v:g}" for k, v in overrides.items())
    text = (f"# Upset recovery (seed {seed}, {per} per aircraft ({grid}), start {altitude_m:g} m, "
            f"floor {floor_m:g} m above the ground, {pitch_mode} pitch{extra})\n\n{table}\n\n"
            f"Recovered: tilt within 10° of the law's target tilt to the end of the "
            f"{duration_s:g} s run (≥ 5 s); time from release; median over the recovered "
            f"upsets; altitude loss = start altitude − lowest altitude of the run.\n\n"
            f"## Every upset\n\n{detail_table(results)}\n")
    (out / "summary.md").write_text(text)
    with (out / "summary.json").open("w") as f:
        json.dump({"seed": seed, "count": count, "grid": grid, "overrides": overrides or {},
                   "altitude_m": altitude_m,
                   "pitch_mode": pitch_mode, "known_failures": sorted(known_set),
                   "duration_s": duration_s, "floor_m": floor_m, "aircraft": summaries,
                   "upsets": [asdict(r) for r in results]}, f, indent=2, allow_nan=False)
        f.write("\n")
    if known:
        sys.stderr.write("known failures (a library defect, see --known-failures):\n" +
                         "".join(f"  {r.scenario}\n" for r in known))
    if xpass:
        sys.stderr.write("known failures that now PASS (remove them from --known-failures):\n"
                         + "".join(f"  {r.aircraft}:{r.index}\n" for r in xpass))
    if failed:
        sys.stderr.write("failed upsets (fly one again with `python -m helical_sil run FILE "
                         "--out DIR`):\n" + "".join(f"  {r.scenario}\n" for r in failed))
    return len(failed) + len(xpass), table
