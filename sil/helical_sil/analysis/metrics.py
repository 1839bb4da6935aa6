"""Metrics of a run (per commanded segment and for the whole run) and the
pass/fail evaluation of a scenario's criteria. Definitions: sil/README.md."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from helical_sil.config.scenario import PassCriterion
from helical_sil.sensors.frames import wrap_deg
from helical_sil.sim.lockstep import G, RunResult, Segment

SAT_LEVEL = 0.999
TURN_CHANGE_MIN_DEG_S = 1.0
BANK_CAPTURE_DEG = 5.0


def _f(x: float | np.floating | None) -> float | None:
    if x is None:
        return None
    v = float(x)
    return None if not math.isfinite(v) else v


def target_bank_deg(turn_rate_deg_s: float, airspeed_m_s: float, inverted: bool,
                    max_tilt: float) -> float:
    """Bank of the law's target tilt (Eq. 5 and the inverted flip), level flight."""
    ratio = math.radians(turn_rate_deg_s) * max(airspeed_m_s, 1.0) / G
    ratio = max(-max_tilt, min(max_tilt, ratio))
    tx, tz = -ratio, 1.0
    if inverted:
        tx, tz = -tx, -tz
    # X = -sin(phi) cos(theta), Z = cos(phi) cos(theta)
    return math.degrees(math.atan2(-tx, tz))


# --- flight-mode metrics (issue 5) ------------------------------------------

MODE_WAYPOINT, MODE_RTH = 2, 3
NAV_F_LOITER = 1 << 4


def straight_leg_mask(res: RunResult) -> np.ndarray:
    """Steps flying a planned leg in waypoint mode, on its second half
    (distance to the target <= half the leg), not circling: where
    cross-track is measured."""
    tel = res.telemetry
    mc = res.scenario.modes
    n = tel["t_s"].size
    if mc is None or not mc.waypoints:
        return np.zeros(n, dtype=bool)
    wp = np.asarray(mc.waypoints, dtype=float)
    idx = np.clip(tel["nav_index"].astype(int), 0, len(wp) - 1)
    leg = np.hypot(wp[idx, 0] - tel["leg_from_north_m"], wp[idx, 1] - tel["leg_from_east_m"])
    loiter = (tel["nav_flags"].astype(int) & NAV_F_LOITER) != 0
    return ((tel["mode"] == MODE_WAYPOINT) & ~loiter & (leg > 1.0) &
            (tel["nav_distance_m"] <= 0.5 * leg) & (tel["nav_arrived"] == 0))


def _bank_rate_deg_s(res: RunResult) -> np.ndarray:
    phi = np.unwrap(np.radians(res.telemetry["phi_deg"]))
    d = np.diff(phi, prepend=phi[:1]) * res.scenario.control_rate_hz
    return np.degrees(d)


def _steady_alt_mask(res: RunResult) -> np.ndarray:
    """Altitude-hold steps at least steady_after_s after their segment began."""
    tel = res.telemetry
    t = tel["t_s"]
    m = np.zeros(t.size, dtype=bool)
    for sg in res.segments:
        m |= (t >= sg.t0 + res.scenario.steady_after_s - 1e-9) & (t < sg.t1 - 1e-9)
    return m & (tel["altitude_hold"] > 0.5) & np.isfinite(tel["cmd_altitude_m"])


