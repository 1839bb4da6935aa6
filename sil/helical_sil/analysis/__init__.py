"""What a flight shows: its metrics and plots.

Owns: metrics.py (per segment and per run: turn entry, turn-rate error,
overshoot, altitude lost, sideslip, recovery ...; the pass criteria) and
plots.py (the PNG plots of a run).

May import: sim (a run's result), config and sensors.
Imported by: campaigns and cli.
"""
