"""The JSBSim models a user can fly: which of the installed wheel's aircraft
are fixed-wing with an engine, and whether each trims (`aircraft list`).

A model is listed when its XML has a wing area and at least one engine and is
not a rotorcraft, an airship or a launch vehicle: gliders, bombs, balloons,
airships, rockets and helicopters are left out (the helical-turn law needs a wing and a throttle for its airspeed
hold). Whether it trims is asked of JSBSim itself: a straight, level trim
(`simulation/do_simple_trim`) at each speed of a sweep, at one altitude; the
first failure's message is JSBSim's own.
"""

from __future__ import annotations

import contextlib
import math
import os
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterator

FT = 0.3048
# the sweep of true airspeeds (m/s) each model is trimmed at: from a light
# aircraft's approach to a jet's cruise
TRIM_SPEEDS_M_S = (25.0, 35.0, 50.0, 70.0, 100.0, 140.0, 200.0)
DEFAULT_ALTITUDE_M = 1500.0


@dataclass
class ModelInfo:
    name: str
    path: Path
    fixed_wing: bool
    why_not: str = ""                 # why a model is not flyable ("no engine", ...)
    engines: int = 0
    wing_area_m2: float = 0.0
    trims_at: list[float] = field(default_factory=list)  # m/s of the sweep that trimmed
    trim_error: str = ""              # JSBSim's reason at the first speed that failed

    @property
    def trims(self) -> bool:
        return bool(self.trims_at)


def models_root() -> Path:
    import jsbsim
    return Path(jsbsim.get_default_root_dir()) / "aircraft"


def _wing_area_m2(root: ET.Element) -> float:
    el = root.find("metrics/wingarea")
    if el is None or el.text is None:
        return 0.0
    v = float(el.text)
    unit = el.get("unit", "FT2").upper()
    return v * FT * FT if unit == "FT2" else v


_ROTOR = re.compile(r"\b(helicopter|rotor)\b", re.IGNORECASE)


def classify(path: Path) -> ModelInfo:
    """Read one model's XML: is it a fixed-wing aircraft with an engine?"""
    name = path.parent.name
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
        root = ET.fromstring(text)
    except (ET.ParseError, OSError) as e:
        return ModelInfo(name, path, False, f"unreadable XML ({e})")
    engines = len(root.findall("propulsion/engine"))
    area = _wing_area_m2(root)
    info = ModelInfo(name, path, False, engines=engines, wing_area_m2=area)
    if _ROTOR.search(text):
        info.why_not = "rotorcraft"
    elif root.find("buoyant_forces") is not None:
        info.why_not = "airship or balloon (buoyant)"
    elif "launch vehicle" in text.lower():
        info.why_not = "launch vehicle"
    elif engines == 0:
        info.why_not = "no engine (glider, bomb or body)"
    elif area <= 0.0:
        info.why_not = "no wing area"
    else:
        info.fixed_wing = True
    return info


def find_models(root: Path | None = None) -> list[ModelInfo]:
    """Every <dir>/<dir>.xml under JSBSim's aircraft folder, classified."""
    base = root if root is not None else models_root()
    out = []
    for d in sorted(base.iterdir(), key=lambda p: p.name.lower()):
        xml = d / f"{d.name}.xml"
        if d.is_dir() and xml.is_file():
            out.append(classify(xml))
    return out


@contextlib.contextmanager
def _quiet() -> Iterator[None]:
    """JSBSim prints banners and trim reports on C++ stdout: keep them out."""
    try:
        fd = os.dup(1)
    except OSError:
        yield
        return
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        try:
            yield
        finally:
            os.dup2(fd, 1)
            os.close(fd)


@contextlib.contextmanager
def _scratch_cwd() -> Iterator[None]:
    """Some models carry <output> directives, and JSBSim opens their CSV files
    in the working directory at run_ic (disable_output does not stop it): run
    the model in a temporary directory, removed afterwards."""
    import tempfile
    here = os.getcwd()
    with tempfile.TemporaryDirectory(prefix="ht_aircraft_") as tmp:
        os.chdir(tmp)
        try:
            yield
        finally:
            os.chdir(here)


