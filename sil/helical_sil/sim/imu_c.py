"""The IMU error model in C (boards/sil/sil_imu_model.c), for the flight loop.

``models.ImuModel`` stays the reference (its tests, its documentation): this
class takes one, already seeded, copies what it drew once (error matrices,
biases, vibration phases) into the C model and hands the C model its triads'
random numbers a block at a time from the same numpy generators, in the same
order. The samples are the Python model's bit for bit
(sil/tests/test_imu_model_c.py); only the cost differs: one C call per
control step for all its IMU samples instead of a Python call per sim frame.

The flight loop gives each sim frame's JSBSim values as one row of ``IN_PROPS``
(``frame_row``), then ``run`` turns a control step's rows into samples.
"""

from __future__ import annotations

import ctypes
from typing import Any

import numpy as np

from helical_sil.sensors import models as sensors_mod

_D = ctypes.c_double
_I = ctypes.c_int32

# the JSBSim properties of one sim frame, in sil_imu_model.h's SIL_IMU_IN_* order
IN_PROPS = ("velocities/p-rad_sec", "velocities/q-rad_sec", "velocities/r-rad_sec",
            "forces/fbx-total-lbs", "forces/fby-total-lbs", "forces/fbz-total-lbs",
            "inertia/mass-slugs")
N_IN = len(IN_PROPS)
# models._TriadErrors draws its normals 6 * 512 at a time; the same block here
BLOCK = 6 * 512
# sil_imu_model_run's answers
OK, BAD_TIME, NOT_FINITE, FEW_NORMALS = 0, 1, 2, 3


class Triad(ctypes.Structure):
    _fields_ = [("matrix", (_D * 3) * 3), ("bias", _D * 3), ("walk_state", _D * 3),
                ("sigma", _D), ("walk", _D), ("full_scale", _D)]


class ImuModelC(ctypes.Structure):
    _fields_ = [("gyro", Triad), ("accel", Triad), ("phase_gyro", _D * 3),
                ("phase_accel", _D * 3), ("rate_hz", _D), ("vibration_hz", _D),
                ("vibration_gyro", _D), ("vibration_accel", _D), ("t_last_s", _D),
                ("have_last", _I)]


def _declare(lib: ctypes.CDLL) -> None:
    if getattr(lib, "_imu_declared", False):
        return
    lib.sil_imu_model_size.restype = ctypes.c_uint32
    if lib.sil_imu_model_size() != ctypes.sizeof(ImuModelC):
        raise RuntimeError("sil_imu_model_size: C and Python structs differ: rebuild the "
                           "board library")
    p = ctypes.c_void_p
    lib.sil_imu_model_run.restype = ctypes.c_int
    lib.sil_imu_model_run.argtypes = [p, p, _I, _D, _D, p, p, _I, p, p, p, p]
    lib._imu_declared = True


class _Normals:
    """One triad's normals: the generator's stream, refilled a block at a
    time as models._TriadErrors does (a block is a whole number of samples,
    so what is left joins the next block and the order is the stream's)."""

    def __init__(self, rng: np.random.Generator) -> None:
        self.rng = rng
        self.buf = np.empty(0)
        self.addr = 0  # the buffer's address: .ctypes per call costs more than the model
        self.next = 0

    def take(self, n_samples: int) -> tuple[int, int]:
        """(address, count) of the next 6 * n_samples normals."""
        need = 6 * n_samples
        if self.next + need > len(self.buf):
            blocks = [self.buf[self.next:]]
            have = len(blocks[0])
            while have < need:
                blocks.append(self.rng.standard_normal(BLOCK))
                have += BLOCK
            self.buf = np.concatenate(blocks)
            self.addr = self.buf.ctypes.data
            self.next = 0
        at = self.addr + 8 * self.next
        self.next += need
        return at, need


class CImu:
    """The C twin of one seeded ``models.ImuModel`` (which must not be
    sampled itself afterwards: the two would share its generators)."""

    def __init__(self, ref: sensors_mod.ImuModel, lib: ctypes.CDLL) -> None:
        _declare(lib)
        self._run = lib.sil_imu_model_run
        m = ImuModelC()
        for dst, src in ((m.gyro, ref.gyro), (m.accel, ref.accel)):
            for i in range(3):
                for j in range(3):
                    dst.matrix[i][j] = src.matrix[i][j]
                dst.bias[i] = src.bias[i]
                dst.walk_state[i] = src.walk_state[i]
            dst.sigma, dst.walk, dst.full_scale = src.sigma, src.walk, src.full_scale
        for i in range(3):
            m.phase_gyro[i] = ref.phase_gyro[i]
            m.phase_accel[i] = ref.phase_accel[i]
        cfg = ref.cfg
        m.rate_hz, m.vibration_hz = cfg.rate_hz, cfg.vibration_hz
        m.vibration_gyro, m.vibration_accel = cfg.gyro.vibration_rad_s, cfg.accel.vibration_g
        if ref.t_last is not None:
            m.t_last_s, m.have_last = ref.t_last, 1
        if ref.gyro._normals or ref.accel._normals:
            raise ValueError("CImu: the reference model has already drawn noise")
        self.model = m
        self.gyro_bias = tuple(float(b) for b in ref.gyro.bias)
        self._ng, self._na = _Normals(ref.gyro.rng), _Normals(ref.accel.rng)
        self._at = _I(0)
        self._at_addr = ctypes.addressof(self._at)
        self._ptr = ctypes.addressof(m)

    def walk_state(self) -> tuple[float, float, float]:
        """The gyro bias random walk now (library axes, rad/s)."""
        w = self.model.gyro.walk_state
        return (w[0], w[1], w[2])

    def run(self, rows: Any, n: int, t_base_s: float,
            dt_s: float) -> tuple[np.ndarray, np.ndarray]:
        """The samples of n frames taken at t_base_s + (j + 1) * dt_s: rows holds
        n * N_IN doubles (a ctypes array, in IN_PROPS order per frame). Returns
        (gyro rad/s, accel g), n rows of 3 each, new arrays. Raises ValueError
        as models.ImuModel.sample does (a time off the IMU period, a state not
        finite); the run is then over (the normals of the refused batch are
        spent)."""
        out = np.empty((2, n, 3))
        addr = out.ctypes.data
        ag, ng = self._ng.take(n)
        aa, _na = self._na.take(n)
        rc = self._run(self._ptr, ctypes.addressof(rows), n, t_base_s, dt_s, ag, aa, ng,
                       addr, addr + 8 * 3 * n, None, self._at_addr)
        if rc != OK:
            self._raise(rc, rows, t_base_s, dt_s)
        return out[0], out[1]

    def _raise(self, rc: int, rows: Any, t_base_s: float, dt_s: float) -> None:
        j = self._at.value
        t = t_base_s + (j + 1) * dt_s
        if rc == NOT_FINITE:
            row = [rows[j * N_IN + i] for i in range(N_IN)]
            raise ValueError(f"imu: non-finite state at t={t:.6f} s: "
                             + ", ".join(f"{p}={v!r}" for p, v in zip(IN_PROPS, row)))
        if rc == BAD_TIME:
            raise ValueError(f"imu: sample at t={t!r} s is not one period "
                             f"(1/{self.model.rate_hz:g} s) after the previous one")
        raise ValueError(f"imu: sil_imu_model_run answered {rc} at sample {j}")
