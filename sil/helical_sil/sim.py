"""The lockstep loop: JSBSim at sim_rate_hz, the C board at control_rate_hz.

No wall-clock pacing and only seeded randomness, so a run is a pure function
of (scenario file, aircraft file, board library, JSBSim version): repeated runs
give bit-identical telemetry.
"""

from __future__ import annotations

import contextlib
import math
import os
import sys
import time
from collections import deque
from dataclasses import dataclass, field
from typing import Iterator

import jsbsim
import numpy as np

from helical_sil import frames
from helical_sil.board import Board
from helical_sil.scenario import Scenario

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
)


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


@dataclass
class RunResult:
    scenario: Scenario
    telemetry: dict[str, np.ndarray]
    segments: list[Segment]
    wall_s: float
    trims: dict[str, float] = field(default_factory=dict)


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
        level, wind_kt = TURBULENCE_LEVELS[sc.turbulence]
        if level:
            fdm["atmosphere/turb-type"] = 3
            fdm["atmosphere/turbulence/milspec/windspeed_at_20ft_AGL-fps"] = wind_kt * KT / FT
            fdm["atmosphere/turbulence/milspec/severity"] = level
        else:
            fdm["atmosphere/turbulence/milspec/severity"] = 0
            fdm["atmosphere/turbulence/milspec/windspeed_at_20ft_AGL-fps"] = 0.0
    return fdm


def board_config(sc: Scenario, trims: dict[str, float]) -> dict[str, float]:
    g = sc.gains
    return {
        "kp_aileron": g["kp_aileron"], "kp_elevator": g["kp_elevator"], "kp_rudder": g["kp_rudder"],
        "kff_aileron": g["kff_aileron"], "kff_elevator": g["kff_elevator"],
        "kff_rudder": g["kff_rudder"],
        "kd_aileron": g["kd_aileron"], "kd_elevator": g["kd_elevator"], "kd_rudder": g["kd_rudder"],
        "v_ref_m_s": g["v_ref"], "v_min_m_s": g["v_min"], "max_tilt": g["max_tilt"],
        "schedule": int(g["schedule"]),
        "alt_kp_pitch_per_m": g["alt_kp"], "alt_ki_pitch_per_m_s": g["alt_ki"],
        "alt_kd_pitch_per_m_s": g["alt_kd"], "alt_max_pitch": g["alt_max_pitch"],
        "alt_max_integral_pitch": g["alt_max_integral"], "alt_max_error_m": g["alt_max_error_m"],
        "alt_integral_band_m": min(g["alt_integral_band_m"], g["alt_max_error_m"]),
        "alt_integral_upright": g["alt_integral_upright"],
        "alt_integral_inverted": g["alt_integral_inverted"],
        "spd_throttle_trim": g.get("throttle_trim", trims["throttle"]),
        "spd_throttle_min": g["throttle_min"], "spd_throttle_max": g["throttle_max"],
        "spd_kp_throttle_per_m_s": g["spd_kp"], "spd_ki_throttle_per_m": g["spd_ki"],
        "spd_kff_throttle_per_pitch": g["spd_kff_pitch"],
        "spd_max_integral_throttle": g["spd_max_integral"],
        "trim_aileron": trims["aileron"], "trim_elevator": trims["elevator"],
        "trim_rudder": trims["rudder"],
        "control_rate_hz": sc.control_rate_hz,
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


def run(sc: Scenario, board_lib: str | None = None) -> RunResult:
    """Fly one scenario; returns the telemetry at the control rate."""
    fdm = make_fdm(sc)
    n_engines = fdm.get_propulsion().get_num_engines()
    trim_ail, trim_elev, trim_rud = frames.surfaces_from_jsbsim(
        fdm["fcs/aileron-cmd-norm"], fdm["fcs/elevator-cmd-norm"], fdm["fcs/rudder-cmd-norm"])
    trims = {"aileron": float(trim_ail), "elevator": float(trim_elev), "rudder": float(trim_rud),
             "throttle": float(fdm["fcs/throttle-cmd-norm[0]"]),
             "pitch_trim": float(fdm["fcs/pitch-trim-cmd-norm"])}
    board = Board(board_config(sc, trims), board_lib)

    rng = np.random.Generator(np.random.PCG64(sc.seed))
    bias = sc.gyro_bias_rad_s * rng.choice(np.array([-1.0, 1.0]), size=3)

    segs = _segments(sc)
    n_sub = sc.sim_rate_hz // sc.control_rate_hz
    dt_ctl = 1.0 / sc.control_rate_hz
    steps = int(round(sc.duration_s * sc.control_rate_hz))
    ncol = len(COLUMNS)
    log = np.zeros((steps, ncol), dtype=np.float64)
    fifo: deque[tuple[float, ...]] = deque()
    north = east = 0.0
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
            cmd_ptr += 1
        seg = segs[seg_i]
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
        fifo.append(meas)
        if len(fifo) > sc.latency_steps + 1:
            fifo.popleft()
        m = fifo[0]
        (sens.dcm_x, sens.dcm_y, sens.dcm_z, sens.gyro_x, sens.gyro_y, sens.gyro_z,
         sens.airspeed_m_s, sens.altitude_m, sens.climb_m_s) = m
        a = board.step()
        ail, elev, rud = frames.surfaces_to_jsbsim(a.aileron, a.elevator, a.rudder)
        fdm["fcs/aileron-cmd-norm"] = ail
        fdm["fcs/elevator-cmd-norm"] = elev
        fdm["fcs/rudder-cmd-norm"] = rud
        for e in range(n_engines):
            fdm[f"fcs/throttle-cmd-norm[{e}]"] = a.throttle

        log[k] = (
            t, seg_i, seg.turn_rate_deg_s,
            math.degrees(frames.earth_turn_rate(p, q, r, phi, theta)),
            math.degrees(a.turn_rate_used_rad_s),
            math.degrees(phi), math.degrees(theta), math.degrees(psi), h,
            alt_target if seg.altitude_hold else math.nan, float(seg.altitude_hold),
            hdot, vt, target_airspeed if cmd.speed_hold else math.nan,
            fdm["aero/beta-deg"], fdm["aero/alpha-deg"], p, q, r, x, y, z,
            m[3], m[4], m[5], m[6],
            float(seg.inverted), float(cmd.pitch_mode), a.pitch_cmd, a.roll_error, a.pitch_error,
            a.law_aileron, a.law_elevator, a.law_rudder, a.aileron, a.elevator, a.rudder,
            a.throttle, float(a.flags), north, east,
        )
        vn = fdm["velocities/v-north-fps"] * FT
        ve = fdm["velocities/v-east-fps"] * FT
        for _ in range(n_sub):
            if not fdm.run():
                raise SimError(f"JSBSim stopped at t = {fdm['simulation/sim-time-sec']:.2f} s")
        north += vn * dt_ctl
        east += ve * dt_ctl
        if h < 5.0:
            log = log[: k + 1]
            break
    wall = time.perf_counter() - t_wall
    tel = {name: log[:, i].copy() for i, name in enumerate(COLUMNS)}
    return RunResult(sc, tel, segs, wall, trims)


def write_csv(res: RunResult, path: str | os.PathLike[str]) -> None:
    """Telemetry at the control rate; %.17g round-trips every double exactly."""
    arr = np.column_stack([res.telemetry[c] for c in COLUMNS])
    np.savetxt(path, arr, delimiter=",", header=",".join(COLUMNS), comments="", fmt="%.17g")