def nav_metrics(res: RunResult, m: np.ndarray) -> dict[str, Any]:
    """cross_track_rms/max_m, waypoints_reached, waypoint_miss_max_m,
    bank_rate_rms_deg_s, altitude_rms_m over the steps of mask m."""
    tel = res.telemetry
    out: dict[str, Any] = {}
    if not m.any():
        return out
    straight = straight_leg_mask(res) & m
    xt = tel["cross_track_m"][straight]
    out["cross_track_rms_m"] = _f(np.sqrt(np.mean(xt ** 2))) if xt.size else None
    out["cross_track_max_m"] = _f(np.max(np.abs(xt))) if xt.size else None
    out["straight_leg_s"] = _f(xt.size / res.scenario.control_rate_hz)
    idx = np.nonzero(m)[0]
    reached = tel["nav_reached"]
    before = reached[idx[0] - 1] if idx[0] > 0 else 0.0
    out["waypoints_reached"] = _f(reached[idx[-1]] - before)
    arr = np.nonzero((tel["nav_arrived"] > 0.5) & m & (tel["mode"] == MODE_WAYPOINT))[0]
    arr = arr[arr > 0]
    mc = res.scenario.modes
    if arr.size and mc is not None and mc.waypoints:
        # how far from the waypoint the aircraft was when it counted as reached
        wp = np.asarray(mc.waypoints, dtype=float)
        which = np.clip(tel["nav_index"][arr - 1].astype(int), 0, len(wp) - 1)
        miss = np.hypot(wp[which, 0] - tel["north_m"][arr], wp[which, 1] - tel["east_m"][arr])
        out["waypoint_miss_max_m"] = _f(np.max(miss))
        if res.scenario.modes is not None:
            out["waypoints_within_radius"] = _f(
                np.sum(miss <= res.scenario.modes.arrival_radius_m + 1e-6))
    br = _bank_rate_deg_s(res)[m]
    out["bank_rate_rms_deg_s"] = _f(np.sqrt(np.mean(br ** 2)))
    am = _steady_alt_mask(res) & m
    if am.any():
        dh = tel["altitude_m"][am] - tel["cmd_altitude_m"][am]
        out["altitude_rms_m"] = _f(np.sqrt(np.mean(dh ** 2)))
    return out


def failsafe_metrics(res: RunResult) -> dict[str, Any]:
    """RC loss: when the failsafe took over, and how the return home ended."""
    tel = res.telemetry
    fs = np.nonzero(tel["failsafe"] > 0.5)[0]
    if not fs.size:
        return {}
    t = tel["t_s"]
    out: dict[str, Any] = {}
    lost = np.nonzero(tel["rc_fresh"] < 0.5)[0]
    if lost.size:
        out["failsafe_entry_s"] = _f(t[fs[0]] - t[lost[0]])
    d_home = np.hypot(tel["north_m"], tel["east_m"])
    out["home_distance_end_m"] = _f(d_home[fs[-1]])
    loiter = fs[(tel["nav_flags"][fs].astype(int) & NAV_F_LOITER) != 0]
    if loiter.size:
        t_l = t[loiter]
        settled = loiter[t_l >= t_l[0] + 60.0]  # a minute after the loiter began
        mc = res.scenario.modes
        if settled.size and mc is not None:
            out["loiter_radius_error_m"] = _f(np.max(np.abs(d_home[settled] -
                                                            mc.loiter_radius_m)))
    return out


# --- fault campaign (issue 7) ---------------------------------------------

RECOVERY_TILT_DEG = 10.0   # recovered: tilt within this of the target ...
RECOVERY_HOLD_S = 5.0      # ... from then to the end of the run, at least this long


def target_tilt(res: RunResult) -> np.ndarray:
    """The law's target tilt (helical_turn.c target_tilt: Eq. 5, 6, inverted
    flip) at each step, from the logged command: turn rate used by the law,
    the sensed airspeed (at least v_min), the pitch ratio given to the law
    (the altitude hold's output when it is on) and the inverted flag. (n, 3)."""
    tel = res.telemetry
    g = res.scenario.gains
    s = np.maximum(tel["law_airspeed_m_s"], g["v_min"])
    ratio = np.clip(np.radians(tel["turn_rate_used_deg_s"]) * s / G, -g["max_tilt"],
                    g["max_tilt"])
    p = tel["pitch_cmd"]
    t = 1.0 / np.sqrt(1.0 + p ** 2)
    r = 1.0 / np.sqrt(1.0 + ratio ** 2)
    sign = np.where(tel["inverted"] > 0.5, -1.0, 1.0)
    return np.column_stack([sign * -ratio * r * t, -p * t, sign * r * t])


def tilt_error_deg(res: RunResult) -> np.ndarray:
    """Angle between the actual tilt (the DCM bottom row) and the target tilt."""
    tel = res.telemetry
    act = np.column_stack([tel["dcm_x"], tel["dcm_y"], tel["dcm_z"]])
    act /= np.linalg.norm(act, axis=1, keepdims=True)
    dot = np.clip(np.sum(act * target_tilt(res), axis=1), -1.0, 1.0)
    return np.degrees(np.arccos(dot))