def trim_sweep(info: ModelInfo, altitude_m: float = DEFAULT_ALTITUDE_M,
               speeds: tuple[float, ...] = TRIM_SPEEDS_M_S) -> None:
    """Trim the model straight and level at each speed; fills trims_at and
    trim_error (JSBSim's message at the first speed that failed)."""
    import jsbsim
    for v in speeds:
        with _quiet(), _scratch_cwd():
            try:
                fdm = jsbsim.FGFDMExec(None)
                fdm.set_debug_level(0)
                if not fdm.load_model(info.name):
                    info.trim_error = "JSBSim could not load the model"
                    return
                fdm["ic/h-sl-ft"] = altitude_m / FT
                fdm["ic/vt-fps"] = v / FT
                fdm["ic/gamma-deg"] = 0.0
                ok, err = bool(fdm.run_ic()), "run_ic failed"
                if ok:
                    fdm["propulsion/set-running"] = -1
                    fdm["simulation/do_simple_trim"] = 1
            except Exception as e:  # jsbsim.TrimFailureError, LogExceptionError and kin
                ok, err = False, str(e).strip() or type(e).__name__
        if ok:
            info.trims_at.append(v)
        elif not info.trim_error:
            info.trim_error = f"{err} (at {v:g} m/s)"


def _trimmed(args: tuple[ModelInfo, float]) -> ModelInfo:
    info, altitude_m = args
    trim_sweep(info, altitude_m)
    return info


def list_models(altitude_m: float = DEFAULT_ALTITUDE_M, root: Path | None = None,
                progress: Callable[[int, int, str], None] | None = None,
                include_all: bool = False, jobs: int = 1) -> list[ModelInfo]:
    """The fixed-wing models with an engine (all models with include_all),
    each trimmed over the sweep, on jobs processes."""
    models = find_models(root)
    flyable = [m for m in models if m.fixed_wing]
    done: dict[str, ModelInfo] = {}
    if jobs <= 1:
        for i, m in enumerate(flyable):
            if progress is not None:
                progress(i, len(flyable), m.name)
            done[m.name] = _trimmed((m, altitude_m))
    else:
        from concurrent.futures import ProcessPoolExecutor, as_completed
        with ProcessPoolExecutor(max_workers=jobs) as ex:
            futs = [ex.submit(_trimmed, (m, altitude_m)) for m in flyable]
            for i, f in enumerate(as_completed(futs)):
                r = f.result()
                done[r.name] = r
                if progress is not None:
                    progress(i + 1, len(flyable), r.name)
    if progress is not None and jobs <= 1:
        progress(len(flyable), len(flyable), "done")
    out = [done.get(m.name, m) for m in models]
    return out if include_all else [m for m in out if m.fixed_wing]


def explain(m: ModelInfo) -> str:
    """What a user should know about a model's trim, in one line."""
    if not m.fixed_wing:
        return m.why_not
    if m.trims:
        return ""
    if "does not exist" in m.trim_error:
        return (f"needs a property JSBSim alone does not define ({m.trim_error}); a "
                "FlightGear-only model")
    why = m.trim_error.split(" (at ")[0]
    return (f"JSBSim: \"{why}\" at every speed of the sweep; fly it with [initial] trim = "
            "false (released at the initial speed untrimmed)")


# --- aircraft new: a starter aircraft file from JSBSim's own trims -------------

