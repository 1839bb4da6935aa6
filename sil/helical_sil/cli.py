"""Command line: `python -m helical_sil run|batch ...`."""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
import traceback
from pathlib import Path
from typing import Any, Iterable

from helical_sil.campaigns.backend import BACKENDS, BackendError, map_ordered
from helical_sil.campaigns.runner import progress_bar, run_one
from helical_sil.config.scenario import ScenarioError, load_scenario
from helical_sil.sim.board import BoardError
from helical_sil.sim.lockstep import SimError

# The exit status of every subcommand: one text, shown by each --help and
# mirrored in sil/README.md ("Exit status").
EXIT_OK, EXIT_CRITERION, EXIT_INPUT, EXIT_RUNTIME, EXIT_BUG = 0, 1, 2, 3, 4
EXIT_STATUS = """exit status:
  0  every pass criterion passed (compare: the table was printed; serve: the
     flight ran to --duration or was stopped by Ctrl-C / SIGTERM)
  1  a pass criterion failed (batch: in at least one scenario; upsets: an upset
     was not recovered, or a known failure recovered)
  2  bad input or usage, found before anything is flown: a scenario or aircraft
     file that does not load (the message names the file and the key), an --out
     that is not a writable folder, a bad argument, an unreadable metrics.json
  3  the board library or JSBSim failed (missing or stale library, a parameter
     the board refused, a run that could not finish, serve: ground contact),
     or writing an output failed after the flight
  4  an internal error of the harness (a bug: the traceback is printed)"""

RUN_OUTPUTS = ("telemetry.csv", "metrics.json")


class UsageError(Exception):
    """A bad command-line argument or output folder: exit 2, nothing flown."""


def prepare_out(arg: str, names: Iterable[str] = ()) -> Path:
    """The output folder --out, created and proven writable before anything is
    flown (a flight must not be lost to an output path). names: files or
    folders that will be written in it; an existing one must be of that kind
    (a name ending in '/' is a folder)."""
    if not arg.strip():
        raise UsageError("--out is empty: give an output folder ('.' for the current one)")
    out = Path(arg)
    if out.exists() and not out.is_dir():
        raise UsageError(f"--out {out}: exists and is not a folder")
    try:
        out.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(dir=out, prefix=".helical_sil_write_test_")
        os.close(fd)
        os.unlink(probe)
    except OSError as e:
        raise UsageError(f"--out {out}: cannot write there: {e.strerror or e}") from None
    for n in names:
        q = out / n
        want_dir = n.endswith("/")
        if q.is_symlink():  # writing would follow it and overwrite its target
            raise UsageError(f"--out {out}: {q} is a symbolic link (to {os.readlink(q)}): not "
                             "overwritten; remove it or choose another --out")
        if q.exists() and q.is_dir() != want_dir:
            raise UsageError(f"--out {out}: {q} exists and is not a "
                             f"{'folder' if want_dir else 'file'}")
    return out

def prepare_file(arg: str, option: str) -> Path:
    """An output file an option names, checked before anything is flown: not
    a folder, not a symbolic link (its target would be overwritten), in a
    folder that exists and can be written."""
    if not arg.strip():
        raise UsageError(f"{option} is empty: give a file name")
    f = Path(arg)
    if f.is_symlink():
        raise UsageError(f"{option} {f}: is a symbolic link (to {os.readlink(f)}): not overwritten")
    if f.is_dir():
        raise UsageError(f"{option} {f}: is a folder, not a file")
    parent = f.parent if str(f.parent) else Path(".")
    if not parent.is_dir():
        raise UsageError(f"{option} {f}: the folder {parent} does not exist")
    if not os.access(parent, os.W_OK | os.X_OK) or (f.exists() and not os.access(f, os.W_OK)):
        raise UsageError(f"{option} {f}: cannot write there")
    return f


SUMMARY_COLS = (
    ("scenario", "scenario", "{}"),
    ("aircraft", "aircraft", "{}"),
    ("turn_rate_rmse_deg_s", "rmse°/s", "{:.2f}"),
    ("turn_rate_error_pct", "err%", "{:.1f}"),
    ("turn_entry_s", "entry s", "{:.2f}"),
    ("bank_overshoot_deg", "ovs°", "{:.1f}"),
    ("altitude_change_per_360_m", "Δh/360 m", "{:.1f}"),
    ("sideslip_rms_deg", "β rms°", "{:.2f}"),
    ("max_altitude_loss_m", "h loss m", "{:.1f}"),
    ("surface_saturation_frac", "sat", "{:.2f}"),
    ("attitude_source", "attitude", "{}"),
    ("attitude_error_rms_deg", "att err°", "{:.2f}"),
    ("sim_speed_x_realtime", "×RT", "{:.0f}"),
    ("result", "result", "{}"),
)


def _summary_row(m: dict[str, Any]) -> dict[str, str]:
    """The headline numbers of a run: the worst over its segments."""
    segs = m["segments"]
    row: dict[str, str] = {"scenario": m["scenario"], "aircraft": m["aircraft"]}

    def worst(key: str, absval: bool = False) -> float | None:
        vals = [s[key] for s in segs if s.get(key) is not None]
        if not vals:
            return None
        return max(vals, key=lambda v: abs(v)) if absval else max(vals)

    vals = {
        "turn_rate_rmse_deg_s": worst("turn_rate_rmse_deg_s"),
        "turn_rate_error_pct": worst("turn_rate_error_pct"),
        "turn_entry_s": worst("turn_entry_s"),
        "bank_overshoot_deg": worst("bank_overshoot_deg"),
        "altitude_change_per_360_m": worst("altitude_change_per_360_m", absval=True),
        "sideslip_rms_deg": m["run"]["sideslip_rms_deg"],
        "max_altitude_loss_m": m["run"]["max_altitude_loss_m"],
        "surface_saturation_frac": m["run"]["surface_saturation_frac"],
        "sim_speed_x_realtime": m["run"]["sim_speed_x_realtime"],
        "attitude_source": m["run"].get("attitude_source"),
        "attitude_error_rms_deg": m["run"].get("attitude_error_rms_deg"),
    }
    for key, _h, fmt in SUMMARY_COLS[2:-1]:
        v = vals[key]
        row[key] = "-" if v is None else fmt.format(v)
    n_ok = sum(c["ok"] for c in m["pass_criteria"])
    row["result"] = f"{'PASS' if m['passed'] else 'FAIL'} {n_ok}/{len(m['pass_criteria'])}"
    return row


