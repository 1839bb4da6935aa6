"""Sensor-level SIL: the IMU, GPS, pitot and baro a board would read, made from
JSBSim's state (sensor_truth.py gives the ideal values) plus seeded errors.

Outputs are in the units of the firmware's estimator (include/helical/dcm.h):

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
  density is JSBSim's, exact). It is also what sim.py feeds the board today.
- Baro (``BaroSample``): static pressure with noise and drift -> ISA pressure
  altitude (m) for the configured QNH (101325 Pa: altitude above sea level in
  JSBSim's standard atmosphere).

Randomness: every sensor has its own numpy Generator (PCG64 seeded with
(seed, stream)), one stream for the per-sample noise and one for the errors
drawn once (bias, scale, cross-axis), and every call draws the same count of
numbers whatever the configuration, so switching one error or one sensor off
never changes another's noise. Same seed -> identical samples.

Defaults are typical MEMS-grade values; the source of each is in the field's
comment and in sil/README.md ("Sensor models").
"""

from __future__ import annotations

import dataclasses
import math
from collections import deque
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from helical_sil import sensor_truth as st
from helical_sil.sensor_truth import FdmState, read_fdm_state  # re-exported

__all__ = [
    "AccelConfig", "BaroConfig", "BaroSample", "FdmState", "GpsConfig", "GpsSample",
    "GyroConfig", "ImuConfig", "ImuSample", "PitotConfig", "PitotSample", "SensorConfig",
    "SensorModel", "config_from_dict", "read_fdm_state",
]

DEG = math.pi / 180.0
PSI_PA = 6894.757293168  # Pa per psi

# PCG64 stream ids (the second word of the seed); distinct per sensor and purpose
STREAM_GYRO_NOISE, STREAM_GYRO_CONST = 0x5E01, 0x5E02
STREAM_ACCEL_NOISE, STREAM_ACCEL_CONST = 0x5E03, 0x5E04
STREAM_MOUNT, STREAM_VIBRATION = 0x5E05, 0x5E06
STREAM_GPS = 0x5E07
STREAM_PITOT, STREAM_PITOT_CONST = 0x5E08, 0x5E09
STREAM_BARO, STREAM_BARO_CONST = 0x5E0A, 0x5E0B

# timing tolerance of the IMU period and the GPS epochs (float sums of dt)
T_EPS_S = 1e-6


def _rng(seed: int, stream: int) -> np.random.Generator:
    return np.random.Generator(np.random.PCG64([seed, stream]))


def _check_nonneg(obj: object, *names: str) -> None:
    for n in names:
        v = getattr(obj, n)
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0.0):
            raise ValueError(f"'{n}': expected a finite number >= 0, got {v!r}")


def _check_pos(obj: object, *names: str) -> None:
    for n in names:
        v = getattr(obj, n)
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0.0):
            raise ValueError(f"'{n}': expected a finite number > 0, got {v!r}")


# ---------------------------------------------------------------- configuration
# White noise: a noise density N (unit/sqrt(Hz)) sampled at rate_hz, white up to
# the Nyquist frequency, gives a per-sample sigma of N * sqrt(rate_hz / 2) (the
# datasheets' own rule: total RMS = density * sqrt(bandwidth)). Constant errors
# (bias, scale, cross-axis) are drawn once per axis, normal with the given
# sigma; a datasheet's +/- tolerance is taken as 3 sigma. A random walk of
# density W (unit/sqrt(s)) has a standard deviation W * sqrt(t) after t seconds.


