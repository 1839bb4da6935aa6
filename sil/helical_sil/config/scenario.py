"""Scenario and aircraft files (TOML): parsing and validation.

Every error names the offending key (e.g. ``command[2].turn_rate_deg_s``) and
the file. The schema is documented in sil/README.md.
"""

from __future__ import annotations

import math
import re
import reprlib
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from helical_sil.config import params
from helical_sil.sensors import config as sensor_config

SIL_DIR = Path(__file__).resolve().parents[2]
DEFAULT_AIRCRAFT_DIR = SIL_DIR / "scenarios" / "aircraft"

# The law's rows of the parameter table (include/helical/params.def), by its
# names, units, bounds and defaults; pitch_mode is not a [gains] key (each
# [[command]] chooses the pitch method).
LAW_PARAMS = tuple(p.name for p in params.LAW if p.name != "pitch_mode")
# The holds' rows of the table (params.HOLDS: alt_kp .. spd_max_integral,
# throttle_min/max/trim), and the altitude hold's initial integrators, which
# are harness state (a run that starts in trimmed flight), not parameters.
INTEGRATOR_KEYS = ("alt_integral_upright", "alt_integral_inverted")
HOLD_PARAMS = tuple(p.name for p in params.HOLDS) + INTEGRATOR_KEYS
GAIN_KEYS = LAW_PARAMS + HOLD_PARAMS
# Defaults of the parameters an aircraft file may leave out: the table's; the
# integrators start at 0; throttle_trim has none here (absent: JSBSim's trim).
GAIN_DEFAULTS: dict[str, float] = {
    **{k: params.LAW_BY_NAME[k].default for k in LAW_PARAMS},
    **{p.name: p.default for p in params.HOLDS if p.name != "throttle_trim"},
    **{k: 0.0 for k in INTEGRATOR_KEYS},
}

# The range of every gain key, in the file's units (_gains checks it, the
# cross-field messages quote it): the table's rows, exactly as the board
# checks them; the integrators within +-4 (the largest max_integral).
GAIN_BOUNDS: dict[str, tuple[float, float]] = {
    **{k: (params.LAW_BY_NAME[k].min, params.LAW_BY_NAME[k].max) for k in LAW_PARAMS},
    **{p.name: (p.min, p.max) for p in params.HOLDS},
    **{k: (-4.0, 4.0) for k in INTEGRATOR_KEYS},
}
# Pairs the board requires in order (low <= high). Checked on the merged gains
# (defaults, aircraft file, scenario), so the error names both keys and the
# file each value came from, instead of the board refusing one of them later.
GAIN_ORDER = (("v_min", "v_ref"), ("throttle_min", "throttle_max"),
              ("alt_integral_band_m", "alt_max_error_m"),
              ("alt_protect_valid_m_s", "alt_protect_m_s"))

# A scenario or aircraft file larger than this is refused before parsing: a
# 10 000-command scenario is about 0.4 MB, and a device such as /dev/zero
# would otherwise be read forever.
MAX_FILE_BYTES = 16 * 1024 * 1024
# An aircraft name is a file name inside the aircraft folders, nothing else:
# no separators, no "..", no absolute path, no NUL, a bounded length.
AIRCRAFT_NAME_RE = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.\-]{0,63}")

TURBULENCE = ("none", "light", "moderate", "severe")
PITCH_MODES = ("earth_frame", "tilt_cross")

# the estimator against JSBSim (metrics.estimator_metrics), per segment and run
ESTIMATOR_METRICS = ("attitude_error_rms_deg", "attitude_error_max_deg", "heading_error_max_deg",
                     "gyro_bias_error_deg_s")
SEGMENT_METRICS = (
    "turn_rate_rmse_deg_s", "turn_rate_error_pct", "turn_entry_s", "bank_overshoot_deg",
    "altitude_change_m", "altitude_change_per_360_m", "sideslip_rms_deg",
    "max_altitude_loss_m", "surface_saturation_frac", "wrong_way_yaw_deg",
    "entry_altitude_loss_m", "heading_disturbance_deg", "altitude_error_max_m",
    "path_altitude_loss_m",
    "airspeed_error_max_m_s",
    # flight modes (issue 5)
    "cross_track_rms_m", "cross_track_max_m", "waypoints_reached", "waypoint_miss_max_m",
    "bank_rate_rms_deg_s", "altitude_rms_m",
    # --- fault campaign (issue 7) ---
    "bank_abs_max_deg", "bank_error_max_deg", "tilt_error_max_deg", "airspeed_min_m_s",
    "airspeed_max_m_s", "min_altitude_m",
    # the air mass (metrics.air_mass_metrics)
    "air_relative_altitude_error_max_m", "unavoidable_sink_max_m",
    "altitude_error_net_of_air_max_m", "air_down_m", "wind_down_max_m_s", "wind_up_max_m_s",
    # --- end fault campaign ---
    *ESTIMATOR_METRICS,
    # law options (issue 17)
    "bank_entry_s", "steady_sideslip_rms_deg",
)
# metrics computed only with [metrics] climb_capability_m_s
NEEDS_CLIMB_CAPABILITY = ("unavoidable_sink_max_m", "altitude_error_net_of_air_max_m",
                          "min_altitude_net_of_air_m")
RUN_METRICS = (
    "max_altitude_loss_m", "surface_saturation_frac", "sideslip_rms_deg",
    "sim_speed_x_realtime", "altitude_error_max_m",
    # flight modes (issue 5)
    "altitude_change_m", "cross_track_rms_m", "cross_track_max_m", "waypoints_reached",
    "waypoints_within_radius", "waypoint_miss_max_m", "bank_rate_rms_deg_s", "altitude_rms_m",
    "failsafe_entry_s", "home_distance_end_m", "loiter_radius_error_m",
    # --- fault campaign (issue 7) ---
    "recovery_time_s", "tilt_error_end_deg", "min_altitude_m", "bank_abs_max_deg",
    "airspeed_min_m_s", "airspeed_max_m_s", "min_altitude_net_of_air_m",
    # --- end fault campaign ---
    *ESTIMATOR_METRICS,
    # law options (issue 17)
    "near_vertical_s", "near_vertical_aileron_tv_per_s",
)

# --- flight modes (issue 5): [modes], [nav], [fbw], [aoa], [[waypoint]], [[rc]] ---
_MODES_ROW, _NAV_ROW, _FBW_ROW = (params.MODE_GROUPS[k] for k in ("modes", "nav", "fbw"))
MODE_PULSES_US = {"manual": 1000, "fbw": 1500, "waypoint": 2000, "rth": 2150}
MODES_KEYS = ("pitch_mode", "rc_loss_ticks", "rc_recover_ticks", "blend_ticks",
              "turn_slew_deg_s2", "pitch_slew_per_s", "cruise_m_s")
