"""The C IMU model (boards/sil/sil_imu_model.c through sim/imu_c.py) gives the
Python reference model's samples (sensors/models.py ImuModel) bit for bit:
seeded random states and batch sizes, every error on, the full scale hit,
and the same refusals (a time off the IMU period, a state not finite)."""

from __future__ import annotations

import ctypes
import dataclasses
import math

import numpy as np
import pytest
from sensor_states import state

from helical_sil.sensors import truth as st
from helical_sil.sensors.models import SensorConfig, SensorModel
from helical_sil.sim import imu_c
from helical_sil.sim.board import Board

FT = st.FT


def _frames(rng: np.random.Generator, n: int, big: bool) -> np.ndarray:
    """n rows of IN_PROPS: rates (rad/s), body forces (lbf), mass (slug)."""
    scale = 60.0 if big else 1.5  # big: past the gyro's full scale
    rows = np.empty((n, imu_c.N_IN))
    rows[:, 0:3] = rng.normal(0.0, scale, size=(n, 3))
    rows[:, 3:6] = rng.normal(0.0, 3000.0, size=(n, 3)) + np.array([0.0, 0.0, -2500.0])
    rows[:, 6] = rng.uniform(50.0, 200.0, size=n)
    return rows


def _state(row: np.ndarray) -> st.FdmState:
    """The FdmState read_fdm_state makes of the same JSBSim values."""
    m = float(row[6])
    f = tuple(float(row[3 + i]) / m * FT for i in range(3))
    return state(pqr_rad_s=(float(row[0]), float(row[1]), float(row[2])),
                 f_frd_m_s2=(f[0], f[1], f[2]))


def _config(rate_hz: float, small_range: bool) -> SensorConfig:
    cfg = SensorConfig()  # every error on: the defaults
    imu = dataclasses.replace(cfg.imu, rate_hz=rate_hz)
    if small_range:
        imu = dataclasses.replace(imu, gyro=dataclasses.replace(imu.gyro, range_rad_s=2.0),
                                  accel=dataclasses.replace(imu.accel, range_g=1.5))
    return dataclasses.replace(cfg, imu=imu)


@pytest.mark.parametrize("seed,rate_hz,small_range", [(1, 120.0, False), (7, 120.0, True),
                                                      (42, 1000.0, False), (3, 200.0, True)])
def test_c_model_equals_the_python_model_bit_for_bit(board_lib: str, seed: int,
                                                     rate_hz: float, small_range: bool) -> None:
    cfg = _config(rate_hz, small_range)
    ref = SensorModel(cfg, seed=seed)
    twin = imu_c.CImu(SensorModel(cfg, seed=seed)._imu, Board.library(board_lib))
    rng = np.random.Generator(np.random.PCG64(seed))
    dt = 1.0 / rate_hz
    t = 0.0
    k = 0
    saturated = 0
    # batches of 1..9 frames: across the 512-sample blocks of normals
    for _ in range(300):
        n = int(rng.integers(1, 10))
        rows = _frames(rng, n, small_range)
        arr = (ctypes.c_double * rows.size)(*rows.ravel())
        base = k * dt - dt  # the frames at base + (j + 1) * dt
        g, a = twin.run(arr, n, base, dt)
        for j in range(n):
            want = ref.imu(_state(rows[j]), base + (j + 1) * dt)
            assert tuple(g[j]) == want.gyro_rad_s, (k + j, g[j], want.gyro_rad_s)
            assert tuple(a[j]) == want.accel_g, (k + j, a[j], want.accel_g)
            saturated += want.gyro_saturated + want.accel_saturated
        k += n
        t = base + n * dt
        assert twin.walk_state() == tuple(ref._imu.gyro.walk_state)
    assert k > 1024 and t > 0.0  # crossed two blocks of normals
    if small_range:
        assert saturated > 10  # the clip was exercised
    else:
        assert saturated == 0


def test_c_model_refuses_what_the_python_model_refuses(board_lib: str) -> None:
    cfg = _config(120.0, False)
    twin = imu_c.CImu(SensorModel(cfg, seed=1)._imu, Board.library(board_lib))
    rows = (ctypes.c_double * (2 * imu_c.N_IN))(*([0.1, 0.0, 0.0, 0.0, 0.0, -3000.0, 100.0] * 2))
    dt = 1.0 / 120.0
    twin.run(rows, 1, -dt, dt)  # t = 0
    with pytest.raises(ValueError, match="not one period"):
        twin.run(rows, 1, 0.5 * dt, dt)  # t = 1.5 dt
    rows[imu_c.N_IN + 1] = math.nan  # q of the second frame
    with pytest.raises(ValueError, match="non-finite state.*q-rad_sec=nan"):
        twin.run(rows, 2, 0.0, dt)
    # the first frame of the refused batch was taken: the model is at t = dt
    twin.run(rows, 1, dt, dt)


def test_c_model_refuses_a_model_that_has_drawn(board_lib: str) -> None:
    m = SensorModel(_config(120.0, False), seed=1)
    m.imu(state(), 0.0)
    with pytest.raises(ValueError, match="already drawn"):
        imu_c.CImu(m._imu, Board.library(board_lib))