# The starter gains: the c172p's tuned set (sil/scenarios/aircraft/c172p.toml),
# which also flew a light taildragger's turns (issue 16), with the roll axis
# scaled by the model's roll authority against the c172p's (below).
STARTER_GAINS: dict[str, float] = {
    "kp_aileron": 5.0, "kp_elevator": 6.0, "kp_rudder": 0.3,
    "kd_aileron": 0.7, "kd_elevator": 1.0, "kd_rudder": 1.0,
    "kff_aileron": 0.0, "kff_elevator": 1.0, "kff_rudder": 0.5,
    "alt_kp": 0.02, "alt_ki": 0.004, "alt_kd": 0.04, "alt_max_pitch": 0.25,
    "alt_max_integral": 0.2, "spd_kp": 0.08, "spd_ki": 0.02, "spd_kff_pitch": 1.5,
}
# The c172p's roll rate after 1 s of full aileron from a trim at 50 m/s, 1500 m
# (roll_authority("c172p", 50.0) = 0.870 with jsbsim 1.3.3; its tuned gains
# fly at 50 m/s), the reference the starter roll gains are scaled against.
C172P_ROLL_RATE_RAD_S = 0.87
# a model's own stability augmentation, as its flight-control channels name it
_SAS = re.compile(r"yaw[ _-]?damper|\bSAS\b|stability augmentation", re.IGNORECASE)
# the starter v_ref: the fastest trimmed speed at no more than cruise power
CRUISE_THROTTLE = 0.75


@dataclass
class TrimPoint:
    speed_m_s: float
    throttle: float
    elevator: float
    alpha_deg: float


def _trimmed_fdm(model: str, v: float, altitude_m: float) -> Any:
    """A JSBSim instance trimmed straight and level at v, or raises with
    JSBSim's message. Run inside _quiet() and _scratch_cwd()."""
    import jsbsim
    fdm = jsbsim.FGFDMExec(None)
    fdm.set_debug_level(0)
    if not fdm.load_model(model):
        raise RuntimeError(f"JSBSim could not load model {model!r}")
    fdm["ic/h-sl-ft"] = altitude_m / FT
    fdm["ic/vt-fps"] = v / FT
    fdm["ic/gamma-deg"] = 0.0
    if not fdm.run_ic():
        raise RuntimeError("run_ic failed")
    fdm["propulsion/set-running"] = -1
    fdm["simulation/do_simple_trim"] = 1
    return fdm


def trim_points(model: str, altitude_m: float = DEFAULT_ALTITUDE_M, lo: float = 15.0,
                hi: float = 260.0, ratio: float = 1.12) -> tuple[list[TrimPoint], str]:
    """JSBSim's straight, level trims over a geometric speed sweep: the points
    that trimmed, and JSBSim's message where it did not (the first one)."""
    pts: list[TrimPoint] = []
    err = ""
    v = lo
    while v <= hi:
        with _quiet(), _scratch_cwd():
            try:
                fdm = _trimmed_fdm(model, v, altitude_m)
                pts.append(TrimPoint(v, float(fdm["fcs/throttle-cmd-norm[0]"]),
                                     float(fdm["fcs/elevator-pos-norm"]),
                                     float(fdm["aero/alpha-deg"])))
            except Exception as e:  # jsbsim's trim and property errors
                if not err:
                    err = f"{str(e).strip() or type(e).__name__} (at {v:.0f} m/s)"
        v *= ratio
    return pts, err


def roll_authority(model: str, v: float, altitude_m: float = DEFAULT_ALTITUDE_M) -> float:
    """The roll rate (rad/s) one second after full right aileron from a trim
    at v: what the aileron can do, which the starter roll gains follow."""
    with _quiet(), _scratch_cwd():
        fdm = _trimmed_fdm(model, v, altitude_m)
        fdm["fcs/aileron-cmd-norm"] = 1.0
        t_end = fdm["simulation/sim-time-sec"] + 1.0
        while fdm["simulation/sim-time-sec"] < t_end:
            fdm.run()
        return abs(float(fdm["velocities/p-rad_sec"]))


# each surface: the command, and the position properties a JSBSim FCS writes
SURFACES = (("aileron", "fcs/aileron-cmd-norm", ("fcs/left-aileron-pos-rad",
                                                 "fcs/right-aileron-pos-rad")),
            ("elevator", "fcs/elevator-cmd-norm", ("fcs/elevator-pos-rad",)),
            ("rudder", "fcs/rudder-cmd-norm", ("fcs/rudder-pos-rad",)))


