"""The lockstep loop: JSBSim at sim_rate_hz, the C board at control_rate_hz.

No wall-clock pacing and only seeded randomness, so a run is a pure function
of (scenario file, aircraft file, board library, JSBSim version): repeated runs
give bit-identical telemetry.
"""

from __future__ import annotations

import contextlib
import ctypes
import math
import os
import sys
import time
from collections import deque
from dataclasses import dataclass, field
from typing import Any, Iterator

import jsbsim
import numpy as np

from helical_sil.config import params
from helical_sil.config.scenario import ESTIMATOR_KEYS, Scenario
from helical_sil.sensors import frames
from helical_sil.sensors import models as sensors_mod
from helical_sil.sim import board as board_mod
from helical_sil.sim import imu_c
from helical_sil.sim.board import IMU_MAX, Board
from helical_sil.sim.board import Board as _SilBoard  # the class itself (live/pil.py swaps Board)
from helical_sil.sim.faults import SensorFaults  # fault campaign (issue 7)

G = 9.80665
FT = frames.FT
KT = frames.KT

# Mil-F-8785C style turbulence for JSBSim's "milspec" model (turb-type 3):
# (probability-of-exceedance index, wind speed at 20 ft in knots).
TURBULENCE_LEVELS = {"none": (0, 0.0), "light": (3, 15.0), "moderate": (4, 30.0),
                     "severe": (6, 45.0)}

COLUMNS = (
    "t_s", "segment", "cmd_turn_rate_deg_s", "turn_rate_deg_s", "turn_rate_used_deg_s",
    "phi_deg", "theta_deg", "psi_deg", "altitude_m", "cmd_altitude_m", "altitude_hold",
    "climb_m_s", "airspeed_m_s", "cmd_airspeed_m_s", "beta_deg", "alpha_deg",
    "p_rad_s", "q_rad_s", "r_rad_s", "dcm_x", "dcm_y", "dcm_z",
    "sens_gyro_x", "sens_gyro_y", "sens_gyro_z", "sens_airspeed_m_s",
    "inverted", "pitch_mode", "pitch_cmd", "roll_error", "pitch_error",
    "law_aileron", "law_elevator", "law_rudder", "aileron", "elevator", "rudder", "throttle",
    "flags", "north_m", "east_m",
    # flight modes (zero when a scenario has none)
    "mode", "failsafe", "rc_fresh", "nav_index", "nav_arrived", "nav_reached", "nav_flags",
    "cross_track_m", "nav_distance_m", "leg_from_north_m", "leg_from_east_m",
    "turn_target_deg_s", "nav_turn_rate_deg_s", "blend", "aoa_pitch_offset", "aoa_trim",
    "aoa_active",
    # the air mass (issue 7): total wind (steady + turbulence) at the step, and the
    # air's vertical displacement since t = 0 (the down wind integrated every sim frame)
    "wind_north_m_s", "wind_east_m_s", "wind_down_m_s", "air_down_m",
    # the firmware's estimator (issue 13): its bottom row and Euler angles, the
    # gyro-bias estimate, its flags, the angle between the estimated and the
    # true earth-down vector, the heading error, and whether the GPS was on
    "est_x", "est_y", "est_z", "est_roll_deg", "est_pitch_deg", "est_yaw_deg",
    "est_bias_x_deg_s", "est_bias_y_deg_s", "est_bias_z_deg_s", "est_flags",
    "attitude_error_deg", "heading_error_deg", "gps_on", "true_bias_x_deg_s",
    "true_bias_y_deg_s", "true_bias_z_deg_s",
    # the airspeed the law was given: the pitot's, or the GPS ground speed when
    # the firmware judges the pitot dead (fw_step.c navigation)
    "law_airspeed_m_s",
)
MODE_NAMES = ("manual", "fbw", "waypoint", "rth")
MODE_THRESHOLDS_US = (1250, 1750, 2100)  # modes.h defaults (the board uses them)
RC_CENTRE_US, RC_TRAVEL_US = 1500, 500


@dataclass
class Segment:
    label: str
    t0: float
    t1: float
    turn_rate_deg_s: float
    prev_turn_rate_deg_s: float
    altitude_hold: bool
    altitude_m: float
    climb_m_s: float  # rate at which the hold's target moves to altitude_m; 0 = a step
    pitch: float
    inverted: bool
    prev_inverted: bool
    pitch_mode: str
    mode: str = ""        # flight modes: the mode the switch selects ("" = no modes)
    guided: bool = False  # waypoint / RTH / RC lost: the turn rate comes from navigation
    link: bool = True


@dataclass
class RunResult:
    scenario: Scenario
    telemetry: dict[str, np.ndarray]
    segments: list[Segment]
    wall_s: float
    trims: dict[str, float] = field(default_factory=dict)
    # why the run ended before its duration (ground contact), else None
    end_reason: str | None = None
    end_t_s: float | None = None