def recovery_metrics(res: RunResult) -> dict[str, Any]:
    """recovery_time_s: from t = 0 until the tilt error is within
    RECOVERY_TILT_DEG for the rest of the run (None if it is not within it at
    the end, or for less than RECOVERY_HOLD_S); tilt_error_end_deg: the largest
    tilt error over the last RECOVERY_HOLD_S; min_altitude_m; bank and
    airspeed extremes."""
    tel = res.telemetry
    t = tel["t_s"]
    err = tilt_error_deg(res)
    out: dict[str, Any] = {}
    bad = np.nonzero(err > RECOVERY_TILT_DEG)[0]
    dt = 1.0 / res.scenario.control_rate_hz
    t_rec = 0.0 if not bad.size else float(t[bad[-1]] + dt)
    end = float(t[-1] + dt)
    out["recovery_time_s"] = t_rec if end - t_rec >= RECOVERY_HOLD_S - 1e-9 else None
    out["tilt_error_end_deg"] = _f(np.max(err[t >= end - RECOVERY_HOLD_S - 1e-9]))
    out["min_altitude_m"] = _f(np.min(tel["altitude_m"]))
    out["bank_abs_max_deg"] = _f(np.max(np.abs(tel["phi_deg"])))
    out["airspeed_min_m_s"] = _f(np.min(tel["airspeed_m_s"]))
    out["airspeed_max_m_s"] = _f(np.max(tel["airspeed_m_s"]))
    return out


def fault_segment_metrics(res: RunResult, seg: Segment, idx: np.ndarray,
                          steady: np.ndarray, err: np.ndarray) -> dict[str, Any]:
    """bank_abs_max_deg, airspeed_min/max_m_s, min_altitude_m over the
    segment; bank_error_max_deg (against the law's target bank) and
    tilt_error_max_deg over its steady part."""
    tel = res.telemetry
    sc = res.scenario
    phi = tel["phi_deg"][idx]
    v = tel["airspeed_m_s"][idx]
    out: dict[str, Any] = {
        "bank_abs_max_deg": _f(np.max(np.abs(phi))),
        "airspeed_min_m_s": _f(np.min(v)),
        "airspeed_max_m_s": _f(np.max(v)),
        "min_altitude_m": _f(np.min(tel["altitude_m"][idx])),
    }
    if steady.any():
        phi_t = target_bank_deg(seg.turn_rate_deg_s, float(np.mean(v[steady])), seg.inverted,
                                sc.gains["max_tilt"])
        out["bank_error_max_deg"] = _f(np.max(np.abs(
            np.asarray(wrap_deg(phi[steady] - phi_t), dtype=float))))
        out["tilt_error_max_deg"] = _f(np.max(err[idx][steady]))
    return out
# --- end fault campaign ---


def air_relative_altitude(res: RunResult, idx: np.ndarray) -> np.ndarray:
    """Altitude relative to the air mass over the steps idx of a segment: the
    altitude plus the air's downward displacement since the segment's first
    step (the down wind integrated at the sim rate, telemetry `air_down_m`).
    A downdraft that carries the aircraft down leaves it unchanged; climbing
    or sinking through the air changes it."""
    tel = res.telemetry
    air = tel["air_down_m"][idx]
    return np.asarray(tel["altitude_m"][idx] + (air - air[0]), dtype=float)


def unavoidable_sink(air_down_m: np.ndarray, target_m: np.ndarray, climb_capability_m_s: float,
                     dt_s: float) -> np.ndarray:
    """How far below its target an ideal aircraft must be at each step: one that
    starts on the target and climbs through the air at climb_capability_m_s
    whenever it is below it (and never overshoots). The deficit grows while
    the air sinks (plus the target rises) faster than the aircraft can climb,
    and shrinks at the climb capability otherwise (a Lindley recursion):
        U[k+1] = max(0, U[k] + (air_down[k+1] - air_down[k])
                             + (target[k+1] - target[k]) - climb_capability * dt)
    air_down_m: the air's cumulative downward displacement (telemetry
    `air_down_m`); target_m: the hold's target (NaN where the hold is off:
    U restarts at 0 there)."""
    n = air_down_m.size
    u = np.zeros(n, dtype=float)
    d_air = np.diff(air_down_m)
    d_tgt = np.nan_to_num(np.diff(target_m), nan=0.0)
    on = np.isfinite(target_m)
    c = climb_capability_m_s * dt_s
    for k in range(n - 1):
        u[k + 1] = max(0.0, u[k] + d_air[k] + d_tgt[k] - c) if on[k + 1] and on[k] else 0.0
    return u


