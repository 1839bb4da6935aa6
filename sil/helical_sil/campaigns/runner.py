"""One scenario flown to its output folder, the unit every campaign is made
of: `run` flies one, `batch` and `upsets` fly many (through backend.py).

run_one writes telemetry.csv, metrics.json (with the scenario's pass
criteria evaluated) and, unless told not to, the PNG plots; progress_bar is the
progress bar on stderr of batch, upsets, tune and `aircraft list`.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path
from typing import Any

from helical_sil.config.scenario import Scenario, load_scenario


def run_one(path: Path, out: Path, board_lib: str | None, plots: bool = True,
            csv: bool = True, seed: int | None = None,
            scenario: Scenario | None = None, attitude: str | None = None) -> dict[str, Any]:
    """Fly one scenario and write its outputs; returns metrics.json's content.
    seed (fault campaign, issue 7): fly it with this seed instead of its own.
    scenario: the file already loaded (not loaded again)."""
    from helical_sil.analysis import metrics as met
    from helical_sil.sim import lockstep

    sc = scenario if scenario is not None else load_scenario(path)
    if seed is not None:
        sc.seed, sc.name = seed, f"{sc.name}_seed{seed}"
    if attitude is not None:  # --attitude: truth or estimate, whatever the file says
        sc.attitude_source = attitude
    out.mkdir(parents=True, exist_ok=True)
    # the firmware's own flight log, next to telemetry.csv (docs/flight-log.md)
    res = lockstep.run(sc, board_lib, log_path=out / "flight.bin" if csv else None)
    m = met.run_metrics(res)
    checks = met.evaluate(m, sc.criteria)
    m["pass_criteria"] = checks
    m["passed"] = all(c["ok"] for c in checks)
    if csv:
        lockstep.write_csv(res, out / "telemetry.csv")
    with (out / "metrics.json").open("w") as f:
        json.dump(m, f, indent=2, allow_nan=False)
        f.write("\n")
    if plots:
        from helical_sil.analysis.plots import write_plots
        write_plots(res, out)
    return m


def progress_bar(i: int, n: int, name: str, t0: float) -> None:
    """A progress bar on stderr: redrawn in place on a terminal, one line per
    scenario in a log (ctest, CI)."""
    width = 30
    done = int(width * i / n) if n else width
    bar = "#" * done + "-" * (width - done)
    text = f"[{bar}] {i}/{n} {time.perf_counter() - t0:6.1f}s {name[:32]:<32}"
    if sys.stderr.isatty():
        sys.stderr.write("\r" + text + ("\n" if i == n else ""))
    else:
        sys.stderr.write(text.rstrip() + "\n")
    sys.stderr.flush()
