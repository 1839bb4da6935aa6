"""`python -m helical_sil options`: the law's options (issue 17) side by side.

Every row (a suite scenario, or an airframe's standard manoeuvres) is flown
once per variant of the law, on the attitude the scenario names (the
estimate unless it pins the truth):
- `seed`: the seed's law, every option off (turn_trim = 0 too);
- one variant per option: the seed's law with that option alone on;
- `combo`: the options of --combo together (default: all of them);
- `recommended`: the options that help somewhere and hurt nowhere against
  `seed` (computed from the single-option runs, flown in a second pass).
Each variant is flown again at twice the tuned gains (tune.TUNED), the
stability margin of tune.py: a limit cycle there shows as a large steady
turn-rate RMS error.

The per-row metrics (worst over the row's segments):
- entry_ratio: turn_entry_s / the full-aileron time to the turn's target
  bank (roll_limit.py), entries from straight flight (the issue's
  comparison); bank_ratio: bank_entry_s / the full-aileron time to 90 % of
  that bank (like for like);
- turn_rate_error_pct (steady part), steady_sideslip_rms_deg (steady part of
  the turns), bank_overshoot_deg, entry_altitude_loss_m (altitude lost in the
  entry window of every turn-rate change: the rolls); the run's
  sideslip_rms_deg and cross_track_max_m (waypoint legs: all a guided
  scenario shows);
- rmse_2x_deg_s: the steady turn-rate RMS error at 2x the gains, and
  limit_cycle_2x: the 2x run hit the ground, or that RMS error exceeds both
  LIMIT_CYCLE_RMSE_DEG_S and twice the 1x run's.
"""

from __future__ import annotations

import copy
import csv
import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

from helical_sil.config import params

# The options: (name, where the row lives, the value that turns it on by default).
# turn_trim is item 3 (a guidance row, on by default in the firmware);
# kp_sideslip's and vertical_fade's "on" values are a starting point, --on overrides.
OPTIONS: tuple[tuple[str, str, float], ...] = (
    ("roll_in", "law", 1.0),
    ("kp_sideslip", "law", 1.0),
    ("turn_trim", "guidance", 1.0),
    ("vertical_fade", "law", 0.1),
)
OPTION_NAMES = tuple(o[0] for o in OPTIONS)
GOALS = {"entry_ratio": 1.5, "turn_rate_error_pct": 2.0, "steady_sideslip_rms_deg": 1.0}
# a metric worse by more than this is "hurts", better by more "helps" (noise floors
# of a seeded, bit-reproducible run: these are changes a reader would notice)
TOLERANCE = {"entry_ratio": 0.05, "bank_ratio": 0.05, "turn_rate_error_pct": 0.25,
             "steady_sideslip_rms_deg": 0.1, "bank_overshoot_deg": 1.0,
             "entry_altitude_loss_m": 1.0, "rmse_2x_deg_s": 0.25,
             "sideslip_rms_deg": 0.1, "cross_track_max_m": 2.0}
METRICS = ("entry_ratio", "bank_ratio", "turn_rate_error_pct", "steady_sideslip_rms_deg",
           "bank_overshoot_deg", "entry_altitude_loss_m", "rmse_2x_deg_s",
           # the whole run: what the waypoint scenarios (guided, no constant turn
           # command) can show -- the run's sideslip RMS and largest cross-track
           "sideslip_rms_deg", "cross_track_max_m")
# ... and by more than this fraction of the seed's value: a few per cent of a
# large number (the heading law's 200-450 m cross-track at the corners, tens of
# metres of altitude) is the path of a perturbed flight, not the option's effect
REL_TOLERANCE = 0.05
LIMIT_CYCLE_RMSE_DEG_S = 0.5  # tune.GOALS' oscillation goal
TURN_MIN_DEG_S = 1.0


class OptionsError(ValueError):
    """A bad --set / --on / --combo argument (exit 2)."""


def row_of(name: str) -> tuple[str, params.Param]:
    """Where a parameter lives: ("law", row) for the law's rows ([gains]),
    ("guidance", row) for the guidance's ([guidance])."""
    if name in params.LAW_BY_NAME and name != "pitch_mode":
        return "law", params.LAW_BY_NAME[name]
    if name in params.GUIDANCE_BY_NAME:
        return "guidance", params.GUIDANCE_BY_NAME[name]
    raise OptionsError(f"{name!r}: not a row of the law or the guidance in the parameter "
                       "table (include/helical/params.def)")


