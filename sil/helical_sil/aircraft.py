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
import os
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Iterator

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