NAV_KEYS = ("law", "turn_rate_max_deg_s", "l1_m", "arrival_radius_m", "loiter_radius_m",
            "home_alt_m", "loop")
NAV_LAWS = ("heading", "l1")
FBW_KEYS = ("turn_rate_max_deg_s", "pitch_max", "deadband_us")
AOA_KEYS = ("enabled", "v_ref_m_s", "v_enable_m_s", "load_max",
            "aoa_normal_deg", "aoa_normal_slope_deg", "aoa_inverted_deg", "aoa_inverted_slope_deg",
            "trim_normal", "trim_normal_slope", "trim_inverted", "trim_inverted_slope")
RC_KEYS = ("t_s", "label", "mode", "mode_us", "aileron", "turn_rate_deg_s", "elevator", "rudder",
           "throttle", "inverted", "link")
WAYPOINT_KEYS = ("north_m", "east_m", "alt_m")


class ScenarioError(ValueError):
    """A scenario or aircraft file is wrong; the message names the key."""


@dataclass
class Command:
    t_s: float
    label: str
    turn_rate_deg_s: float | None = None
    pitch: float | None = None
    altitude_m: float | None = None
    climb_m_s: float | None = None
    airspeed_m_s: float | None = None
    throttle: float | None = None
    inverted: bool | None = None
    pitch_mode: str | None = None
    gps: bool | None = None  # False: a GPS outage from here (no fresh fixes), True: back


@dataclass
class RcEntry:
    """One [[rc]] entry: what the scripted pilot's transmitter sends from t_s on.
    Fields left None keep their previous value."""
    t_s: float
    label: str
    mode_us: int | None = None
    aileron: float | None = None     # stick, [-1, 1], + = right
    turn_rate_deg_s: float | None = None  # FBW: the aileron stick that commands this rate
    elevator: float | None = None    # stick, [-1, 1], + = pull (climb)
    rudder: float | None = None
    throttle: float | None = None    # [0, 1]
    inverted: bool | None = None
    link: bool | None = None         # False: receiver dead (rc_fresh = 0)


@dataclass
class ModesConfig:
    """The flight modes' parameters (physical units, the board's names);
    defaults and bounds are the parameter table's rows (params.MODE_GROUPS)."""
    pitch_mode: str = "earth_frame"
    rc_loss_ticks: int = int(_MODES_ROW["rc_loss_ticks"].default)
    rc_recover_ticks: int = int(_MODES_ROW["rc_recover_ticks"].default)
    blend_ticks: int = int(_MODES_ROW["blend_ticks"].default)
    turn_slew_deg_s2: float = _MODES_ROW["turn_slew_deg_s2"].default
    pitch_slew_per_s: float = _MODES_ROW["pitch_slew_per_s"].default
    cruise_m_s: float | None = None  # default: the initial airspeed
    law: str = "heading"
    nav_turn_rate_max_deg_s: float = _NAV_ROW["turn_rate_max_deg_s"].default
    l1_m: float = _NAV_ROW["l1_m"].default
    arrival_radius_m: float = _NAV_ROW["arrival_radius_m"].default
    loiter_radius_m: float = _NAV_ROW["loiter_radius_m"].default
    home_alt_m: float | None = None  # default: the initial altitude
    loop: bool = bool(_NAV_ROW["loop"].default)
    fbw_turn_rate_max_deg_s: float = _FBW_ROW["turn_rate_max_deg_s"].default
    fbw_pitch_max: float = _FBW_ROW["pitch_max"].default
    fbw_deadband_us: float = _FBW_ROW["deadband_us"].default
    aoa: dict[str, float] = field(default_factory=dict)
    waypoints: list[tuple[float, float, float]] = field(default_factory=list)
    rc: list[RcEntry] = field(default_factory=list)


@dataclass
class PassCriterion:
    metric: str
    segment: str  # a command label, or "run"
    max: float | None = None
    min: float | None = None


@dataclass
class Aircraft:
    name: str
    model: str
    description: str
    gains: dict[str, float]
    altitude_m: float
    airspeed_m_s: float
    # defaults of the flight-mode tables ([modes], [nav], [fbw], [aoa]) for this airframe
    mode_tables: dict[str, dict[str, Any]] = field(default_factory=dict)
    # the aircraft file that set each gain (absent: GAIN_DEFAULTS), for error messages
    gain_sources: dict[str, Path] = field(default_factory=dict)
    # [envelope]: the model's limits a run is checked against (ENVELOPE_KEYS)
    envelope: dict[str, float] = field(default_factory=dict)


# An aircraft file's [envelope] (written by `aircraft new`): the highest angle
# of attack the model holds (its <alphalimits>, else its highest trimmed
# alpha) and the fastest speed it was trimmed at; a run reports the time
# beyond either (metrics.envelope_metrics).
ENVELOPE_KEYS = {"stall_alpha_deg": (1.0, 45.0), "max_airspeed_m_s": (1.0, 400.0)}


# --- fault campaign (issue 7) ---
UPSET_KEYS = ("roll_deg", "pitch_deg", "heading_deg", "calibrated_airspeed_m_s", "p_deg_s",
              "q_deg_s", "r_deg_s")
SENSOR_KEYS = ("gyro_noise_rad_s", "gyro_bias_rad_s", "airspeed_noise_m_s", "latency_steps",
               "fault_start_s", "airspeed_stuck_m_s", "airspeed_spike_m_s",
               "airspeed_spike_rate_hz", "gyro_saturation_rad_s")


@dataclass
class Upset:
    """[upset]: after the trim at [initial] (the servo trims, throttle and pitch
    trim the harness carries over), the aircraft is re-initialised at this
    attitude, calibrated airspeed and body rates (JSBSim ic/*), not trimmed."""
    roll_deg: float
    pitch_deg: float
    heading_deg: float
    calibrated_airspeed_m_s: float
    p_deg_s: float = 0.0
    q_deg_s: float = 0.0
    r_deg_s: float = 0.0
# --- end fault campaign ---


