"""ctypes binding of the host board (boards/sil/sil_board.h).

The structs below mirror the C header field by field; the sizes are checked
against the library at load time so a mismatch fails loudly instead of
silently corrupting memory.
"""

from __future__ import annotations

import ctypes
import os
from pathlib import Path
from typing import Any

from helical_sil.config import params as ptable

ABI_VERSION = 15
IMU_MAX = 32  # SIL_IMU_MAX: IMU samples per control step
RC_COUNT = 8  # SIL_RC_COUNT
MAX_WAYPOINTS = 64  # SIL_MAX_WAYPOINTS
LINK_TX_MAX = 8192  # bytes the link is asked for at once (Board.link_tx)

_D = ctypes.c_double
_I = ctypes.c_int32


class SilConfig(ctypes.Structure):
    _fields_ = [
        # ABI 11: one value per row of the parameter table, in its order and units
        ("law", _D * len(ptable.LAW)),
        ("estimator", _D * len(ptable.ESTIMATOR)),
        # ABI 12: the guidance between the modes and the law (the turn-rate trim)
        ("guidance", _D * len(ptable.GUIDANCE)),
        # ABI 13: the altitude and airspeed holds, the same way
        ("alt_hold", _D * len(ptable.ALT_HOLD)),
        ("speed_hold", _D * len(ptable.SPEED_HOLD)),
        *((n, _D) for n in (
            "alt_integral_upright", "alt_integral_inverted",
            "trim_aileron", "trim_elevator", "trim_rudder")),
        ("control_rate_hz", _I),
        # flight modes (ABI 6)
        *((n, _I) for n in ("modes_enabled", "modes_pitch_mode")),
        # ABI 14: the modes' own rows, fly-by-wire, navigation, the AoA model
        ("modes", _D * len(ptable.MODES)),
        ("fbw", _D * len(ptable.FBW)),
        ("nav", _D * len(ptable.NAV)),
        ("aoa", _D * len(ptable.AOA)),
        ("waypoint_count", _I),
        ("waypoints", (_D * 3) * MAX_WAYPOINTS),
        # ABI 15: the ground-station link's MAVLink system and component ids
        ("link_sysid", _I), ("link_compid", _I),
    ]


# Defaults of the ABI-6 flight-mode fields: modes off (the scenario's commands
# fly the board, as before ABI 6); and of the ABI-7 fields.
MODES_CONFIG_DEFAULTS: dict[str, Any] = {
    "modes_enabled": 0, "modes_pitch_mode": 0,
    "waypoint_count": 0, "waypoints": [],
    # the altitude hold's initial integrators: none
    "alt_integral_upright": 0.0, "alt_integral_inverted": 0.0,
    # ABI 15: MAVLink system 1, component 1 (MAV_COMP_ID_AUTOPILOT1)
    "link_sysid": 1, "link_compid": 1,
}


class SilSensors(ctypes.Structure):
    _fields_ = [
        # the raw seam (ABI 8): IMU samples since the last control step, GPS, pitot, baro
        ("imu_count", _I),
        ("gyro_rad_s", (_D * 3) * IMU_MAX),
        ("accel_g", (_D * 3) * IMU_MAX),
        ("gps_fresh", _I), ("gps_fix", _I),
        *((n, _D) for n in ("gps_lat_deg", "gps_lon_deg", "gps_alt_m")),
        ("gps_vel_ned_m_s", _D * 3),
        ("airspeed_fresh", _I), ("pitot_m_s", _D),
        ("baro_fresh", _I), ("baro_alt_m", _D),
        # JSBSim's truth: the solution the control flies on when use_truth
        ("use_truth", _I),
        *((n, _D) for n in (
            "dcm_x", "dcm_y", "dcm_z", "gyro_x", "gyro_y", "gyro_z",
            "airspeed_m_s", "altitude_m", "climb_m_s",
            "north_m", "east_m", "vel_north_m_s", "vel_east_m_s", "heading_rad")),
        # ABI 9: align the estimator to the truth above before this step's samples
        ("align_to_truth", _I),
    ]