def markdown_table(heads: list[str], rows: list[list[str]]) -> str:
    """A Markdown table, each column as wide as its widest cell."""
    widths = [max([len(h), *(len(r[i]) for r in rows)]) for i, h in enumerate(heads)]
    line = "| " + " | ".join(h.ljust(w) for h, w in zip(heads, widths)) + " |"
    sep = "|" + "|".join("-" * (w + 2) for w in widths) + "|"
    body = ["| " + " | ".join(c.ljust(w) for c, w in zip(r, widths)) + " |" for r in rows]
    return "\n".join([line, sep, *body])


def format_table(rows: list[dict[str, str]]) -> str:
    return markdown_table([h for _k, h, _f in SUMMARY_COLS],
                          [[r.get(k, "") for k, _h, _f in SUMMARY_COLS] for r in rows])


def cmd_run(args: argparse.Namespace) -> int:
    sc = load_scenario(Path(args.scenario))  # exit 2 before anything is made or flown
    names: tuple[str, ...] = RUN_OUTPUTS
    if not args.no_plots:
        from helical_sil.analysis.plots import PLOT_FILES
        names += PLOT_FILES
    out = prepare_out(args.out, names)
    # --- PIL (issue 8): --target pil flies the firmware image under QEMU ---
    if getattr(args, "target", "sil") == "pil":
        from helical_sil.live import pil
        with pil.as_sim_target(args.elf) as pil_runs:
            m = run_one(Path(args.scenario), out, args.board_lib,
                        plots=not args.no_plots, scenario=sc, attitude=args.attitude)
        if pil.report(pil_runs[-1], out) != 0:
            m["passed"] = False
    else:
        m = run_one(Path(args.scenario), out, args.board_lib,
                    plots=not args.no_plots, scenario=sc, attitude=args.attitude)
    # --- end PIL ---
    print(format_table([_summary_row(m)]))
    for c in m["pass_criteria"]:
        lim = " ".join(x for x in (f"min {c['min']}" if c["min"] is not None else "",
                                    f"max {c['max']}" if c["max"] is not None else "") if x)
        val = "n/a" if c["value"] is None else f"{c['value']:.3f}"
        print(f"  {'ok  ' if c['ok'] else 'FAIL'} {c['segment']}.{c['metric']} = {val} ({lim})")
        if c.get("reason"):
            print(f"       {c['reason']}")
    for line in m["run"].get("envelope", []):
        print(f"  envelope: {line}")
    print(f"wrote {Path(args.out).resolve()} (metrics.json, telemetry.csv"
          f"{', plots' if not args.no_plots else ''})")
    return 0 if m["passed"] else 1


def _batch_files(args: argparse.Namespace) -> list[Path]:
    """The scenario files of a batch, every one loaded once: a bad file (or
    --only naming no file) is exit 2 before anything is flown."""
    d = Path(args.directory)
    try:
        files = sorted(p for p in d.glob("*.toml") if p.is_file()) if d.is_dir() else []
    except OSError as e:
        raise UsageError(f"{d}: cannot list the folder: {e.strerror or e}") from None
    if not files:
        raise UsageError(f"no *.toml scenarios in {d}")
    if args.only:
        missing = sorted(set(args.only) - {f.stem for f in files})
        if missing:
            raise UsageError(f"--only: no scenario {', '.join(missing)} in {d}")
        files = [f for f in files if f.stem in set(args.only)]
    errors = []
    for f in files:
        try:
            load_scenario(f)
        except ScenarioError as e:
            errors.append(str(e))
    if errors:
        raise ScenarioError("\n".join(errors) + f"\n{len(errors)} bad scenario file(s); "
                            "nothing flown")
    return files


def _batch_one(job: tuple[str, str, str | None, bool, int | None, str | None]
               ) -> tuple[str, dict[str, Any] | None, str | None]:
    """One batch run, in whichever process the backend gives it: (its output
    folder's name, metrics.json's content or None, the error or None)."""
    f, out, board_lib, plots, seed, attitude = job
    try:
        m = run_one(Path(f), Path(out), board_lib, plots=plots, seed=seed, attitude=attitude)
    except (ScenarioError, SimError) as e:
        return Path(out).name, None, str(e)
    return Path(out).name, m, None


def _add_backend_args(p: argparse.ArgumentParser, jobs_help: str) -> None:
    p.add_argument("--jobs", type=int, default=1, help=jobs_help)
    p.add_argument("--backend", choices=BACKENDS, default="local",
                   help="where the runs execute: this machine's processes (local, the "
                        "default) or Ray (pip install 'helical-sil[ray]'); the results are "
                        "the same bit for bit")
    p.add_argument("--address", default=None,
                   help="--backend ray: an existing Ray cluster (ray://host:10001 or "
                        "host:6379); default: a local Ray with --jobs CPUs for this run")