@dataclass
class Scenario:
    path: Path
    name: str
    description: str
    aircraft: Aircraft
    duration_s: float
    seed: int
    control_rate_hz: int
    sim_rate_hz: int
    altitude_m: float
    airspeed_m_s: float
    heading_deg: float
    trim: bool
    gains: dict[str, float]
    wind_north_m_s: float = 0.0
    wind_east_m_s: float = 0.0
    wind_down_m_s: float = 0.0
    turbulence: str = "none"
    gyro_noise_rad_s: float = 0.0
    gyro_bias_rad_s: float = 0.0
    airspeed_noise_m_s: float = 0.0
    latency_steps: int = 0
    # --- fault campaign (issue 7): sensor faults from fault_start_s on, and the upset IC ---
    fault_start_s: float = 0.0
    airspeed_stuck_m_s: float | None = None   # the airspeed reads this constant
    airspeed_spike_m_s: float = 0.0           # one-step spikes of +-this size ...
    airspeed_spike_rate_hz: float = 0.0       # ... this many per second on average
    gyro_saturation_rad_s: float | None = None  # each gyro clips at +-this
    upset: Upset | None = None                # released untrimmed at this state
    # --- end fault campaign ---
    steady_after_s: float = 8.0
    entry_window_s: float = 6.0
    # the aircraft's best climb through the air (m/s) for the air-mass metrics
    # (metrics.unavoidable_sink); None: altitude_error_net_of_air_max_m is not computed
    climb_capability_m_s: float | None = None
    commands: list[Command] = field(default_factory=list)
    criteria: list[PassCriterion] = field(default_factory=list)
    modes: ModesConfig | None = None  # flight modes: the [[rc]] timeline flies the board
    # --- sensor-level SIL (issue 13) ---
    # "estimate" (default): the firmware's estimator on the simulated sensors;
    # "truth": JSBSim's attitude, for comparison
    attitude_source: str = "estimate"
    sensor_model: dict[str, Any] = field(default_factory=dict)  # [sensor_model] tables
    estimator: dict[str, float] = field(default_factory=dict)   # [estimator] overrides
    guidance: dict[str, float] = field(default_factory=dict)    # [guidance] overrides (table units)


# --- typed getters ----------------------------------------------------------

_SHOW = reprlib.Repr()
_SHOW.maxstring, _SHOW.maxother, _SHOW.maxlevel = 60, 60, 3


def _show(v: Any) -> str:
    """A value for an error message: bounded in length and nesting depth (a
    deeply nested array must not blow up the message, or repr's recursion)."""
    return _SHOW.repr(v)


def _key(k: str) -> str:
    """A key for an error message, printable and bounded (keys come from the file)."""
    return k if k.isprintable() and len(k) <= 80 else _show(k)


def _where(src: Path, key: str) -> str:
    return f"{src}: '{_key(key)}'"


def _num(src: Path, key: str, v: Any, lo: float | None = None, hi: float | None = None) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise ScenarioError(f"{_where(src, key)}: expected a number, got {type(v).__name__} {_show(v)}")
    try:
        x = float(v)
    except OverflowError:  # an integer beyond double range
        x = math.inf
    if not math.isfinite(x):
        raise ScenarioError(f"{_where(src, key)}: must be finite, got {_show(v)}")
    if lo is not None and x < lo:
        raise ScenarioError(f"{_where(src, key)}: must be >= {lo}, got {_show(v)}")
    if hi is not None and x > hi:
        raise ScenarioError(f"{_where(src, key)}: must be <= {hi}, got {_show(v)}")
    return x


def _int(src: Path, key: str, v: Any, lo: int | None = None, hi: int | None = None) -> int:
    if isinstance(v, bool) or not isinstance(v, int):
        raise ScenarioError(f"{_where(src, key)}: expected an integer, got {type(v).__name__} {_show(v)}")
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        raise ScenarioError(f"{_where(src, key)}: must be in [{lo}, {hi}], got {_show(v)}")
    return v


def _bool(src: Path, key: str, v: Any) -> bool:
    if not isinstance(v, bool):
        raise ScenarioError(f"{_where(src, key)}: expected true or false, got {type(v).__name__} {_show(v)}")
    return v


def _str(src: Path, key: str, v: Any, choices: tuple[str, ...] | None = None) -> str:
    if not isinstance(v, str):
        raise ScenarioError(f"{_where(src, key)}: expected a string, got {type(v).__name__} {_show(v)}")
    if choices is not None and v not in choices:
        raise ScenarioError(f"{_where(src, key)}: must be one of {', '.join(choices)}; got {_show(v)}")
    return v


def _table(src: Path, key: str, v: Any) -> dict[str, Any]:
    if not isinstance(v, dict):
        raise ScenarioError(f"{_where(src, key)}: expected a table, got {type(v).__name__}")
    return v


def _check_keys(src: Path, prefix: str, table: dict[str, Any], allowed: tuple[str, ...]) -> None:
    for k in table:
        if k not in allowed:
            name = f"{prefix}.{k}" if prefix else k
            raise ScenarioError(
                f"{_where(src, name)}: unknown key (allowed here: {', '.join(allowed)})")



def _timeline_entry(src: Path, pre: str, raw: Any, keys: Any, duration: float, last_t: float,
                    labels: set[str], default_label: str) -> tuple[dict[str, Any], float, str]:
    """What every timeline entry ([[command]], [[rc]]) shares: a table of known
    keys, a time t_s within the run that does not go back, and a label that is
    unique (the new label is added to labels)."""
    c = _table(src, pre, raw)
    _check_keys(src, pre, c, keys)
    if "t_s" not in c:
        raise ScenarioError(f"{_where(src, pre + '.t_s')}: missing (required)")
    t = _num(src, pre + ".t_s", c["t_s"], 0.0, duration)
    if t < last_t:
        raise ScenarioError(f"{_where(src, pre + '.t_s')}: times must not decrease ({t} < {last_t})")
    label = _str(src, pre + ".label", c.get("label", default_label))
    if label in labels or label == "run":
        raise ScenarioError(f"{_where(src, pre + '.label')}: duplicate or reserved label {_show(label)}")
    labels.add(label)
    return c, t, label

def _read_bytes(path: Path) -> bytes:
    """The file's bytes; a missing, unreadable, special or huge file is a
    ScenarioError naming it."""
    try:
        if path.is_dir():
            raise ScenarioError(f"{path}: is a directory, not a TOML file")
        if not path.exists():
            raise ScenarioError(f"{path}: no such file")
        if not path.is_file():
            raise ScenarioError(f"{path}: not a regular file (a device, socket or pipe)")
        with path.open("rb") as f:
            data = f.read(MAX_FILE_BYTES + 1)
    except ScenarioError:
        raise
    except OSError as e:  # permission denied, name too long, I/O error ...
        raise ScenarioError(f"{path}: cannot read: {e.strerror or e}") from None
    except ValueError as e:  # a NUL in the path
        raise ScenarioError(f"{_show(str(path))}: not a usable path: {e}") from None
    if len(data) > MAX_FILE_BYTES:
        raise ScenarioError(f"{path}: larger than {MAX_FILE_BYTES} bytes; not a scenario file")
    return data


