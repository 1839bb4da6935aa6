"""Sensor-level SIL: the IMU, GPS, pitot and baro a board would read, made from
JSBSim's state (truth.py gives the ideal values) plus seeded errors.

Outputs are in the units of the firmware's estimator (include/helical/estimator/dcm.h):

- IMU (``ImuSample``), library body axes (X left wing, Y forward, Z down):
  gyro rad/s, specific force in standard g (level flight [0, 0, -1]). The IMU
  is at the CG. Per sample: true value + vibration, then the misalignment
  (mounting rotation), cross-axis coupling and scale-factor matrix, then the
  constant bias, the bias random walk and white noise, then the full-scale
  clip. One call per IMU sample at ``ImuConfig.rate_hz``.
- GPS (``GpsSample``): 3D-fix flag, geodetic latitude / longitude (deg),
  altitude above sea level (m), NED ground velocity (m/s). Fixes are measured
  at epochs k / rate_hz and delivered ``latency_s`` later; ``gps_enabled =
  False`` is an outage (no fresh fixes, the fix flag drops at once).
- Pitot (``PitotSample``): the differential pressure with noise, turned into
  TRUE airspeed (``airspeed_m_s``) with the ambient density, and indicated
  airspeed (``ias_m_s``, sea-level density). True, because both consumers need
  the speed through the air: the law's target bank tan(phi) = omega V / g and
  the estimator's centripetal term omega x v; a board gets it from the
  differential pressure and the static pressure and temperature (here the
  density is JSBSim's, exact). sim/lockstep.py feeds the board the indicated
  airspeed, as a board's pitot driver gives it: the firmware makes it true.
- Baro (``BaroSample``): static pressure with noise and drift -> ISA pressure
  altitude (m) for the configured QNH (101325 Pa: altitude above sea level in
  JSBSim's standard atmosphere).

Randomness: every sensor has its own numpy Generator (PCG64 seeded with
(seed, stream)), one stream for the per-sample noise and one for the errors
drawn once (bias, scale, cross-axis), and every call draws the same count of
numbers whatever the configuration, so switching one error or one sensor off
never changes another's noise. Same seed -> identical samples.

The configuration (typical MEMS-grade defaults, the source of each) is in
config.py and sil/README.md ("Sensor models").
"""

from __future__ import annotations

import dataclasses
import math
from collections import deque
from dataclasses import dataclass

import numpy as np

from helical_sil.sensors import truth as st
from helical_sil.sensors.config import (  # re-exported: the module's API
    AccelConfig, BaroConfig, GpsConfig, GyroConfig, ImuConfig, PitotConfig, SensorConfig,
    config_from_dict)
from helical_sil.sensors.truth import FdmState, read_fdm_state  # re-exported

__all__ = [
    "AccelConfig", "BaroConfig", "BaroSample", "FdmState", "GpsConfig", "GpsSample",
    "GyroConfig", "ImuConfig", "ImuSample", "PitotConfig", "PitotSample", "SensorConfig",
    "SensorModel", "config_from_dict", "read_fdm_state",
]

# PCG64 stream ids (the second word of the seed); distinct per sensor and purpose
STREAM_GYRO_NOISE, STREAM_GYRO_CONST = 0x5E01, 0x5E02
STREAM_ACCEL_NOISE, STREAM_ACCEL_CONST = 0x5E03, 0x5E04
STREAM_MOUNT, STREAM_VIBRATION = 0x5E05, 0x5E06
STREAM_GPS = 0x5E07
STREAM_PITOT = 0x5E08
STREAM_BARO, STREAM_BARO_CONST = 0x5E0A, 0x5E0B

# timing tolerance of the IMU period and the GPS epochs (float sums of dt)
T_EPS_S = 1e-6


def _rng(seed: int, stream: int) -> np.random.Generator:
    return np.random.Generator(np.random.PCG64([seed, stream]))


# ---------------------------------------------------------------- samples
@dataclass(frozen=True)
class ImuSample:
    t_s: float
    gyro_rad_s: tuple[float, float, float]  # library axes
    accel_g: tuple[float, float, float]  # specific force, library axes
    gyro_saturated: bool  # an axis sits at its full scale
    accel_saturated: bool


@dataclass(frozen=True)
class GpsSample:
    t_s: float  # time of this call
    fix_3d: bool  # the fields below are a valid 3D fix
    fresh: bool  # a new solution arrived at this call
    t_valid_s: float  # epoch the solution describes (t_s - age); nan before the first
    lat_deg: float  # 0 until the first fix; the last fix's values during an outage
    lon_deg: float
    alt_msl_m: float
    vel_ned_m_s: tuple[float, float, float]