class SilCommand(ctypes.Structure):
    _fields_ = [
        *((n, _D) for n in ("turn_rate_rad_s", "pitch_ratio", "altitude_m", "airspeed_m_s",
                            "throttle")),
        *((n, _I) for n in ("altitude_hold", "speed_hold", "inverted", "pitch_mode")),
        ("rc_us", _I * RC_COUNT),
        ("rc_fresh", _I),
    ]


class SilActuators(ctypes.Structure):
    _fields_ = [
        *((n, _D) for n in ("aileron", "elevator", "rudder", "throttle",
                            "law_aileron", "law_elevator", "law_rudder", "pitch_cmd",
                            "turn_rate_used_rad_s", "roll_error", "pitch_error")),
        ("flags", _I),
        *((n, _I) for n in ("mode", "selected_mode", "failsafe", "rc_good", "inverted_cmd",
                            "nav_index", "nav_arrived", "nav_flags", "nav_reached")),
        *((n, _D) for n in ("turn_target_rad_s", "turn_cmd_rad_s", "nav_turn_rate_rad_s",
                            "cross_track_m", "nav_distance_m", "target_altitude_m",
                            "leg_from_north_m", "leg_from_east_m", "blend",
                            "aoa_pitch_offset", "aoa_trim", "aoa_loading")),
        ("aoa_active", _I),
        # ABI 8: the estimator and the solution the control flew on
        ("control_ran", _I),
        *((n, _D) for n in ("est_x", "est_y", "est_z", "est_roll_deg", "est_pitch_deg",
                            "est_yaw_deg")),
        ("est_bias_rad_s", _D * 3),
        ("est_flags", _I),
        *((n, _D) for n in ("nav_x", "nav_y", "nav_z", "nav_airspeed_m_s", "nav_altitude_m",
                            "nav_climb_m_s", "nav_north_m", "nav_east_m")),
        ("guard_engaged", _I),
    ]


class ParamInfo(ctypes.Structure):
    """ht_param_info_t (include/helical/params.h): one row of the compiled table."""
    _fields_ = [("name", ctypes.c_char_p), ("unit", ctypes.c_char_p), ("format", ctypes.c_char_p),
                ("description", ctypes.c_char_p), ("min_raw", _I), ("max_raw", _I),
                ("default_raw", _I), ("scale", _I), ("bytes", ctypes.c_uint8)]


class BoardError(RuntimeError):
    """The board library is missing, stale, or refused a parameter."""


def find_board_library(explicit: str | os.PathLike[str] | None = None) -> Path:
    """The shared library: explicit path, $HT_SIL_BOARD_LIB, or the host build tree."""
    if explicit:
        p = Path(explicit)
        if not p.is_file():
            raise BoardError(f"board library not found: {p}")
        return p
    env = os.environ.get("HT_SIL_BOARD_LIB")
    if env:
        p = Path(env)
        if not p.is_file():
            raise BoardError(f"HT_SIL_BOARD_LIB points to a missing file: {p}")
        return p
    root = Path(__file__).resolve().parents[3]
    for cand in (root / "build" / "host" / "boards" / "sil" / "libhelical_sil_board.so",
                 root / "build" / "host" / "boards" / "sil" / "libhelical_sil_board.dylib"):
        if cand.is_file():
            return cand
    raise BoardError(
        "board library libhelical_sil_board.so not found: build the host preset "
        "(cmake --workflow --preset host) or set HT_SIL_BOARD_LIB")


def table_values(config: dict[str, Any]) -> dict[str, dict[str, float]]:
    """Each table group's values of a board config, in the table's units, by
    its config key (params.BOARD_GROUPS: "law", "estimator", "guidance",
    "alt_hold", "speed_hold"): config[key] (name -> value) over the table's
    defaults; unknown names are refused. The IMU runs at three samples per
    control step unless said (the SIL's 120 Hz at 40 Hz)."""
    out: dict[str, dict[str, float]] = {}
    for key, _group, rows in ptable.BOARD_GROUPS:
        into = {p.name: p.default for p in rows}
        if key == "estimator":
            into["imu_rate_hz"] = float(3 * int(config.get("control_rate_hz", 40)))
        for k, v in config.get(key, {}).items():
            if k not in into:
                raise BoardError(f"board config {key}: unknown parameter '{k}' "
                                 f"(the table's: {', '.join(p.name for p in rows)})")
            into[k] = float(v)
        out[key] = into
    return out