def cmd_batch(args: argparse.Namespace) -> int:
    if args.jobs < 1:
        raise UsageError("--jobs must be at least 1")
    files = _batch_files(args)
    # --- fault campaign (issue 7): --seeds flies every scenario once per seed ---
    seeds: list[int | None] = list(args.seeds) if getattr(args, "seeds", None) else [None]
    att = getattr(args, "attitude", "scenario")
    # --attitude both: every scenario on JSBSim's truth and on the estimate, side by side
    atts: list[str | None] = ["truth", "estimate"] if att == "both" else (
        [None] if att == "scenario" else [att])
    runs4 = [(f, sd, a, (f.stem if sd is None else f"{f.stem}_seed{sd}")
              + ("" if att != "both" else f"_{a}")) for f in files for sd in seeds for a in atts]
    runs = [(f, sd, n) for f, sd, _a, n in runs4]
    run_att = {n: a for _f, _sd, a, n in runs4}
    out = prepare_out(args.out, ["summary.md", "summary.json", *(n + "/" for _f, _s, n in runs)])
    rows, results = [], {}
    t0 = time.perf_counter()
    failed_run = False
    files = [f for f, _sd, _n in runs]
    progress_bar(0, len(files), "", t0)
    jobs = [(str(f), str(out / name), args.board_lib, not args.no_plots, sd, run_att[name])
            for f, sd, name in runs]
    done = map_ordered(_batch_one, jobs, jobs=args.jobs, backend=args.backend,
                       address=args.address,
                       progress=lambda k, r: progress_bar(k, len(files), r[0], t0))
    for (_f, _sd, name), (_n, m, err) in zip(runs, done):
        if err is not None:  # the file changed meanwhile, or the simulation failed
            sys.stderr.write(f"\nerror: {err}\n")
            failed_run = True
            rows.append({"scenario": name, "result": "ERROR"})
            continue
        rows.append(_summary_row(m))
        results[name] = {"passed": m["passed"], "run": m["run"],
                         "pass_criteria": m["pass_criteria"]}
    # --- end fault campaign ---
    progress_bar(len(files), len(files), "done", t0)
    table = format_table(rows)
    print(table)
    (out / "summary.md").write_text(table + "\n")
    with (out / "summary.json").open("w") as fh:
        json.dump(results, fh, indent=2)
    n_pass = sum(r["passed"] for r in results.values())
    n_fail = len(results) - n_pass
    n_err = len(files) - len(results)
    print(f"{n_pass} passed, {n_fail} failed" + (f", {n_err} could not be flown" if n_err else ""))
    print(f"wrote {out.resolve()}")
    if failed_run:
        return EXIT_RUNTIME
    return EXIT_OK if n_fail == 0 else EXIT_CRITERION


COMPARE_KEYS = ("turn_entry_s", "wrong_way_yaw_deg", "entry_altitude_loss_m",
                "turn_rate_error_pct", "bank_overshoot_deg", "max_altitude_loss_m",
                "path_altitude_loss_m", "heading_disturbance_deg", "altitude_error_max_m",
                "sideslip_rms_deg")


def _load_metrics(p: Path) -> dict[str, Any]:
    """A run's metrics.json with the fields compare reads; anything else is exit 2
    naming the file."""
    if not p.is_file():
        raise UsageError(f"{p}: no such file (give run output folders)")
    try:
        m = json.loads(p.read_bytes().decode("utf-8"))
    except OSError as e:
        raise UsageError(f"{p}: cannot read: {e.strerror or e}") from None
    except (UnicodeDecodeError, ValueError, RecursionError) as e:
        raise UsageError(f"{p}: not a metrics.json (not JSON: {e})") from None
    segs = m.get("segments") if isinstance(m, dict) else None
    if (not isinstance(m, dict) or not isinstance(m.get("scenario"), str)
            or not isinstance(segs, list)
            or not all(isinstance(s, dict) and isinstance(s.get("label"), str) for s in segs)):
        raise UsageError(f"{p}: not a metrics.json ('scenario' and 'segments[].label' expected)")
    return m


def _cell(v: Any) -> str:
    if v is None:
        return "-"
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        return f"{v:.2f}"
    return str(v)[:16]


# compare of batch folders: per scenario, these summary columns of each batch
BATCH_COMPARE_COLS = ("turn_rate_error_pct", "turn_entry_s", "altitude_change_per_360_m",
                      "max_altitude_loss_m", "attitude_error_rms_deg", "result")


def _batch_runs(d: Path) -> dict[str, dict[str, str]]:
    """A batch folder's runs (summary.json's names), each as its summary row
    (from its own metrics.json)."""
    try:
        names = list(json.loads((d / "summary.json").read_text(encoding="utf-8")))
    except (OSError, UnicodeDecodeError, ValueError) as e:
        raise UsageError(f"{d / 'summary.json'}: not a batch summary ({e})") from None
    return {n: _summary_row(_load_metrics(d / n / "metrics.json")) for n in names}


def _batch_columns(dirs: list[Path]) -> tuple[list[str], list[dict[str, dict[str, str]]]]:
    """The columns to put side by side: one per batch folder, or, for one
    folder of `batch --attitude both`, its truth and its estimate runs."""
    if len(dirs) == 1:
        runs = _batch_runs(dirs[0])
        pairs = [("truth", "_truth"), ("estimate", "_estimate")]
        cols = [{n[:-len(suf)]: r for n, r in runs.items() if n.endswith(suf)}
                for _h, suf in pairs]
        if not cols[0] or not cols[1]:
            raise UsageError(f"{dirs[0]}: one batch folder compares only a batch flown with "
                             "--attitude both; give two or more folders otherwise")
        return [h for h, _s in pairs], cols
    return [d.name for d in dirs], [_batch_runs(d) for d in dirs]


