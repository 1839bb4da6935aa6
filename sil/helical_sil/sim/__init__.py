"""One flight: JSBSim and the C host board in lockstep.

Owns: board.py (the host board library libhelical_sil_board.so through
ctypes: its ABI mirrored in ctypes structures), faults.py (the scenario's
sensor faults, applied to the sensor values before the board sees them) and
lockstep.py (the flight loop: JSBSim at the sim rate, the board at the
control rate; the telemetry of a run, telemetry.csv).

May import: config and sensors.
Imported by: analysis, campaigns, live and cli.
"""
