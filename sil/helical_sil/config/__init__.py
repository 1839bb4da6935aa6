"""What a flight is made of: the parameter table, scenario and aircraft files.

Owns: params.py (the mirror of include/helical/params.def: every parameter's
name, unit, bounds and default), scenario.py (scenario and aircraft TOML
files: parsing and validation, every error naming its key and file) and
aircraft.py (the JSBSim models that can be flown, and a starter aircraft
file for one: `aircraft list`, `aircraft new`).

May import: sensors (to check a scenario's [sensor_model] tables).
Imported by: sim, analysis, campaigns, live and cli.
"""
