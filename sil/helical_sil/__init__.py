"""helical_sil: the helical-turn C controller flies JSBSim aircraft in lockstep.

The subpackages, lowest layer first (a module imports its own subpackage and
lower layers only; tests/test_package_layout.py checks it, and that there is
no import cycle, lazy imports included):

- sensors: frames, the ideal sensors, the sensor error models and their config
- config: the parameter table, scenario and aircraft files
- sim: the host board (ctypes), the sensor faults, the lockstep flight loop
- analysis: the metrics and plots of a flight
- campaigns (many flights: runner, backend, upsets, tune, options, roll limit)
  and live (serve: MAVLink; pil: QEMU), which do not import each other
- cli.py: the command line; __main__.py: `python -m helical_sil`
"""

__version__ = "0.1.0"