@contextlib.contextmanager
def _quiet_stdout() -> Iterator[None]:
    """JSBSim prints a banner on C++ stdout; keep our CLI output clean."""
    try:
        fd = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):
        yield
        return
    sys.stdout.flush()
    saved = os.dup(fd)
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), fd)
        try:
            yield
        finally:
            sys.stdout.flush()
            os.dup2(saved, fd)
            os.close(saved)


# Below this height above the ground (JSBSim's position/h-agl-ft) a run has hit
# the ground: the gear or the belly is on the terrain.
GROUND_CONTACT_M = 1.0


class SimError(RuntimeError):
    pass


def make_fdm(sc: Scenario) -> jsbsim.FGFDMExec:
    """Load, initialise and (optionally) trim the aircraft of a scenario."""
    with _quiet_stdout():
        fdm = jsbsim.FGFDMExec(None)
        fdm.set_debug_level(0)
        fdm["simulation/randomseed"] = sc.seed
        if not fdm.load_model(sc.aircraft.model):
            raise SimError(f"JSBSim could not load aircraft model {sc.aircraft.model!r}")
        fdm.set_dt(1.0 / sc.sim_rate_hz)
        fdm["ic/h-sl-ft"] = sc.altitude_m / FT
        fdm["ic/vt-fps"] = sc.airspeed_m_s / FT
        fdm["ic/psi-true-deg"] = sc.heading_deg
        fdm["ic/gamma-deg"] = 0.0
        fdm["atmosphere/wind-north-fps"] = sc.wind_north_m_s / FT
        fdm["atmosphere/wind-east-fps"] = sc.wind_east_m_s / FT
        fdm["atmosphere/wind-down-fps"] = sc.wind_down_m_s / FT
        if not fdm.run_ic():
            raise SimError("JSBSim run_ic failed")
        fdm["propulsion/set-running"] = -1
        if sc.trim:
            try:
                fdm["simulation/do_simple_trim"] = 1
            except Exception as e:  # jsbsim raises TrimFailureError
                raise SimError(f"JSBSim trim failed for {sc.aircraft.name} at "
                               f"{sc.airspeed_m_s} m/s: {e}") from None
        if sc.upset is not None:  # fault campaign (issue 7)
            _release_upset(fdm, sc)
        level, wind_kt = TURBULENCE_LEVELS[sc.turbulence]
        if level:
            fdm["atmosphere/turb-type"] = 3
            fdm["atmosphere/turbulence/milspec/windspeed_at_20ft_AGL-fps"] = wind_kt * KT / FT
            fdm["atmosphere/turbulence/milspec/severity"] = level
        else:
            fdm["atmosphere/turbulence/milspec/severity"] = 0
            fdm["atmosphere/turbulence/milspec/windspeed_at_20ft_AGL-fps"] = 0.0
    return fdm


# The steady wind's ramp-in time at the start of a run (see the loop in run()).
WIND_RAMP_S = 5.0


# --- fault campaign (issue 7) ---
def _release_upset(fdm: jsbsim.FGFDMExec, sc: Scenario) -> None:
    """After the trim at [initial] (its surface, throttle and pitch-trim settings
    stay: the servo trims the harness carries over), re-initialise JSBSim at the
    upset attitude, calibrated airspeed and body rates; no trim there."""
    assert sc.upset is not None
    u = sc.upset
    keep = {k: fdm[k] for k in ("fcs/aileron-cmd-norm", "fcs/elevator-cmd-norm",
                                "fcs/rudder-cmd-norm", "fcs/pitch-trim-cmd-norm")}
    n_eng = fdm.get_propulsion().get_num_engines()
    keep.update({f"fcs/throttle-cmd-norm[{e}]": fdm[f"fcs/throttle-cmd-norm[{e}]"]
                 for e in range(n_eng)})
    fdm["ic/h-sl-ft"] = sc.altitude_m / FT
    fdm["ic/vc-kts"] = u.calibrated_airspeed_m_s / KT
    fdm["ic/alpha-deg"] = 0.0  # velocity along the body axis: the attitude sets the path
    fdm["ic/beta-deg"] = 0.0
    fdm["ic/phi-deg"] = u.roll_deg
    fdm["ic/theta-deg"] = u.pitch_deg
    fdm["ic/psi-true-deg"] = u.heading_deg
    fdm["ic/p-rad_sec"] = math.radians(u.p_deg_s)
    fdm["ic/q-rad_sec"] = math.radians(u.q_deg_s)
    fdm["ic/r-rad_sec"] = math.radians(u.r_deg_s)
    for k, v in keep.items():
        fdm[k] = v
    if not fdm.run_ic():
        raise SimError("JSBSim run_ic failed at the upset initial condition")
    for k, v in keep.items():
        fdm[k] = v
# --- end fault campaign ---