class Board:
    """One firmware instance (the C struct lives in a ctypes buffer we own)."""

    _libs: dict[str, ctypes.CDLL] = {}

    @staticmethod
    def library(lib_path: str | os.PathLike[str] | None = None) -> ctypes.CDLL:
        """The board library, loaded once per path and checked (ABI, struct sizes)."""
        path = str(find_board_library(lib_path))
        lib = Board._libs.get(path)
        if lib is None:
            lib = ctypes.CDLL(path)
            _declare(lib)
            Board._libs[path] = lib
        return lib

    def __init__(self, config: dict[str, Any], lib_path: str | os.PathLike[str] | None = None):
        lib = Board.library(lib_path)
        self._lib = lib
        self._state = ctypes.create_string_buffer(int(lib.sil_board_size()))
        cfg = SilConfig()
        full = {**MODES_CONFIG_DEFAULTS, **config}
        values = table_values(full)
        fields = {n for n, _t in SilConfig._fields_}
        for k in full:
            if k not in fields:
                raise BoardError(f"board config: unknown key '{k}'")
        for key, _group, rows in ptable.BOARD_GROUPS:
            arr = getattr(cfg, key)
            for i, p in enumerate(rows):
                arr[i] = values[key][p.name]
        for name, _t in SilConfig._fields_:
            if name in values:
                continue
            if name not in full:
                raise BoardError(f"board config lacks '{name}'")
            if name == "waypoints":
                wps = full[name]
                if len(wps) > MAX_WAYPOINTS:
                    raise BoardError(f"more than {MAX_WAYPOINTS} waypoints")
                for i, wp in enumerate(wps):
                    for k in range(3):
                        cfg.waypoints[i][k] = float(wp[k])
                continue
            setattr(cfg, name, full[name])
        err = ctypes.create_string_buffer(160)
        if lib.sil_board_init(self._state, ctypes.byref(cfg), err, len(err)) != 0:
            raise BoardError(f"the board refused parameter {err.value.decode()}")
        self._sensors = SilSensors()
        self._sensors.use_truth = 1  # the truth fields fly unless a caller gives raw samples
        self._command = SilCommand()
        self._act = SilActuators()
        self._step = lib.sil_board_step
        # the step's pointers, made once: per call they cost as much as the C step
        self._step_args = (self._state, ctypes.byref(self._sensors),
                           ctypes.byref(self._command), ctypes.byref(self._act))
        self._tx = ctypes.create_string_buffer(LINK_TX_MAX)
        self._log: ctypes.Array[ctypes.c_char] | None = None  # log_open

    @property
    def sensors(self) -> SilSensors:
        return self._sensors

    @property
    def command(self) -> SilCommand:
        return self._command

    def step(self) -> SilActuators:
        """Run one firmware control step on the current sensors and command. The
        result is the board's own buffer: read it before the next step."""
        self._step(*self._step_args)
        return self._act

    # --- the flight log (boards/sil/sil_log.h): firmware/log's writer into a file ---
    def log_open(self, path: str | os.PathLike[str]) -> None:
        """Log every later control step to path (DataFlash .bin), header first."""
        lib = self._lib
        self._log = ctypes.create_string_buffer(int(lib.sil_log_size()))
        err = ctypes.create_string_buffer(160)
        if lib.sil_log_open(self._log, self._state, os.fsencode(path), err, len(err)) != 0:
            self._log = None
            raise BoardError(f"{err.value.decode()}: {path}")

    def log_close(self) -> int:
        """Finish the log; returns the records dropped (0 for a file)."""
        log, self._log = getattr(self, "_log", None), None
        if log is None:
            return 0
        dropped = int(self._lib.sil_log_close(log, self._state))
        if dropped < 0:
            raise BoardError("the flight log could not be written completely")
        return dropped

    # --- ABI 15: the ground-station link (firmware/link/fw_link.h): bytes only ---
    def link_rx(self, data: bytes) -> None:
        """Bytes from the ground station into the firmware's MAVLink parser."""
        if data:
            self._lib.sil_link_rx(self._state, data, len(data))

    def link_tx(self, cap: int = LINK_TX_MAX) -> bytes:
        """Up to cap bytes the firmware has queued for the ground station."""
        n = int(self._lib.sil_link_tx(self._state, self._tx, min(cap, LINK_TX_MAX)))
        return self._tx.raw[:n]

    def link_counters(self) -> dict[str, int]:
        """The link's counters by their C names (frames received, dropped by
        reason, sent, queue overflows)."""
        lib = self._lib
        return {lib.sil_link_counter_name(i).decode(): int(lib.sil_link_counter(self._state, i))
                for i in range(lib.sil_link_counter_count())}