@dataclass(frozen=True)
class GyroConfig:
    # ICM-42688-P datasheet: rate noise spectral density 0.0028 deg/s/sqrt(Hz)
    noise_density_rad_s_rthz: float = 0.0028 * DEG
    # ICM-42688-P: zero-rate output initial tolerance +/-0.5 deg/s (3 sigma)
    bias_sigma_rad_s: float = 0.5 / 3.0 * DEG
    # assumption: the ZRO temperature drift (+/-0.005 deg/s/degC, ICM-42688-P)
    # over a 4 degC change in 10 minutes: 0.02 deg/s / sqrt(600 s)
    bias_walk_rad_s_rts: float = 0.02 / math.sqrt(600.0) * DEG
    # ICM-42688-P: sensitivity scale factor tolerance +/-0.5 % (3 sigma)
    scale_sigma: float = 0.005 / 3.0
    # MPU-6000 datasheet: cross-axis sensitivity +/-2 % (3 sigma)
    cross_axis_sigma: float = 0.02 / 3.0
    # full scale +/-2000 deg/s (the ICM-42688-P's and MPU-6000's largest range)
    range_rad_s: float = 2000.0 * DEG
    # assumption: angular vibration amplitude on each axis (0.5 deg/s)
    vibration_rad_s: float = 0.5 * DEG

    def __post_init__(self) -> None:
        _check_nonneg(self, "noise_density_rad_s_rthz", "bias_sigma_rad_s",
                      "bias_walk_rad_s_rts", "scale_sigma", "cross_axis_sigma",
                      "vibration_rad_s")
        _check_pos(self, "range_rad_s")


@dataclass(frozen=True)
class AccelConfig:
    # ICM-42688-P datasheet: noise spectral density 70 ug/sqrt(Hz)
    noise_density_g_rthz: float = 70e-6
    # ICM-42688-P: zero-g output initial tolerance +/-20 mg (3 sigma)
    bias_sigma_g: float = 0.020 / 3.0
    # assumption: a zero-g temperature drift of 0.15 mg/degC over 4 degC in
    # 10 minutes: 0.6 mg / sqrt(600 s)
    bias_walk_g_rts: float = 0.6e-3 / math.sqrt(600.0)
    # ICM-42688-P: sensitivity scale factor tolerance +/-0.5 % (3 sigma)
    scale_sigma: float = 0.005 / 3.0
    # MPU-6000: cross-axis sensitivity +/-2 % (3 sigma)
    cross_axis_sigma: float = 0.02 / 3.0
    # full scale +/-16 g (the ICM-42688-P's and MPU-6000's largest range)
    range_g: float = 16.0
    # assumption: engine/propeller vibration amplitude on each axis, a
    # soft-mounted board on a piston single (well below the ~0.3 g RMS at which
    # estimators are commonly said to suffer)
    vibration_g: float = 0.2

    def __post_init__(self) -> None:
        _check_nonneg(self, "noise_density_g_rthz", "bias_sigma_g", "bias_walk_g_rts",
                      "scale_sigma", "cross_axis_sigma", "vibration_g")
        _check_pos(self, "range_g")


@dataclass(frozen=True)
class ImuConfig:
    # samples per second; the estimator's default (dcm.h imu_rate_hz = 200)
    rate_hz: float = 200.0
    gyro: GyroConfig = field(default_factory=GyroConfig)
    accel: AccelConfig = field(default_factory=AccelConfig)
    # mounting misalignment of the board (one rotation for gyro and accel):
    # sigma of each small angle. 0: the board's level was calibrated.
    mount_sigma_rad: float = 0.0
    # vibration frequency: the blade-passing frequency of a two-blade
    # propeller at 2400 rpm (the c172p's cruise), below the 100 Hz Nyquist limit
    vibration_hz: float = 80.0

    def __post_init__(self) -> None:
        _check_pos(self, "rate_hz")
        _check_nonneg(self, "mount_sigma_rad", "vibration_hz")


@dataclass(frozen=True)
class GpsConfig:
    # navigation rate: u-blox M8 runs 5-10 Hz with several GNSS (up to 18 Hz one)
    rate_hz: float = 5.0
    # assumption: the solution trails its epoch by tens of ms, plus the serial
    # transfer of a UBX-NAV-PVT message (100 bytes, 26 ms at 38400 baud)
    latency_s: float = 0.1
    # u-blox NEO-M8N: horizontal accuracy 2.5 m CEP -> sigma per axis CEP/1.1774
    pos_sigma_h_m: float = 2.5 / 1.1774
    # assumption: vertical error twice the horizontal (VDOP ~ 2 HDOP)
    pos_sigma_v_m: float = 2.0 * 2.5 / 1.1774
    # assumption: the position error wanders (Gauss-Markov) with this time
    # constant (atmospheric delays, multipath); 0 = white
    pos_tau_s: float = 60.0
    # u-blox NEO-M8N: velocity accuracy 0.05 m/s (50 %) -> sigma 0.05/0.6745
    vel_sigma_m_s: float = 0.05 / 0.6745

    def __post_init__(self) -> None:
        _check_pos(self, "rate_hz")
        _check_nonneg(self, "latency_s", "pos_sigma_h_m", "pos_sigma_v_m", "pos_tau_s",
                      "vel_sigma_m_s")