def board_config(sc: Scenario, trims: dict[str, float]) -> dict[str, Any]:
    g = sc.gains
    return {
        # the law's rows of the parameter table, by their names (the scenario's
        # [gains] keys; pitch_mode is chosen per command, the table's default here)
        "law": {p.name: g[p.name] for p in params.LAW if p.name in g},
        # the holds' rows of the table, by their names (the [gains] keys); the
        # trim throttle, unless the file gives it, is JSBSim's own trim
        "alt_hold": {p.name: g[p.name] for p in params.ALT_HOLD},
        "speed_hold": {p.name: g.get(p.name, trims["throttle"]) if p.name == "throttle_trim"
                       else g[p.name] for p in params.SPEED_HOLD},
        "alt_integral_upright": g["alt_integral_upright"],
        "alt_integral_inverted": g["alt_integral_inverted"],
        "trim_aileron": trims["aileron"], "trim_elevator": trims["elevator"],
        "trim_rudder": trims["rudder"],
        "control_rate_hz": sc.control_rate_hz,
        "estimator": estimator_config(sc),
        "guidance": dict(sc.guidance),
    }


def estimator_config(sc: Scenario) -> dict[str, float]:
    """The firmware estimator's parameters in the table's units: its defaults
    (params.def), the scenario's [estimator] overrides (converted from their
    SIL units, scenario.ESTIMATOR_KEYS), the IMU at the sim rate and the
    sensors' full scales."""
    model = sensors_mod.config_from_dict(sc.sensor_model)
    est = params.estimator_defaults()
    est.update({
        "imu_rate_hz": float(sc.sim_rate_hz),
        "gyro_limit": model.imu.gyro.range_rad_s,
        "accel_limit": model.imu.accel.range_g,
        # the estimator is told the receiver's latency: by default the one the
        # scenario's GPS model has (a user sets it from the receiver's datasheet)
        "gps_latency": model.gps.latency_s * 1000.0,
    })
    for key, v in sc.estimator.items():
        name, factor = ESTIMATOR_KEYS[key]
        est[name] = v * factor
    return est


def sensor_model(sc: Scenario) -> sensors_mod.SensorModel:
    """The scenario's sensors: the IMU at the sim rate, the [sensor_model] tables."""
    cfg = sensors_mod.config_from_dict(sc.sensor_model)
    cfg = sensors_mod.config_from_dict({"imu": {"rate_hz": float(sc.sim_rate_hz)}}, cfg)
    return sensors_mod.SensorModel(cfg, seed=sc.seed)


def mode_of_pulse(us: int) -> str:
    return MODE_NAMES[sum(us >= t for t in MODE_THRESHOLDS_US)]


def stick_pulse_us(stick: float, deadband_us: float) -> int:
    """The pulse of a stick position that fbw.c reads back as `stick` (outside
    the deadband the reading is (|d| - deadband) / (travel - deadband))."""
    if stick == 0.0:
        return RC_CENTRE_US
    d = abs(stick) * (RC_TRAVEL_US - deadband_us) + deadband_us
    return int(round(RC_CENTRE_US + math.copysign(d, stick)))


def stick_of_pulse(us: int, deadband_us: float) -> float:
    d = us - RC_CENTRE_US
    if abs(d) <= deadband_us:
        return 0.0
    return max(-1.0, min(1.0, math.copysign((abs(d) - deadband_us) /
                                            (RC_TRAVEL_US - deadband_us), d)))


@dataclass
class RcState:
    mode_us: int = 1000
    aileron_us: int = RC_CENTRE_US
    elevator_us: int = RC_CENTRE_US
    rudder_us: int = RC_CENTRE_US
    throttle_us: int = 1000
    inverted: bool = False
    link: bool = True

    def pulses(self) -> list[int]:
        # inputs: 0 aileron, 1 elevator, 2 throttle, 3 rudder, 4 mode, 5 inverted (modes.h)
        return [self.aileron_us, self.elevator_us, self.throttle_us, self.rudder_us,
                self.mode_us, 2000 if self.inverted else 1000, 1500, 1500]


def rc_timeline(sc: Scenario, throttle_trim: float) -> list[RcState]:
    """The transmitter state after each [[rc]] entry (fields persist)."""
    mc = sc.modes
    assert mc is not None
    cur = RcState(throttle_us=int(round(1000 + 1000 * throttle_trim)))
    out = []
    for e in mc.rc:
        cur = RcState(**vars(cur))
        if e.mode_us is not None:
            cur.mode_us = e.mode_us
        if e.aileron is not None:
            cur.aileron_us = int(round(RC_CENTRE_US + RC_TRAVEL_US * e.aileron))
        if e.turn_rate_deg_s is not None:
            cur.aileron_us = stick_pulse_us(e.turn_rate_deg_s / mc.fbw_turn_rate_max_deg_s,
                                            mc.fbw_deadband_us)
        if e.elevator is not None:
            cur.elevator_us = int(round(RC_CENTRE_US + RC_TRAVEL_US * e.elevator))
        if e.rudder is not None:
            cur.rudder_us = int(round(RC_CENTRE_US + RC_TRAVEL_US * e.rudder))
        if e.throttle is not None:
            cur.throttle_us = int(round(1000 + 1000 * e.throttle))
        if e.inverted is not None:
            cur.inverted = e.inverted
        if e.link is not None:
            cur.link = e.link
        out.append(cur)
    return out


