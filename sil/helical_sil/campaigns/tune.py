"""`python -m helical_sil tune AIRCRAFT.toml`: gains from SIL flights.

The search: Optuna's TPE sampler (a well-kept, pure-Python optimiser with a
resumable SQLite store and a seeded sampler, so a tuning is reproducible and
can be stopped and continued; chosen over scipy's local methods because the
objective is noisy and non-smooth: saturation, limit cycles, ground contact).
Each trial flies the standard manoeuvres (MANOEUVRES) on the firmware's own
estimate, trials in rounds of --jobs on the chosen backend (local or Ray).

The objective adds each manoeuvre metric over its goal (issue 17's goals
where it has them): turn entry / 1.5 s, steady turn-rate error / 2 %,
overshoot / 5 deg, sideslip RMS / 1 deg, altitude lost in the entries and
reversals / 10 m, the steady turns' RMS turn-rate error / 0.5 deg/s
(oscillation), and 5 x the fraction of steps with a saturated surface; a run
that fails to fly (a refused gain, ground contact) costs FAIL_COST. Every
trial is also flown at twice its gains (the gain sweep of the stability
margin) and a quarter of that cost is added, so gains that limit-cycle at 2x
lose.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from helical_sil.config import params
from helical_sil.config.scenario import load_aircraft

# the law's gains the search moves (the holds keep the file's)
TUNED = ("kp_aileron", "kd_aileron", "kff_aileron", "kp_elevator", "kd_elevator",
         "kp_rudder", "kd_rudder", "kff_rudder")
# a gain the file gives as 0 is searched in [0, ZERO_SPAN]; any other in
# [g / SPAN, g * SPAN] (log-uniform), both within the table's bounds
SPAN = 4.0
ZERO_SPAN = 2.0
FAIL_COST = 100.0
GOALS = {"turn_entry_s": 1.5, "turn_rate_error_pct": 2.0, "bank_overshoot_deg": 5.0,
         "sideslip_rms_deg": 1.0, "entry_altitude_loss_m": 10.0,
         # the steady turns' RMS turn-rate error: oscillation (no turbulence here)
         "turn_rate_rmse_deg_s": 0.5}


def turn_rate_deg_s(v_ref_m_s: float, bank_deg: float = 30.0) -> float:
    """The coordinated turn rate of a bank at an airspeed: g tan(bank) / V."""
    return math.degrees(9.80665 * math.tan(math.radians(bank_deg)) / v_ref_m_s)


# The standard manoeuvres' pass criteria (the pass rate of `tune`'s report):
# per turn, and over the run.
CRITERIA = (("right", "turn_entry_s", 3.0), ("left", "turn_entry_s", 3.0),
            ("right", "turn_rate_error_pct", 5.0), ("left", "turn_rate_error_pct", 5.0),
            ("right", "bank_overshoot_deg", 10.0), ("left", "bank_overshoot_deg", 10.0),
            ("run", "sideslip_rms_deg", 3.0), ("run", "max_altitude_loss_m", 30.0))


def manoeuvres_toml(aircraft: str, v_ref_m_s: float, altitude_m: float,
                    trim: bool = True) -> str:
    """The standard manoeuvres at v_ref, on the estimate: wings level, a
    30-deg-bank right turn, a reversal to the left, wings level again, with
    CRITERIA. trim = False releases a model JSBSim cannot trim untrimmed."""
    w = round(turn_rate_deg_s(v_ref_m_s), 2)
    crit = "".join(f'[[pass]]\nsegment = "{s}"\nmetric = "{m}"\nmax = {x:g}\n'
                   for s, m, x in CRITERIA)
    return f'''# written by `python -m helical_sil tune`: the standard manoeuvres
aircraft = "{aircraft}"
duration_s = 50
seed = 1
[initial]
altitude_m = {altitude_m:g}
airspeed_m_s = {v_ref_m_s:g}
trim = {"true" if trim else "false"}
[[command]]
t_s = 0
label = "level"
turn_rate_deg_s = 0
airspeed_m_s = {v_ref_m_s:g}
[[command]]
t_s = 5
label = "right"
turn_rate_deg_s = {w:g}
[[command]]
t_s = 25
label = "left"
turn_rate_deg_s = {-w:g}
[[command]]
t_s = 45
label = "out"
turn_rate_deg_s = 0
{crit}'''


@dataclass
class Flight:
    gains: dict[str, float]
    cost: float
    metrics: dict[str, float]
    error: str = ""
    passed: int = 0        # CRITERIA passed
    criteria: int = len(CRITERIA)


def _metrics_of(m: dict[str, Any]) -> dict[str, float]:
    """The objective's metrics of one manoeuvres run: the worst over the two
    turns (entry, error, overshoot, altitude lost in the entry), the run's
    sideslip RMS and saturation, and the bank-rate RMS (limit cycles)."""
    segs = {s["label"]: s for s in m["segments"]}
    out: dict[str, float] = {}
    for k in ("turn_entry_s", "turn_rate_error_pct", "bank_overshoot_deg",
              "entry_altitude_loss_m"):
        vals = [abs(segs[lab][k]) for lab in ("right", "left")
                if segs.get(lab, {}).get(k) is not None]
        out[k] = max(vals) if vals else math.inf
    out["sideslip_rms_deg"] = float(m["run"]["sideslip_rms_deg"])
    out["surface_saturation_frac"] = float(m["run"]["surface_saturation_frac"])
    # oscillation in the steady turns (a limit cycle raises it)
    rm = [segs[lab].get("turn_rate_rmse_deg_s") for lab in ("right", "left")]
    out["turn_rate_rmse_deg_s"] = max((b for b in rm if b is not None), default=math.inf)
    return out


def cost_of(metrics: dict[str, float]) -> float:
    c = sum(metrics[k] / goal for k, goal in GOALS.items())
    c += 5.0 * metrics["surface_saturation_frac"]
    return min(c, FAIL_COST) if math.isfinite(c) else FAIL_COST


def fly(job: tuple[str, str, dict[str, float], str | None]) -> Flight:
    """One trial's flight (in whichever process the backend gives it)."""
    scenario, out, gains, board_lib = job
    from helical_sil.analysis.metrics import evaluate, run_metrics
    from helical_sil.config.scenario import load_scenario
    from helical_sil.sim import lockstep
    from helical_sil.sim.board import BoardError
    sc = load_scenario(scenario)
    sc.gains.update(gains)
    try:
        res = lockstep.run(sc, board_lib)
    except (BoardError, lockstep.SimError) as e:
        return Flight(gains, FAIL_COST, {}, str(e))
    m = run_metrics(res)
    if res.end_reason is not None:
        return Flight(gains, FAIL_COST, {}, res.end_reason)
    checks = evaluate(m, sc.criteria)
    met = _metrics_of(m)
    return Flight(gains, cost_of(met), met, passed=sum(c["ok"] for c in checks),
                  criteria=len(checks))