@dataclass(frozen=True)
class PitotConfig:
    # MS4525DO-DS5AI001DP (+/-1 psi, 14 bits over 80 % of the span: 1.05 Pa per
    # count): noise sigma about one count
    noise_pa: float = 1.0
    # zero offset left after the power-up zeroing (the raw error band, +/-1 % FS,
    # is removed by it)
    offset_pa: float = 0.0
    # full scale 1 psi: 111 m/s equivalent airspeed (the T-37 may reach it in a
    # dive; raise it for fast aircraft)
    range_pa: float = 1.0 * PSI_PA

    def __post_init__(self) -> None:
        _check_nonneg(self, "noise_pa")
        _check_pos(self, "range_pa")
        if not math.isfinite(self.offset_pa):
            raise ValueError(f"'offset_pa': expected a finite number, got {self.offset_pa!r}")


@dataclass(frozen=True)
class BaroConfig:
    # MS5611-01BA03: resolution RMS 0.012 mbar (1.2 Pa, ~0.1 m) at OSR 4096
    noise_pa: float = 1.2
    # sigma of a constant offset; 0: the altimeter setting (QNH) absorbs it
    # (raw absolute accuracy +/-1.5 mbar, MS5611)
    offset_sigma_pa: float = 0.0
    # assumption: thermal drift of the offset as a random walk, ~2.4 Pa
    # (0.2 m) in 10 minutes
    drift_pa_rts: float = 0.1
    # altimeter setting: the ISA sea-level pressure gives JSBSim's altitude
    qnh_pa: float = st.ISA_P0_PA

    def __post_init__(self) -> None:
        _check_nonneg(self, "noise_pa", "offset_sigma_pa", "drift_pa_rts")
        _check_pos(self, "qnh_pa")


@dataclass(frozen=True)
class SensorConfig:
    imu: ImuConfig = field(default_factory=ImuConfig)
    gps: GpsConfig = field(default_factory=GpsConfig)
    pitot: PitotConfig = field(default_factory=PitotConfig)
    baro: BaroConfig = field(default_factory=BaroConfig)

    @staticmethod
    def ideal(imu_rate_hz: float = 200.0, gps_rate_hz: float = 5.0,
              gps_latency_s: float = 0.0) -> SensorConfig:
        """No errors at all (the full scale and the GPS timing stay)."""
        return SensorConfig(
            imu=ImuConfig(rate_hz=imu_rate_hz,
                          gyro=GyroConfig(noise_density_rad_s_rthz=0.0, bias_sigma_rad_s=0.0,
                                          bias_walk_rad_s_rts=0.0, scale_sigma=0.0,
                                          cross_axis_sigma=0.0, vibration_rad_s=0.0),
                          accel=AccelConfig(noise_density_g_rthz=0.0, bias_sigma_g=0.0,
                                            bias_walk_g_rts=0.0, scale_sigma=0.0,
                                            cross_axis_sigma=0.0, vibration_g=0.0)),
            gps=GpsConfig(rate_hz=gps_rate_hz, latency_s=gps_latency_s, pos_sigma_h_m=0.0,
                          pos_sigma_v_m=0.0, vel_sigma_m_s=0.0),
            pitot=PitotConfig(noise_pa=0.0),
            baro=BaroConfig(noise_pa=0.0, drift_pa_rts=0.0))


