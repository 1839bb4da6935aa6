"""The SIL's speed against JSBSim's own (issue 32), measured side by side.

For each scenario: JSBSim's bare loop (the scenario's aircraft, trim and sim
rate, fdm.run() for the flight's duration, nothing else) and the SIL flight
of the same scenario (lockstep.run: the sensor models, the C board, the
telemetry), alternated --repeat times in one process; the median of each is
reported in times real time and as the ratio SIL / bare (1 = the harness
costs nothing beyond the physics), from wall time and from CPU time (the
process's: steadier when other work shares the cores; the SIL's includes
its flight setup, a slight overcount). Startup (imports, the board library's
load, JSBSim's load and trim) is timed apart: it is paid once per flight
whatever its length.

--batch and --tune add the wall time of `helical_sil batch sil/scenarios`
and of a `helical_sil tune` search, both on --jobs processes (2 by default:
the machine of the docs' figures).

--update-doc writes the tables to docs/generated/sil-speed.md, the figures
the docs quote. Run through scripts/bench.sh --sil (the SIL venv; the host preset's board
library must be built). Prints Markdown; exits 2 on a bad argument and 3 when
a flight cannot be flown, naming it.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

T_START = time.perf_counter()  # before the harness's imports: startup includes them

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "generated" / "sil-speed.md"
DEFAULT_SCENARIOS = ("sil/scenarios/default.toml", "sil/scenarios/c172p_helical_level.toml")


def _median(xs: list[float]) -> float:
    return float(statistics.median(xs))


def bare_loop_s(lockstep: object, sc: object) -> tuple[float, float]:
    """Wall and CPU time of JSBSim alone flying sc's duration at sc's sim rate."""
    fdm = lockstep.make_fdm(sc)  # type: ignore[attr-defined]
    n = int(round(sc.duration_s * sc.control_rate_hz)) * (  # type: ignore[attr-defined]
        sc.sim_rate_hz // sc.control_rate_hz)  # type: ignore[attr-defined]
    run = fdm.run
    t0, c0 = time.perf_counter(), time.process_time()
    for _ in range(n):
        run()
    return time.perf_counter() - t0, time.process_time() - c0


def measure_ratio(paths: list[Path], repeat: int) -> list[dict[str, object]]:
    t_imp = time.perf_counter()
    from helical_sil.config import scenario
    from helical_sil.sim import lockstep
    from helical_sil.sim.board import Board
    imports_s = time.perf_counter() - T_START
    t0 = time.perf_counter()
    Board.library(None)
    board_load_s = time.perf_counter() - t0
    del t_imp
    rows = []
    for p in paths:
        try:
            sc = scenario.load_scenario(p)
        except Exception as e:  # the loader's message names the file and key
            print(f"bench_sil: {p}: {e}", file=sys.stderr)
            raise SystemExit(2) from None
        bare, sil, setup, bare_cpu, sil_cpu = [], [], [], [], []
        for _ in range(repeat):
            w, c = bare_loop_s(lockstep, sc)
            bare.append(w)
            bare_cpu.append(c)
            t0, c0 = time.perf_counter(), time.process_time()
            try:
                res = lockstep.run(sc)
            except lockstep.SimError as e:
                print(f"bench_sil: {p}: the flight failed: {e}", file=sys.stderr)
                raise SystemExit(3) from None
            setup.append(time.perf_counter() - t0 - res.wall_s)
            sil.append(res.wall_s)
            # CPU time of the whole call (setup included: a slight overcount);
            # steadier than wall time on a shared machine
            sil_cpu.append(time.process_time() - c0)
        dur = sc.duration_s if res.end_t_s is None else res.end_t_s
        rows.append({
            "scenario": p.name, "aircraft": sc.aircraft.name, "duration_s": dur,
            "sim_rate_hz": sc.sim_rate_hz, "source": sc.attitude_source,
            "bare_x": sc.duration_s / _median(bare), "sil_x": dur / _median(sil),
            "ratio": (dur / _median(sil)) / (sc.duration_s / _median(bare)),
            "cpu_ratio": (dur / _median(sil_cpu)) / (sc.duration_s / _median(bare_cpu)),
            "setup_s": _median(setup),
        })
    return [{"imports_s": imports_s, "board_load_s": board_load_s}, *rows]


def wall_of(cmd: list[str]) -> tuple[float, int]:
    env = dict(os.environ, MPLBACKEND="Agg")
    t0 = time.perf_counter()
    rc = subprocess.run(cmd, cwd=ROOT, env=env, stdout=subprocess.DEVNULL,
                        stderr=subprocess.DEVNULL).returncode
    return time.perf_counter() - t0, rc


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="scripts/bench.sh --sil", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenarios", nargs="*", type=Path,
                    help=f"scenario files (default: {', '.join(DEFAULT_SCENARIOS)})")
    ap.add_argument("--repeat", type=int, default=3,
                    help="bare and SIL runs alternated per scenario; medians (default 3)")
    ap.add_argument("--batch", action="store_true",
                    help="also time `helical_sil batch sil/scenarios --jobs JOBS --no-plots`")
    ap.add_argument("--tune", type=int, default=0, metavar="TRIALS",
                    help="also time `helical_sil tune` of T37 with TRIALS trials (0: no)")
    ap.add_argument("--jobs", type=int, default=2, help="processes for --batch and --tune")
    ap.add_argument("--update-doc", action="store_true",
                    help=f"also write the tables to {DOC.relative_to(ROOT)}")
    a = ap.parse_args(argv)
    if a.repeat < 1 or a.jobs < 1 or a.tune < 0:
        print("bench_sil: --repeat and --jobs must be >= 1, --tune >= 0", file=sys.stderr)
        return 2
    paths = a.scenarios or [ROOT / s for s in DEFAULT_SCENARIOS]
    for p in paths:
        if not p.is_file():
            print(f"bench_sil: no scenario file {p}", file=sys.stderr)
            return 2
    res = measure_ratio(paths, a.repeat)
    start = res[0]
    out: list[str] = []
    emit = out.append  # the tables: to stdout and, with --update-doc, to the doc
    emit(f"## SIL speed against JSBSim's bare loop (median of {a.repeat}, side by side)\n")
    emit("| scenario | aircraft | attitude | flown s | sim Hz | JSBSim alone × real time "
         "| SIL × real time | SIL / JSBSim | same, CPU time | flight setup s |")
    emit("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for r in res[1:]:
        emit(f"| {r['scenario']} | {r['aircraft']} | {r['source']} | {r['duration_s']:.0f} "
             f"| {r['sim_rate_hz']} | {r['bare_x']:.0f} | {r['sil_x']:.0f} "
             f"| {r['ratio']:.2f} | {r['cpu_ratio']:.2f} | {r['setup_s']:.3f} |")
    emit(f"\nStartup, once per process: imports {start['imports_s']:.2f} s, board library "
         f"{start['board_load_s'] * 1000:.0f} ms; per flight: JSBSim load and trim, board "
         "init (the last column).")
    if a.batch or a.tune:
        emit(f"\n## Campaign wall times ({a.jobs} jobs, {os.cpu_count()} CPUs)\n")
        emit("| command | wall s | exit |")
        emit("| --- | ---: | ---: |")
        py = sys.executable
        with tempfile.TemporaryDirectory() as tmp:
            if a.batch:
                cmd = [py, "-m", "helical_sil", "batch", "sil/scenarios", "--out",
                       f"{tmp}/batch", "--no-plots", "--jobs", str(a.jobs)]
                w, rc = wall_of(cmd)
                emit(f"| `helical_sil batch sil/scenarios --no-plots --jobs {a.jobs}` "
                     f"| {w:.1f} | {rc} |")
            if a.tune:
                cmd = [py, "-m", "helical_sil", "tune", "sil/scenarios/aircraft/T37.toml",
                       "--out", f"{tmp}/tune", "--trials", str(a.tune), "--jobs", str(a.jobs)]
                w, rc = wall_of(cmd)
                emit(f"| `helical_sil tune T37.toml --trials {a.tune} --jobs {a.jobs}` "
                     f"| {w:.1f} | {rc} |")
    text = "\n".join(out) + "\n"
    sys.stdout.write(text)
    if a.update_doc:
        argv_s = " ".join(sys.argv[1:])
        DOC.parent.mkdir(parents=True, exist_ok=True)
        DOC.write_text(
            "<!-- generated by scripts/bench.sh --sil --update-doc: do not edit by hand -->\n"
            f"# SIL speed (generated)\n\nWritten by `scripts/bench.sh --sil {argv_s}` "
            f"at commit `{_git('rev-parse', '--short', 'HEAD')}` on "
            f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {os.cpu_count()} CPUs, "
            f"load average {os.getloadavg()[0]:.1f} at the end (other work on the cores slows "
            "both columns; the ratios are measured side by side, the CPU-time one is the "
            "steadier).\n\n" + text.replace("## ", "### "))
        sys.stderr.write(f"bench_sil: wrote {DOC.relative_to(ROOT)}\n")
    return 0


def _git(*args: str) -> str:
    r = subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True)
    return r.stdout.strip() or "unknown"


if __name__ == "__main__":
    sys.exit(main())
