"""The full-aileron limit of an airframe (issue 17): how fast the aileron
alone can bank the aircraft, measured in the SIL on the same JSBSim model,
initial condition and trim as a scenario.

From the scenario's trimmed, wings-level flight (calm air, no upset), the
aileron command is set to full (JSBSim `fcs/aileron-cmd-norm` = +-1, what
the law's aileron saturated at +-1 gives through the output stage) at t = 0
and held; elevator, rudder and throttle stay at the trim. The bank is
recorded every sim frame. `time_to_bank` is the first time the bank reaches
a given angle (linear interpolation between frames).

What the campaign compares (options.py, sil/README "Law options"):
- the issue's comparison: the law's turn entry (metrics `turn_entry_s`, time
  to 90 % of the commanded turn-rate change) against the full-aileron time to
  the turn's whole target bank, atan(omega V / g);
- the like-for-like one: the law's `bank_entry_s` (time to 90 % of the bank
  change) against the full-aileron time to 90 % of the same bank.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass

import numpy as np

from helical_sil.config.scenario import Scenario

LIMIT_WINDOW_S = 5.0   # long enough for any target bank up to 90 deg on the slowest model


@dataclass
class FullAileron:
    """Bank (deg) against time (s) after full aileron each way."""
    t_s: np.ndarray
    phi_right_deg: np.ndarray
    phi_left_deg: np.ndarray
    airspeed_m_s: float
    trimmed: bool

    def time_to_bank(self, bank_deg: float) -> float | None:
        """First time the full-aileron roll towards bank_deg reaches it (the
        right roll for a positive bank, the left roll for a negative one);
        None if it does not within the window; 0 for a zero bank."""
        if bank_deg == 0.0:
            return 0.0
        phi = self.phi_right_deg if bank_deg > 0 else -self.phi_left_deg
        return first_crossing(self.t_s, phi - phi[0], abs(bank_deg))


def first_crossing(t: np.ndarray, y: np.ndarray, level: float) -> float | None:
    """The first time y reaches level (y rising through it), linearly
    interpolated between samples; None if it never does."""
    hit = np.nonzero(y >= level)[0]
    if hit.size == 0:
        return None
    k = int(hit[0])
    if k == 0:
        return float(t[0])
    y0, y1 = float(y[k - 1]), float(y[k])
    f = (level - y0) / (y1 - y0) if y1 != y0 else 1.0
    return float(t[k - 1] + f * (t[k] - t[k - 1]))


def _roll(sc: Scenario, direction: float, window_s: float) -> tuple[np.ndarray, np.ndarray]:
    from helical_sil.sim import lockstep
    fdm = lockstep.make_fdm(sc)
    fdm["fcs/aileron-cmd-norm"] = direction
    n = int(round(window_s * sc.sim_rate_hz))
    t = np.zeros(n + 1)
    phi = np.zeros(n + 1)
    phi[0] = math.degrees(fdm["attitude/phi-rad"])
    dt = 1.0 / sc.sim_rate_hz
    for k in range(1, n + 1):
        fdm.run()
        t[k] = k * dt
        phi[k] = math.degrees(fdm["attitude/phi-rad"])
    # unwrap: a roll past 180 deg keeps counting
    return t, np.degrees(np.unwrap(np.radians(phi)))


def measure(sc: Scenario, window_s: float = LIMIT_WINDOW_S) -> FullAileron:
    """Full aileron right and left from the scenario's initial condition and
    trim (calm air, no upset, no sensor faults: only the aircraft)."""
    s = copy.copy(sc)
    s.turbulence = "none"
    s.wind_north_m_s = s.wind_east_m_s = s.wind_down_m_s = 0.0
    s.upset = None
    t, right = _roll(s, 1.0, window_s)
    _, left = _roll(s, -1.0, window_s)
    return FullAileron(t, right, left, s.airspeed_m_s, s.trim)


def coordinated_bank_deg(turn_rate_deg_s: float, airspeed_m_s: float) -> float:
    """The bank of a coordinated level turn: atan(omega V / g)."""
    return math.degrees(math.atan(math.radians(turn_rate_deg_s) * airspeed_m_s / 9.80665))
