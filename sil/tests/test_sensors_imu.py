"""The IMU error model: noise statistics, bias (constant and random walk),
scale factor, cross-axis and mounting misalignment, vibration, saturation,
determinism and independent random streams. Fixed seeds throughout."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from sensor_states import LEVEL, state

from helical_sil.sensors import truth as st
from helical_sil.sensors.models import (AccelConfig, GyroConfig, ImuConfig, SensorConfig,
                                        SensorModel)

IDEAL = SensorConfig.ideal()
ZERO_GYRO = IDEAL.imu.gyro
ZERO_ACCEL = IDEAL.imu.accel


def _imu_cfg(rate_hz: float = 200.0, gyro: GyroConfig = ZERO_GYRO,
             accel: AccelConfig = ZERO_ACCEL, **kw: float) -> SensorConfig:
    return dataclasses.replace(IDEAL, imu=ImuConfig(rate_hz=rate_hz, gyro=gyro, accel=accel,
                                                    **kw))


def _run(model: SensorModel, n: int, s: st.FdmState = LEVEL) -> tuple[np.ndarray, np.ndarray]:
    dt = 1.0 / model.config.imu.rate_hz
    out = [model.imu(s, k * dt) for k in range(n)]
    return (np.array([o.gyro_rad_s for o in out]), np.array([o.accel_g for o in out]))


def test_ideal_config_reads_the_truth_exactly() -> None:
    s = state(pqr_rad_s=(0.1, -0.2, 0.3), f_frd_m_s2=(1.0, 2.0, -12.0))
    g, a = _run(SensorModel(IDEAL, seed=1), 5, s)
    assert np.array_equal(g, np.tile([0.2, 0.1, 0.3], (5, 1)))  # (-q, p, r)
    assert np.allclose(a, np.tile([-2.0 / st.G0, 1.0 / st.G0, -12.0 / st.G0], (5, 1)),
                       rtol=0, atol=1e-15)


@pytest.mark.parametrize("rate_hz", [100.0, 200.0, 1000.0])
def test_white_noise_matches_the_density(rate_hz: float) -> None:
    nd_g, nd_a = 0.0028 * math.pi / 180.0, 70e-6
    cfg = _imu_cfg(rate_hz, dataclasses.replace(ZERO_GYRO, noise_density_rad_s_rthz=nd_g),
                   dataclasses.replace(ZERO_ACCEL, noise_density_g_rthz=nd_a))
    g, a = _run(SensorModel(cfg, seed=7), 20000)
    a = a - np.array([0.0, 0.0, -1.0])
    for x, nd in ((g, nd_g), (a, nd_a)):
        sigma = nd * math.sqrt(rate_hz / 2.0)  # white up to Nyquist
        std = x.std(axis=0)
        assert np.all(np.abs(std / sigma - 1.0) < 0.03), (std, sigma)
        assert np.all(np.abs(x.mean(axis=0)) < 4.0 * sigma / math.sqrt(len(x)))
        lag1 = [np.corrcoef(x[:-1, i], x[1:, i])[0, 1] for i in range(3)]
        assert np.all(np.abs(lag1) < 0.03), lag1  # white


def test_constant_bias_is_constant_and_has_its_sigma() -> None:
    sig_g, sig_a = 0.01, 0.005
    cfg = _imu_cfg(gyro=dataclasses.replace(ZERO_GYRO, bias_sigma_rad_s=sig_g),
                   accel=dataclasses.replace(ZERO_ACCEL, bias_sigma_g=sig_a))
    bg, ba = [], []
    for seed in range(300):
        g, a = _run(SensorModel(cfg, seed=seed), 3)
        assert np.array_equal(g[0], g[2]) and np.array_equal(a[0], a[2])
        bg.append(g[0])
        ba.append(a[0] - np.array([0.0, 0.0, -1.0]))
    for b, sig in ((np.array(bg), sig_g), (np.array(ba), sig_a)):
        assert abs(b.std() / sig - 1.0) < 0.1, b.std()
        assert abs(b.mean()) < 4.0 * sig / math.sqrt(b.size)


def test_bias_random_walk_grows_as_sqrt_t() -> None:
    w_g, w_a = 1e-3, 2e-4  # per sqrt(s)
    rate = 20.0  # the walk's statistics do not depend on the rate
    cfg = _imu_cfg(rate, dataclasses.replace(ZERO_GYRO, bias_walk_rad_s_rts=w_g),
                   dataclasses.replace(ZERO_ACCEL, bias_walk_g_rts=w_a))
    t_check = (1.0, 4.0, 9.0)
    idx = [int(round(t * rate)) for t in t_check]
    eg: list[list[np.ndarray]] = [[] for _ in t_check]
    ea: list[list[np.ndarray]] = [[] for _ in t_check]
    for seed in range(300):
        g, a = _run(SensorModel(cfg, seed=seed), idx[-1] + 1)
        assert np.array_equal(g[0], [0.0, 0.0, 0.0])  # starts at zero
        for j, i in enumerate(idx):
            eg[j].append(g[i])
            ea[j].append(a[i] - np.array([0.0, 0.0, -1.0]))
    for e, w in ((eg, w_g), (ea, w_a)):
        stds = [float(np.std(np.array(x))) for x in e]
        for t, s in zip(t_check, stds):
            assert abs(s / (w * math.sqrt(t)) - 1.0) < 0.1, (t, s, w * math.sqrt(t))
        # sqrt(t): 4x the time, 2x the spread; 9x, 3x
        assert abs(stds[1] / stds[0] - 2.0) < 0.2 and abs(stds[2] / stds[0] - 3.0) < 0.3


def test_scale_factor_and_cross_axis_matrix() -> None:
    sig_s, sig_c = 0.004, 0.006
    cfg = _imu_cfg(gyro=dataclasses.replace(ZERO_GYRO, scale_sigma=sig_s,
                                            cross_axis_sigma=sig_c))
    diag, off = [], []
    for seed in range(200):
        m = np.zeros((3, 3))
        for j in range(3):  # unit rate about library axis j (X = -q, Y = p, Z = r)
            pqr = [(0.0, -1.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)][j]
            model = SensorModel(cfg, seed=seed)
            m[:, j] = model.imu(state(pqr_rad_s=pqr), 0.0).gyro_rad_s
        e = m - np.eye(3)
        diag.extend(np.diag(e))
        off.extend(e[~np.eye(3, dtype=bool)])
    assert abs(np.std(diag) / sig_s - 1.0) < 0.1
    assert abs(np.std(off) / sig_c - 1.0) < 0.1


def test_mounting_misalignment_is_one_rotation_for_both_sensors() -> None:
    cfg = _imu_cfg(mount_sigma_rad=math.radians(2.0))
    angles = []
    for seed in range(200):
        mg, ma = np.zeros((3, 3)), np.zeros((3, 3))
        for j in range(3):
            pqr = [(0.0, -1.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)][j]
            frd = [(0.0, -1.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)][j]
            model = SensorModel(cfg, seed=seed)
            mg[:, j] = model.imu(state(pqr_rad_s=pqr), 0.0).gyro_rad_s
            model = SensorModel(cfg, seed=seed)
            ma[:, j] = np.array(model.imu(state(f_frd_m_s2=tuple(
                st.G0 * c for c in frd)), 0.0).accel_g)
        assert np.allclose(mg, ma, atol=1e-15)  # the same board for both
        assert np.allclose(mg @ mg.T, np.eye(3), atol=1e-12)  # a rotation
        assert math.isclose(np.linalg.det(mg), 1.0, abs_tol=1e-12)
        angles.append(math.acos(min(1.0, (np.trace(mg) - 1.0) / 2.0)))
    # |rotation vector| of three N(0, s) angles: RMS s sqrt(3)
    rms = math.sqrt(np.mean(np.square(angles)))
    assert abs(rms / (math.radians(2.0) * math.sqrt(3.0)) - 1.0) < 0.1


def test_vibration_is_a_sinusoid_at_its_frequency() -> None:
    amp_a, amp_g, f = 0.3, 0.02, 80.0
    cfg = _imu_cfg(1000.0, dataclasses.replace(ZERO_GYRO, vibration_rad_s=amp_g),
                   dataclasses.replace(ZERO_ACCEL, vibration_g=amp_a), vibration_hz=f)
    g, a = _run(SensorModel(cfg, seed=3), 1000)  # 1 s, 80 whole periods
    a = a - np.array([0.0, 0.0, -1.0])
    for x, amp in ((g, amp_g), (a, amp_a)):
        assert np.all(np.abs(x) <= amp + 1e-12)
        assert np.allclose(np.sqrt((x**2).mean(axis=0)), amp / math.sqrt(2.0), rtol=1e-9)
        spec = np.abs(np.fft.rfft(x, axis=0))
        assert np.all(np.argmax(spec, axis=0) == 80)  # 1 Hz bins


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_saturation_clips_at_full_scale(sign: float) -> None:
    m = SensorModel(SensorConfig.ideal(), seed=0)
    lim_g = math.radians(2000.0)
    # library axes: gyro (-q, p, r), accel (-y, x, z) of FRD
    big = m.imu(state(pqr_rad_s=(sign * 40.0, -sign * 50.0, sign * 60.0),
                      f_frd_m_s2=(sign * 20 * st.G0, -sign * 17 * st.G0, sign * 30 * st.G0)), 0.0)
    assert big.gyro_rad_s == (sign * lim_g, sign * lim_g, sign * lim_g)
    assert big.accel_g == (sign * 16.0, sign * 16.0, sign * 16.0)
    assert big.gyro_saturated and big.accel_saturated
    below = m.imu(state(pqr_rad_s=(0.0, 0.0, sign * 0.999 * lim_g),
                        f_frd_m_s2=(0.0, 0.0, sign * 15.99 * st.G0)), 0.005)
    assert below.gyro_rad_s[2] == pytest.approx(sign * 0.999 * lim_g, rel=1e-12)
    assert below.accel_g[2] == pytest.approx(sign * 15.99, rel=1e-12)
    assert not below.gyro_saturated and not below.accel_saturated
    # exactly at the full scale reads the full scale and flags it
    at = m.imu(state(f_frd_m_s2=(0.0, 0.0, sign * 16.0 * st.G0)), 0.010)
    assert at.accel_g[2] == sign * 16.0 and at.accel_saturated


def test_saturation_applies_after_the_errors() -> None:
    # -2 g on a 2 g sensor with a bias: a negative bias clips, a positive one reads
    cfg = _imu_cfg(accel=dataclasses.replace(ZERO_ACCEL, bias_sigma_g=0.1, range_g=2.0))
    signs = set()
    for seed in range(20):
        bias = SensorModel(cfg, seed=seed).imu(state(f_frd_m_s2=(0.0, 0.0, 0.0)), 0.0).accel_g[2]
        got = SensorModel(cfg, seed=seed).imu(state(f_frd_m_s2=(0.0, 0.0, -2.0 * st.G0)), 0.0)
        assert got.accel_g[2] == max(-2.0, -2.0 + bias)
        assert got.accel_saturated == (bias <= 0.0)
        signs.add(bias > 0.0)
    assert signs == {True, False}


def test_same_seed_same_samples_other_seed_other_samples() -> None:
    def run(seed: int) -> tuple[np.ndarray, np.ndarray]:
        return _run(SensorModel(SensorConfig(), seed=seed), 500,
                    state(pqr_rad_s=(0.1, 0.2, 0.3)))

    g1, a1 = run(5)
    g2, a2 = run(5)
    g3, a3 = run(6)
    assert np.array_equal(g1, g2) and np.array_equal(a1, a2)
    assert not np.array_equal(g1, g3) and not np.array_equal(a1, a3)


def test_each_error_and_sensor_has_its_own_stream() -> None:
    base = SensorConfig()
    g0, a0 = _run(SensorModel(base, seed=9), 300)
    # gyro noise off: the accelerometer's samples do not change
    no_gn = dataclasses.replace(base, imu=dataclasses.replace(
        base.imu, gyro=dataclasses.replace(base.imu.gyro, noise_density_rad_s_rthz=0.0)))
    g1, a1 = _run(SensorModel(no_gn, seed=9), 300)
    assert np.array_equal(a0, a1) and not np.array_equal(g0, g1)
    # gyro noise off leaves the gyro's bias and walk as they were
    no_walk = dataclasses.replace(no_gn, imu=dataclasses.replace(
        no_gn.imu, gyro=dataclasses.replace(no_gn.imu.gyro, bias_walk_rad_s_rts=0.0)))
    g2, _ = _run(SensorModel(no_walk, seed=9), 300)
    assert np.array_equal(g1[0], g2[0])  # same constant errors
    # other sensors, switched off or called, do not touch the IMU
    m = SensorModel(base, seed=9)
    m.gps_enabled = False
    dt = 1.0 / base.imu.rate_hz
    g3 = np.array([(m.gps(LEVEL, k * dt), m.pitot(LEVEL, k * dt), m.baro(LEVEL, k * dt),
                    m.imu(LEVEL, k * dt))[3].gyro_rad_s for k in range(300)])
    assert np.array_equal(g0, g3)


def test_imu_refuses_a_call_off_its_rate() -> None:
    m = SensorModel(SensorConfig(), seed=0)
    m.imu(LEVEL, 0.0)
    m.imu(LEVEL, 0.005)
    with pytest.raises(ValueError, match=r"imu: called 0.00833333 s after .* rate_hz=200"):
        m.imu(LEVEL, 0.005 + 1.0 / 120.0)
    with pytest.raises(ValueError, match="t_s must be finite"):
        m.imu(LEVEL, math.nan)
    with pytest.raises(ValueError, match=r"imu: non-finite state: pqr_rad_s=\(nan"):
        m.imu(state(pqr_rad_s=(math.nan, 0.0, 0.0)), 0.010)
    m.imu(LEVEL, 0.010)  # a refused call does not advance the model


def test_default_config_level_reading_is_close_to_one_g() -> None:
    # the realistic defaults on a level state: within the datasheet's 3-sigma
    # bias, scale and cross-axis errors plus the vibration of 1 g up
    g, a = _run(SensorModel(SensorConfig(), seed=1), 200)
    assert np.all(np.abs(a.mean(axis=0) - [0.0, 0.0, -1.0]) < 0.02 + 0.02 + 0.005)
    assert np.all(np.abs(g.mean(axis=0)) < math.radians(0.5) + 0.001)
