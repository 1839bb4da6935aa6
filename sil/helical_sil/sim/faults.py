"""Sensor faults of the fault campaign (issue 7), applied in Python to the
sensor values before the C step (the board sees only the faulty values).

From ``fault_start_s`` on (the [sensors] keys, sil/README.md):

- ``airspeed_stuck_m_s``: the airspeed reads this constant (0 = a dead pitot);
- ``airspeed_spike_m_s`` / ``airspeed_spike_rate_hz``: one-control-step spikes
  of +- that size (random sign), Poisson in time at that mean rate;
- ``gyro_saturation_rad_s``: each gyro axis clips at +- that value (the board's
  Q11 format itself clips at +-16 rad/s).

Gyro noise and bias, airspeed noise and latency are the older keys (from t = 0;
lockstep.py). The spikes draw from their own generator, seeded from the scenario
seed, so scenarios without these faults draw exactly the numbers they drew
before (their telemetry is unchanged).
"""

from __future__ import annotations

import math

import numpy as np

from helical_sil.config.scenario import Scenario

# stream of the spike generator: PCG64 seeded with (scenario seed, this)
SPIKE_STREAM = 0x7A17


def active(sc: Scenario) -> bool:
    return (sc.airspeed_stuck_m_s is not None or sc.airspeed_spike_m_s > 0.0
            or sc.gyro_saturation_rad_s is not None)


class SensorFaults:
    """Per-run state of the faults; ``apply`` is called once per control step."""

    def __init__(self, sc: Scenario) -> None:
        self.sc = sc
        self.on = active(sc)
        self.rng = np.random.Generator(np.random.PCG64([sc.seed, SPIKE_STREAM]))
        self.p_spike = sc.airspeed_spike_rate_hz / sc.control_rate_hz
        self.spikes = 0
        self.spike_m_s = 0.0  # this step's spike (0: none), for apply_pitot

    def apply(self, t: float, meas: tuple[float, ...]) -> tuple[float, ...]:
        """meas = (x, y, z, gx, gy, gz, airspeed, altitude, climb), SI units."""
        if not self.on:
            return meas
        sc = self.sc
        # the spike generator advances every step (also before the start) so a
        # spike's time does not depend on fault_start_s
        u, sign = (self.rng.random(), self.rng.random()) if self.p_spike > 0.0 else (1.0, 0.0)
        self.spike_m_s = 0.0
        if t < sc.fault_start_s - 1e-9:
            return meas
        x, y, z, gx, gy, gz, vt, h, hdot = meas
        if sc.gyro_saturation_rad_s is not None:
            lim = sc.gyro_saturation_rad_s
            gx, gy, gz = (min(lim, max(-lim, g)) for g in (gx, gy, gz))
        if sc.airspeed_stuck_m_s is not None:
            vt = sc.airspeed_stuck_m_s
        elif u < self.p_spike:
            self.spike_m_s = math.copysign(sc.airspeed_spike_m_s, sign - 0.5)
            vt = max(0.0, vt + self.spike_m_s)
            self.spikes += 1
        return (x, y, z, gx, gy, gz, vt, h, hdot)

    def apply_pitot(self, t: float, v: float) -> float:
        """The same airspeed fault on the simulated pitot's reading (the
        sensor-level path); call after apply() of the same step."""
        if not self.on or t < self.sc.fault_start_s - 1e-9:
            return v
        if self.sc.airspeed_stuck_m_s is not None:
            return self.sc.airspeed_stuck_m_s
        return max(0.0, v + self.spike_m_s)