def fly_with_margin(job: tuple[str, str, dict[str, float], str | None]) -> Flight:
    """A trial: the gains, and the same gains doubled (the stability margin
    of the gain sweep); the cost adds a quarter of the doubled flight's, so
    gains that limit-cycle at 2x lose to gains that do not."""
    scenario, out, gains, board_lib = job
    f1 = fly(job)
    f2 = fly((scenario, out, {k: 2.0 * v for k, v in gains.items()}, board_lib))
    f1.metrics = {**f1.metrics, **{f"{k}_2x": v for k, v in f2.metrics.items()}}
    f1.cost = min(FAIL_COST, f1.cost + 0.25 * f2.cost)
    return f1


def search_space(start: dict[str, float]) -> dict[str, tuple[float, float, bool]]:
    """Per tuned gain: (low, high, log) within the table's bounds."""
    space = {}
    for k in TUNED:
        row = params.LAW_BY_NAME[k]
        g = start[k]
        if g <= 0.0:
            space[k] = (0.0, min(ZERO_SPAN, row.max), False)
        else:
            space[k] = (max(g / SPAN, 1e-3), min(g * SPAN, row.max), True)
    return space


def tuned_toml(src_text: str, gains: dict[str, float]) -> str:
    """The aircraft file with its [gains] values replaced (missing keys added
    at the end of the table), comments and everything else kept."""
    lines = src_text.splitlines()
    out, in_gains, seen = [], False, set()
    for line in lines:
        head = re.match(r"\s*\[([^\]]+)\]", line)
        if head:
            if in_gains:
                out += [f"{k} = {gains[k]:.4g}  # tuned" for k in gains if k not in seen]
                seen.update(gains)
            in_gains = head.group(1).strip() == "gains"
        m = re.match(r"\s*([A-Za-z_0-9]+)\s*=", line)
        if in_gains and m and m.group(1) in gains:
            k = m.group(1)
            out.append(f"{k} = {gains[k]:.4g}  # tuned")
            seen.add(k)
            continue
        out.append(line)
    if in_gains:
        out += [f"{k} = {gains[k]:.4g}  # tuned" for k in gains if k not in seen]
    return "\n".join(out) + "\n"


