"""Many flights: one scenario flown to its outputs, and the campaigns of them.

Owns: runner.py (run_one: a scenario flown to telemetry.csv, metrics.json
and plots, the unit of `run`, `batch` and `upsets`; the progress bar),
backend.py (where the runs execute: local processes or Ray, results in input
order), upsets.py (the upset-recovery campaign), tune.py (gains from SIL
flights, Optuna), options.py (the law's options side by side) and
roll_limit.py (an airframe's full-aileron roll, which options.py compares
against).

May import: analysis, sim, config and sensors; not live, not cli.
Imported by: cli.
"""
