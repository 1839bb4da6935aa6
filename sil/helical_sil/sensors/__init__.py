"""The sensors a board reads, made from JSBSim's state, and the axes they are in.

Owns: frames.py (JSBSim's FRD/NED axes and surfaces against the library's
body axes and surfaces), truth.py (the ideal IMU, GPS, pitot and baro of one
JSBSim state snapshot, the ISA atmosphere), config.py (the sensor models'
configuration: one frozen dataclass per sensor, ``config_from_dict``) and
models.py (the seeded error models on top of the ideal values).

May import: nothing else of helical_sil (the lowest layer).
Imported by: config (scenario.py checks a [sensor_model] table), sim, analysis
(metrics.py's angle wrap), live (serve.py).
"""