def _load_toml(path: Path) -> dict[str, Any]:
    data = _read_bytes(path)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        line = data.count(b"\n", 0, e.start) + 1
        raise ScenarioError(f"{path}: not UTF-8 text (byte 0x{data[e.start]:02x} on line {line}); "
                            "TOML files are UTF-8") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ScenarioError(f"{path}: not valid TOML: {e}") from None
    except RecursionError:  # tomllib parses nested arrays and inline tables recursively
        raise ScenarioError(f"{path}: arrays or inline tables nested too deeply to parse") from None


def _gains(src: Path, prefix: str, table: dict[str, Any]) -> dict[str, float]:
    _check_keys(src, prefix, table, GAIN_KEYS)
    out: dict[str, float] = {}
    for k, v in table.items():
        key = f"{prefix}.{k}"
        if k == "schedule":
            out[k] = 1.0 if (_bool(src, key, v) if isinstance(v, bool) else _int(src, key, v, 0, 1)) else 0.0
        elif k in params.LAW_BY_NAME:
            out[k] = _table_value(src, key, v, params.LAW_BY_NAME[k])
        elif k in params.HOLDS_BY_NAME:
            out[k] = _table_value(src, key, v, params.HOLDS_BY_NAME[k])
        else:
            lo, hi = GAIN_BOUNDS[k]
            out[k] = _num(src, key, v, lo, hi)
    return out


def _check_gain_order(src: Path, gains: dict[str, float], sources: dict[str, Path]) -> None:
    """GAIN_ORDER on the merged gains. sources: the file that set each key
    (absent: the default)."""
    def origin(k: str) -> str:
        f = sources.get(k)
        return "default" if f is None else ("this file" if f == src else f"set in {f}")

    for lo_k, hi_k in GAIN_ORDER:
        if lo_k in gains and hi_k in gains and gains[lo_k] > gains[hi_k]:
            (a, b), (c, d) = GAIN_BOUNDS[lo_k], GAIN_BOUNDS[hi_k]
            raise ScenarioError(
                f"{_where(src, 'gains.' + lo_k)} = {gains[lo_k]:g} ({origin(lo_k)}) must not "
                f"exceed 'gains.{hi_k}' = {gains[hi_k]:g} ({origin(hi_k)}); bounds: "
                f"{lo_k} in [{a:g}, {b:g}], {hi_k} in [{c:g}, {d:g}], {lo_k} <= {hi_k}")


# --- aircraft -----------------------------------------------------------------

def _check_model_name(src: Path, model: str) -> None:
    """A JSBSim model is a folder of JSBSim's aircraft root named like an
    aircraft file (AIRCRAFT_NAME_RE: no '/', no leading '.'), so a name
    cannot reach another path ("../../etc/passwd"); if the folder is there,
    it must not be a link out of the root."""
    if not AIRCRAFT_NAME_RE.fullmatch(model) or ".." in model:
        raise ScenarioError(
            f"{_where(src, 'model')}: not a JSBSim model name: {_show(model)} (a name is up to 64 "
            "letters, digits, '_', '-', '.', starting with a letter or digit: a folder of "
            "JSBSim's aircraft root, e.g. \"c172p\")")
    try:
        from helical_sil.config.aircraft import models_root
        root = models_root()
    except ImportError:  # no JSBSim here: the name's form is all there is to check
        return
    folder = root / model
    if folder.exists() and not folder.resolve().is_relative_to(root.resolve()):
        raise ScenarioError(f"{_where(src, 'model')}: {folder} is a link to {folder.resolve()}, "
                            f"outside JSBSim's aircraft root {root}: not flown")


def load_aircraft(name: str, search_dirs: list[Path], src: Path, key: str = "aircraft") -> Aircraft:
    """Find <name>.toml in the search dirs (the scenario's aircraft/ folder first).
    The name is a plain file name (AIRCRAFT_NAME_RE): it cannot leave the folders."""
    known = sorted({q.stem for d in search_dirs if d.is_dir() for q in d.glob("*.toml")})
    if not AIRCRAFT_NAME_RE.fullmatch(name):
        raise ScenarioError(
            f"{_where(src, key)}: not an aircraft name: {_show(name)} (a name is up to 64 "
            "letters, digits, '_', '-', '.', starting with a letter or digit, of a file "
            f"<name>.toml in the aircraft folders; known: {', '.join(known) or 'none'})")
    for d in search_dirs:
        p = d / f"{name}.toml"
        if p.is_file():
            break
    else:
        raise ScenarioError(
            f"{_where(src, key)}: unknown aircraft {_show(name)} (known: {', '.join(known) or 'none'})")
    # a link may point anywhere: the file flown must be one of the folder's own
    if not p.resolve().is_relative_to(d.resolve()):
        raise ScenarioError(f"{_where(src, key)}: {p} is a link to {p.resolve()}, outside the "
                            f"aircraft folder {d}: not flown")
    doc = _load_toml(p)
    _check_keys(p, "", doc, ("model", "description", "gains", "initial", "modes", "nav", "fbw",
                             "aoa", "envelope"))
    # no silent defaults for what makes an airframe: the JSBSim model and the
    # speed the gains are tuned at (the library's v_ref of 15 m/s would fly a
    # 50 m/s aircraft on gains scaled for a model plane)
    for key, why in (("model", "the JSBSim model to fly, e.g. model = \"c172p\""),
                     ("gains", "the [gains] table, with at least v_ref (the airspeed the gains "
                               "are tuned at)")):
        if key not in doc:
            raise ScenarioError(f"{_where(p, key)}: missing (required): {why}")
    model = _str(p, "model", doc["model"])
    _check_model_name(p, model)
    desc = _str(p, "description", doc.get("description", ""))
    gains = dict(GAIN_DEFAULTS)
    gtable = _table(p, "gains", doc["gains"])
    if "v_ref" not in gtable:
        row = params.LAW_BY_NAME["v_ref"]
        raise ScenarioError(f"{_where(p, 'gains.v_ref')}: missing (required): the airspeed the "
                            f"gains are tuned at, {row.bounds_text()}")
    own = _gains(p, "gains", gtable)
    gains.update(own)
    sources = {k: p for k in own}
    _check_gain_order(p, gains, sources)  # an aircraft file flies on its own
    init = _table(p, "initial", doc.get("initial", {}))
    _check_keys(p, "initial", init, ("altitude_m", "airspeed_m_s"))
    alt = _num(p, "initial.altitude_m", init.get("altitude_m", 1500.0), 10.0, 20000.0)
    spd = _num(p, "initial.airspeed_m_s", init.get("airspeed_m_s", gains["v_ref"]), 5.0, 300.0)
    tables = {k: _table(p, k, doc[k]) for k in ("modes", "nav", "fbw", "aoa") if k in doc}
    # parse once here so a bad aircraft file names its own key
    _parse_mode_tables(p, tables, ModesConfig())
    env_t = _table(p, "envelope", doc.get("envelope", {}))
    _check_keys(p, "envelope", env_t, tuple(ENVELOPE_KEYS))
    envelope = {k: _num(p, f"envelope.{k}", v, *ENVELOPE_KEYS[k]) for k, v in env_t.items()}
    return Aircraft(name=name, model=model, description=desc, gains=gains, altitude_m=alt,
                    airspeed_m_s=spd, mode_tables=tables, gain_sources=sources,
                    envelope=envelope)


