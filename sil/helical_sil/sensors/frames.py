"""Frame conversions between JSBSim (x forward, y right, z down: FRD) and the
library's body axes (X left wing, Y forward, Z down), and surface mapping.

Checked numerically in tests/test_frames.py against JSBSim's own
local-to-body matrix and against the aircraft's response to each surface.
"""

from __future__ import annotations

import math

import numpy as np

FT = 0.3048  # metres per foot
KT = 0.514444  # m/s per knot


def down_in_frd(phi: float, theta: float) -> tuple[float, float, float]:
    """Earth-down seen in JSBSim body axes: [-sin th, sin ph cos th, cos ph cos th]."""
    ct = math.cos(theta)
    return (-math.sin(theta), math.sin(phi) * ct, math.cos(phi) * ct)


def frd_to_lib(v: tuple[float, float, float] | np.ndarray) -> tuple[float, float, float]:
    """A body vector from FRD axes to library axes: X = -y, Y = x, Z = z."""
    return (-float(v[1]), float(v[0]), float(v[2]))


def dcm_bottom_row(phi: float, theta: float) -> tuple[float, float, float]:
    """The library's DCM bottom row [X, Y, Z] from JSBSim Euler angles (rad)."""
    return frd_to_lib(down_in_frd(phi, theta))


def body_rates_lib(p: float, q: float, r: float) -> tuple[float, float, float]:
    """JSBSim p, q, r (rad/s) as rotation rates about library X, Y, Z: (-q, p, r)."""
    return (-q, p, r)


def earth_turn_rate(p: float, q: float, r: float, phi: float, theta: float) -> float:
    """Rotation rate about the earth vertical, + = right turn (clockwise from above)."""
    d = down_in_frd(phi, theta)
    return p * d[0] + q * d[1] + r * d[2]


def surfaces_to_jsbsim(aileron: float, elevator: float,
                       rudder: float) -> tuple[float, float, float]:
    """Library surfaces (ail + roll right, elev + nose up, rud + nose right) to
    JSBSim fcs/*-cmd-norm (ail + roll right, elev + nose DOWN, rud + nose LEFT)."""
    return (aileron, -elevator, -rudder)


def surfaces_from_jsbsim(aileron: float, elevator: float,
                         rudder: float) -> tuple[float, float, float]:
    """The inverse of surfaces_to_jsbsim (the mapping is its own inverse)."""
    return (aileron, -elevator, -rudder)


def wrap_deg(a: np.ndarray | float) -> np.ndarray | float:
    """Angle(s) wrapped to [-180, 180)."""
    return (np.asarray(a) + 180.0) % 360.0 - 180.0
