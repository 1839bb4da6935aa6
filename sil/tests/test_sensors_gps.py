"""The GPS model: epochs at its rate, latency exact, the outage switch, noise
statistics (white and Gauss-Markov), determinism."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from sensor_states import LEVEL, state

from helical_sil.sensors import truth as st
from helical_sil.sensors.models import GpsConfig, GpsSample, SensorConfig, SensorModel

IMU_DT = 1.0 / 200.0


def _moving(t: float) -> st.FdmState:
    """A state that encodes its own time: latitude, altitude and velocity."""
    return state(lat_deg=47.0 + 1e-4 * t, lon_deg=8.0 - 2e-4 * t, alt_msl_m=1500.0 + 3.0 * t,
                 v_ned_m_s=(50.0 + t, -t, 0.5 * t))


def _cfg(**kw: float) -> SensorConfig:
    ideal = SensorConfig.ideal()
    return dataclasses.replace(ideal, gps=dataclasses.replace(ideal.gps, **kw))


def _fly(model: SensorModel, seconds: float, dt: float = IMU_DT,
         outage: tuple[float, float] | None = None) -> list[GpsSample]:
    out = []
    for k in range(int(round(seconds / dt)) + 1):
        t = k * dt
        if outage is not None:
            model.gps_enabled = not (outage[0] - 1e-9 <= t < outage[1] - 1e-9)
        out.append(model.gps(_moving(t), t))
    return out


@pytest.mark.parametrize("rate_hz,latency_s,dt", [(5.0, 0.1, IMU_DT), (10.0, 0.13, IMU_DT),
                                                   (10.0, 0.0, IMU_DT), (5.0, 0.25, 1 / 120)])
def test_rate_and_latency_are_exact(rate_hz: float, latency_s: float, dt: float) -> None:
    out = _fly(SensorModel(_cfg(rate_hz=rate_hz, latency_s=latency_s), seed=1), 3.0, dt)
    fresh = [o for o in out if o.fresh]
    n_expected = int(math.floor((3.0 - latency_s) * rate_hz + 1e-9)) + 1
    assert len(fresh) == n_expected
    for i, f in enumerate(fresh):
        assert f.fix_3d
        assert f.t_valid_s == pytest.approx(i / rate_hz, abs=1e-12)  # epochs k / rate
        assert f.t_s - f.t_valid_s == pytest.approx(latency_s, abs=1e-9)  # exact latency
        want = _moving(f.t_valid_s)  # the state at the epoch, not at delivery
        assert (f.lat_deg, f.lon_deg, f.alt_msl_m) == pytest.approx(
            (want.lat_deg, want.lon_deg, want.alt_msl_m), abs=1e-12)
        assert f.vel_ned_m_s == pytest.approx(want.v_ned_m_s, abs=1e-12)
    # between deliveries the last fix is held, not fresh
    assert sum(o.fix_3d and not o.fresh for o in out) > 0
    before = [o for o in out if o.t_s < latency_s - 1e-9]
    assert all(not o.fix_3d and not o.fresh for o in before)  # no fix yet


def test_outage_drops_the_fix_at_once_and_recovers_at_the_next_epoch() -> None:
    rate, lat = 5.0, 0.1
    out = _fly(SensorModel(_cfg(rate_hz=rate, latency_s=lat), seed=1), 4.0,
               outage=(1.03, 2.07))
    during = [o for o in out if 1.03 - 1e-9 <= o.t_s < 2.07 - 1e-9]
    assert during and all(not o.fix_3d and not o.fresh for o in during)
    # the fix measured at 1.0 s was queued for 1.1 s: lost in the outage
    after = [o for o in out if o.t_s >= 2.07 - 1e-9]
    first = next(o for o in after if o.fresh)
    assert first.t_valid_s == pytest.approx(2.2) and first.t_s == pytest.approx(2.3)
    # no fix flag between the end of the outage and that first fresh fix
    assert all(not o.fix_3d for o in after if o.t_s < 2.3 - 1e-9)
    assert all(o.fix_3d for o in after if o.t_s >= 2.3 - 1e-9)


def test_noise_after_an_outage_is_the_uninterrupted_noise() -> None:
    cfg = SensorConfig()  # default noise: Gauss-Markov position, white velocity
    a = [o for o in _fly(SensorModel(cfg, seed=4), 5.0) if o.fresh]
    b = [o for o in _fly(SensorModel(cfg, seed=4), 5.0, outage=(1.0, 2.0)) if o.fresh]
    tail_a = {round(o.t_valid_s, 6): o for o in a if o.t_valid_s > 2.0}
    tail_b = {round(o.t_valid_s, 6): o for o in b if o.t_valid_s > 2.0}
    assert tail_a.keys() == tail_b.keys() and len(tail_a) > 10
    for k in tail_a:
        assert tail_a[k] == tail_b[k]


def _errors(out: list[GpsSample]) -> np.ndarray:
    """N, E, D position errors (m) and N, E, D velocity errors (m/s) of fresh fixes."""
    rows = []
    for o in out:
        if o.fresh:
            s = LEVEL
            m_lat, m_lon = st.metres_per_degree(s.lat_deg, s.alt_msl_m)
            rows.append(((o.lat_deg - s.lat_deg) * m_lat, (o.lon_deg - s.lon_deg) * m_lon,
                         s.alt_msl_m - o.alt_msl_m,
                         *(np.array(o.vel_ned_m_s) - np.array(s.v_ned_m_s))))
    return np.array(rows)


def _fly_level(model: SensorModel, n_epochs: int) -> list[GpsSample]:
    rate = model.config.gps.rate_hz
    return [model.gps(LEVEL, k / rate) for k in range(n_epochs)]


def test_white_noise_statistics() -> None:
    cfg = _cfg(rate_hz=5.0, pos_sigma_h_m=2.0, pos_sigma_v_m=4.0, pos_tau_s=0.0,
               vel_sigma_m_s=0.1)
    e = _errors(_fly_level(SensorModel(cfg, seed=2), 10000))
    want = np.array([2.0, 2.0, 4.0, 0.1, 0.1, 0.1])
    assert np.all(np.abs(e.std(axis=0) / want - 1.0) < 0.03), e.std(axis=0)
    assert np.all(np.abs(e.mean(axis=0)) < 4.0 * want / math.sqrt(len(e)))
    lag1 = [np.corrcoef(e[:-1, i], e[1:, i])[0, 1] for i in range(6)]
    assert np.all(np.abs(lag1) < 0.04)


def test_gauss_markov_position_error() -> None:
    tau, rate = 2.0, 5.0
    cfg = _cfg(rate_hz=rate, pos_sigma_h_m=2.0, pos_sigma_v_m=4.0, pos_tau_s=tau)
    e = _errors(_fly_level(SensorModel(cfg, seed=3), 40000))[:, :3]
    # stationary: the spread of the configured sigma; correlated over tau
    assert np.all(np.abs(e.std(axis=0) / np.array([2.0, 2.0, 4.0]) - 1.0) < 0.06)
    # autocorrelation exp(-lag / (rate tau)); the estimate's sigma at lag
    # tau is 0.007 here (40 000 epochs, three axes): 0.03 is 4 sigma
    for lag, tol in ((1, 0.01), (10, 0.03)):
        rho = np.mean([np.corrcoef(e[:-lag, i], e[lag:, i])[0, 1] for i in range(3)])
        assert rho == pytest.approx(math.exp(-lag / (rate * tau)), abs=tol)


def test_same_seed_same_fixes() -> None:
    a = _fly(SensorModel(SensorConfig(), seed=8), 3.0)
    b = _fly(SensorModel(SensorConfig(), seed=8), 3.0)
    c = _fly(SensorModel(SensorConfig(), seed=9), 3.0)
    assert a == b and a != c


def test_gps_off_does_not_change_other_sensors() -> None:
    def air(gps_on: bool) -> list[tuple[float, float]]:
        m = SensorModel(SensorConfig(), seed=5)
        m.gps_enabled = gps_on
        return [(m.gps(LEVEL, k * 0.01), m.pitot(LEVEL, k * 0.01).airspeed_m_s,
                 m.baro(LEVEL, k * 0.01).altitude_m)[1:] for k in range(200)]

    assert air(True) == air(False)


def test_bad_configuration_is_named() -> None:
    with pytest.raises(ValueError, match="'rate_hz': expected a finite number > 0"):
        GpsConfig(rate_hz=0.0)
    with pytest.raises(ValueError, match="'latency_s': expected a finite number >= 0"):
        GpsConfig(latency_s=-0.1)
    with pytest.raises(ValueError, match="gps: t_s must be finite"):
        SensorModel(SensorConfig(), seed=0).gps(LEVEL, math.inf)


def test_a_late_caller_gets_fixes_labelled_with_its_own_time() -> None:
    # called every 0.03 s: epoch 0.2 s is first seen at 0.21 s, with that state
    out = _fly(SensorModel(_cfg(rate_hz=5.0, latency_s=0.1), seed=1), 1.0, dt=0.03)
    fresh = [o for o in out if o.fresh]
    assert fresh[1].t_valid_s == pytest.approx(0.21)
    assert fresh[1].lat_deg == pytest.approx(_moving(0.21).lat_deg, abs=1e-12)
    assert fresh[1].t_s == pytest.approx(0.33)  # first call at or after 0.31 s