def compiled_table(lib_path: str | os.PathLike[str] | None = None) -> dict[str, list[dict[str, Any]]]:
    """The parameter table as the C side compiled it (sil_param_info), per
    group (params.BOARD_GROUPS' C names: "LAW", "DCM", "GUIDE", "ALT", "SPEED"):
    name, unit, format, stored bounds and default."""
    lib = Board.library(lib_path)
    out: dict[str, list[dict[str, Any]]] = {}
    for g, (_k, key, _rows) in enumerate(ptable.BOARD_GROUPS):
        rows = []
        for i in range(lib.sil_param_count(g)):
            r = lib.sil_param_info(g, i).contents
            rows.append({"name": r.name.decode(), "unit": r.unit.decode(),
                         "format": r.format.decode(), "description": r.description.decode(),
                         "min_raw": r.min_raw, "max_raw": r.max_raw,
                         "default_raw": r.default_raw, "scale": r.scale, "bytes": r.bytes})
        out[key] = rows
    return out


def _declare(lib: ctypes.CDLL) -> None:
    lib.sil_board_abi_version.restype = ctypes.c_int
    for fn in ("sil_board_size", "sil_config_size", "sil_sensors_size", "sil_command_size",
               "sil_actuators_size"):
        getattr(lib, fn).restype = ctypes.c_size_t
    got = lib.sil_board_abi_version()
    if got != ABI_VERSION:
        raise BoardError(f"board library ABI {got}, harness expects {ABI_VERSION}: rebuild")
    for fn, st in (("sil_config_size", SilConfig), ("sil_sensors_size", SilSensors),
                   ("sil_command_size", SilCommand), ("sil_actuators_size", SilActuators)):
        if getattr(lib, fn)() != ctypes.sizeof(st):
            raise BoardError(f"{fn}: C and Python structs differ: rebuild the board library")
    lib.sil_board_init.restype = ctypes.c_int
    lib.sil_board_init.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_char_p,
                                   ctypes.c_size_t]
    lib.sil_param_count.restype = ctypes.c_int
    lib.sil_param_count.argtypes = [ctypes.c_int]
    lib.sil_param_info.restype = ctypes.POINTER(ParamInfo)
    lib.sil_param_info.argtypes = [ctypes.c_int, ctypes.c_int]
    lib.sil_board_step.restype = None
    lib.sil_board_step.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p,
                                   ctypes.c_void_p]
    # ABI 15: the ground-station link
    lib.sil_link_rx.restype = None
    lib.sil_link_rx.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_size_t]
    lib.sil_link_tx.restype = ctypes.c_size_t
    lib.sil_link_tx.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t]
    lib.sil_link_counter_count.restype = ctypes.c_int
    lib.sil_link_counter_count.argtypes = []
    lib.sil_link_counter_name.restype = ctypes.c_char_p
    lib.sil_link_counter_name.argtypes = [ctypes.c_int]
    lib.sil_link_counter.restype = ctypes.c_uint32
    lib.sil_link_counter.argtypes = [ctypes.c_void_p, ctypes.c_int]
    # the flight log (sil_log.h)
    lib.sil_log_size.restype = ctypes.c_size_t
    lib.sil_log_size.argtypes = []
    lib.sil_log_open.restype = ctypes.c_int
    lib.sil_log_open.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_char_p,
                                 ctypes.c_char_p, ctypes.c_size_t]
    lib.sil_log_close.restype = ctypes.c_int32
    lib.sil_log_close.argtypes = [ctypes.c_void_p, ctypes.c_void_p]