def parse_set(items: list[str], what: str = "--set") -> dict[str, float]:
    """KEY=VALUE items (law or guidance rows of the table, in the table's
    units), checked against the rows' bounds."""
    out: dict[str, float] = {}
    for it in items:
        key, sep, val = it.partition("=")
        key = key.strip()
        if not sep or not key:
            raise OptionsError(f"{what} {it!r}: expected KEY=VALUE")
        try:
            v = float(val)
        except ValueError:
            raise OptionsError(f"{what} {it!r}: {val!r} is not a number") from None
        _, row = row_of(key)
        why = row.check(v)
        if why is not None:
            raise OptionsError(f"{what} {key} = {v:g} {why}")
        out[key] = v
    return out


def available_options() -> list[str]:
    """The options whose rows exist in this table (a table without them
    flies the others)."""
    out = []
    for name in OPTION_NAMES:
        try:
            row_of(name)
            out.append(name)
        except OptionsError:
            pass
    return out


@dataclass
class Variant:
    name: str
    overrides: dict[str, float]
    on: tuple[str, ...] = ()


def variants(on_values: dict[str, float], combo: list[str], base: dict[str, float],
             options: list[str] | None = None) -> list[Variant]:
    """seed, each option alone, and the combination; base (--set) on all."""
    opts = available_options() if options is None else options
    seed = {**{k: 0.0 for k in opts}, **base}
    out = [Variant("seed", dict(seed))]
    for k in opts:
        out.append(Variant(k, {**seed, k: on_values[k]}, (k,)))
    c = [k for k in combo if k in opts]
    if len(c) > 1:
        out.append(Variant("combo", {**seed, **{k: on_values[k] for k in c}}, tuple(c)))
    return out


def apply_overrides(sc: Any, overrides: dict[str, float]) -> None:
    """Set the table rows on a loaded scenario: law rows into its gains,
    guidance rows into its [guidance]."""
    for k, v in overrides.items():
        where, _ = row_of(k)
        (sc.gains if where == "law" else sc.guidance)[k] = v


# --- flying ---------------------------------------------------------------------

@dataclass
class Job:
    scenario: str
    variant: str
    overrides: dict[str, float]
    gain_scale: float
    board_lib: str | None


def _turn_segments(m: dict[str, Any]) -> list[dict[str, Any]]:
    return [s for s in m["segments"] if abs(s.get("turn_rate_cmd_deg_s") or 0.0) >= TURN_MIN_DEG_S]


def fly(job: Job) -> dict[str, Any]:
    """One flight; returns its metrics (segments and run) or the error."""
    from helical_sil.analysis.metrics import run_metrics
    from helical_sil.campaigns import tune
    from helical_sil.config.scenario import load_scenario
    from helical_sil.sim import lockstep
    from helical_sil.sim.board import BoardError
    sc = load_scenario(job.scenario)
    apply_overrides(sc, job.overrides)
    if job.gain_scale != 1.0:
        for k in tune.TUNED:
            sc.gains[k] = min(sc.gains[k] * job.gain_scale, params.LAW_BY_NAME[k].max)
    try:
        try:
            res = lockstep.run(sc, job.board_lib)
        except lockstep.SimError as e:
            if "trim failed" not in str(e).lower() or not sc.trim:
                raise
            sc.trim = False  # as tune.py: a model JSBSim cannot trim flies released
            res = lockstep.run(sc, job.board_lib)
    except (BoardError, lockstep.SimError, ValueError) as e:
        return {"error": str(e)}
    m = run_metrics(res)
    m["trimmed"] = sc.trim
    return m


def limit_job(job: tuple[str, str | None]) -> dict[str, Any]:
    """The full-aileron roll of a scenario's aircraft at its initial
    condition, as lists (picklable)."""
    from helical_sil.campaigns import roll_limit
    from helical_sil.config.scenario import load_scenario
    from helical_sil.sim import lockstep
    sc = load_scenario(job[0])
    try:
        try:
            fa = roll_limit.measure(sc)
        except lockstep.SimError as e:
            if "trim failed" not in str(e).lower():
                raise
            sc.trim = False
            fa = roll_limit.measure(sc)
    except (lockstep.SimError, ValueError) as e:
        return {"error": str(e)}
    return {"t_s": fa.t_s.tolist(), "right": fa.phi_right_deg.tolist(),
            "left": fa.phi_left_deg.tolist(), "airspeed_m_s": fa.airspeed_m_s,
            "trimmed": fa.trimmed}


