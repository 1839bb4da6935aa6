"""The parameter table (include/helical/params.def), read by the harness.

The C side expands the same file with the preprocessor; this module parses its
rows, so the SIL configuration (sim/board.py), the scenario loader's bounds and
defaults (scenario.py, sim/lockstep.py) and the HIL configuration frames (live/pil.py) all
follow the one declaration. sil/tests/test_params.py compares this view with
the table compiled into the board library (names, units, formats, stored
bounds and defaults), so the two readers cannot drift apart.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

DEF_PATH = Path(__file__).resolve().parents[3] / "include" / "helical" / "params.def"


@dataclass(frozen=True)
class Format:
    name: str       # as messages show it (HT_PFMT_NAME_*)
    scale: float    # stored = round(value * scale)
    nbytes: int     # on the HIL link, little-endian
    lo: int         # the C type's range
    hi: int
    signed: bool


FORMATS: dict[str, Format] = {
    "Q16": Format("Q16", 65536.0, 4, -(2 ** 31), 2 ** 31 - 1, True),
    "CM32": Format("int32 x100", 100.0, 4, -(2 ** 31), 2 ** 31 - 1, True),
    "CM16": Format("int16 x100", 100.0, 2, -(2 ** 15), 2 ** 15 - 1, True),
    "U8": Format("uint8", 1.0, 1, 0, 255, False),
    "U16": Format("uint16", 1.0, 2, 0, 65535, False),
    "Q14": Format("Q14", 16384.0, 2, -(2 ** 15), 2 ** 15 - 1, True),
    "MS16": Format("uint16 x1000", 1000.0, 2, 0, 65535, False),
    "I16": Format("int16", 1.0, 2, -(2 ** 15), 2 ** 15 - 1, True),
    "I32": Format("int32", 1.0, 4, -(2 ** 31), 2 ** 31 - 1, True),
}


def _round_half_away(x: float) -> int:
    """C's llround and HT_PARAM_RAW: to nearest, halves away from zero."""
    a = abs(x)
    f = math.floor(a)
    r = int(f + 1 if a - f >= 0.5 else f)
    return r if x >= 0 else -r


@dataclass(frozen=True)
class Param:
    group: str       # "LAW", "DCM", "GUIDE", "ALT", "SPEED", "MODES", "FBW", "NAV", "AOA"
    index: int       # 0-based row in its group (the id is index + 1)
    id: str          # HT_P_<id> / HT_DCM_P_<id>
    name: str
    c_field: str
    unit: str
    fmt: Format
    fmt_key: str     # Q16, CM32, ...
    min: float       # in the unit
    max: float
    default: float
    description: str

    def raw(self, value: float) -> int:
        """The stored integer of an engineering value (HT_PARAM_RAW)."""
        return _round_half_away(value * self.fmt.scale)

    @property
    def min_raw(self) -> int:
        return self.raw(self.min)

    @property
    def max_raw(self) -> int:
        return self.raw(self.max)

    @property
    def default_raw(self) -> int:
        return self.raw(self.default)

    def bounds_text(self) -> str:
        """'[0, 64] (per unit error, Q16)': the bounds and how it is stored."""
        return f"[{self.min:g}, {self.max:g}] ({self.unit}, {self.fmt.name})"

    def check(self, value: float) -> str | None:
        """None when the value is legal by its own row; else why not."""
        if not math.isfinite(value):
            return "is not finite"
        if value < self.min or value > self.max:
            return f"is outside {self.bounds_text()}"
        if self.fmt.scale == 1.0 and value != math.floor(value):
            return f"is not a whole number ({self.unit}, {self.fmt.name})"
        return None


_ROW = re.compile(r"^\s*X\((?P<args>.*)\)\s*\\?\s*$")
_LIST = re.compile(r"^#define\s+HT_PARAMS_(?P<group>[A-Z0-9_]+)\(X\)")
_NUMBER = re.compile(r"^-?[0-9]+(\.[0-9]+)?$")


class TableError(ValueError):
    """params.def does not follow its own rules (see its header)."""


def _split(args: str, where: str) -> list[str]:
    out, cur, quoted = [], "", False
    for ch in args:
        if ch == '"':
            quoted = not quoted
            cur += ch
        elif ch == "," and not quoted:
            out.append(cur.strip())
            cur = ""
        else:
            cur += ch
    if quoted:
        raise TableError(f"{where}: unterminated string")
    out.append(cur.strip())
    return out


def _string(tok: str, where: str) -> str:
    if len(tok) < 2 or tok[0] != '"' or tok[-1] != '"' or '"' in tok[1:-1] or "\\" in tok:
        raise TableError(f"{where}: expected a plain string literal, got {tok!r}")
    return tok[1:-1]


def _number(tok: str, where: str) -> float:
    if not _NUMBER.match(tok):
        raise TableError(f"{where}: min, max and default are plain decimal numbers, got {tok!r}")
    return float(tok)