def _parse_mode_tables(src: Path, tables: dict[str, dict[str, Any]], mc: ModesConfig) -> None:
    """[modes], [nav], [fbw], [aoa] into mc (keys given override mc's values)."""
    def row(table: str, k: str, v: Any) -> float:
        """A value of one of the modes' table rows: its bounds are the table's."""
        return _table_value(src, f"{table}.{k}", v, params.MODE_GROUPS[table][k])

    t = tables.get("modes", {})
    _check_keys(src, "modes", t, MODES_KEYS)
    if "pitch_mode" in t:
        mc.pitch_mode = _str(src, "modes.pitch_mode", t["pitch_mode"], PITCH_MODES)
    for k in ("rc_loss_ticks", "rc_recover_ticks", "blend_ticks"):
        if k in t:
            setattr(mc, k, int(row("modes", k, t[k])))
    for k in ("turn_slew_deg_s2", "pitch_slew_per_s", "cruise_m_s"):
        if k in t:
            setattr(mc, k, row("modes", k, t[k]))
    t = tables.get("nav", {})
    _check_keys(src, "nav", t, NAV_KEYS)
    if "law" in t:
        mc.law = _str(src, "nav.law", t["law"], NAV_LAWS)
    if "loop" in t:
        mc.loop = _bool(src, "nav.loop", t["loop"])
    for k, attr in (("turn_rate_max_deg_s", "nav_turn_rate_max_deg_s"), ("l1_m", "l1_m"),
                    ("arrival_radius_m", "arrival_radius_m"),
                    ("loiter_radius_m", "loiter_radius_m"), ("home_alt_m", "home_alt_m")):
        if k in t:
            setattr(mc, attr, row("nav", k, t[k]))
    t = tables.get("fbw", {})
    _check_keys(src, "fbw", t, FBW_KEYS)
    for k in ("turn_rate_max_deg_s", "pitch_max", "deadband_us"):
        if k in t:
            setattr(mc, "fbw_" + k, row("fbw", k, t[k]))
    t = tables.get("aoa", {})
    _check_keys(src, "aoa", t, AOA_KEYS)
    for k, v in t.items():
        if k == "enabled":
            mc.aoa[k] = 1.0 if _bool(src, f"aoa.{k}", v) else 0.0
        else:
            mc.aoa[k] = row("aoa", k, v)


def _parse_modes(src: Path, doc: dict[str, Any], ac: Aircraft, duration: float,
                 labels: set[str]) -> ModesConfig:
    mc = ModesConfig()
    _parse_mode_tables(src, ac.mode_tables, mc)   # the airframe's defaults
    aoa_defaults = dict(mc.aoa)
    tables = {k: _table(src, k, doc[k]) for k in ("modes", "nav", "fbw", "aoa") if k in doc}
    mc.aoa = {}
    _parse_mode_tables(src, tables, mc)           # the scenario's values
    mc.aoa = {**aoa_defaults, **mc.aoa}
    wps = doc.get("waypoint", [])
    if not isinstance(wps, list):
        raise ScenarioError(f"{_where(src, 'waypoint')}: expected an array of tables [[waypoint]]")
    if len(wps) > 64:
        raise ScenarioError(f"{_where(src, 'waypoint')}: at most 64 waypoints, got {len(wps)}")
    for i, w in enumerate(wps):
        pre = f"waypoint[{i}]"
        w = _table(src, pre, w)
        _check_keys(src, pre, w, WAYPOINT_KEYS)
        for k in ("north_m", "east_m"):
            if k not in w:
                raise ScenarioError(f"{_where(src, pre + '.' + k)}: missing (required)")
        mc.waypoints.append((_num(src, pre + ".north_m", w["north_m"], -1e6, 1e6),
                             _num(src, pre + ".east_m", w["east_m"], -1e6, 1e6),
                             _num(src, pre + ".alt_m", w["alt_m"], 10.0, 20000.0)
                             if "alt_m" in w else math.nan))
    rcs = doc.get("rc", [])
    if not isinstance(rcs, list) or not rcs:
        raise ScenarioError(f"{_where(src, 'rc')}: flight modes need an [[rc]] timeline "
                            "(an array of tables, at least one entry)")
    last_t = -1.0
    for i, c in enumerate(rcs):
        pre = f"rc[{i}]"
        c, t, label = _timeline_entry(src, pre, c, RC_KEYS, duration, last_t, labels, f"rc{i}")
        last_t = t
        e = RcEntry(t_s=t, label=label)
        if "mode" in c and "mode_us" in c:
            raise ScenarioError(f"{_where(src, pre + '.mode_us')}: give either mode or mode_us, not both")
        if "mode" in c:
            e.mode_us = MODE_PULSES_US[_str(src, pre + ".mode", c["mode"],
                                            tuple(MODE_PULSES_US))]
        if "mode_us" in c:
            e.mode_us = _int(src, pre + ".mode_us", c["mode_us"], 0, 3000)
        if "aileron" in c and "turn_rate_deg_s" in c:
            raise ScenarioError(
                f"{_where(src, pre + '.turn_rate_deg_s')}: give either aileron or turn_rate_deg_s, not both")
        for k in ("aileron", "elevator", "rudder"):
            if k in c:
                setattr(e, k, _num(src, f"{pre}.{k}", c[k], -1.0, 1.0))
        if "turn_rate_deg_s" in c:
            e.turn_rate_deg_s = _num(src, pre + ".turn_rate_deg_s", c["turn_rate_deg_s"],
                                     -mc.fbw_turn_rate_max_deg_s, mc.fbw_turn_rate_max_deg_s)
        if "throttle" in c:
            e.throttle = _num(src, pre + ".throttle", c["throttle"], 0.0, 1.0)
        if "inverted" in c:
            e.inverted = _bool(src, pre + ".inverted", c["inverted"])
        if "link" in c:
            e.link = _bool(src, pre + ".link", c["link"])
        mc.rc.append(e)
    return mc