def tune(aircraft_file: Path, out: Path, trials: int, seed: int, jobs: int, backend: str,
         address: str | None, board_lib: str | None,
         progress: Callable[[int, int, str], None] | None = None) -> dict[str, Any]:
    """Search, then fly the starter, the best and twice the best; write the
    report (report.md, search.png, result.json) and the tuned aircraft file."""
    import optuna

    from helical_sil.campaigns.backend import map_ordered
    ac = load_aircraft(aircraft_file.stem, [aircraft_file.parent], aircraft_file)
    out.mkdir(parents=True, exist_ok=True)
    (out / "aircraft").mkdir(exist_ok=True)
    (out / "aircraft" / aircraft_file.name).write_text(aircraft_file.read_text())
    scen = out / "manoeuvres.toml"
    scen.write_text(manoeuvres_toml(ac.name, ac.gains["v_ref"], ac.altitude_m))
    start = {k: ac.gains[k] for k in TUNED}
    space = search_space(start)
    # a model JSBSim cannot trim flies the manoeuvres released untrimmed
    probe = fly((str(scen), "", start, board_lib))
    trimmed = "trim failed" not in probe.error.lower()
    if not trimmed:
        scen.write_text(manoeuvres_toml(ac.name, ac.gains["v_ref"], ac.altitude_m, trim=False))

    optuna.logging.set_verbosity(optuna.logging.WARNING)
    storage = f"sqlite:///{(out / 'study.db').resolve()}"
    study = optuna.create_study(study_name=f"tune_{ac.name}", storage=storage,
                                load_if_exists=True, direction="minimize",
                                sampler=optuna.samplers.TPESampler(seed=seed))
    if len(study.trials) == 0:
        study.enqueue_trial(start)  # the starter gains are trial 0
    done0 = len([t for t in study.trials if t.state.is_finished()])
    todo = max(0, trials - done0)
    k = 0
    while k < todo:
        batch = [study.ask() for _ in range(min(jobs, todo - k))]
        gains = [{g: t.suggest_float(g, lo, hi, log=log) for g, (lo, hi, log) in space.items()}
                 for t in batch]
        res = map_ordered(fly_with_margin,
                          [(str(scen), str(out / f"trial_{t.number}"), g, board_lib)
                           for t, g in zip(batch, gains)],
                          jobs=jobs, backend=backend, address=address)
        for t, r in zip(batch, res):
            for key, v in r.metrics.items():
                t.set_user_attr(key, v)
            if r.error:
                t.set_user_attr("error", r.error)
            study.tell(t, r.cost)
        k += len(batch)
        if progress is not None:
            progress(done0 + k, trials, f"best {study.best_value:.3f}")
    best = {g: float(study.best_params[g]) for g in TUNED}
    double = {g: 2.0 * v for g, v in best.items()}
    starter_f, best_f, double_f = map_ordered(
        fly, [(str(scen), "", g, board_lib) for g in (start, best, double)],
        jobs=min(jobs, 3), backend=backend, address=address)
    tuned_file = out / f"{aircraft_file.stem}_tuned.toml"
    tuned_file.write_text(tuned_toml(aircraft_file.read_text(), best))
    values = [t.value for t in study.trials if t.value is not None]
    _plot(values, out / "search.png", ac.name)
    result = {"aircraft": ac.name, "trials": len(values), "seed": seed, "trimmed": trimmed,
              "passed_starter": starter_f.passed, "passed_best": best_f.passed,
              "criteria": len(CRITERIA), "error_starter": starter_f.error,
              "error_best": best_f.error, "starter": start,
              "best": best, "cost_starter": starter_f.cost, "cost_best": best_f.cost,
              "cost_2x_best": double_f.cost, "metrics_starter": starter_f.metrics,
              "metrics_best": best_f.metrics, "metrics_2x_best": double_f.metrics,
              "error_2x_best": double_f.error, "tuned_file": str(tuned_file)}
    (out / "result.json").write_text(json.dumps(result, indent=1) + "\n")
    (out / "report.md").write_text(report_md(result))
    return result