def parse(text: str) -> list[Param]:
    """Every row of the table, in file order (groups in their own order)."""
    params: list[Param] = []
    group: str | None = None
    counts: dict[str, int] = {}
    for n, line in enumerate(text.splitlines(), 1):
        where = f"params.def:{n}"
        m = _LIST.match(line)
        if m:
            group = m.group("group")
            counts.setdefault(group, 0)
            continue
        r = _ROW.match(line)
        if r is None:
            if group is not None and not line.rstrip().endswith("\\"):
                group = None  # the list ended (its last row has no continuation)
            continue
        if group is None:
            raise TableError(f"{where}: a row outside an HT_PARAMS_<GROUP>(X) list")
        a = _split(r.group("args"), where)
        if len(a) != 9:
            raise TableError(f"{where}: a row has 9 columns, this one {len(a)}")
        pid, name, field, unit, fmt, lo, hi, dflt, desc = a
        if fmt not in FORMATS:
            raise TableError(f"{where}: unknown format {fmt!r} (known: {', '.join(FORMATS)})")
        for tok in (pid, name, field):
            if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", tok):
                raise TableError(f"{where}: {tok!r} is not an identifier")
        p = Param(group, counts[group], pid, name, field, _string(unit, where), FORMATS[fmt], fmt,
                  _number(lo, where), _number(hi, where), _number(dflt, where),
                  _string(desc, where))
        if not p.min <= p.default <= p.max:
            raise TableError(f"{where}: default {p.default:g} outside [{p.min:g}, {p.max:g}]")
        if not (p.fmt.lo <= p.min_raw and p.max_raw <= p.fmt.hi):
            raise TableError(f"{where}: [{p.min:g}, {p.max:g}] does not fit {fmt}")
        counts[group] += 1
        params.append(p)
        if not line.rstrip().endswith("\\"):
            group = None
    names = [p.group + "." + p.name for p in params]
    if len(set(names)) != len(names):
        raise TableError("params.def: a name appears twice in one group")
    return params


def load(path: Path = DEF_PATH) -> list[Param]:
    return parse(path.read_text(encoding="utf-8"))


TABLE: list[Param] = load()
LAW: tuple[Param, ...] = tuple(p for p in TABLE if p.group == "LAW")
ESTIMATOR: tuple[Param, ...] = tuple(p for p in TABLE if p.group == "DCM")
GUIDANCE: tuple[Param, ...] = tuple(p for p in TABLE if p.group == "GUIDE")
LAW_BY_NAME: dict[str, Param] = {p.name: p for p in LAW}
ESTIMATOR_BY_NAME: dict[str, Param] = {p.name: p for p in ESTIMATOR}
GUIDANCE_BY_NAME: dict[str, Param] = {p.name: p for p in GUIDANCE}
ALT_HOLD: tuple[Param, ...] = tuple(p for p in TABLE if p.group == "ALT")
SPEED_HOLD: tuple[Param, ...] = tuple(p for p in TABLE if p.group == "SPEED")
HOLDS: tuple[Param, ...] = ALT_HOLD + SPEED_HOLD
HOLDS_BY_NAME: dict[str, Param] = {p.name: p for p in HOLDS}
MODES: tuple[Param, ...] = tuple(p for p in TABLE if p.group == "MODES")
FBW: tuple[Param, ...] = tuple(p for p in TABLE if p.group == "FBW")
NAV: tuple[Param, ...] = tuple(p for p in TABLE if p.group == "NAV")
AOA: tuple[Param, ...] = tuple(p for p in TABLE if p.group == "AOA")
# the flight modes' groups by their scenario table ([modes], [fbw], [nav], [aoa])
MODE_GROUPS: dict[str, dict[str, Param]] = {
    "modes": {p.name: p for p in MODES}, "fbw": {p.name: p for p in FBW},
    "nav": {p.name: p for p in NAV}, "aoa": {p.name: p for p in AOA}}

# The board configuration's groups (sil_config_t's arrays, SIL_GROUP_* order):
# the key of each in a board config dict, the C side's group name, the rows.
BOARD_GROUPS: tuple[tuple[str, str, tuple[Param, ...]], ...] = (
    ("law", "LAW", LAW), ("estimator", "DCM", ESTIMATOR), ("guidance", "GUIDE", GUIDANCE),
    ("alt_hold", "ALT", ALT_HOLD), ("speed_hold", "SPEED", SPEED_HOLD),
    ("modes", "MODES", MODES), ("fbw", "FBW", FBW), ("nav", "NAV", NAV), ("aoa", "AOA", AOA))


def law_defaults() -> dict[str, float]:
    """The law's defaults, in the table's units (its default column)."""
    return {p.name: p.default for p in LAW}


def estimator_defaults() -> dict[str, float]:
    return {p.name: p.default for p in ESTIMATOR}


def guidance_defaults() -> dict[str, float]:
    return {p.name: p.default for p in GUIDANCE}


def payload(params: tuple[Param, ...], values: dict[str, float]) -> bytes:
    """A HIL configuration payload: each row in order, its value (table
    units, absent = the default) converted as the SIL board converts it
    (round half away from zero, saturated to the type), little-endian."""
    out = b""
    for p in params:
        v = float(values.get(p.name, p.default))
        if v != v:
            raw = 0
        else:
            s = v * p.fmt.scale
            raw = p.fmt.lo if s <= p.fmt.lo else (p.fmt.hi if s >= p.fmt.hi else
                                                 _round_half_away(s))
        out += raw.to_bytes(p.fmt.nbytes, "little", signed=p.fmt.signed)
    return out


def payload_length(params: tuple[Param, ...]) -> int:
    return sum(p.fmt.nbytes for p in params)