# --- scenario -----------------------------------------------------------------

TOP_KEYS = ("aircraft", "description", "duration_s", "seed", "control_rate_hz", "sim_rate_hz",
            "initial", "gains", "wind", "sensors", "command", "pass", "metrics",
            "modes", "nav", "fbw", "aoa", "waypoint", "rc",
            "upset",  # fault campaign (issue 7)
            "attitude", "sensor_model", "estimator",  # sensor-level SIL (issue 13)
            "guidance")
COMMAND_KEYS = ("t_s", "label", "turn_rate_deg_s", "pitch", "altitude_m", "climb_m_s",
                "airspeed_m_s",
                "throttle", "inverted", "pitch_mode", "gps")
ATTITUDE_SOURCES = ("estimate", "truth")
# [estimator]: the firmware estimator's rows of the parameter table, each key
# -> (the table's name, the factor from the key's unit to the table's). A row
# is a key by its own name unless the SIL derives it (imu_rate_hz from the sim
# rate, gyro_limit and accel_limit from the sensor model) or an older key
# spelling with its unit is kept (ESTIMATOR_SPELLINGS).
_SIL_DERIVED = ("imu_rate_hz", "gyro_limit", "accel_limit")
ESTIMATOR_SPELLINGS: dict[str, tuple[str, str, float]] = {
    # table name: (scenario key, its unit, factor key unit -> table unit)
    "gyro_bias_max": ("gyro_bias_max_deg_s", "deg/s", math.pi / 180.0),
    "gps_min_speed": ("gps_min_speed_m_s", "m/s", 1.0),
    "accel_band": ("accel_band_g", "g", 1.0),
    "gps_latency": ("gps_latency_s", "s", 1000.0),
}
ESTIMATOR_KEYS: dict[str, tuple[str, float]] = {
    ESTIMATOR_SPELLINGS.get(p.name, (p.name, p.unit, 1.0))[0]:
        (p.name, ESTIMATOR_SPELLINGS.get(p.name, (p.name, p.unit, 1.0))[2])
    for p in params.ESTIMATOR if p.name not in _SIL_DERIVED
}


def _table_value(src: Path, key: str, v: Any, p: params.Param, factor: float = 1.0,
                 unit: str | None = None) -> float:
    """A value of a table row given in the file (in unit = the row's unit /
    factor): a number within the row's bounds, or an error quoting them:
    "'gains.kp_aileron' = 65 is outside [0, 64] (per unit error, Q16)"."""
    x = _num(src, key, v)
    why = p.check(x * factor)
    if why is not None:
        if factor != 1.0:
            why = (f"is outside [{p.min / factor:g}, {p.max / factor:g}] ({unit}; the table's "
                   f"{p.name} in {p.bounds_text()})")
        raise ScenarioError(f"{_where(src, key)} = {_show(v)} {why}")
    return x


# --- fault campaign (issue 7) ---
def _check_sensor_numbers(src: Path, prefix: str, table: dict[str, Any]) -> None:
    """Every number of [sensor_model] finite as a double, named by its key (an
    integer beyond double range would otherwise be a traceback)."""
    for k, v in table.items():
        key = f"{prefix}.{k}"
        if isinstance(v, dict):
            _check_sensor_numbers(src, key, v)
        elif isinstance(v, (int, float)) and not isinstance(v, bool):
            _num(src, key, v)


# The sensor model's rates and the GPS latency as the firmware meets them: a
# GPS at most one fix per simulation step (a faster one is a loop of fixes
# per step that never ends at 1e9 Hz), the latency the estimator is told by
# default within its row (params.def gps_latency, [0, 500] ms).
GPS_LATENCY_MAX_S = 0.5


def _check_sensor_rates(src: Path, sc: Scenario, model: Any, latency_given: bool) -> None:
    gps_hz = model.gps.rate_hz
    if not 0.0 < gps_hz <= sc.sim_rate_hz:
        raise ScenarioError(f"{_where(src, 'sensor_model.gps.rate_hz')}: must be in (0, "
                            f"{sc.sim_rate_hz}] Hz (at most one fix per sim step, sim_rate_hz), "
                            f"got {_show(gps_hz)} Hz")
    imu_hz = model.imu.rate_hz
    if not 0.0 < imu_hz <= 1000.0:
        raise ScenarioError(f"{_where(src, 'sensor_model.imu.rate_hz')}: must be in (0, 1000] Hz "
                            f"(the SIL samples the IMU at sim_rate_hz), got {_show(imu_hz)} Hz")
    lat = model.gps.latency_s
    if not latency_given and not 0.0 <= lat <= GPS_LATENCY_MAX_S:
        raise ScenarioError(
            f"{_where(src, 'sensor_model.gps.latency_s')}: must be in [0, {GPS_LATENCY_MAX_S}] s "
            f"(the estimator is told it: its gps_latency row is [0, 500] ms; set "
            f"estimator.gps_latency_s to fly a longer true latency), got {_show(lat)} s")