@dataclass(frozen=True)
class PitotSample:
    t_s: float
    airspeed_m_s: float  # TRUE airspeed from the measured differential pressure
    ias_m_s: float  # indicated: the same pressure at sea-level density
    diff_pressure_pa: float  # measured, clipped to [0, range]
    saturated: bool


@dataclass(frozen=True)
class BaroSample:
    t_s: float
    altitude_m: float  # pressure altitude for qnh_pa
    pressure_pa: float  # measured static pressure


# ---------------------------------------------------------------- models
def _small_rotation(angles: np.ndarray) -> np.ndarray:
    """Rotation matrix (Rodrigues) of the rotation vector ``angles`` (rad)."""
    th = float(np.linalg.norm(angles))
    if th == 0.0:
        return np.eye(3)
    k = angles / th
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + math.sin(th) * kx + (1.0 - math.cos(th)) * (kx @ kx)


class _TriadErrors:
    """The errors of one 3-axis sensor (gyro or accelerometer)."""

    def __init__(self, seed: int, noise_stream: int, const_stream: int, rate_hz: float,
                 noise_density: float, bias_sigma: float, walk: float, scale_sigma: float,
                 cross_sigma: float, full_scale: float, mount: np.ndarray) -> None:
        c = _rng(seed, const_stream).normal(0.0, 1.0, size=12)  # fixed draw count
        self.bias = [float(b) for b in bias_sigma * c[0:3]]
        s = np.diag(scale_sigma * c[3:6])
        off = cross_sigma * c[6:12]
        s[0, 1], s[0, 2], s[1, 0], s[1, 2], s[2, 0], s[2, 1] = off
        m = (np.eye(3) + s) @ mount  # the sensor reads m @ (true value)
        self.matrix = [[float(v) for v in row] for row in m]
        self.rng = _rng(seed, noise_stream)
        # normals drawn a block at a time: the same stream as six per call
        # (numpy fills an array from the generator in order), a tenth the cost
        self._normals: list[float] = []
        self._next = 0
        self.sigma = noise_density * math.sqrt(rate_hz / 2.0)
        self.walk = walk
        self.walk_state = [0.0, 0.0, 0.0]
        self.full_scale = full_scale

    def apply(self, true: tuple[float, float, float],
              dt_s: float) -> tuple[tuple[float, float, float], bool]:
        # plain floats: numpy's per-call overhead on 3-vectors is most of the cost
        if self._next + 6 > len(self._normals):
            self._normals = self.rng.standard_normal(6 * 512).tolist()
            self._next = 0
        n = self._next  # fixed draw count: 3 walk, 3 noise
        w = self._normals[n:n + 6]
        self._next = n + 6
        k = self.walk * math.sqrt(dt_s)
        ws = self.walk_state
        fs = self.full_scale
        out = []
        saturated = False
        for i in range(3):
            ws[i] += k * w[i]
            r = self.matrix[i]
            v = (r[0] * true[0] + r[1] * true[1] + r[2] * true[2] + self.bias[i] + ws[i]
                 + self.sigma * w[3 + i])
            if abs(v) >= fs:
                saturated = True
                v = math.copysign(fs, v)
            out.append(v)
        return (out[0], out[1], out[2]), saturated