def compare_batches(dirs: list[Path]) -> str:
    """Per scenario, the headline numbers of each batch side by side (the
    worst over its segments, as batch's own table)."""
    heads, cols = _batch_columns(dirs)
    names = [n for n in cols[0] if all(n in c for c in cols[1:])]
    if not names:
        raise UsageError("the batches have no scenario in common")
    titles = {k: h for k, h, _f in SUMMARY_COLS}
    head = ["scenario"] + [f"{titles[k]} {h}" for k in BATCH_COMPARE_COLS for h in heads]
    rows = [[n] + [c[n].get(k, "-") for k in BATCH_COMPARE_COLS for c in cols] for n in names]
    passed = [sum(c[n]["result"].startswith("PASS") for n in names) for c in cols]
    return markdown_table(head, rows) + "\n" + ", ".join(
        f"{h}: {p}/{len(names)} passed" for h, p in zip(heads, passed))


def cmd_compare(args: argparse.Namespace) -> int:
    """Side by side, per segment label, the metrics of two or more runs; or,
    given batch folders, per scenario."""
    dirs = [Path(d) for d in args.runs]
    if all((d / "summary.json").is_file() for d in dirs):
        print(compare_batches(dirs))
        return 0
    runs = [_load_metrics(Path(d) / "metrics.json") for d in args.runs]
    keys = tuple(args.metrics) if args.metrics else COMPARE_KEYS
    labels = [s["label"] for s in runs[0]["segments"]]
    names = [r["scenario"] for r in runs]
    rows = []
    for lab in labels:
        segs = [{s["label"]: s for s in r["segments"]}.get(lab, {}) for r in runs]
        for k in keys:
            vals = [sg.get(k) for sg in segs]
            if all(v is None for v in vals):
                continue
            rows.append([lab, k] + [_cell(v) for v in vals])
    print(markdown_table(["segment", "metric"] + names, rows))
    return 0


# --- fault campaign (issue 7): the upset-recovery campaign ---
def cmd_upsets(args: argparse.Namespace) -> int:
    from helical_sil.campaigns import upsets
    from helical_sil.config.scenario import DEFAULT_AIRCRAFT_DIR, load_aircraft
    if args.count < 1:
        raise UsageError("--count must be at least 1")
    if args.jobs < 1:
        raise UsageError("--jobs must be at least 1")
    for ac in args.aircraft:  # exit 2 before the output folder is made
        load_aircraft(ac, [DEFAULT_AIRCRAFT_DIR], Path("upsets"), "--aircraft")
    from helical_sil.campaigns.options import OptionsError, parse_set
    try:
        overrides = parse_set(args.set, "--set")
    except OptionsError as e:
        raise UsageError(str(e)) from None
    out = prepare_out(args.out, ["summary.md", "summary.json", *(ac + "/" for ac in args.aircraft)])
    total = len(upsets.upset_list(args.aircraft[0], args.count, args.seed, args.grid))
    try:
        known = upsets.parse_known(args.known_failures, args.aircraft, total)
    except ValueError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    n_failed, table = upsets.run_campaign(
        args.aircraft, args.count, args.seed, out, args.board_lib,
        altitude_m=args.altitude_m, duration_s=args.duration_s, floor_m=args.floor_m,
        jobs=args.jobs, plots=args.plots, known_failures=known,
        pitch_mode=args.pitch_mode, attitude=args.attitude, backend=args.backend,
        address=args.address, grid=args.grid, overrides=overrides)
    print(table)
    print(f"wrote {out.resolve()} (summary.md, summary.json, one folder and "
          "scenario file per upset)")
    return 0 if n_failed == 0 else 1


class _HelpFormatter(argparse.HelpFormatter):
    """Wraps descriptions as usual but keeps the exit-status table's lines."""

    def _fill_text(self, text: str, width: int, indent: str) -> str:
        if text.startswith("exit status:"):
            return "".join(indent + line for line in text.splitlines(keepends=True))
        return super()._fill_text(text, width, indent)


# every parser: the same exit-status table after the options
_HELP: dict[str, Any] = {"epilog": EXIT_STATUS, "formatter_class": _HelpFormatter}


def _add_upsets_parser(sub: Any) -> None:
    from helical_sil.campaigns import upsets
    u = sub.add_parser(
        "upsets", **_HELP, help="upset-recovery campaign: random attitudes, recover to level flight",
        description="Fly COUNT seeded random upsets per aircraft (any bank, pitch +-80 deg, "
                    "inverted, airspeed from near the stall to a little above cruise, body "
                    "rates up to "
                    "+-20 deg/s; released untrimmed after a cruise trim) with the controller "
                    "commanded to level upright flight on the altitude hold (at the start "
                    "altitude) and airspeed hold. An upset is recovered when the tilt stays "
                    "within 10 deg of the law's target tilt to the end of the run (at least "
                    "5 s) and the lowest point stays above --floor-m. Writes one scenario "
                    "file and output folder per upset, summary.md and summary.json; exit 1 "
                    "if any upset fails.")
    u.add_argument("--aircraft", nargs="+", default=["T37", "c172p"],
                   help="aircraft names (default: T37 c172p)")
    u.add_argument("--count", type=int, default=50, help="upsets per aircraft (default 50)")
    u.add_argument("--seed", type=int, default=1, help="campaign seed (default 1)")
    u.add_argument("--out", required=True, help="output directory")
    u.add_argument("--altitude-m", type=float, default=upsets.DEFAULT_ALTITUDE_M,
                   help=f"start altitude, m above sea level (JSBSim's ground is at sea "
                        f"level; default {upsets.DEFAULT_ALTITUDE_M:g})")
    u.add_argument("--duration-s", type=float, default=upsets.DEFAULT_DURATION_S,
                   help=f"length of each run (default {upsets.DEFAULT_DURATION_S:g})")
    u.add_argument("--floor-m", type=float, default=upsets.DEFAULT_FLOOR_M,
                   help=f"lowest altitude allowed, m above the ground (default "
                        f"{upsets.DEFAULT_FLOOR_M:g})")
    _add_backend_args(u, "parallel runs (default 1)")
    u.add_argument("--plots", action="store_true", help="also write the PNG plots of each run")
    u.add_argument("--attitude", choices=("truth", "estimate"), default="estimate",
                   help="what the law flies on: the firmware's estimate (default) or "
                        "JSBSim's truth")
    u.add_argument("--pitch-mode", choices=("earth_frame", "tilt_cross"), default="earth_frame",
                   help="the law's pitch method (default earth_frame, the tuned one)")
    u.add_argument("--known-failures", nargs="*", default=[], metavar="AIRCRAFT:INDEX",
                   help="upsets failing on a known library defect: reported as failures, "
                        "not counted in the exit status; exit 1 if one of them passes")
    u.add_argument("--grid", choices=upsets.GRIDS, default="random",
                   help="random: COUNT seeded upsets (default); vertical: the near-vertical "
                        "grid (pitch +-90 and +-85 deg, roll 0/90/180/-90, lowest and highest "
                        "speed: 32 per aircraft; issue 17); both: the random ones, then the grid")
    u.add_argument("--set", nargs="*", default=[], metavar="KEY=VALUE",
                   help="law or guidance rows of the parameter table for every upset "
                        "(written into each scenario file), e.g. vertical_fade=0.1")
    u.set_defaults(func=cmd_upsets)