def _parse_faults(src: Path, doc: dict[str, Any], sens: dict[str, Any], sc: Scenario) -> None:
    """The sensor-fault keys of [sensors] and the [upset] table."""
    sc.fault_start_s = _num(src, "sensors.fault_start_s", sens.get("fault_start_s", 0.0), 0.0,
                            sc.duration_s)
    if "airspeed_stuck_m_s" in sens:
        sc.airspeed_stuck_m_s = _num(src, "sensors.airspeed_stuck_m_s",
                                     sens["airspeed_stuck_m_s"], 0.0, 300.0)
    sc.airspeed_spike_m_s = _num(src, "sensors.airspeed_spike_m_s",
                                 sens.get("airspeed_spike_m_s", 0.0), 0.0, 300.0)
    sc.airspeed_spike_rate_hz = _num(src, "sensors.airspeed_spike_rate_hz",
                                     sens.get("airspeed_spike_rate_hz", 0.0), 0.0,
                                     float(sc.control_rate_hz))
    if (sc.airspeed_spike_m_s > 0.0) != (sc.airspeed_spike_rate_hz > 0.0):
        raise ScenarioError(f"{_where(src, 'sensors.airspeed_spike_rate_hz')}: spikes need both "
                            "airspeed_spike_m_s and airspeed_spike_rate_hz > 0")
    if "gyro_saturation_rad_s" in sens:
        sc.gyro_saturation_rad_s = _num(src, "sensors.gyro_saturation_rad_s",
                                        sens["gyro_saturation_rad_s"], 0.01, 16.0)
    if "upset" not in doc:
        return
    up = _table(src, "upset", doc["upset"])
    _check_keys(src, "upset", up, UPSET_KEYS)
    for k in ("roll_deg", "pitch_deg"):
        if k not in up:
            raise ScenarioError(f"{_where(src, 'upset.' + k)}: missing (required)")
    sc.upset = Upset(
        roll_deg=_num(src, "upset.roll_deg", up["roll_deg"], -180.0, 180.0),
        pitch_deg=_num(src, "upset.pitch_deg", up["pitch_deg"], -90.0, 90.0),
        heading_deg=_num(src, "upset.heading_deg", up.get("heading_deg", sc.heading_deg),
                         -360.0, 360.0),
        calibrated_airspeed_m_s=_num(src, "upset.calibrated_airspeed_m_s",
                                     up.get("calibrated_airspeed_m_s", sc.airspeed_m_s),
                                     5.0, 300.0),
        **{k: _num(src, f"upset.{k}", up.get(k, 0.0), -360.0, 360.0)
           for k in ("p_deg_s", "q_deg_s", "r_deg_s")})
    if not sc.trim:
        raise ScenarioError(f"{_where(src, 'initial.trim')}: an [upset] starts from the trim at "
                            "[initial] (its servo trims), so trim must stay true")
# --- end fault campaign ---


