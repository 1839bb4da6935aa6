"""Metrics of a run (per commanded segment and for the whole run) and the
pass/fail evaluation of a scenario's criteria. Definitions: sil/README.md."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from helical_sil.frames import wrap_deg
from helical_sil.scenario import PassCriterion
from helical_sil.sim import G, RunResult, Segment

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
    idx = np.nonzero(m)[0]
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

    if steady.any():
        out["turn_rate_rmse_deg_s"] = _f(np.sqrt(np.mean((w[steady] - cmd) ** 2)))
        out["turn_rate_mean_deg_s"] = _f(np.mean(w[steady]))
        if abs(cmd) >= TURN_CHANGE_MIN_DEG_S:
            out["turn_rate_error_pct"] = _f(100.0 * abs(np.mean(w[steady]) - cmd) / abs(cmd))
        if seg.altitude_hold:
            ha = tel["cmd_altitude_m"][idx][steady]
            out["altitude_error_max_m"] = _f(np.max(np.abs(h[steady] - ha)))
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
    return out


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
    return {"scenario": sc.name, "aircraft": sc.aircraft.name, "seed": sc.seed,
            "control_rate_hz": sc.control_rate_hz, "sim_rate_hz": sc.sim_rate_hz,
            "trims": res.trims, "run": run, "segments": segs}


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
    return out