def limit_of(d: dict[str, Any]) -> Any:
    import numpy as np

    from helical_sil.campaigns.roll_limit import FullAileron
    return FullAileron(np.asarray(d["t_s"]), np.asarray(d["right"]), np.asarray(d["left"]),
                       d["airspeed_m_s"], d["trimmed"])


ROLL_IN_PROBE_BANK_DEG = 30.0


def reachable_roll_rate(d: dict[str, Any] | None) -> float | None:
    """roll_in_rate_max for a row (rad/s): the mean bank rate of the
    full-aileron roll to 30 deg in its slower direction, a bank rate the
    airframe reaches (the row's documented meaning); None when the roll
    does not reach 30 deg either way or was not measured. Clamped to the
    row's bounds (0, 8]."""
    if not d or "error" in d:
        return None
    fa = limit_of(d)
    times = [fa.time_to_bank(ROLL_IN_PROBE_BANK_DEG), fa.time_to_bank(-ROLL_IN_PROBE_BANK_DEG)]
    if any(t is None or t <= 0.0 for t in times):
        return None
    rate = math.radians(ROLL_IN_PROBE_BANK_DEG) / max(t for t in times if t is not None)
    return round(min(max(rate, 0.01), 8.0), 3)


def with_roll_in_rate(overrides: dict[str, float], limit: dict[str, Any] | None,
                      fixed: bool) -> dict[str, float]:
    """A variant's overrides for one row: with roll_in on and no
    roll_in_rate_max given (fixed), the row's reachable_roll_rate."""
    if not overrides.get("roll_in") or fixed:
        return overrides
    rate = reachable_roll_rate(limit)
    return overrides if rate is None else {**overrides, "roll_in_rate_max": rate}


def row_metrics(m: dict[str, Any], m2: dict[str, Any] | None,
                limit: dict[str, Any] | None) -> dict[str, Any]:
    """One row of the table from a run's metrics (m), its 2x run (m2) and
    the full-aileron roll (limit): the worst of each metric over the row's
    segments (METRICS), the limit times, and the 2x verdict."""
    out: dict[str, Any] = {k: None for k in METRICS}
    if "error" in m:
        out["error"] = m["error"]
        return out
    if m["run"].get("end_reason"):
        out["error"] = m["run"]["end_reason"]
    segs = m["segments"]
    turns = _turn_segments(m)

    def worst(key: str, ss: list[dict[str, Any]]) -> float | None:
        vals = [abs(s[key]) for s in ss if s.get(key) is not None]
        return max(vals) if vals else None

    out["turn_rate_error_pct"] = worst("turn_rate_error_pct", turns)
    out["steady_sideslip_rms_deg"] = worst("steady_sideslip_rms_deg", turns)
    out["bank_overshoot_deg"] = worst("bank_overshoot_deg", segs)
    out["entry_altitude_loss_m"] = worst("entry_altitude_loss_m", segs)
    out["sideslip_rms_deg"] = m["run"].get("sideslip_rms_deg")
    out["cross_track_max_m"] = m["run"].get("cross_track_max_m")
    fa = limit_of(limit) if limit and "error" not in limit else None
    ratios, bratios, lims = [], [], []
    prev = 0.0
    for s in segs:
        cmd = s.get("turn_rate_cmd_deg_s") or 0.0
        # entries from straight upright flight (the full-aileron roll starts there)
        if (abs(cmd) >= TURN_MIN_DEG_S and abs(prev) < TURN_MIN_DEG_S and not s.get("inverted")
                and fa is not None and s.get("bank_target_deg") is not None):
            bank = float(s["bank_target_deg"])
            t_full = fa.time_to_bank(bank)
            t_90 = fa.time_to_bank(0.9 * bank)
            lims.append(t_full)
            te, tb = s.get("turn_entry_s"), s.get("bank_entry_s")
            ratios.append(None if te is None or not t_full else te / t_full)
            bratios.append(None if tb is None or not t_90 else tb / t_90)
        prev = cmd
    if ratios:
        # an entry never reached counts as infinitely slow
        out["entry_ratio"] = max(math.inf if r is None else r for r in ratios)
        out["bank_ratio"] = max(math.inf if r is None else r for r in bratios)
        out["full_aileron_s"] = max((x for x in lims if x is not None), default=None)
    if m2 is not None:
        rm2 = worst("turn_rate_rmse_deg_s", _turn_segments(m2)) if "error" not in m2 else None
        rm1 = worst("turn_rate_rmse_deg_s", turns)
        out["rmse_2x_deg_s"] = rm2
        ground = "error" in m2 or bool(m2["run"].get("end_reason"))
        out["limit_cycle_2x"] = ground or (rm2 is not None and rm2 > LIMIT_CYCLE_RMSE_DEG_S
                                           and rm2 > 2.0 * (rm1 or 0.0))
    return out