def _mode_segments(sc: Scenario, rcs: list[RcState]) -> list[Segment]:
    mc = sc.modes
    assert mc is not None
    segs: list[Segment] = []
    prev_turn, prev_inv = 0.0, False
    if mc.rc[0].t_s > 0.0:
        segs.append(Segment("start", 0.0, 0.0, 0.0, 0.0, False, sc.altitude_m, 0.0, 0.0, False,
                            False, mc.pitch_mode, "manual", False, True))
    for e, r in zip(mc.rc, rcs):
        mode = mode_of_pulse(r.mode_us) if r.link else "rth"
        guided = mode in ("waypoint", "rth")
        turn = pitch = 0.0
        if mode == "fbw":
            turn = stick_of_pulse(r.aileron_us, mc.fbw_deadband_us) * mc.fbw_turn_rate_max_deg_s
            pitch = stick_of_pulse(r.elevator_us, mc.fbw_deadband_us) * mc.fbw_pitch_max
        inv = r.inverted and r.link and mode != "manual"
        segs.append(Segment(e.label, e.t_s, 0.0, turn, prev_turn, guided,
                            mc.home_alt_m if mode == "rth" else sc.altitude_m, 0.0, pitch,
                            inv, prev_inv, mc.pitch_mode, mode, guided, r.link))
        prev_turn, prev_inv = turn, inv
    for i, sg in enumerate(segs):
        sg.t1 = segs[i + 1].t0 if i + 1 < len(segs) else sc.duration_s
    return [sg for sg in segs if sg.t1 > sg.t0 or sg is segs[-1]]


def modes_board_config(sc: Scenario) -> dict[str, object]:
    mc = sc.modes
    assert mc is not None
    a = mc.aoa
    assert mc.cruise_m_s is not None and mc.home_alt_m is not None
    return {
        "modes_enabled": 1, "modes_pitch_mode": 1 if mc.pitch_mode == "tilt_cross" else 0,
        # the table's rows by their names; the rest at the table's defaults
        "modes": {"rc_loss_ticks": mc.rc_loss_ticks, "rc_recover_ticks": mc.rc_recover_ticks,
                  "blend_ticks": mc.blend_ticks, "turn_slew_deg_s2": mc.turn_slew_deg_s2,
                  "pitch_slew_per_s": mc.pitch_slew_per_s, "cruise_m_s": mc.cruise_m_s},
        "fbw": {"turn_rate_max_deg_s": mc.fbw_turn_rate_max_deg_s,
                "pitch_max": mc.fbw_pitch_max, "deadband_us": mc.fbw_deadband_us},
        "nav": {"law": 1 if mc.law == "l1" else 0, "loop": int(mc.loop),
                "turn_rate_max_deg_s": mc.nav_turn_rate_max_deg_s, "l1_m": mc.l1_m,
                "arrival_radius_m": mc.arrival_radius_m, "loiter_radius_m": mc.loiter_radius_m,
                # whole metres (the default is the initial altitude)
                "home_alt_m": math.copysign(math.floor(abs(mc.home_alt_m) + 0.5), mc.home_alt_m)},
        # the model's speeds default to the aircraft's v_ref and half of it
        "aoa": {"v_ref_m_s": sc.gains["v_ref"], "v_enable_m_s": sc.gains["v_ref"] / 2.0, **a},
        "waypoint_count": len(mc.waypoints), "waypoints": list(mc.waypoints),
    }


def _segments(sc: Scenario) -> list[Segment]:
    cur = {"turn": 0.0, "alt_hold": True, "alt": sc.altitude_m, "climb": 0.0, "pitch": 0.0,
           "inv": False, "mode": "earth_frame"}
    cmds = list(sc.commands)
    segs: list[Segment] = []
    if not cmds or cmds[0].t_s > 0.0:
        segs.append(Segment("start", 0.0, 0.0, 0.0, 0.0, True, sc.altitude_m, 0.0, 0.0, False,
                            False, "earth_frame"))
    for c in cmds:
        prev_turn, prev_inv = cur["turn"], cur["inv"]
        if c.turn_rate_deg_s is not None:
            cur["turn"] = c.turn_rate_deg_s
        if c.pitch is not None:
            cur["alt_hold"], cur["pitch"] = False, c.pitch
        if c.altitude_m is not None:
            cur["alt_hold"], cur["alt"] = True, c.altitude_m
            cur["climb"] = c.climb_m_s or 0.0
        if c.inverted is not None:
            cur["inv"] = c.inverted
        if c.pitch_mode is not None:
            cur["mode"] = c.pitch_mode
        segs.append(Segment(c.label, c.t_s, 0.0, float(cur["turn"]), float(prev_turn),
                            bool(cur["alt_hold"]), float(cur["alt"]), float(cur["climb"]),
                            float(cur["pitch"]),
                            bool(cur["inv"]), bool(prev_inv), str(cur["mode"])))
    for i, s in enumerate(segs):
        s.t1 = segs[i + 1].t0 if i + 1 < len(segs) else sc.duration_s
    return [s for s in segs if s.t1 > s.t0 or s is segs[-1]]