def air_mass_metrics(res: RunResult, idx: np.ndarray, steady: np.ndarray) -> dict[str, Any]:
    """Altitude-hold segment, over its steady part (as altitude_error_max_m):
    - air_relative_altitude_error_max_m: largest |air-relative altitude (above)
      - the hold's target| (reported; it grows with the air's displacement
      even when the hold keeps its altitude exactly, so it is no criterion);
    - unavoidable_sink_max_m: largest unavoidable_sink (from the run's start,
      with the scenario's climb_capability_m_s);
    - altitude_error_net_of_air_max_m: largest of (altitude - target) and
      (target - altitude - unavoidable sink): the altitude error minus the
      part no aircraft of that climb capability could have avoided;
    - air_down_m: how far the air moved down over the segment;
      wind_down_max_m_s / wind_up_max_m_s: strongest down / up wind."""
    tel = res.telemetry
    if "air_down_m" not in tel or not steady.any():
        return {}
    h = tel["altitude_m"][idx]
    target = tel["cmd_altitude_m"][idx]
    w = tel["wind_down_m_s"][idx]
    air = tel["air_down_m"][idx]
    out: dict[str, Any] = {
        "air_relative_altitude_error_max_m": _f(np.max(np.abs(
            air_relative_altitude(res, idx)[steady] - target[steady]))),
        "air_down_m": _f(air[-1] - air[0]),
        "wind_down_max_m_s": _f(max(0.0, float(np.max(w)))),
        "wind_up_max_m_s": _f(max(0.0, float(-np.min(w)))),
    }
    c = res.scenario.climb_capability_m_s
    if c is not None:
        u = unavoidable_sink(tel["air_down_m"], tel["cmd_altitude_m"], c,
                             1.0 / res.scenario.control_rate_hz)[idx]
        err = np.maximum(h - target, target - h - u)
        out["unavoidable_sink_max_m"] = _f(np.max(u[steady]))
        out["altitude_error_net_of_air_max_m"] = _f(np.max(err[steady]))
    return out


def min_altitude_net_of_air(res: RunResult) -> dict[str, Any]:
    """min_altitude_net_of_air_m: the lowest altitude over the run, each step
    raised by that step's unavoidable_sink (the scenario's
    climb_capability_m_s): how low the aircraft went beyond what the air forced
    on any aircraft of that climb capability. Absent without a climb
    capability or the air telemetry."""
    tel = res.telemetry
    c = res.scenario.climb_capability_m_s
    if c is None or "air_down_m" not in tel or tel["altitude_m"].size == 0:
        return {}
    u = unavoidable_sink(tel["air_down_m"], tel["cmd_altitude_m"], c,
                         1.0 / res.scenario.control_rate_hz)
    return {"min_altitude_net_of_air_m": _f(np.min(tel["altitude_m"] + u))}


def estimator_metrics(tel: dict[str, np.ndarray], idx: np.ndarray) -> dict[str, Any]:
    """The firmware estimator against JSBSim over the steps idx (whichever
    attitude the law flew on): attitude_error_rms/max_deg (the angle between
    the estimated and the true earth-down vectors), heading_error_max_deg, and
    gyro_bias_error_deg_s (|estimated - true gyro bias| at the last step)."""
    if idx.size == 0 or "attitude_error_deg" not in tel:
        return {}
    e = tel["attitude_error_deg"][idx]
    k = idx[-1]
    db = [tel[f"est_bias_{a}_deg_s"][k] - tel[f"true_bias_{a}_deg_s"][k] for a in "xyz"]
    return {
        "attitude_error_rms_deg": _f(np.sqrt(np.mean(e ** 2))),
        "attitude_error_max_deg": _f(np.max(e)),
        "heading_error_max_deg": _f(np.max(np.abs(tel["heading_error_deg"][idx]))),
        "gyro_bias_error_deg_s": _f(math.sqrt(sum(d * d for d in db))),
    }