def compare(seed: dict[str, Any], other: dict[str, Any]) -> tuple[list[str], list[str]]:
    """Where a variant helps and where it hurts against the seed's row, by
    more than TOLERANCE and REL_TOLERANCE of the seed's value; a metric the seed measured and the variant cannot (an entry
    never reached: inf or None) hurts, and so does a new limit cycle or
    ground contact."""
    helps, hurts = [], []
    for k in METRICS:
        a, b = seed.get(k), other.get(k)
        if a is None and b is None:
            continue
        if b is None or (a is not None and math.isinf(b) and not math.isinf(a)):
            if a is not None:
                hurts.append(k)
            continue
        if a is None or math.isinf(a):
            if not math.isinf(b):
                helps.append(k)
            continue
        tol = max(TOLERANCE[k], REL_TOLERANCE * abs(a))
        if b > a + tol:
            hurts.append(k)
        elif b < a - tol:
            helps.append(k)
    if other.get("limit_cycle_2x") and not seed.get("limit_cycle_2x"):
        hurts.append("limit_cycle_2x")
    if other.get("error") and not seed.get("error"):
        hurts.append("error")
    return helps, hurts


def verdicts(table: dict[str, dict[str, dict[str, Any]]], options: list[str]
             ) -> dict[str, dict[str, Any]]:
    """Per option (flown alone): the rows and metrics where it helps and hurts."""
    out = {}
    for k in options:
        helps, hurts = [], []
        for row, by_var in table.items():
            if k not in by_var or "seed" not in by_var:
                continue
            h, x = compare(by_var["seed"], by_var[k])
            helps += [f"{row}:{m}" for m in h]
            hurts += [f"{row}:{m}" for m in x]
        out[k] = {"helps": helps, "hurts": hurts, "keep": bool(helps) and not hurts}
    return out


# --- output ---------------------------------------------------------------------

def _fmt(v: Any, f: str = "{:.2f}") -> str:
    if v is None:
        return "-"
    if isinstance(v, bool):
        return "LC" if v else "ok"
    if isinstance(v, float) and math.isinf(v):
        return "never"
    return f.format(v)