def run(sc: Scenario, board_lib: str | None = None,
        log_path: str | os.PathLike[str] | None = None) -> RunResult:
    """Fly one scenario; returns the telemetry at the control rate. log_path:
    the firmware's flight log (DataFlash .bin, docs/flight-log.md) goes there."""
    fdm = make_fdm(sc)
    n_engines = fdm.get_propulsion().get_num_engines()
    throttle_props = [f"fcs/throttle-cmd-norm[{e}]" for e in range(n_engines)]
    trim_ail, trim_elev, trim_rud = frames.surfaces_from_jsbsim(
        fdm["fcs/aileron-cmd-norm"], fdm["fcs/elevator-cmd-norm"], fdm["fcs/rudder-cmd-norm"])
    trims = {"aileron": float(trim_ail), "elevator": float(trim_elev), "rudder": float(trim_rud),
             "throttle": float(fdm["fcs/throttle-cmd-norm[0]"]),
             "pitch_trim": float(fdm["fcs/pitch-trim-cmd-norm"])}
    cfg: dict[str, object] = dict(board_config(sc, trims))
    rcs: list[RcState] = []
    if sc.modes is not None:
        cfg.update(modes_board_config(sc))
        rcs = rc_timeline(sc, trims["throttle"])
    board = Board(cfg, board_lib)
    # the PIL target's board (live/pil.py) writes no log yet: only the SIL host board
    logging = log_path is not None and isinstance(board, _SilBoard)
    if logging:
        board.log_open(log_path)

    rng = np.random.Generator(np.random.PCG64(sc.seed))
    bias = sc.gyro_bias_rad_s * rng.choice(np.array([-1.0, 1.0]), size=3)
    faults = SensorFaults(sc)  # fault campaign (issue 7)

    model = sensor_model(sc)
    use_truth = sc.attitude_source == "truth"
    # the IMU's per-sample model runs in C (boards/sil/sil_imu_model.c), fed
    # each sim frame's JSBSim values: the Python model's samples, a fraction
    # of the cost (imu_c.py)
    # (board_mod.Board: the library even when a host swaps lockstep.Board, live/pil.py)
    imu = imu_c.CImu(model._imu, board_mod.Board.library(board_lib))
    n_sub = sc.sim_rate_hz // sc.control_rate_hz
    dt_sim = 1.0 / sc.sim_rate_hz
    frame_rows = (ctypes.c_double * (imu_c.N_IN * n_sub))()
    frame_props = imu_c.IN_PROPS
    n_in = imu_c.N_IN
    frame_rows[0:n_in] = [fdm[name] for name in frame_props]
    # the first control step's samples: the state after the trim (at t = 0:
    # -dt + 1 * dt is 0 exactly), n_sub times
    g0, a0 = imu.run(frame_rows, 1, -dt_sim, dt_sim)
    imu_batch = (np.repeat(g0, n_sub, axis=0), np.repeat(a0, n_sub, axis=0))
    imu_fifo: deque[ImuBatch] = deque()
    seam = ImuSeam(sens_arrays(board.sensors))
    # the legacy gyro errors ([sensors] gyro_*) also act on the IMU samples
    imu_bias = bias if sc.gyro_bias_rad_s > 0.0 else np.zeros(3)
    imu_rng = np.random.Generator(np.random.PCG64([sc.seed, 0x1A1]))
    gps_on = True

    segs = _segments(sc) if sc.modes is None else _mode_segments(sc, rcs)
    rc_ptr = -1
    dt_ctl = 1.0 / sc.control_rate_hz
    steps = int(round(sc.duration_s * sc.control_rate_hz))
    ncol = len(COLUMNS)
    log = np.zeros((steps, ncol), dtype=np.float64)
    fifo: deque[tuple[float, ...]] = deque()
    north = east = 0.0
    air_down = 0.0
    steady_wind = any(w != 0.0 for w in (sc.wind_north_m_s, sc.wind_east_m_s, sc.wind_down_m_s))
    seg_i = 0
    cmd = board.command
    sens = board.sensors
    cmd.speed_hold = 1
    cmd.airspeed_m_s = sc.airspeed_m_s
    cmd.throttle = trims["throttle"]
    target_airspeed = sc.airspeed_m_s
    cmd_ptr = 0
    alt_target = sc.altitude_m
    was_hold = True
    end_reason: str | None = None
    end_t: float | None = None
    t_wall = time.perf_counter()
    for k in range(steps):
        t = k * dt_ctl
        while seg_i + 1 < len(segs) and segs[seg_i + 1].t0 <= t + 1e-9:
            seg_i += 1
        while cmd_ptr < len(sc.commands) and sc.commands[cmd_ptr].t_s <= t + 1e-9:
            c = sc.commands[cmd_ptr]
            if c.airspeed_m_s is not None:
                cmd.speed_hold, target_airspeed = 1, c.airspeed_m_s
                cmd.airspeed_m_s = c.airspeed_m_s
            if c.throttle is not None:
                cmd.speed_hold, cmd.throttle = 0, c.throttle
            if c.gps is not None:
                gps_on = c.gps
                model.gps_enabled = gps_on
            cmd_ptr += 1
        seg = segs[seg_i]
        if sc.modes is not None:
            while rc_ptr + 1 < len(rcs) and sc.modes.rc[rc_ptr + 1].t_s <= t + 1e-9:
                rc_ptr += 1
                r = rcs[rc_ptr]
                for i, us in enumerate(r.pulses()):
                    cmd.rc_us[i] = us
                cmd.rc_fresh = int(r.link)
        cmd.turn_rate_rad_s = math.radians(seg.turn_rate_deg_s)
        cmd.altitude_hold = int(seg.altitude_hold)
        cmd.pitch_ratio = seg.pitch
        cmd.inverted = int(seg.inverted)
        cmd.pitch_mode = 1 if seg.pitch_mode == "tilt_cross" else 0

        phi = fdm["attitude/phi-rad"]
        theta = fdm["attitude/theta-rad"]
        psi = fdm["attitude/psi-rad"]
        p = fdm["velocities/p-rad_sec"]
        q = fdm["velocities/q-rad_sec"]
        r = fdm["velocities/r-rad_sec"]
        vt = fdm["velocities/vt-fps"] * FT
        h = fdm["position/h-sl-ft"] * FT
        hdot = fdm["velocities/h-dot-fps"] * FT
        if seg.altitude_hold and not was_hold:
            alt_target = h  # a ramp starts from where the aircraft is
        was_hold = seg.altitude_hold
        if seg.climb_m_s > 0.0:
            step_m = seg.climb_m_s * dt_ctl
            alt_target = min(max(seg.altitude_m, alt_target - step_m), alt_target + step_m)
        else:
            alt_target = seg.altitude_m
        cmd.altitude_m = alt_target
        x, y, z = frames.dcm_bottom_row(phi, theta)
        gx, gy, gz = frames.body_rates_lib(p, q, r)
        meas = (x, y, z, gx, gy, gz, vt, h, hdot)
        if sc.gyro_noise_rad_s > 0.0 or sc.gyro_bias_rad_s > 0.0 or sc.airspeed_noise_m_s > 0.0:
            ng = rng.normal(0.0, 1.0, size=4)
            meas = (x, y, z,
                    gx + bias[0] + sc.gyro_noise_rad_s * ng[0],
                    gy + bias[1] + sc.gyro_noise_rad_s * ng[1],
                    gz + bias[2] + sc.gyro_noise_rad_s * ng[2],
                    vt + sc.airspeed_noise_m_s * ng[3], h, hdot)
        meas = faults.apply(t, meas)  # fault campaign (issue 7): no-op without faults
        fifo.append(meas)
        if len(fifo) > sc.latency_steps + 1:
            fifo.popleft()
        m = fifo[0]
        (sens.dcm_x, sens.dcm_y, sens.dcm_z, sens.gyro_x, sens.gyro_y, sens.gyro_z,
         sens.airspeed_m_s, sens.altitude_m, sens.climb_m_s) = m
        vn = fdm["velocities/v-north-fps"] * FT
        ve = fdm["velocities/v-east-fps"] * FT
        # GPS: position from the start point and ground velocity (not delayed)
        sens.north_m, sens.east_m, sens.vel_north_m_s, sens.vel_east_m_s = north, east, vn, ve
        sens.heading_rad = psi
        sens.use_truth = int(use_truth)
        # the run starts in flight: the estimator starts aligned to JSBSim's
        # attitude, as if aligned on the ground before takeoff (zero bias)
        sens.align_to_truth = int(k == 0)
        _board_seam(sc, sens, model, sensors_mod.read_fdm_state(fdm), t, imu_batch, imu_fifo,
                    faults, imu_bias, imu_rng, seam)
        a = board.step()
        ail, elev, rud = frames.surfaces_to_jsbsim(a.aileron, a.elevator, a.rudder)
        fdm["fcs/aileron-cmd-norm"] = ail
        fdm["fcs/elevator-cmd-norm"] = elev
        fdm["fcs/rudder-cmd-norm"] = rud
        for throttle_prop in throttle_props:
            fdm[throttle_prop] = a.throttle

        cmd_turn_deg_s = seg.turn_rate_deg_s
        log_alt_hold, log_inv = seg.altitude_hold, seg.inverted
        log_speed_hold = bool(cmd.speed_hold)
        if sc.modes is not None:
            cmd_turn_deg_s = math.degrees(a.turn_cmd_rad_s)
            log_alt_hold = a.mode in (2, 3)
            log_inv = bool(a.inverted_cmd)
            log_speed_hold = log_alt_hold
            alt_target = a.target_altitude_m
            target_airspeed = float(sc.modes.cruise_m_s or 0.0)
        log[k] = (
            t, seg_i, cmd_turn_deg_s,
            math.degrees(frames.earth_turn_rate(p, q, r, phi, theta)),
            math.degrees(a.turn_rate_used_rad_s),
            math.degrees(phi), math.degrees(theta), math.degrees(psi), h,
            alt_target if log_alt_hold else math.nan, float(log_alt_hold),
            hdot, vt, target_airspeed if log_speed_hold else math.nan,
            fdm["aero/beta-deg"], fdm["aero/alpha-deg"], p, q, r, x, y, z,
            m[3], m[4], m[5], m[6],
            float(log_inv), float(cmd.pitch_mode), a.pitch_cmd, a.roll_error, a.pitch_error,
            a.law_aileron, a.law_elevator, a.law_rudder, a.aileron, a.elevator, a.rudder,
            a.throttle, float(a.flags), north, east,
            float(a.mode), float(a.failsafe), float(cmd.rc_fresh), float(a.nav_index),
            float(a.nav_arrived), float(a.nav_reached), float(a.nav_flags), a.cross_track_m,
            a.nav_distance_m, a.leg_from_north_m, a.leg_from_east_m,
            math.degrees(a.turn_target_rad_s), math.degrees(a.nav_turn_rate_rad_s), a.blend,
            a.aoa_pitch_offset, a.aoa_trim, float(a.aoa_active),
            fdm["atmosphere/total-wind-north-fps"] * FT, fdm["atmosphere/total-wind-east-fps"] * FT,
            fdm["atmosphere/total-wind-down-fps"] * FT, air_down,
            a.est_x, a.est_y, a.est_z, a.est_roll_deg, a.est_pitch_deg, a.est_yaw_deg,
            *(math.degrees(b_) for b_ in a.est_bias_rad_s), float(a.est_flags),
            _angle_deg((a.est_x, a.est_y, a.est_z), (x, y, z)),
            _wrap180(a.est_yaw_deg - math.degrees(psi)), float(gps_on),
            *(math.degrees(b_) for b_ in true_gyro_bias(imu.gyro_bias, imu.walk_state(),
                                                        imu_bias)),
            a.nav_airspeed_m_s,
        )
        if steady_wind:
            # JSBSim's run_ic and trim reset atmosphere/wind-*-fps, so the
            # steady wind is applied here, ramped in over WIND_RAMP_S: a step
            # would hit the trimmed aircraft as a gust of the full wind speed
            ramp = min(1.0, (t + dt_ctl) / WIND_RAMP_S)
            fdm["atmosphere/wind-north-fps"] = ramp * sc.wind_north_m_s / FT
            fdm["atmosphere/wind-east-fps"] = ramp * sc.wind_east_m_s / FT
            fdm["atmosphere/wind-down-fps"] = ramp * sc.wind_down_m_s / FT
        for j in range(n_sub):
            if not fdm.run():
                raise SimError(f"JSBSim stopped at t = {fdm['simulation/sim-time-sec']:.2f} s")
            # rectangle rule at the sim rate on the wind after each frame
            air_down += fdm["atmosphere/total-wind-down-fps"] * FT * dt_sim
            # the frame's state for the IMU (rates, forces, mass)
            frame_rows[j * n_in:(j + 1) * n_in] = [fdm[name] for name in frame_props]
        # the IMU samples each frame's state (one C call for the step's frames)
        try:
            imu_batch = imu.run(frame_rows, n_sub, t, dt_sim)
        except ValueError as e:  # NaN rates or forces: JSBSim's model diverged
            raise SimError(f"JSBSim's state is not finite at t = "
                           f"{fdm['simulation/sim-time-sec']:.2f} s (the model diverged): "
                           f"{e}") from None
        north += vn * dt_ctl
        east += ve * dt_ctl
        agl = fdm["position/h-agl-ft"] * FT
        if agl < GROUND_CONTACT_M:
            # the aircraft hit the ground: the run stops here and fails
            # (metrics.evaluate), whatever its criteria say
            end_t = (k + 1) * dt_ctl
            end_reason = (f"ground contact at t = {end_t:.2f} s: {agl:.1f} m above the ground, "
                          f"sinking at {-fdm['velocities/h-dot-fps'] * FT:.1f} m/s, "
                          f"{fdm['velocities/vt-fps'] * FT:.1f} m/s true airspeed")
            log = log[: k + 1]
            break
    wall = time.perf_counter() - t_wall
    tel = {name: log[:, i].copy() for i, name in enumerate(COLUMNS)}
    if logging:
        board.log_close()
    return RunResult(sc, tel, segs, wall, trims, end_reason, end_t)