def segment_metrics(res: RunResult, seg: Segment) -> dict[str, Any]:
    tel = res.telemetry
    sc = res.scenario
    t = tel["t_s"]
    m = (t >= seg.t0 - 1e-9) & (t < seg.t1 - 1e-9)
    out: dict[str, Any] = {"label": seg.label, "t0_s": seg.t0, "t1_s": seg.t1,
                           "turn_rate_cmd_deg_s": seg.turn_rate_deg_s, "inverted": seg.inverted,
                           "pitch_mode": seg.pitch_mode}
    if not m.any():
        return out
    if sc.modes is not None:
        out["mode"] = seg.mode
        out.update(nav_metrics(res, m))
    idx = np.nonzero(m)[0]
    out.update(estimator_metrics(tel, idx))
    ts = t[idx] - seg.t0
    w = tel["turn_rate_deg_s"][idx]
    h = tel["altitude_m"][idx]
    psi_u = np.degrees(np.unwrap(np.radians(tel["psi_deg"][idx])))
    phi = tel["phi_deg"][idx]
    beta = tel["beta_deg"][idx]
    v = tel["airspeed_m_s"][idx]
    steady = ts >= sc.steady_after_s
    entry = ts <= sc.entry_window_s
    cmd = seg.turn_rate_deg_s
    change = cmd - seg.prev_turn_rate_deg_s

    if seg.guided:
        # the turn rate comes from navigation: no constant command to compare with
        out["altitude_change_m"] = _f(h[-1] - h[0])
        out["sideslip_rms_deg"] = _f(np.sqrt(np.mean(beta ** 2)))
        out["max_altitude_loss_m"] = _f(max(0.0, h[0] - np.min(h)))
        sat = np.maximum.reduce([np.abs(tel[k][idx]) for k in ("aileron", "elevator", "rudder")])
        out["surface_saturation_frac"] = _f(np.mean(sat >= SAT_LEVEL))
        return out

    if steady.any():
        out["turn_rate_rmse_deg_s"] = _f(np.sqrt(np.mean((w[steady] - cmd) ** 2)))
        if abs(cmd) >= TURN_CHANGE_MIN_DEG_S:  # issue 17: coordination in the steady turn
            out["steady_sideslip_rms_deg"] = _f(np.sqrt(np.mean(beta[steady] ** 2)))
        out["turn_rate_mean_deg_s"] = _f(np.mean(w[steady]))
        if abs(cmd) >= TURN_CHANGE_MIN_DEG_S:
            out["turn_rate_error_pct"] = _f(100.0 * abs(np.mean(w[steady]) - cmd) / abs(cmd))
        if seg.altitude_hold:
            ha = tel["cmd_altitude_m"][idx][steady]
            out["altitude_error_max_m"] = _f(np.max(np.abs(h[steady] - ha)))
            out.update(air_mass_metrics(res, idx, steady))
        va = tel["cmd_airspeed_m_s"][idx][steady]
        if np.all(np.isfinite(va)):
            out["airspeed_error_max_m_s"] = _f(np.max(np.abs(v[steady] - va)))
    else:
        out["turn_rate_rmse_deg_s"] = None

    if abs(change) >= TURN_CHANGE_MIN_DEG_S:
        frac = (w - seg.prev_turn_rate_deg_s) / change
        hit = np.nonzero(frac >= 0.9)[0]
        out["turn_entry_s"] = _f(ts[hit[0]]) if hit.size else None
        s = math.copysign(1.0, change)
        out["entry_altitude_loss_m"] = _f(max(0.0, h[0] - np.min(h[entry])))
        if abs(seg.prev_turn_rate_deg_s) < TURN_CHANGE_MIN_DEG_S:
            dpsi = psi_u[entry] - psi_u[0]
            out["wrong_way_yaw_deg"] = _f(max(0.0, float(np.max(-s * dpsi))))

    # bank overshoot against the law's target bank
    v_ref = float(np.mean(v[steady])) if steady.any() else float(np.mean(v))
    phi_t = target_bank_deg(cmd, v_ref, seg.inverted, sc.gains["max_tilt"])
    if abs(float(wrap_deg(phi_t - phi[0]))) >= BANK_CAPTURE_DEG:
        err = np.asarray(wrap_deg(phi - phi_t), dtype=float)
        cap = np.nonzero(np.abs(err) < BANK_CAPTURE_DEG)[0]
        if cap.size and cap[0] > 0:
            s_app = -math.copysign(1.0, err[cap[0] - 1])
            out["bank_overshoot_deg"] = _f(max(0.0, float(np.max(s_app * err[cap[0]:]))))
        else:
            out["bank_overshoot_deg"] = None
        out["bank_target_deg"] = _f(phi_t)
        out["bank_entry_s"] = bank_entry_s(ts, phi, phi_t)

    out["altitude_change_m"] = _f(h[-1] - h[0])
    turned = psi_u[-1] - psi_u[0]
    out["heading_change_deg"] = _f(turned)
    if abs(turned) >= 90.0:
        out["altitude_change_per_360_m"] = _f((h[-1] - h[0]) / (abs(turned) / 360.0))
    if abs(cmd) < TURN_CHANGE_MIN_DEG_S:
        out["heading_disturbance_deg"] = _f(np.max(np.abs(psi_u - psi_u[0])))
    if not seg.altitude_hold:
        # altitude lost relative to the commanded flight path h0 + integral of
        # pitch * horizontal airspeed (pitch ratio = vertical / horizontal speed)
        v_h = v / math.sqrt(1.0 + seg.pitch ** 2)
        dt = 1.0 / sc.control_rate_hz
        path = h[0] + seg.pitch * np.concatenate(([0.0], np.cumsum(v_h[:-1]) * dt))
        out["path_altitude_loss_m"] = _f(max(0.0, float(np.max(path - h))))
    out["sideslip_rms_deg"] = _f(np.sqrt(np.mean(beta ** 2)))
    out["max_altitude_loss_m"] = _f(max(0.0, h[0] - np.min(h)))
    sat = np.maximum.reduce([np.abs(tel[k][idx]) for k in ("aileron", "elevator", "rudder")])
    out["surface_saturation_frac"] = _f(np.mean(sat >= SAT_LEVEL))
    if sc.modes is None:  # fault campaign (issue 7)
        out.update(fault_segment_metrics(res, seg, idx, steady, tilt_error_deg(res)))
    return out