def surface_travel_deg(model: str, v: float, altitude_m: float = DEFAULT_ALTITUDE_M
                       ) -> dict[str, float | None]:
    """Each surface's deflection at full positive command (deg, 0.5 s after
    the step from the trim at v), or None when the model's FCS does not
    write the standard position property."""
    out: dict[str, float | None] = {}
    for name, cmd, props in SURFACES:
        with _quiet(), _scratch_cwd():
            fdm = _trimmed_fdm(model, v, altitude_m)
            fdm[cmd] = 1.0
            t_end = fdm["simulation/sim-time-sec"] + 0.5
            while fdm["simulation/sim-time-sec"] < t_end:
                fdm.run()
            vals = []
            for prop in props:
                try:
                    vals.append(abs(float(fdm[prop])))
                except Exception:  # the model does not define it
                    pass
        out[name] = round(math.degrees(max(vals)), 1) if vals and max(vals) > 0.0 else None
    return out


def stability_augmentation(info: ModelInfo) -> str:
    """The model's own damper or SAS, as named in its XML (the model's file
    and the system files beside it), or ""."""
    for f in [info.path, *sorted(info.path.parent.glob("Systems/*.xml"))]:
        try:
            m = _SAS.search(f.read_text(encoding="utf-8", errors="replace"))
        except OSError:
            continue
        if m:
            return f"{m.group(0)} ({f.relative_to(info.path.parent)})"
    return ""


def alpha_limit_deg(info: ModelInfo) -> float | None:
    """The model's own stall angle of attack (<aerodynamics><alphalimits><max>),
    in degrees, or None when it states none."""
    try:
        el = ET.parse(info.path).getroot().find("aerodynamics/alphalimits")
    except (ET.ParseError, OSError):
        return None
    mx = None if el is None else el.find("max")
    if mx is None or mx.text is None:
        return None
    v = float(mx.text)
    return v if el.get("unit", "RAD").upper() == "DEG" else math.degrees(v)


def starter(model: str, altitude_m: float = DEFAULT_ALTITUDE_M) -> dict[str, Any]:
    """Everything a starter aircraft file says, measured: the trim sweep, the
    suggested v_ref and v_min, the trim throttle, the roll authority, the
    scaled gains, and the notes (no trim; the model's own SAS)."""
    info = next((m for m in find_models() if m.name == model), None)
    if info is None:
        raise ValueError(f"no JSBSim model {model!r} in {models_root()}")
    if not info.fixed_wing:
        raise ValueError(f"{model} is not flyable here: {info.why_not}")
    pts, err = trim_points(model, altitude_m)
    out: dict[str, Any] = {"model": model, "altitude_m": altitude_m, "points": pts,
                           "trim_error": err, "sas": stability_augmentation(info)}
    if not pts:
        return out
    at_cruise = [p for p in pts if p.throttle <= CRUISE_THROTTLE]
    cruise = at_cruise[-1] if at_cruise else pts[0]
    v_ref = round(cruise.speed_m_s, 1)
    v_min = round(max(pts[0].speed_m_s, v_ref / 32.0, 1.0), 1)
    try:
        p = roll_authority(model, v_ref, altitude_m)
    except Exception:  # JSBSim did not trim again at v_ref: no measurement
        p = 0.0
    scale = min(4.0, max(0.25, C172P_ROLL_RATE_RAD_S / p)) if p > 0.0 else 1.0
    gains = dict(STARTER_GAINS)
    for k in ("kp_aileron", "kd_aileron"):
        gains[k] = round(gains[k] * scale, 3)
    alpha_max = alpha_limit_deg(info)
    try:
        out["travel_deg"] = surface_travel_deg(model, v_ref, altitude_m)
    except Exception:  # JSBSim did not trim again at v_ref: no measurement
        out["travel_deg"] = {name: None for name, _c, _p in SURFACES}
    out.update(v_ref=v_ref, v_min=v_min, throttle=cruise.throttle, roll_rate=p,
               roll_scale=scale, gains=gains,
               stall_alpha_deg=round(alpha_max if alpha_max is not None
                                     else max(q.alpha_deg for q in pts), 1),
               stall_alpha_source="the model's <alphalimits>" if alpha_max is not None
               else "the highest trimmed alpha",
               max_airspeed_m_s=round(pts[-1].speed_m_s, 1))
    return out