def _angle_deg(a: tuple[float, float, float], b: tuple[float, float, float]) -> float:
    """The angle between two vectors (the estimated and the true earth-down)."""
    # the sums written out (no generator: this runs every control step); the
    # same additions in the same order as sum(), so the same bits
    na = math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])
    nb = math.sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2])
    if na == 0.0 or nb == 0.0:
        return 180.0
    c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (na * nb)
    return math.degrees(math.acos(max(-1.0, min(1.0, c))))


def _wrap180(d: float) -> float:
    return (d + 180.0) % 360.0 - 180.0


def true_gyro_bias(bias: tuple[float, ...], walk: tuple[float, ...],
                   extra: np.ndarray) -> tuple[float, ...]:
    """The gyro's true bias now (library axes, rad/s): the model's constant
    bias and random walk plus the legacy [sensors] gyro_bias_rad_s."""
    return tuple(float(b + w + e) for b, w, e in zip(bias, walk, extra))


def model_bias(model: sensors_mod.SensorModel, extra: np.ndarray) -> tuple[float, ...]:
    """true_gyro_bias of a Python-sampled model (live/serve.py's loop)."""
    tri = model._imu.gyro  # the model's constant bias and its random walk
    return true_gyro_bias(tuple(tri.bias), tuple(tri.walk_state), extra)