def config_from_dict(d: Mapping[str, Any], base: SensorConfig | None = None) -> SensorConfig:
    """A SensorConfig from nested tables ({"imu": {"gyro": {...}}, "gps": {...}}),
    e.g. a TOML [sensor_model] table; omitted keys keep ``base`` (default
    SensorConfig()). ValueError names the key: 'imu.gyro.noise': unknown key."""

    def build(obj: Any, tab: Mapping[str, Any], path: str) -> Any:
        if not isinstance(tab, Mapping):
            raise ValueError(f"'{path}': expected a table, got {type(tab).__name__}")
        fields = {f.name: f for f in dataclasses.fields(obj)}
        changes: dict[str, Any] = {}
        for k, v in tab.items():
            key = f"{path}.{k}" if path else str(k)
            if k not in fields:
                raise ValueError(f"'{key}': unknown key (allowed here: {', '.join(fields)})")
            cur = getattr(obj, k)
            if dataclasses.is_dataclass(cur):
                changes[k] = build(cur, v, key)
            elif isinstance(v, bool) or not isinstance(v, (int, float)):
                raise ValueError(f"'{key}': expected a number, got {type(v).__name__} {v!r}")
            else:
                changes[k] = float(v)
        try:
            return dataclasses.replace(obj, **changes)
        except ValueError as e:  # the field checks name the field: add the path
            msg = str(e)
            if path and msg.startswith("'"):
                msg = f"'{path}.{msg[1:]}"
            raise ValueError(msg) from None

    return build(base if base is not None else SensorConfig(), d, "")


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
        self.sigma = noise_density * math.sqrt(rate_hz / 2.0)
        self.walk = walk
        self.walk_state = [0.0, 0.0, 0.0]
        self.full_scale = full_scale

    def apply(self, true: tuple[float, float, float],
              dt_s: float) -> tuple[tuple[float, float, float], bool]:
        # plain floats: numpy's per-call overhead on 3-vectors is most of the cost
        w = self.rng.standard_normal(6).tolist()  # fixed draw count: 3 walk, 3 noise
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
        self.t_last = t_s
        wt = 2.0 * math.pi * self.cfg.vibration_hz * t_s
        ag, aa = self.cfg.gyro.vibration_rad_s, self.cfg.accel.vibration_g
        tg, ta = st.ideal_gyro_rad_s(s), st.ideal_accel_g(s)
        pg, pa = self.phase_gyro, self.phase_accel
        g, g_sat = self.gyro.apply((tg[0] + ag * math.sin(wt + pg[0]),
                                    tg[1] + ag * math.sin(wt + pg[1]),
                                    tg[2] + ag * math.sin(wt + pg[2])), dt)
        a, a_sat = self.accel.apply((ta[0] + aa * math.sin(wt + pa[0]),
                                     ta[1] + aa * math.sin(wt + pa[1]),
                                     ta[2] + aa * math.sin(wt + pa[2])), dt)
        return ImuSample(t_s, g, a, g_sat, a_sat)


class GpsModel:
    """Fixes at epochs k / rate_hz, each delivered latency_s later.

    ``sample`` may be called at any rate; a fix is measured at the first call
    at or after its epoch (call at a multiple of the GPS rate, e.g. at every
    IMU sample or sim frame, for exact epochs) and delivered at the first call
    at or after epoch + latency. The position error is a Gauss-Markov process
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
            fix = self._measure(s, t_epoch)  # advances the error even in an outage
            if self.enabled:
                self.queue.append((t_epoch + c.latency_s, fix))
            self.next_epoch += 1
        fresh = None
        while self.queue and self.queue[0][0] <= t_s + T_EPS_S:
            fresh = self.queue.popleft()[1]
        if fresh is not None:
            self.last, self.have_fix = fresh, True
            return dataclasses.replace(fresh, t_s=t_s, fresh=True)
        if self.last is None:
            return GpsSample(t_s, False, False, math.nan, 0.0, 0.0, 0.0, (0.0, 0.0, 0.0))
        return dataclasses.replace(self.last, t_s=t_s, fresh=False, fix_3d=self.have_fix)

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

    >>> model = SensorModel(SensorConfig(), seed=scenario.seed)
    >>> s = read_fdm_state(fdm)          # after each fdm.run()
    >>> imu = model.imu(s, t)            # every 1 / config.imu.rate_hz seconds
    >>> gps = model.gps(s, t)            # any rate that hits the GPS epochs
    >>> pitot, baro = model.pitot(s, t), model.baro(s, t)
    >>> model.gps_enabled = False        # an outage
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