def markdown(table: dict[str, dict[str, dict[str, Any]]], names: list[str],
             verdict: dict[str, dict[str, Any]], title: str, command: str) -> str:
    """One table per metric (rows x variants), the goals met per variant, and
    the verdict per option."""
    lines = [f"# {title}", "", f"Command: `{command}`", ""]
    heads = ["row"] + names
    fmts = {"entry_altitude_loss_m": "{:.1f}", "bank_overshoot_deg": "{:.1f}",
            "turn_rate_error_pct": "{:.1f}"}
    lines += ["## Goals met (rows meeting the goal / rows measured)", "",
              "| metric | goal | " + " | ".join(names) + " |",
              "|" + "---|" * (len(names) + 2)]
    for k, goal in GOALS.items():
        cells = []
        for n in names:
            vals = [t[n].get(k) for t in table.values() if n in t]
            meas = [v for v in vals if v is not None]
            cells.append(f"{sum(1 for v in meas if v <= goal)}/{len(meas)}")
        lines.append(f"| {k} | <= {goal:g} | " + " | ".join(cells) + " |")
    lc = [f"{sum(1 for t in table.values() if t.get(n, {}).get('limit_cycle_2x'))}"
          for n in names]
    lines.append("| limit cycles at 2x gains | 0 | " + " | ".join(lc) + " |")
    err = [f"{sum(1 for t in table.values() if t.get(n, {}).get('error'))}" for n in names]
    lines.append("| runs that failed (ground, no trim...) | 0 | " + " | ".join(err) + " |")
    lines.append("")
    for k in METRICS + ("limit_cycle_2x",):
        lines += [f"## {k}", "", "| " + " | ".join(heads) + " |", "|" + "---|" * len(heads)]
        for row, by_var in table.items():
            cells = [_fmt(by_var.get(n, {}).get(k), fmts.get(k, "{:.2f}")) for n in names]
            lines.append(f"| {row} | " + " | ".join(cells) + " |")
        lines.append("")
    lines += ["## Full-aileron limit (s to the target bank)", "",
              "| row | full aileron s |", "|---|---|"]
    for row, by_var in table.items():
        lines.append(f"| {row} | {_fmt(by_var.get('seed', {}).get('full_aileron_s'))} |")
    lines += ["", "## Verdict per option (alone, against seed)", "",
              "| option | helps (rows:metrics) | hurts (rows:metrics) | keep |",
              "|---|---|---|---|"]
    for k, v in verdict.items():
        lines.append(f"| {k} | {len(v['helps'])}: {', '.join(v['helps'][:12])}"
                     f"{' ...' if len(v['helps']) > 12 else ''} | {len(v['hurts'])}: "
                     f"{', '.join(v['hurts'][:12])}{' ...' if len(v['hurts']) > 12 else ''} | "
                     f"{'yes' if v['keep'] else 'no'} |")
    errs = [(row, n, t[n]["error"]) for row, t in table.items() for n in names
            if t.get(n, {}).get("error")]
    if errs:
        lines += ["", "## Failed runs", ""] + [f"- {r} / {n}: {e[:160]}" for r, n, e in errs]
    return "\n".join(lines) + "\n"


def write_csv(table: dict[str, dict[str, dict[str, Any]]], names: list[str], path: Path) -> None:
    keys = list(METRICS) + ["limit_cycle_2x", "full_aileron_s", "error"]
    with path.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["row", "variant", *keys])
        for row, by_var in table.items():
            for n in names:
                if n in by_var:
                    w.writerow([row, n, *[by_var[n].get(k) for k in keys]])