# One control step's IMU samples: gyro (rad/s) and accel (g), n rows of 3.
ImuBatch = tuple[np.ndarray, np.ndarray]


def sens_arrays(sens: object) -> tuple[np.ndarray, np.ndarray]:
    """numpy views of the board's IMU sample arrays (SIL_IMU_MAX rows of 3)."""
    return (np.ctypeslib.as_array(sens.gyro_rad_s),  # type: ignore[attr-defined]
            np.ctypeslib.as_array(sens.accel_g))  # type: ignore[attr-defined]


@dataclass
class ImuSeam:
    """Where _board_seam writes a step's IMU samples: views of the board's arrays."""
    views: tuple[np.ndarray, np.ndarray]


def _raw_sensors(sc: Scenario, sens: object, model: sensors_mod.SensorModel,
                 state: sensors_mod.FdmState, t: float, imu_batch: list[sensors_mod.ImuSample],
                 fifo: deque[ImuBatch], faults: SensorFaults,
                 bias: np.ndarray, rng: np.random.Generator) -> None:
    """_board_seam for a list of Python ImuSample (live/serve.py's loop)."""
    batch = (np.array([s.gyro_rad_s for s in imu_batch], dtype=np.float64).reshape(-1, 3),
             np.array([s.accel_g for s in imu_batch], dtype=np.float64).reshape(-1, 3))
    _board_seam(sc, sens, model, state, t, batch, fifo, faults, bias, rng,
                ImuSeam(sens_arrays(sens)))


