"""helical_sil: the helical-turn C controller flies JSBSim aircraft in lockstep."""

__version__ = "0.1.0"