# --- law options (issue 17) ---
ENTRY_FRACTION = 0.9     # entry = 90 % of the commanded change (turn rate or bank)
NEAR_VERTICAL = 0.1      # sqrt(X^2 + Z^2) below this: the fuselage within 5.7 deg of vertical


def bank_entry_s(ts: np.ndarray, phi_deg: np.ndarray, target_deg: float,
                 fraction: float = ENTRY_FRACTION) -> float | None:
    """Time (ts: from the command) until the bank first covers `fraction` of the
    change from its first value to target_deg (wrapped, so a roll through
    +-180 counts the short way); None if it never does. The law's side of the
    full-aileron comparison (campaigns/roll_limit.py measures the aileron's side with
    the same definition)."""
    if ts.size == 0:
        return None
    change = float(wrap_deg(target_deg - phi_deg[0]))
    if abs(change) < 1e-9:
        return 0.0
    frac = np.asarray(wrap_deg(phi_deg - phi_deg[0]), dtype=float) / change
    hit = np.nonzero(frac >= fraction)[0]
    return _f(ts[hit[0]]) if hit.size else None


def near_vertical_metrics(tel: dict[str, np.ndarray], dt_s: float) -> dict[str, Any]:
    """Near a vertical fuselage (JSBSim's attitude: sqrt(X^2 + Z^2) <
    NEAR_VERTICAL), how much the law's aileron moved: near_vertical_s (time
    spent there) and near_vertical_aileron_tv_per_s (the total variation of
    the law's aileron command per second there: a noise-driven +-1
    bang-bang gives up to 2 x the control rate, a steady command 0).
    Absent when the run never comes near the vertical."""
    xz = np.hypot(tel["dcm_x"], tel["dcm_z"])
    near = xz < NEAR_VERTICAL
    if not near.any():
        return {}
    da = np.abs(np.diff(tel["law_aileron"]))
    both = near[1:] & near[:-1]
    t_near = float(np.count_nonzero(near)) * dt_s
    tv = float(np.sum(da[both]))
    return {"near_vertical_s": t_near,
            "near_vertical_aileron_tv_per_s": _f(tv / max(float(np.count_nonzero(both)) * dt_s,
                                                          dt_s))}
# --- end law options ---