def _board_seam(sc: Scenario, sens: object, model: sensors_mod.SensorModel,
                state: sensors_mod.FdmState, t: float, imu_batch: ImuBatch,
                fifo: deque[ImuBatch], faults: SensorFaults,
                bias: np.ndarray, rng: np.random.Generator, seam: ImuSeam) -> None:
    """The board seam of one control step: the IMU samples since the previous
    step (delayed by latency_steps), GPS, pitot and baro. The legacy [sensors]
    errors act here too: gyro bias and noise on every sample, the faults'
    gyro clipping from fault_start_s, the pitot through faults.apply.
    Element by element the arithmetic of the per-sample loop it replaced (the
    same sums, the noise drawn in the same order: 3 per sample)."""
    fifo.append(imu_batch)
    if len(fifo) > sc.latency_steps + 1:
        fifo.popleft()
    gyro, accel = fifo[0]
    n = min(len(gyro), IMU_MAX)
    sens.imu_count = n  # type: ignore[attr-defined]
    lim = sc.gyro_saturation_rad_s if t >= sc.fault_start_s - 1e-9 else None
    g = gyro[:n] + bias
    if sc.gyro_noise_rad_s > 0.0:
        g = g + sc.gyro_noise_rad_s * rng.normal(0.0, 1.0, size=(n, 3))
    if lim is not None:
        g = np.minimum(lim, np.maximum(-lim, g))
    seam.views[0][:n] = g
    seam.views[1][:n] = accel[:n]
    gps = model.gps(state, t)
    sens.gps_fresh = int(gps.fresh)  # type: ignore[attr-defined]
    sens.gps_fix = 3 if gps.fix_3d else 0  # type: ignore[attr-defined]
    sens.gps_lat_deg, sens.gps_lon_deg = gps.lat_deg, gps.lon_deg  # type: ignore[attr-defined]
    sens.gps_alt_m = gps.alt_msl_m  # type: ignore[attr-defined]
    for k in range(3):
        sens.gps_vel_ned_m_s[k] = gps.vel_ned_m_s[k]  # type: ignore[attr-defined]
    # what the board's pitot driver gives: INDICATED airspeed (sea-level
    # density, boards/devices/airspeed_ms4525.h); the firmware step makes it
    # true with the baro (include/helical/estimator/air_data.h), as on the board
    pitot = model.pitot(state, t).ias_m_s
    if sc.airspeed_noise_m_s > 0.0:
        pitot += sc.airspeed_noise_m_s * float(rng.normal())
    # the faults' pitot (stuck, spikes) through the same function as the truth path
    pitot = faults.apply_pitot(t, pitot) if hasattr(faults, "apply_pitot") else pitot
    sens.airspeed_fresh, sens.pitot_m_s = 1, pitot  # type: ignore[attr-defined]
    sens.baro_fresh, sens.baro_alt_m = 1, model.baro(state, t).altitude_m  # type: ignore[attr-defined]


def write_csv(res: RunResult, path: str | os.PathLike[str]) -> None:
    """Telemetry at the control rate; %.17g round-trips every double exactly."""
    arr = np.column_stack([res.telemetry[c] for c in COLUMNS])
    np.savetxt(path, arr, delimiter=",", header=",".join(COLUMNS), comments="", fmt="%.17g")