# --- end fault campaign ---


def cmd_aircraft_list(args: argparse.Namespace) -> int:
    from helical_sil.config import aircraft as acm
    if args.jobs < 1:
        raise UsageError("--jobs must be at least 1")
    t0 = time.perf_counter()
    models = acm.list_models(args.altitude_m, include_all=args.all, jobs=args.jobs,
                             progress=lambda i, n, name: progress_bar(i, n, name, t0))
    rows = [[m.name, "yes" if m.fixed_wing else "no", str(m.engines),
             "yes" if m.trims else ("-" if not m.fixed_wing else "no"),
             ", ".join(f"{v:g}" for v in m.trims_at), acm.explain(m)] for m in models]
    print(markdown_table(["model", "fixed-wing with engine", "engines", "trims",
                          f"trims at (m/s, {args.altitude_m:g} m)", "note"], rows))
    n_fw = sum(m.fixed_wing for m in models)
    n_trim = sum(m.trims for m in models)
    print(f"{n_fw} fixed-wing models with an engine, {n_trim} of them trim at a speed of "
          f"{', '.join(f'{v:g}' for v in acm.TRIM_SPEEDS_M_S)} m/s")
    if args.json:
        Path(args.json).write_text(json.dumps(
            [{"model": m.name, "fixed_wing": m.fixed_wing, "why_not": m.why_not,
              "engines": m.engines, "wing_area_m2": m.wing_area_m2, "trims_at_m_s": m.trims_at,
              "trim_error": m.trim_error} for m in models], indent=1) + "\n")
    return 0


def cmd_aircraft_new(args: argparse.Namespace) -> int:
    from helical_sil.config import aircraft as acm
    out = Path(args.out)
    if out.exists() and not args.force:
        raise UsageError(f"{out} exists (--force overwrites it)")
    try:
        s = acm.starter(args.model, args.altitude_m)
    except ValueError as e:
        raise UsageError(str(e)) from None
    out.write_text(acm.starter_toml(s))
    pts = s["points"]
    if pts:
        print(f"{args.model}: trims at {pts[0].speed_m_s:.1f}-{pts[-1].speed_m_s:.1f} m/s; "
              f"v_ref {s['v_ref']:g}, v_min {s['v_min']:g}, throttle {s['throttle']:.2f}; roll "
              f"{s['roll_rate']:.2f} rad/s after 1 s of full aileron (roll gains x "
              f"{s['roll_scale']:.2f})")
    else:
        why = s["trim_error"].split(" (at ")[0]
        print(f"{args.model}: JSBSim trims it at no speed of the sweep (\"{why}\"): fly it "
              "with [initial] trim = false")
    if s["sas"]:
        print(f"{args.model}: the model has its own stability augmentation: {s['sas']}")
    print(f"wrote {out}")
    return 0


def cmd_tune(args: argparse.Namespace) -> int:
    from helical_sil.campaigns import tune as tn
    if args.jobs < 1 or args.trials < 1:
        raise UsageError("--jobs and --trials must be at least 1")
    src = Path(args.aircraft)
    if not src.is_file():
        raise UsageError(f"{src}: no such aircraft file")
    t0 = time.perf_counter()
    r = tn.tune(src, Path(args.out), args.trials, args.seed, args.jobs, args.backend,
                args.address, args.board_lib,
                progress=lambda i, n, what: progress_bar(i, n, what, t0))
    print(tn.report_md(r))
    print(f"wrote {Path(args.out).resolve()} (report.md, search.png, result.json, "
          f"{Path(r['tuned_file']).name}, study.db: run again to continue the search)")
    return 0


def _add_tune_parser(sub: Any) -> None:
    t = sub.add_parser(
        "tune", **_HELP, help="find the law's gains from SIL flights (Optuna)",
        description="Search the law's gains (kp, kd, kff of the three axes) for an aircraft "
                    "file with Optuna's TPE sampler: each trial flies the standard manoeuvres "
                    "(a 30-degree-bank turn each way at v_ref, on the estimate) and is scored "
                    "by turn entry, steady turn-rate error, overshoot, sideslip, altitude lost "
                    "and saturation against their goals. The starter gains are trial 0; the "
                    "best are also flown at twice their value (the stability margin). Writes "
                    "report.md, search.png, result.json and AIRCRAFT_tuned.toml to --out; the "
                    "search is stored in --out/study.db, so running it again continues it.")
    t.add_argument("aircraft", help="aircraft TOML file (e.g. from `aircraft new`)")
    t.add_argument("--out", required=True, help="output directory (also the study's store)")
    t.add_argument("--trials", type=int, default=40, help="trials in all (default 40)")
    t.add_argument("--seed", type=int, default=1, help="the sampler's seed (default 1)")
    _add_backend_args(t, "trials flown at once (default 1)")
    t.set_defaults(func=cmd_tune)