class ImuModel:
    """Gyro and accelerometer; call ``sample`` once per IMU period."""

    def __init__(self, cfg: ImuConfig, seed: int) -> None:
        self.cfg = cfg
        mount = _small_rotation(cfg.mount_sigma_rad * _rng(seed, STREAM_MOUNT).normal(size=3))
        self.gyro = _TriadErrors(
            seed, STREAM_GYRO_NOISE, STREAM_GYRO_CONST, cfg.rate_hz,
            cfg.gyro.noise_density_rad_s_rthz, cfg.gyro.bias_sigma_rad_s,
            cfg.gyro.bias_walk_rad_s_rts, cfg.gyro.scale_sigma, cfg.gyro.cross_axis_sigma,
            cfg.gyro.range_rad_s, mount)
        self.accel = _TriadErrors(
            seed, STREAM_ACCEL_NOISE, STREAM_ACCEL_CONST, cfg.rate_hz,
            cfg.accel.noise_density_g_rthz, cfg.accel.bias_sigma_g, cfg.accel.bias_walk_g_rts,
            cfg.accel.scale_sigma, cfg.accel.cross_axis_sigma, cfg.accel.range_g, mount)
        # vibration: a sinusoid per axis at vibration_hz, random phases
        ph = _rng(seed, STREAM_VIBRATION).uniform(0.0, 2.0 * math.pi, size=6)
        self.phase_gyro, self.phase_accel = ph[0:3].tolist(), ph[3:6].tolist()
        self.t_last: float | None = None

    def sample(self, s: FdmState, t_s: float) -> ImuSample:
        period = 1.0 / self.cfg.rate_hz
        if not math.isfinite(t_s):
            raise ValueError(f"imu: t_s must be finite, got {t_s!r}")
        if self.t_last is None:
            dt = 0.0
        else:
            dt = t_s - self.t_last
            if abs(dt - period) > T_EPS_S:
                raise ValueError(
                    f"imu: called {dt:.6g} s after the previous sample (t={t_s:.6f} s); "
                    f"the model runs at rate_hz={self.cfg.rate_hz:g} (every {period:.6g} s)")
        tg, ta = st.ideal_gyro_rad_s(s), st.ideal_accel_g(s)
        if not all(math.isfinite(v) for v in tg + ta):
            raise ValueError(f"imu: non-finite state: pqr_rad_s={s.pqr_rad_s}, "
                             f"f_frd_m_s2={s.f_frd_m_s2}")
        self.t_last = t_s
        wt = 2.0 * math.pi * self.cfg.vibration_hz * t_s
        ag, aa = self.cfg.gyro.vibration_rad_s, self.cfg.accel.vibration_g
        pg, pa = self.phase_gyro, self.phase_accel
        g, g_sat = self.gyro.apply((tg[0] + ag * math.sin(wt + pg[0]),
                                    tg[1] + ag * math.sin(wt + pg[1]),
                                    tg[2] + ag * math.sin(wt + pg[2])), dt)
        a, a_sat = self.accel.apply((ta[0] + aa * math.sin(wt + pa[0]),
                                     ta[1] + aa * math.sin(wt + pa[1]),
                                     ta[2] + aa * math.sin(wt + pa[2])), dt)
        return ImuSample(t_s, g, a, g_sat, a_sat)


def _gps_at(g: GpsSample, t_s: float, fresh: bool, fix_3d: bool) -> GpsSample:
    """g as seen by a call at t_s (dataclasses.replace, a tenth of its cost:
    the loop calls this every control step)."""
    return GpsSample(t_s, fix_3d, fresh, g.t_valid_s, g.lat_deg, g.lon_deg, g.alt_msl_m,
                     g.vel_ned_m_s)


class GpsModel:
    """Fixes at epochs k / rate_hz, each delivered latency_s later.

    ``sample`` may be called at any rate; a fix is measured at the first call
    at or after its epoch (call at a multiple of the GPS rate, e.g. at every
    IMU sample or sim frame, for exact epochs; a late call's fix is labelled
    with the call's time) and delivered at the first call at or after that
    time + latency. The position error is a Gauss-Markov process
    per NED axis, advanced at every epoch (also during an outage, so the noise
    after an outage is the noise an uninterrupted run would have)."""

    def __init__(self, cfg: GpsConfig, seed: int) -> None:
        self.cfg = cfg
        self.rng = _rng(seed, STREAM_GPS)
        self.enabled = True
        self.next_epoch = 0  # index k of the next epoch k / rate_hz
        self.queue: deque[tuple[float, GpsSample]] = deque()  # (deliver at, fix)
        self.pos_err: np.ndarray | None = None
        self.last: GpsSample | None = None
        self.have_fix = False  # a fix arrived since the last outage began

    def _measure(self, s: FdmState, t_epoch: float) -> GpsSample:
        c = self.cfg
        w = self.rng.normal(0.0, 1.0, size=6)  # fixed draw count: 3 position, 3 velocity
        sig = np.array([c.pos_sigma_h_m, c.pos_sigma_h_m, c.pos_sigma_v_m])
        if self.pos_err is None or c.pos_tau_s == 0.0:
            self.pos_err = sig * w[0:3]  # stationary start / white
        else:
            a = math.exp(-1.0 / (c.rate_hz * c.pos_tau_s))
            self.pos_err = a * self.pos_err + sig * math.sqrt(1.0 - a * a) * w[0:3]
        m_lat, m_lon = st.metres_per_degree(s.lat_deg, s.alt_msl_m)
        v = np.array(s.v_ned_m_s) + c.vel_sigma_m_s * w[3:6]
        return GpsSample(t_epoch, True, True, t_epoch,
                         s.lat_deg + float(self.pos_err[0]) / m_lat,
                         s.lon_deg + float(self.pos_err[1]) / m_lon,
                         s.alt_msl_m - float(self.pos_err[2]),
                         (float(v[0]), float(v[1]), float(v[2])))

    def sample(self, s: FdmState, t_s: float) -> GpsSample:
        if not math.isfinite(t_s):
            raise ValueError(f"gps: t_s must be finite, got {t_s!r}")
        c = self.cfg
        while self.next_epoch / c.rate_hz <= t_s + T_EPS_S:
            t_epoch = self.next_epoch / c.rate_hz
            # a caller late for the epoch gives the state of its own time: the
            # fix is labelled (and delivered) from when that state was sampled
            t_meas = t_s if t_s > t_epoch + T_EPS_S else t_epoch
            fix = self._measure(s, t_meas)  # advances the error even in an outage
            if self.enabled:
                self.queue.append((t_meas + c.latency_s, fix))
            self.next_epoch += 1
        fresh = None
        while self.queue and self.queue[0][0] <= t_s + T_EPS_S:
            fresh = self.queue.popleft()[1]
        if fresh is not None:
            self.last, self.have_fix = fresh, True
            return _gps_at(fresh, t_s, True, fresh.fix_3d)
        if self.last is None:
            return GpsSample(t_s, False, False, math.nan, 0.0, 0.0, 0.0, (0.0, 0.0, 0.0))
        return _gps_at(self.last, t_s, False, self.have_fix)

    def set_enabled(self, on: bool) -> None:
        """An outage (False): queued fixes are lost, the fix flag drops."""
        self.enabled = bool(on)
        if not self.enabled:
            self.queue.clear()
            self.have_fix = False