def report_md(r: dict[str, Any]) -> str:
    keys = [*GOALS, "surface_saturation_frac"]
    rows = ["| metric | goal | starter | tuned | tuned x 2 (margin) |", "| --- | --- | --- | --- | --- |"]
    for k in keys:
        vals = [r[f"metrics_{w}"].get(k) for w in ("starter", "best", "2x_best")]
        cells = ["-" if v is None else f"{v:.3g}" for v in vals]
        rows.append(f"| {k} | {GOALS.get(k, '-')} | " + " | ".join(cells) + " |")
    rows.append(f"| **cost** | | {r['cost_starter']:.3f} | {r['cost_best']:.3f} | "
                f"{r['cost_2x_best']:.3f} |")
    rows.append(f"| **criteria passed** | | {r['passed_starter']}/{r['criteria']} | "
                f"{r['passed_best']}/{r['criteria']} | |")
    g = ["| gain | starter | tuned |", "| --- | --- | --- |"]
    g += [f"| {k} | {r['starter'][k]:g} | {r['best'][k]:.4g} |" for k in TUNED]
    note = (f"\nAt twice the tuned gains the run failed: {r['error_2x_best']}\n"
            if r["error_2x_best"] else "")
    return (f"# Tuning of {r['aircraft']} ({r['trials']} trials, seed {r['seed']})\n\n"
            "The standard manoeuvres (manoeuvres.toml: a 30-degree-bank turn each way at "
            "v_ref, on the estimate), the starter gains, the best found, and the best at twice "
            "their value (the stability margin: a limit cycle shows as turn-rate RMS error)."
            + ("" if r["trimmed"] else " JSBSim trims this model nowhere: it flew released "
               "untrimmed ([initial] trim = false).") + "\n\n"
            + "\n".join(rows) + "\n\n" + "\n".join(g) + "\n" + note
            + f"\nTuned aircraft file: `{r['tuned_file']}`; the search: `search.png`.\n")


def _plot(values: list[float], path: Path, name: str) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    best = [min(values[: i + 1]) for i in range(len(values))]
    ax.plot(range(len(values)), values, ".", label="trial")
    ax.plot(range(len(values)), best, "-", label="best so far")
    ax.set_yscale("log")
    ax.set_xlabel("trial")
    ax.set_ylabel("cost (sum of metric / goal)")
    ax.set_title(f"tune {name}")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