def _add_aircraft_parser(sub: Any) -> None:
    from helical_sil.config import aircraft as acm
    a = sub.add_parser("aircraft", **_HELP, help="the JSBSim models that can be flown",
                       description="The aircraft of the installed JSBSim wheel.")
    asub = a.add_subparsers(dest="aircraft_cmd", required=True)
    lst = asub.add_parser(
        "list", **_HELP, help="list the flyable models and whether each trims",
        description="Every model of JSBSim's aircraft folder that is fixed-wing with an "
                    "engine (not a glider, rotorcraft, airship, balloon, bomb or launch "
                    "vehicle), each trimmed straight and level by JSBSim at "
                    f"{', '.join(f'{v:g}' for v in acm.TRIM_SPEEDS_M_S)} m/s: the speeds "
                    "that trim, or JSBSim's own reason and what to do. Takes a few minutes "
                    "(a progress bar on stderr).")
    lst.add_argument("--altitude-m", type=float, default=acm.DEFAULT_ALTITUDE_M,
                     help=f"trim altitude above sea level (default {acm.DEFAULT_ALTITUDE_M:g})")
    lst.add_argument("--all", action="store_true",
                     help="also list the models that are not flown, with the reason")
    lst.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                     help="parallel processes (default: the CPU count)")
    lst.add_argument("--json", default=None, help="also write the table as JSON to this file")
    lst.set_defaults(func=cmd_aircraft_list)
    new = asub.add_parser(
        "new", **_HELP, help="write a starter aircraft file for a JSBSim model",
        description="Trim MODEL straight and level with JSBSim over 15-260 m/s and write a "
                    "starter aircraft file: the trims (throttle, elevator, alpha per speed) as "
                    "comments, v_ref (the fastest trimmed speed at no more than 75 %% "
                    "throttle), v_min (the lowest trimmed speed), the trim throttle, and the "
                    "c172p's tuned gains with the roll axis scaled by the model's roll "
                    "authority; a note when the model has its own stability augmentation (a "
                    "yaw damper) or trims nowhere (with JSBSim's reason and the trim = false "
                    "path).")
    new.add_argument("model", help="JSBSim model name (see `aircraft list`)")
    new.add_argument("--out", required=True, help="aircraft TOML file to write")
    new.add_argument("--altitude-m", type=float, default=acm.DEFAULT_ALTITUDE_M,
                     help=f"trim altitude above sea level (default {acm.DEFAULT_ALTITUDE_M:g})")
    new.add_argument("--force", action="store_true", help="overwrite --out")
    new.set_defaults(func=cmd_aircraft_new)


# --- law options (issue 17) ---
def cmd_options(args: argparse.Namespace) -> int:
    """The law's options side by side: a suite of scenarios (SCENARIO_DIR or
    files) or the standard manoeuvres of aircraft files (--aircraft)."""
    import shlex

    from tqdm import tqdm

    from helical_sil.campaigns import options as opt
    if args.jobs < 1:
        raise UsageError("--jobs must be at least 1")
    try:
        base = opt.parse_set(args.set, "--set")
        on = {k: v for k, _, v in opt.OPTIONS}
        on.update(opt.parse_set(args.on, "--on"))
        unknown = [k for k in on if k not in opt.OPTION_NAMES]
        if unknown:
            raise opt.OptionsError(f"--on {unknown[0]}: not an option (options: "
                                   f"{', '.join(opt.OPTION_NAMES)})")
        combo = args.combo if args.combo is not None else list(opt.OPTION_NAMES)
        bad = [k for k in combo if k not in opt.OPTION_NAMES]
        if bad:
            raise opt.OptionsError(f"--combo {bad[0]}: not an option (options: "
                                   f"{', '.join(opt.OPTION_NAMES)})")
    except opt.OptionsError as e:
        raise UsageError(str(e)) from None
    if bool(args.scenarios) == bool(args.aircraft):
        raise UsageError("give scenarios (a folder or files) or --aircraft FILE..., not both")
    out = prepare_out(args.out, ["table.md", "table.csv", "options.png", "result.json"])
    rows: dict[str, str] = {}
    if args.aircraft:
        files = []
        for a in args.aircraft:
            p = Path(a)
            if not p.is_file():
                from helical_sil.config.scenario import DEFAULT_AIRCRAFT_DIR
                p = DEFAULT_AIRCRAFT_DIR / f"{a}.toml"
            if not p.is_file():
                raise UsageError(f"--aircraft {a}: neither a file nor an aircraft of "
                                 "sil/scenarios/aircraft")
            files.append(p)
        rows = opt.manoeuvre_rows(files, out)
        title = f"Law options: the standard manoeuvres of {len(rows)} aircraft"
    else:
        for a in args.scenarios:
            p = Path(a)
            for f in (sorted(p.glob("*.toml")) if p.is_dir() else [p]):
                if args.only and f.stem not in args.only:
                    continue
                rows[f.stem] = str(f)
        if not rows:
            raise UsageError("no scenario files")
        title = f"Law options: {len(rows)} scenarios"
    for name, f in rows.items():  # exit 2 before anything is flown
        load_scenario(f)
    bar = tqdm(total=0, unit="run", desc="options", file=sys.stderr)

    def progress(k: int, n: int, what: str) -> None:
        bar.total = n
        bar.n = k
        bar.set_postfix_str(what)
        bar.refresh()

    cmdline = "python -m helical_sil " + " ".join(shlex.quote(x) for x in sys.argv[1:]) \
        if sys.argv and sys.argv[0].endswith(("__main__.py", "helical_sil")) else \
        "python -m helical_sil options ..."
    camp = opt.Campaign(rows=rows, on_values=on, combo=combo, base=base,
                        margin=not args.no_margin, recommend=not args.no_recommend)
    r = opt.run(camp, out, args.jobs, args.board_lib, args.backend, args.address, title,
                cmdline, progress)
    bar.close()
    print((out / "table.md").read_text())
    print(f"recommended: {', '.join(r['recommended']) or 'none'}")
    print(f"wrote {out.resolve()} (table.md, table.csv, options.png, result.json)")
    return 0