def starter_toml(s: dict[str, Any]) -> str:
    """The aircraft file of starter(): TOML the scenario loader takes."""
    lines = [f"# Starter aircraft file for JSBSim's {s['model']}, written by "
             f"`python -m helical_sil aircraft new {s['model']}`.",
             f"# JSBSim's straight, level trims at {s['altitude_m']:g} m:"]
    for p in s["points"]:
        lines.append(f"#   {p.speed_m_s:6.1f} m/s: throttle {p.throttle:.2f}, elevator "
                     f"{p.elevator:+.3f} (JSBSim's sign), alpha {p.alpha_deg:+.1f} deg")
    if s["trim_error"] and s["points"]:
        lines.append(f"# not trimmed elsewhere; JSBSim said: {s['trim_error']}")
    if s["sas"]:
        lines.append(f"# NOTE: the model has its own stability augmentation: {s['sas']}. "
                     "It acts on the")
        lines.append("# surfaces beside the law (a yaw damper fights a coordinated turn): "
                     "check the turn rate")
        lines.append("# error and the sideslip, and tune (python -m helical_sil tune) before "
                     "trusting the gains.")
    if not s["points"]:
        why = s["trim_error"].split(" (at ")[0]
        lines += [f'# NO TRIM: JSBSim trims this model at no speed of the sweep ("{why}"). Fly '
                  "it with",
                  "# [initial] trim = false in the scenario: it is released untrimmed at the",
                  "# initial speed, and the holds must find the throttle and pitch "
                  "themselves.",
                  f'model = "{s["model"]}"', "", "[gains]",
                  "v_ref = 50.0  # a guess: no trimmed speed to take it from"]
        return "\n".join(lines) + "\n"
    lines += [f"# v_ref: the fastest trimmed speed at <= {CRUISE_THROTTLE:g} throttle (cruise "
              "power); v_min: the lowest trimmed speed",
              f"# roll authority at v_ref: {s['roll_rate']:.2f} rad/s after 1 s of full aileron "
              f"(c172p {C172P_ROLL_RATE_RAD_S:g}); roll gains x {s['roll_scale']:.2f}",
              "# surface travel at full command (deg; - = not written by the model's FCS): "
              + ", ".join(f"{k} {'-' if v is None else f'{v:g}'}"
                          for k, v in s["travel_deg"].items()),
              "# Starter gains: the c172p's tuned set, the roll axis scaled. Tune before "
              "flying anything real.",
              f'model = "{s["model"]}"',
              f'description = "JSBSim {s["model"]} (starter file)"', "",
              "[initial]", f"altitude_m = {s['altitude_m']:g}",
              f"airspeed_m_s = {s['v_ref']:g}", "", "[gains]",
              f"v_ref = {s['v_ref']:g}", f"v_min = {s['v_min']:g}",
              f"throttle_trim = {s['throttle']:.3f}  # JSBSim's trim at v_ref"]
    lines += [f"{k} = {v:g}" for k, v in s["gains"].items()]
    lines += ["", "# What a run is checked against (metrics: run.envelope): the stall angle of "
              f"attack ({s['stall_alpha_source']})", "# and the fastest level trim of the sweep.",
              "[envelope]"]
    if 1.0 <= s["stall_alpha_deg"] <= 45.0:
        lines.append(f"stall_alpha_deg = {s['stall_alpha_deg']:g}")
    else:  # a model that trims at a negative or extreme alpha: no stall limit from it
        lines.append(f"# stall_alpha_deg: {s['stall_alpha_deg']:g} is outside [1, 45]; not set")
    lines.append(f"max_airspeed_m_s = {min(s['max_airspeed_m_s'], 400.0):g}")
    return "\n".join(lines) + "\n"
