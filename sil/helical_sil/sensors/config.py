"""Configuration of the sensor models (models.py): one frozen dataclass per
sensor with documented defaults (the source of each in its comment and in
sil/README.md, "Sensor models"), value checks that name the field, and
``config_from_dict`` for nested tables (a TOML section)."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from helical_sil.sensors import truth as st

DEG = math.pi / 180.0
PSI_PA = 6894.757293168  # Pa per psi


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
    # what is left of the zero-rate output after the power-up gyro calibration
    # every autopilot makes on the ground (the raw ICM-42688-P tolerance is
    # +/-0.5 deg/s, 3 sigma; the SIL starts in the air): assumption, the
    # temperature drift since then, +/-0.05 deg/s (3 sigma)
    bias_sigma_rad_s: float = 0.05 / 3.0 * DEG
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
    # what is left after the six-position accelerometer calibration every
    # autopilot asks for before flight (the raw part: ICM-42688-P zero-g
    # tolerance +/-20 mg, sensitivity +/-0.5 %, MPU-6000 cross-axis +/-2 %, all
    # 3 sigma): assumption, +/-2 mg, +/-0.1 % and +/-0.2 % (3 sigma). The raw
    # figures stay available as [sensor_model.imu.accel] keys.
    bias_sigma_g: float = 0.002 / 3.0
    # assumption: a zero-g temperature drift of 0.15 mg/degC over 4 degC in
    # 10 minutes: 0.6 mg / sqrt(600 s)
    bias_walk_g_rts: float = 0.6e-3 / math.sqrt(600.0)
    scale_sigma: float = 0.001 / 3.0
    cross_axis_sigma: float = 0.002 / 3.0
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
    # MS4525DO-DS5AI005DP, the +/-5 psi part (the 1 psi one saturates at 106 m/s
    # equivalent airspeed, where the T-37 cruises): 14 bits over 80 % of the span,
    # 5.3 Pa per count, noise sigma about one count (0.05 m/s at 100 m/s)
    noise_pa: float = 5.3
    # zero offset left after the power-up zeroing (the raw error band, +/-1 % FS,
    # is removed by it)
    offset_pa: float = 0.0
    # full scale 5 psi: 237 m/s equivalent airspeed
    range_pa: float = 5.0 * PSI_PA

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