def run_metrics(res: RunResult) -> dict[str, Any]:
    tel = res.telemetry
    sc = res.scenario
    h = tel["altitude_m"]
    segs = [segment_metrics(res, s) for s in res.segments]
    sim_s = float(tel["t_s"][-1] + 1.0 / sc.control_rate_hz) if tel["t_s"].size else 0.0
    sat = np.maximum.reduce([np.abs(tel[k]) for k in ("aileron", "elevator", "rudder")])
    alt_errs = [s["altitude_error_max_m"] for s in segs if s.get("altitude_error_max_m") is not None]
    run = {
        "duration_s": sim_s,
        "max_altitude_loss_m": _f(max(0.0, h[0] - np.min(h))),
        "altitude_change_m": _f(h[-1] - h[0]),
        "surface_saturation_frac": _f(np.mean(sat >= SAT_LEVEL)),
        "sideslip_rms_deg": _f(np.sqrt(np.mean(tel["beta_deg"] ** 2))),
        "altitude_error_max_m": _f(max(alt_errs)) if alt_errs else None,
        "sim_speed_x_realtime": _f(sim_s / res.wall_s) if res.wall_s > 0 else None,
        "wall_s": _f(res.wall_s),
    }
    run["attitude_source"] = sc.attitude_source
    run.update(estimator_metrics(tel, np.arange(h.size)))
    if sc.modes is None:
        run.update(recovery_metrics(res))  # fault campaign (issue 7)
        run.update(min_altitude_net_of_air(res))
    if sc.modes is not None:
        run.update(nav_metrics(res, np.ones(h.size, dtype=bool)))
        run.update(failsafe_metrics(res))
    run.update(envelope_metrics(res))
    run.update(near_vertical_metrics(tel, 1.0 / sc.control_rate_hz))  # issue 17
    if res.end_reason is not None:
        run["end_reason"] = res.end_reason
        run["ground_contact_s"] = res.end_t_s
    return {"scenario": sc.name, "aircraft": sc.aircraft.name, "seed": sc.seed,
            "control_rate_hz": sc.control_rate_hz, "sim_rate_hz": sc.sim_rate_hz,
            "trims": res.trims, "run": run, "segments": segs}


def envelope_metrics(res: Any) -> dict[str, Any]:
    """Time beyond the aircraft file's [envelope] (absent: nothing): angle of
    attack above stall_alpha_deg, true airspeed above max_airspeed_m_s, and one
    line each that says so (when it first happened, for how long)."""
    env = res.scenario.aircraft.envelope
    if not env:
        return {}
    tel = res.telemetry
    t = tel["t_s"]
    dt = float(t[1] - t[0]) if t.size > 1 else 0.0
    out: dict[str, Any] = {"envelope": []}
    for key, col, what, unit in (("stall_alpha_deg", "alpha_deg", "angle of attack above the "
                                  "model's stall", "deg"),
                                 ("max_airspeed_m_s", "airspeed_m_s", "airspeed above the fastest "
                                  "trim", "m/s")):
        if key not in env:
            continue
        beyond = tel[col] > env[key]
        name = "time_" + key.replace("_deg", "").replace("_m_s", "") + "_exceeded_s"
        out[name] = float(np.count_nonzero(beyond) * dt)
        if beyond.any():
            i = int(np.argmax(beyond))
            out["envelope"].append(
                f"{what} ({env[key]:g} {unit}) from t = {t[i]:.2f} s, {out[name]:.2f} s in all, "
                f"worst {float(np.max(tel[col])):.1f} {unit}")
    return out


def evaluate(metrics: dict[str, Any], criteria: list[PassCriterion]) -> list[dict[str, Any]]:
    """One entry per criterion: value, limits, ok. A metric that could not be
    measured (None) fails."""
    by_label = {s["label"]: s for s in metrics["segments"]}
    out = []
    for c in criteria:
        src = metrics["run"] if c.segment == "run" else by_label.get(c.segment, {})
        val = src.get(c.metric)
        ok = val is not None
        if ok and c.max is not None and val > c.max:
            ok = False
        if ok and c.min is not None and val < c.min:
            ok = False
        out.append({"segment": c.segment, "metric": c.metric, "value": val, "max": c.max,
                    "min": c.min, "ok": ok})
    if metrics["run"].get("end_reason") is not None:
        # a run that ended on the ground fails, with the reason
        out.append({"segment": "run", "metric": "ground_contact_s",
                    "value": metrics["run"]["ground_contact_s"], "max": None, "min": None,
                    "ok": False, "reason": metrics["run"]["end_reason"]})
    return out