def _add_options_parser(sub: Any) -> None:
    from helical_sil.campaigns import options as opt
    o = sub.add_parser(
        "options", **_HELP, help="the law's options (issue 17) side by side",
        description="Fly every row (the scenarios of a folder, or the standard manoeuvres of "
                    "each --aircraft file: a 30-degree-bank turn each way at v_ref) with the "
                    "seed's law (every option off, turn_trim 0 too), each option alone, and "
                    "their combination, each also at twice the tuned gains (stability "
                    "margin); then the options that help somewhere and hurt nowhere together "
                    "('recommended'). Metrics: turn entry over the full-aileron limit "
                    "(measured per row from its trim), steady turn-rate error, steady "
                    "sideslip RMS, bank overshoot, altitude lost in the rolls, turn-rate RMS "
                    "at 2x. Writes table.md, table.csv, options.png, result.json. Options: "
                    + ", ".join(f"{k} ({w}, on = {v:g})" for k, w, v in opt.OPTIONS)
                    + ". With roll_in on, roll_in_rate_max is each row's reachable bank rate "
                    "(the full-aileron roll's mean rate to 30 deg, the slower way) unless "
                    "--set or --on gives it.")
    o.add_argument("scenarios", nargs="*", help="scenario folder(s) or files")
    o.add_argument("--aircraft", nargs="+", default=None, metavar="FILE|NAME",
                   help="aircraft files (e.g. tune's *_tuned.toml) or names of "
                        "sil/scenarios/aircraft: fly the standard manoeuvres of each")
    o.add_argument("--only", nargs="*", help="scenario names (file stems) to fly")
    o.add_argument("--out", required=True, help="output directory")
    o.add_argument("--set", nargs="*", default=[], metavar="KEY=VALUE",
                   help="law or guidance rows of the parameter table for every variant "
                        "(table units), e.g. turn_trim_tau=5")
    o.add_argument("--on", nargs="*", default=[], metavar="OPTION=VALUE",
                   help="the value that turns an option on (defaults: "
                        + ", ".join(f"{k}={v:g}" for k, _, v in opt.OPTIONS) + ")")
    o.add_argument("--combo", nargs="*", default=None, metavar="OPTION",
                   help="the options of the 'combo' variant (default: all)")
    o.add_argument("--no-margin", action="store_true",
                   help="skip the flights at twice the gains")
    o.add_argument("--no-recommend", action="store_true",
                   help="skip the second pass (the recommended combination)")
    _add_backend_args(o, "parallel runs (default 1)")
    o.set_defaults(func=cmd_options)
# --- end law options ---
def cmd_serve(args: argparse.Namespace) -> int:
    from helical_sil.live import serve as sv
    speed = 0.0 if args.fast else args.speed
    # refused before the flight, not after it
    stats = prepare_file(args.stats_json, "--stats-json") if args.stats_json is not None else None
    try:
        return sv.run_serve(Path(args.scenario), args.mavlink, speed, args.duration, args.mode,
                            args.board_lib, args.sysid, stats)
    except sv.ServeError as e:
        raise UsageError(str(e)) from None


def _add_serve_parser(sub: Any) -> None:
    s = sub.add_parser(
        "serve", **_HELP, help="fly a scenario's aircraft live for a ground station (MAVLink)",
        description="Fly the scenario's aircraft in JSBSim, the firmware in its own flight "
                    "modes (on its estimate unless the scenario's [attitude] says truth), paced "
                    "at --speed x real time, and answer a ground station over UDP with "
                    "MAVLink 2: QGroundControl, MAVProxy or pymavlink watch the flight, read "
                    "and set parameters, upload a mission and switch modes (manual, FBW, "
                    "AUTO = waypoint, RTL = return-to-home). The firmware's link builds and "
                    "parses every message; this command only moves bytes. The pilot is a "
                    "steady transmitter (sticks centred, throttle at the trim, the mode switch "
                    "at --mode). Prints the link's counters at the end (Ctrl-C ends it).")
    s.add_argument("scenario", help="scenario TOML file (its aircraft, initial state, air, "
                                    "sensors; its [modes] and waypoints if it has them)")
    s.add_argument("--mavlink", default="udpout:127.0.0.1:14550",
                   help="udpout:HOST:PORT sends to a ground station listening there (the "
                        "default, udpout:127.0.0.1:14550, is where QGroundControl listens); "
                        "udpin:HOST:PORT listens and answers whoever sends")
    s.add_argument("--speed", type=float, default=1.0,
                   help="N x real time (default 1; 0: as fast as possible)")
    s.add_argument("--fast", action="store_true", help="as fast as possible (= --speed 0)")
    s.add_argument("--duration", type=float, default=None,
                   help="stop after this many seconds of flight (default: until Ctrl-C)")
    s.add_argument("--mode", choices=tuple(("manual", "fbw", "waypoint", "rth")), default=None,
                   help="where the transmitter's mode switch sits (default: the scenario's "
                        "first [[rc]] mode, else fbw)")
    s.add_argument("--sysid", type=int, default=1, help="MAVLink system id (default 1)")
    s.add_argument("--stats-json", default=None,
                   help="also write the end's counters (UDP and the board's link) to this file")
    s.set_defaults(func=cmd_serve)


