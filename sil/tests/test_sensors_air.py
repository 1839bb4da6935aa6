"""Pitot and baro models, and the configuration (defaults, checks, dict loader)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from sensor_states import LEVEL, state

from helical_sil.sensors import truth as st
from helical_sil.sensors.models import (BaroConfig, GyroConfig, PitotConfig, SensorConfig,
                                        SensorModel, config_from_dict)


def _cfg(pitot: PitotConfig | None = None, baro: BaroConfig | None = None) -> SensorConfig:
    ideal = SensorConfig.ideal()
    return dataclasses.replace(ideal, pitot=pitot or ideal.pitot, baro=baro or ideal.baro)


def test_ideal_pitot_reads_true_and_indicated_airspeed() -> None:
    m = SensorModel(SensorConfig.ideal(), seed=0)
    p = m.pitot(LEVEL, 0.0)
    q = 0.5 * LEVEL.rho_kg_m3 * 50.0**2
    assert p.diff_pressure_pa == pytest.approx(q, rel=1e-15)
    assert p.airspeed_m_s == pytest.approx(50.0, rel=1e-14)  # true airspeed
    # indicated: the same pressure at sea-level density, sqrt(rho / rho0) of true
    assert p.ias_m_s == pytest.approx(50.0 * math.sqrt(LEVEL.rho_kg_m3 / 1.225), rel=1e-14)
    assert not p.saturated


def test_pitot_noise_is_in_pressure() -> None:
    cfg = _cfg(pitot=PitotConfig(noise_pa=2.0))
    m = SensorModel(cfg, seed=3)
    s = [m.pitot(LEVEL, k * 0.02) for k in range(20000)]
    q = np.array([x.diff_pressure_pa for x in s]) - 0.5 * LEVEL.rho_kg_m3 * 2500.0
    assert abs(q.std() / 2.0 - 1.0) < 0.03
    assert abs(q.mean()) < 4.0 * 2.0 / math.sqrt(len(q))
    # in airspeed the same pressure noise is sigma_q / (rho V) at speed
    v = np.array([x.airspeed_m_s for x in s])
    assert abs(v.std() / (2.0 / (LEVEL.rho_kg_m3 * 50.0)) - 1.0) < 0.03


def test_pitot_offset_low_speed_and_full_scale() -> None:
    m = SensorModel(_cfg(pitot=PitotConfig(noise_pa=0.0, offset_pa=-5.0, range_pa=6894.757293168)), seed=0)
    # below the offset the pressure is negative: airspeed 0, not NaN
    slow = m.pitot(state(vt_m_s=2.0), 0.0)  # q = 2.1 Pa
    assert slow.diff_pressure_pa == pytest.approx(0.5 * LEVEL.rho_kg_m3 * 4.0 - 5.0)
    assert slow.airspeed_m_s == 0.0 and slow.ias_m_s == 0.0
    fast = m.pitot(state(vt_m_s=150.0), 0.0)  # 11.9 kPa > 1 psi
    assert fast.saturated and fast.diff_pressure_pa == pytest.approx(6894.757293168)
    assert fast.ias_m_s == pytest.approx(math.sqrt(2.0 * 6894.757293168 / 1.225))


def test_baro_noise_drift_and_offset() -> None:
    cfg = _cfg(baro=BaroConfig(noise_pa=1.2, drift_pa_rts=0.0))
    m = SensorModel(cfg, seed=2)
    s = [m.baro(LEVEL, k * 0.02) for k in range(20000)]
    p = np.array([x.pressure_pa for x in s]) - LEVEL.p_static_pa
    assert abs(p.std() / 1.2 - 1.0) < 0.03
    h0 = st.pressure_altitude_m(LEVEL.p_static_pa)
    h = np.array([x.altitude_m for x in s]) - h0
    # 1.2 Pa is ~0.11 m at 1500 m (dh/dp = -1 / (rho g))
    assert abs(h.std() / (1.2 / (LEVEL.rho_kg_m3 * st.G0)) - 1.0) < 0.03
    # drift: a random walk, spread W sqrt(t) over 300 seeds at t = 25 s
    cfg = _cfg(baro=BaroConfig(noise_pa=0.0, drift_pa_rts=0.5))
    end = []
    for seed in range(300):
        mb = SensorModel(cfg, seed=seed)
        end.append([mb.baro(LEVEL, k * 0.5) for k in range(51)][-1].pressure_pa)
    assert abs(np.std(np.array(end) - LEVEL.p_static_pa) / (0.5 * 5.0) - 1.0) < 0.1
    # a constant offset of its sigma, drawn once
    cfg = _cfg(baro=BaroConfig(noise_pa=0.0, drift_pa_rts=0.0, offset_sigma_pa=50.0))
    off = [SensorModel(cfg, seed=seed).baro(LEVEL, 0.0).pressure_pa - LEVEL.p_static_pa
           for seed in range(300)]
    assert abs(np.std(off) / 50.0 - 1.0) < 0.1
    with pytest.raises(ValueError, match="baro: t_s must be finite and not decreasing"):
        mb.baro(LEVEL, 1.0)


def test_baro_qnh_and_ideal_altitude() -> None:
    m = SensorModel(_cfg(baro=BaroConfig(noise_pa=0.0, drift_pa_rts=0.0, qnh_pa=102325.0)),
                    seed=0)
    b = m.baro(LEVEL, 0.0)
    assert b.altitude_m == pytest.approx(st.pressure_altitude_m(LEVEL.p_static_pa, 102325.0))
    # the altimeter law depends on p / QNH only: QNH reads 0 m; 10 hPa above
    # standard adds ~80 m at 1500 m (83 m at sea level, 8.3 m/hPa)
    assert st.pressure_altitude_m(102325.0, 102325.0) == pytest.approx(0.0, abs=1e-9)
    assert b.altitude_m == pytest.approx(
        st.pressure_altitude_m(LEVEL.p_static_pa * 101325.0 / 102325.0), abs=1e-9)
    assert 78.0 < b.altitude_m - st.pressure_altitude_m(LEVEL.p_static_pa) < 84.0


def test_pitot_and_baro_streams_are_independent() -> None:
    def baro_alts(pitot_noise: float) -> list[float]:
        base = SensorConfig()
        m = SensorModel(dataclasses.replace(base, pitot=PitotConfig(noise_pa=pitot_noise)), 1)
        return [(m.pitot(LEVEL, k * 0.1), m.baro(LEVEL, k * 0.1).altitude_m)[1]
                for k in range(100)]

    assert baro_alts(1.0) == baro_alts(0.0)


def test_defaults_are_the_documented_values() -> None:
    c = SensorConfig()
    assert c.imu.rate_hz == 200.0 and c.gps.rate_hz == 5.0 and c.gps.latency_s == 0.1
    assert c.imu.gyro.noise_density_rad_s_rthz == pytest.approx(math.radians(0.0028))
    assert c.imu.gyro.range_rad_s == pytest.approx(math.radians(2000.0))
    assert c.imu.accel.noise_density_g_rthz == 70e-6 and c.imu.accel.range_g == 16.0
    assert c.gps.pos_sigma_h_m == pytest.approx(2.123, abs=1e-3)
    assert c.pitot.range_pa == pytest.approx(5 * 6894.757, abs=1e-2)
    assert c.baro.qnh_pa == 101325.0


def test_config_from_dict() -> None:
    c = config_from_dict({"imu": {"rate_hz": 400, "gyro": {"range_rad_s": 10.0}},
                          "gps": {"latency_s": 0.2}})
    assert c.imu.rate_hz == 400.0 and c.imu.gyro.range_rad_s == 10.0
    assert c.gps.latency_s == 0.2
    assert c.imu.accel == SensorConfig().imu.accel  # the rest: defaults
    base = SensorConfig.ideal()
    assert config_from_dict({}, base) == base
    with pytest.raises(ValueError, match=r"'imu.gyro.noise': unknown key \(allowed here: "
                                         r"noise_density_rad_s_rthz, "):
        config_from_dict({"imu": {"gyro": {"noise": 1.0}}})
    with pytest.raises(ValueError, match=r"'gps.rate_hz': expected a number, got str 'fast'"):
        config_from_dict({"gps": {"rate_hz": "fast"}})
    with pytest.raises(ValueError, match=r"'gps.rate_hz': expected a finite number > 0"):
        config_from_dict({"gps": {"rate_hz": -5}})
    with pytest.raises(ValueError, match=r"'imu.gyro': expected a table, got float"):
        config_from_dict({"imu": {"gyro": 1.0}})
    with pytest.raises(ValueError, match=r"'baro.noise_pa': expected a number, got bool"):
        config_from_dict({"baro": {"noise_pa": True}})


def test_bad_values_are_refused() -> None:
    with pytest.raises(ValueError, match="'noise_density_rad_s_rthz'"):
        GyroConfig(noise_density_rad_s_rthz=math.nan)
    with pytest.raises(ValueError, match="'range_rad_s': expected a finite number > 0"):
        GyroConfig(range_rad_s=0.0)
    with pytest.raises(ValueError, match="'offset_pa': expected a finite number"):
        PitotConfig(offset_pa=math.inf)
    with pytest.raises(ValueError, match="'seed': expected an integer >= 0"):
        SensorModel(SensorConfig(), seed=-1)