def plot(table: dict[str, dict[str, dict[str, Any]]], names: list[str], path: Path,
         title: str) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    shown = ("entry_ratio", "turn_rate_error_pct", "steady_sideslip_rms_deg",
             "bank_overshoot_deg", "entry_altitude_loss_m", "rmse_2x_deg_s")
    rows = list(table)
    fig, axes = plt.subplots(len(shown), 1, figsize=(max(8.0, 0.35 * len(rows) + 3), 3 * len(shown)),
                             sharex=True)
    for ax, k in zip(axes, shown):
        for j, n in enumerate(names):
            xs, ys = [], []
            for i, r in enumerate(rows):
                v = table[r].get(n, {}).get(k)
                if v is not None and math.isfinite(v):
                    xs.append(i + (j - len(names) / 2) * 0.08)
                    ys.append(v)
            ax.plot(xs, ys, "o", ms=4, label=n)
        if k in GOALS:
            ax.axhline(GOALS[k], color="k", lw=0.8, ls="--")
        ax.set_ylabel(k, fontsize=8)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7, ncol=len(names))
    axes[0].set_title(title)
    axes[-1].set_xticks(range(len(rows)))
    axes[-1].set_xticklabels(rows, rotation=90, fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


# --- the campaign ---------------------------------------------------------------

@dataclass
class Campaign:
    rows: dict[str, str]                    # row name -> scenario file
    on_values: dict[str, float]
    combo: list[str]
    base: dict[str, float] = field(default_factory=dict)
    margin: bool = True                     # also fly 2x the gains
    recommend: bool = True                  # second pass: the recommended combination


def run(c: Campaign, out: Path, jobs: int, board_lib: str | None, backend: str = "local",
        address: str | None = None, title: str = "Law options", command: str = "",
        progress: Callable[[int, int, str], None] | None = None) -> dict[str, Any]:
    from helical_sil.campaigns.backend import map_ordered
    opts = available_options()
    vs = variants(c.on_values, c.combo, c.base, opts)
    limits = map_ordered(limit_job, [(p, board_lib) for p in c.rows.values()], jobs=jobs,
                         backend=backend, address=address)
    lim = dict(zip(c.rows, limits))
    table: dict[str, dict[str, dict[str, Any]]] = {r: {} for r in c.rows}

    def fly_variants(vv: list[Variant]) -> None:
        todo = [(r, v, s) for v in vv for r in c.rows for s in ((1.0, 2.0) if c.margin else (1.0,))]
        t0 = time.perf_counter()
        fixed = "roll_in_rate_max" in c.base or "roll_in_rate_max" in c.on_values
        res = map_ordered(fly, [Job(c.rows[r], v.name,
                                    with_roll_in_rate(v.overrides, lim[r], fixed), s, board_lib)
                                for r, v, s in todo], jobs=jobs, backend=backend,
                          address=address,
                          progress=(lambda k, _m: progress(k, len(todo), f"{time.perf_counter() - t0:.0f} s"))
                          if progress else None)
        got: dict[tuple[str, str, float], dict[str, Any]] = {(r, v.name, s): m
                                                             for (r, v, s), m in zip(todo, res)}
        for v in vv:
            for r in c.rows:
                table[r][v.name] = row_metrics(got[(r, v.name, 1.0)], got.get((r, v.name, 2.0)),
                                               lim[r])

    fly_variants(vs)
    verdict = verdicts(table, opts)
    names = [v.name for v in vs]
    keep = [k for k in opts if verdict[k]["keep"]]
    rec = Variant("recommended", {**{k: 0.0 for k in opts}, **c.base,
                                  **{k: c.on_values[k] for k in keep}}, tuple(keep))
    same = [v for v in vs if set(v.on) == set(keep)]
    if c.recommend and not same:
        fly_variants([rec])
        names.append("recommended")
    elif same:
        for r in c.rows:
            table[r]["recommended"] = table[r][same[0].name]
        names.append("recommended")
    (out / "table.md").write_text(
        markdown(table, names, verdict, title, command)
        + f"\nRecommended: {', '.join(keep) or 'none'} on (values: "
        + ", ".join(f"{k} = {c.on_values[k]:g}" for k in keep) + "); variants: "
        + "; ".join(f"{v.name}: " + ", ".join(f"{k}={x:g}" for k, x in v.overrides.items())
                    for v in vs) + "\n")
    write_csv(table, names, out / "table.csv")
    plot(table, names, out / "options.png", title)
    result = {"variants": [{"name": v.name, "overrides": v.overrides} for v in vs],
              "recommended": keep, "verdict": verdict, "table": table,
              "rows": c.rows}
    (out / "result.json").write_text(json.dumps(result, indent=1, default=str) + "\n")
    return result


def manoeuvre_rows(aircraft_files: list[Path], out: Path, altitude_m: float | None = None
                   ) -> dict[str, str]:
    """The standard manoeuvres (tune.manoeuvres_toml: a 30-deg-bank turn each
    way at v_ref) for each aircraft file, written to out/manoeuvres/NAME/
    with the aircraft file beside it; row name = the aircraft's name."""
    from helical_sil.campaigns import tune
    from helical_sil.config.scenario import load_aircraft
    rows = {}
    for f in aircraft_files:
        name = f.stem.removesuffix("_tuned")
        ac = load_aircraft(f.stem, [f.parent], f)
        d = out / "manoeuvres" / name
        (d / "aircraft").mkdir(parents=True, exist_ok=True)
        (d / "aircraft" / f"{name}.toml").write_text(f.read_text())
        p = d / "manoeuvres.toml"
        p.write_text(tune.manoeuvres_toml(name, ac.gains["v_ref"], altitude_m or ac.altitude_m))
        rows[name] = str(p)
    return rows


def copy_scenario_overrides(sc: Any, overrides: dict[str, float]) -> Any:
    """A copy of a loaded scenario with the overrides applied (tests)."""
    s = copy.deepcopy(sc)
    apply_overrides(s, overrides)
    return s