def cmd_plot(args: argparse.Namespace) -> int:
    """The standard plots of a flight log (.bin), board or SIL."""
    from helical_sil.analysis.log_plots import plot_log
    from helical_sil.analysis.log_read import LogError

    out = Path(args.out) if args.out else Path(args.log).with_suffix("")
    try:
        files = plot_log(args.log, out)
    except LogError as e:
        raise UsageError(str(e)) from e
    print(f"wrote {out.resolve()} ({', '.join(f.name for f in files)})")
    return EXIT_OK


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(
        prog="python -m helical_sil", **_HELP,
        description="Software-in-the-loop: the helical-turn C controller (host board "
                    "library) flies JSBSim aircraft through TOML scenarios.")
    ap.add_argument("--board-lib", default=None,
                    help="path of libhelical_sil_board.so (default: $HT_SIL_BOARD_LIB or "
                         "build/host/boards/sil/)")
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run", help="fly one scenario", **_HELP,
                       description="Fly one scenario; write telemetry.csv (control rate), "
                                   "metrics.json and PNG plots to --out (created if "
                                   "needed; checked before the flight).")
    r.add_argument("scenario", help="scenario TOML file")
    r.add_argument("--out", required=True, help="output directory")
    r.add_argument("--no-plots", action="store_true", help="skip the PNG plots")
    r.add_argument("--attitude", choices=("truth", "estimate"), default=None,
                   help="fly on JSBSim's truth or the firmware's estimate, whatever the "
                        "scenario's [attitude] source says")
    # --- PIL (issue 8) ---
    r.add_argument("--target", choices=("sil", "pil"), default="sil",
                   help="sil: the host board library (default); pil: the STM32F405 HIL "
                        "firmware image under qemu-system-arm (docs/hil-protocol.md)")
    r.add_argument("--elf", default=None,
                   help="--target pil: the HIL image (default: $HT_PIL_ELF or "
                        "build/stm32f4/boards/stm32f4/ht_stm32f4_hil.elf)")
    # --- end PIL ---
    r.set_defaults(func=cmd_run)
    b = sub.add_parser("batch", help="fly every scenario of a directory", **_HELP,
                       description="Fly every *.toml of a directory (not its sub-folders), "
                                   "one output folder per scenario, with a progress bar and a "
                                   "summary table (also summary.md, summary.json). Every "
                                   "file is loaded before the first flight: one bad file "
                                   "is exit 2 and nothing is flown.")
    b.add_argument("directory", help="directory of scenario TOML files")
    b.add_argument("--out", required=True, help="output directory")
    b.add_argument("--no-plots", action="store_true", help="skip the PNG plots")
    b.add_argument("--attitude", choices=("scenario", "truth", "estimate", "both"),
                   default="scenario",
                   help="what the law flies on: each file's [attitude] source (default), "
                        "JSBSim's truth, the firmware's estimate, or both side by side")
    b.add_argument("--only", nargs="*", help="scenario names (file stems) to run")
    b.add_argument("--seeds", nargs="+", type=int, default=None,  # fault campaign (issue 7)
                   help="fly every scenario once per seed (instead of its own seed); "
                        "outputs NAME_seedN")
    _add_backend_args(b, "parallel runs (default 1)")
    b.set_defaults(func=cmd_batch)
    c = sub.add_parser("compare", help="metrics of runs side by side", **_HELP,
                       description="Print, per segment label of the first run, the metrics of "
                                   "two or more run output folders side by side (for example "
                                   "feed-forward on and off, or the two pitch methods). Given "
                                   "batch output folders instead (with summary.json), print per "
                                   "scenario the headline numbers of each batch side by side; "
                                   "one folder of `batch --attitude both` gives truth and "
                                   "estimate side by side.")
    c.add_argument("runs", nargs="+",
                   help="run output directories (with metrics.json), or batch output "
                        "directories (with summary.json)")
    c.add_argument("--metrics", nargs="*", help="metric names (default: a standard set)")
    c.set_defaults(func=cmd_compare)
    pl = sub.add_parser("plot", help="the standard plots of a flight log (.bin)", **_HELP,
                        description="Draw attitude (command against flown), turn rate, "
                                    "altitude and airspeed, surfaces and pulses, and the "
                                    "ground track from a DataFlash flight log (.bin, "
                                    "docs/flight-log.md) of a board or of the SIL, read "
                                    "with pymavlink's DFReader.")
    pl.add_argument("log", help="the flight log (.bin)")
    pl.add_argument("--out", default=None,
                    help="output directory (default: the log's path without .bin)")
    pl.set_defaults(func=cmd_plot)
    _add_upsets_parser(sub)  # fault campaign (issue 7)
    _add_aircraft_parser(sub)
    _add_tune_parser(sub)
    _add_options_parser(sub)  # issue 17
    _add_serve_parser(sub)  # ground-station link (issue 15)
    return ap


def main(argv: list[str] | None = None) -> int:
    """The exit status of EXIT_STATUS (argparse itself exits 2 on bad usage, 0
    after --help)."""
    args = build_parser().parse_args(argv)
    try:
        return int(args.func(args))
    except (ScenarioError, UsageError) as e:
        print(f"error: {e}", file=sys.stderr)
        return EXIT_INPUT
    except (BoardError, SimError, BackendError) as e:
        print(f"error: {e}", file=sys.stderr)
        return EXIT_RUNTIME
    except OSError as e:  # inputs and --out were checked: the system failed (disk full ...)
        print(f"error: {e}", file=sys.stderr)
        return EXIT_RUNTIME
    except Exception:  # a bug: keep exit 1 for "a criterion failed"
        traceback.print_exc()
        print("error: internal error of helical_sil (a bug; the traceback is above)",
              file=sys.stderr)
        return EXIT_BUG