def load_scenario(path: str | Path, aircraft_dirs: list[Path] | None = None) -> Scenario:
    src = Path(path)
    doc = _load_toml(src)
    _check_keys(src, "", doc, TOP_KEYS)
    if "aircraft" not in doc:
        raise ScenarioError(f"{_where(src, 'aircraft')}: missing (required)")
    dirs = aircraft_dirs or [src.parent / "aircraft", DEFAULT_AIRCRAFT_DIR]
    ac = load_aircraft(_str(src, "aircraft", doc["aircraft"]), dirs, src)
    if "duration_s" not in doc:
        raise ScenarioError(f"{_where(src, 'duration_s')}: missing (required)")
    duration = _num(src, "duration_s", doc["duration_s"], 0.1, 3600.0)
    seed = _int(src, "seed", doc.get("seed", 1), 0, 2**31 - 1)
    sim_rate = _int(src, "sim_rate_hz", doc.get("sim_rate_hz", 120), 10, 1000)
    ctl_rate = _int(src, "control_rate_hz", doc.get("control_rate_hz", 40), 1, 1000)
    if sim_rate % ctl_rate != 0:
        raise ScenarioError(
            f"{_where(src, 'control_rate_hz')}: must divide sim_rate_hz ({sim_rate}), got {ctl_rate}")

    init = _table(src, "initial", doc.get("initial", {}))
    _check_keys(src, "initial", init, ("altitude_m", "airspeed_m_s", "heading_deg", "trim"))
    gains = dict(ac.gains)
    own = _gains(src, "gains", _table(src, "gains", doc.get("gains", {})))
    gains.update(own)
    _check_gain_order(src, gains, {**ac.gain_sources, **{k: src for k in own}})

    sc = Scenario(
        path=src, name=src.stem, description=_str(src, "description", doc.get("description", "")),
        aircraft=ac, duration_s=duration, seed=seed, control_rate_hz=ctl_rate,
        sim_rate_hz=sim_rate,
        altitude_m=_num(src, "initial.altitude_m", init.get("altitude_m", ac.altitude_m), 10.0,
                        20000.0),
        airspeed_m_s=_num(src, "initial.airspeed_m_s", init.get("airspeed_m_s", ac.airspeed_m_s),
                          5.0, 300.0),
        heading_deg=_num(src, "initial.heading_deg", init.get("heading_deg", 0.0), -360.0, 360.0),
        trim=_bool(src, "initial.trim", init.get("trim", True)),
        gains=gains,
    )

    wind = _table(src, "wind", doc.get("wind", {}))
    _check_keys(src, "wind", wind, ("north_m_s", "east_m_s", "down_m_s", "turbulence"))
    sc.wind_north_m_s = _num(src, "wind.north_m_s", wind.get("north_m_s", 0.0), -100.0, 100.0)
    sc.wind_east_m_s = _num(src, "wind.east_m_s", wind.get("east_m_s", 0.0), -100.0, 100.0)
    sc.wind_down_m_s = _num(src, "wind.down_m_s", wind.get("down_m_s", 0.0), -50.0, 50.0)
    sc.turbulence = _str(src, "wind.turbulence", wind.get("turbulence", "none"), TURBULENCE)

    att = _table(src, "attitude", doc.get("attitude", {}))
    _check_keys(src, "attitude", att, ("source",))
    sc.attitude_source = _str(src, "attitude.source", att.get("source", "estimate"),
                              ATTITUDE_SOURCES)
    sc.sensor_model = _table(src, "sensor_model", doc.get("sensor_model", {}))
    _check_sensor_numbers(src, "sensor_model", sc.sensor_model)
    try:  # the sensor model names a bad key itself
        model = sensor_config.config_from_dict(sc.sensor_model)
    except ValueError as e:
        raise ScenarioError(f"{src}: [sensor_model] {e}") from None
    est = _table(src, "estimator", doc.get("estimator", {}))
    _check_sensor_rates(src, sc, model, "gps_latency_s" in est)
    _check_keys(src, "estimator", est, tuple(ESTIMATOR_KEYS))
    for k, (name, factor) in ESTIMATOR_KEYS.items():
        if k in est:
            unit = ESTIMATOR_SPELLINGS.get(name, ("", params.ESTIMATOR_BY_NAME[name].unit))[1]
            sc.estimator[k] = _table_value(src, "estimator." + k, est[k],
                                           params.ESTIMATOR_BY_NAME[name], factor, unit)
    # [guidance]: the guidance's rows of the parameter table, by name, in its units
    gd = _table(src, "guidance", doc.get("guidance", {}))
    _check_keys(src, "guidance", gd, tuple(params.GUIDANCE_BY_NAME))
    for k, row in params.GUIDANCE_BY_NAME.items():
        if k in gd:
            sc.guidance[k] = _table_value(src, "guidance." + k, gd[k], row)

    sens = _table(src, "sensors", doc.get("sensors", {}))
    _check_keys(src, "sensors", sens, SENSOR_KEYS)
    sc.gyro_noise_rad_s = _num(src, "sensors.gyro_noise_rad_s", sens.get("gyro_noise_rad_s", 0.0),
                               0.0, 1.0)
    sc.gyro_bias_rad_s = _num(src, "sensors.gyro_bias_rad_s", sens.get("gyro_bias_rad_s", 0.0),
                              0.0, 1.0)
    sc.airspeed_noise_m_s = _num(src, "sensors.airspeed_noise_m_s",
                                 sens.get("airspeed_noise_m_s", 0.0), 0.0, 20.0)
    sc.latency_steps = _int(src, "sensors.latency_steps", sens.get("latency_steps", 0), 0, 100)
    _parse_faults(src, doc, sens, sc)  # fault campaign (issue 7)

    met = _table(src, "metrics", doc.get("metrics", {}))
    _check_keys(src, "metrics", met, ("steady_after_s", "entry_window_s",
                                      "climb_capability_m_s"))
    sc.steady_after_s = _num(src, "metrics.steady_after_s", met.get("steady_after_s", 8.0), 0.0,
                             600.0)
    sc.entry_window_s = _num(src, "metrics.entry_window_s", met.get("entry_window_s", 6.0), 0.5,
                             600.0)
    if "climb_capability_m_s" in met:
        sc.climb_capability_m_s = _num(src, "metrics.climb_capability_m_s",
                                       met["climb_capability_m_s"], 0.0, 100.0)

    labels: set[str] = set()
    if "rc" in doc or "modes" in doc:
        if "command" in doc:
            raise ScenarioError(f"{_where(src, 'command')}: a flight-modes scenario ([modes] or "
                                "[[rc]]) is flown by its [[rc]] timeline, not by [[command]]")
        sc.modes = _parse_modes(src, doc, ac, duration, labels)
        if sc.modes.cruise_m_s is None:
            sc.modes.cruise_m_s = sc.airspeed_m_s
        if sc.modes.home_alt_m is None:
            sc.modes.home_alt_m = sc.altitude_m
        sc.modes.waypoints = [(n, e, sc.altitude_m if math.isnan(a) else a)
                              for n, e, a in sc.modes.waypoints]
    else:
        for k in ("nav", "fbw", "aoa", "waypoint"):
            if k in doc:
                raise ScenarioError(f"{_where(src, k)}: only in a flight-modes scenario "
                                    "(give an [[rc]] timeline)")
    cmds = doc.get("command", [])
    if not isinstance(cmds, list):
        raise ScenarioError(f"{_where(src, 'command')}: expected an array of tables [[command]]")
    last_t = -1.0
    for i, c in enumerate(cmds):
        pre = f"command[{i}]"
        c, t, label = _timeline_entry(src, pre, c, COMMAND_KEYS, duration, last_t, labels, f"seg{i}")
        last_t = t
        if "pitch" in c and "altitude_m" in c:
            raise ScenarioError(
                f"{_where(src, pre + '.pitch')}: give either pitch or altitude_m, not both")
        if "throttle" in c and "airspeed_m_s" in c:
            raise ScenarioError(
                f"{_where(src, pre + '.throttle')}: give either throttle or airspeed_m_s, not both")
        cmd = Command(t_s=t, label=label)
        if "turn_rate_deg_s" in c:
            cmd.turn_rate_deg_s = _num(src, pre + ".turn_rate_deg_s", c["turn_rate_deg_s"], -900.0, 900.0)
        if "pitch" in c:
            cmd.pitch = _num(src, pre + ".pitch", c["pitch"], -30.0, 30.0)
        if "altitude_m" in c:
            cmd.altitude_m = _num(src, pre + ".altitude_m", c["altitude_m"], 10.0, 20000.0)
        if "climb_m_s" in c:
            if "altitude_m" not in c:
                raise ScenarioError(
                    f"{_where(src, pre + '.climb_m_s')}: needs altitude_m in the same command")
            cmd.climb_m_s = _num(src, pre + ".climb_m_s", c["climb_m_s"], 0.1, 100.0)
        if "airspeed_m_s" in c:
            cmd.airspeed_m_s = _num(src, pre + ".airspeed_m_s", c["airspeed_m_s"], 5.0, 300.0)
        if "throttle" in c:
            cmd.throttle = _num(src, pre + ".throttle", c["throttle"], 0.0, 1.0)
        if "inverted" in c:
            cmd.inverted = _bool(src, pre + ".inverted", c["inverted"])
        if "pitch_mode" in c:
            cmd.pitch_mode = _str(src, pre + ".pitch_mode", c["pitch_mode"], PITCH_MODES)
        if "gps" in c:
            cmd.gps = _bool(src, pre + ".gps", c["gps"])
        sc.commands.append(cmd)

    crit = doc.get("pass", [])
    if not isinstance(crit, list):
        raise ScenarioError(f"{_where(src, 'pass')}: expected an array of tables [[pass]]")
    for i, c in enumerate(crit):
        pre = f"pass[{i}]"
        c = _table(src, pre, c)
        _check_keys(src, pre, c, ("metric", "segment", "max", "min"))
        if "metric" not in c:
            raise ScenarioError(f"{_where(src, pre + '.metric')}: missing (required)")
        seg = _str(src, pre + ".segment", c.get("segment", "run"))
        allowed = RUN_METRICS if seg == "run" else SEGMENT_METRICS
        metric = _str(src, pre + ".metric", c["metric"], allowed)
        if metric in NEEDS_CLIMB_CAPABILITY and sc.climb_capability_m_s is None:
            raise ScenarioError(f"{_where(src, pre + '.metric')}: {metric} needs "
                                "metrics.climb_capability_m_s")
        if seg != "run" and seg not in labels:
            raise ScenarioError(
                f"{_where(src, pre + '.segment')}: no command has label {_show(seg)} "
                f"(labels: {', '.join(sorted(labels)) or 'none'}; or 'run')")
        if "max" not in c and "min" not in c:
            raise ScenarioError(f"{_where(src, pre)}: give max and/or min")
        crit_max = _num(src, pre + ".max", c["max"]) if "max" in c else None
        crit_min = _num(src, pre + ".min", c["min"]) if "min" in c else None
        if crit_min is not None and crit_max is not None and crit_min > crit_max:
            raise ScenarioError(
                f"{_where(src, pre + '.min')} = {crit_min:g} must not exceed '{pre}.max' = "
                f"{crit_max:g}: no value can pass")
        sc.criteria.append(PassCriterion(metric=metric, segment=seg, max=crit_max, min=crit_min))
    return sc