class PitotModel:
    def __init__(self, cfg: PitotConfig, seed: int) -> None:
        self.cfg = cfg
        self.rng = _rng(seed, STREAM_PITOT)

    def sample(self, s: FdmState, t_s: float) -> PitotSample:
        c = self.cfg
        q = st.ideal_dynamic_pressure_pa(s) + c.offset_pa + c.noise_pa * self.rng.normal()
        # a differential sensor reads both signs; airspeed only from q >= 0
        q_meas = min(max(q, -c.range_pa), c.range_pa)
        q_pos = max(q_meas, 0.0)
        return PitotSample(t_s, math.sqrt(2.0 * q_pos / s.rho_kg_m3),
                           math.sqrt(2.0 * q_pos / st.RHO0_KG_M3), q_meas,
                           abs(q) >= c.range_pa)


class BaroModel:
    def __init__(self, cfg: BaroConfig, seed: int) -> None:
        self.cfg = cfg
        self.rng = _rng(seed, STREAM_BARO)
        self.offset_pa = cfg.offset_sigma_pa * float(_rng(seed, STREAM_BARO_CONST).normal())
        self.drift_pa = 0.0
        self.t_last: float | None = None

    def sample(self, s: FdmState, t_s: float) -> BaroSample:
        c = self.cfg
        if not math.isfinite(t_s) or (self.t_last is not None and t_s < self.t_last):
            raise ValueError(f"baro: t_s must be finite and not decreasing, got {t_s!r} "
                             f"after {self.t_last!r}")
        dt = 0.0 if self.t_last is None else t_s - self.t_last
        self.t_last = t_s
        w = self.rng.normal(0.0, 1.0, size=2)  # fixed draw count: drift, noise
        self.drift_pa += c.drift_pa_rts * math.sqrt(dt) * float(w[0])
        p = s.p_static_pa + self.offset_pa + self.drift_pa + c.noise_pa * float(w[1])
        p = max(p, 1.0)  # a pressure sensor reads > 0
        return BaroSample(t_s, st.pressure_altitude_m(p, c.qnh_pa), p)


class SensorModel:
    """All four sensors of one run, seeded once. The integrator's calls:

        model = SensorModel(SensorConfig(), seed=scenario.seed)
        s = read_fdm_state(fdm)          # after each fdm.run()
        imu = model.imu(s, t)            # every 1 / config.imu.rate_hz seconds
        gps = model.gps(s, t)            # any rate that hits the GPS epochs
        pitot, baro = model.pitot(s, t), model.baro(s, t)
        model.gps_enabled = False        # an outage
    """

    def __init__(self, config: SensorConfig | None = None, seed: int = 0) -> None:
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            raise ValueError(f"'seed': expected an integer >= 0, got {seed!r}")
        self.config = config if config is not None else SensorConfig()
        self._imu = ImuModel(self.config.imu, seed)
        self._gps = GpsModel(self.config.gps, seed)
        self._pitot = PitotModel(self.config.pitot, seed)
        self._baro = BaroModel(self.config.baro, seed)

    @property
    def gps_enabled(self) -> bool:
        return self._gps.enabled

    @gps_enabled.setter
    def gps_enabled(self, on: bool) -> None:
        self._gps.set_enabled(on)

    def imu(self, state: FdmState, t_s: float) -> ImuSample:
        return self._imu.sample(state, t_s)

    def gps(self, state: FdmState, t_s: float) -> GpsSample:
        return self._gps.sample(state, t_s)

    def pitot(self, state: FdmState, t_s: float) -> PitotSample:
        return self._pitot.sample(state, t_s)

    def baro(self, state: FdmState, t_s: float) -> BaroSample:
        return self._baro.sample(state, t_s)
