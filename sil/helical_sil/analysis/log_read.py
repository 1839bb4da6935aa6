"""A DataFlash flight log (.bin, docs/flight-log.md) read with pymavlink's
DFReader into arrays in physical units: the one place that knows each raw
field's fixed-point format (the writer's table, firmware/log/log_df.c)."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
from pymavlink import DFReader

# Fields logged raw, and the counts per unit of docs/flight-log.md (divided,
# so that a decimal scale gives the nearest double: 1523 / 100, not 1523 * 0.01).
# Fields not listed are as DFReader gives them (its own scales: 'c' and 'e'
# are already divided by 100, 'L' by 1e7).
SCALES: dict[str, dict[str, float]] = {
    "IMU": {"GyrX": 2.0**16, "GyrY": 2.0**16, "GyrZ": 2.0**16,
            "AccX": 2.0**16, "AccY": 2.0**16, "AccZ": 2.0**16},
    "ATT": {"DX": 2.0**14, "DY": 2.0**14, "DZ": 2.0**14},
    "HTIN": {"X": 2.0**14, "Y": 2.0**14, "Z": 2.0**14, "Turn": 2.0**11,
             "Pitch": 2.0**16, "Asp": 100.0, "GX": 2.0**11, "GY": 2.0**11, "GZ": 2.0**11,
             "TAcc": 2.0**11, "ALat": 2.0**14},
    "HTO": {"TrnU": 2.0**11, "Tilt": 2.0**16, "TX": 2.0**14, "TY": 2.0**14,
            "TZ": 2.0**14, "REr": 2.0**14, "PEr": 2.0**14, "Ail": 2.0**14,
            "Elv": 2.0**14, "Rud": 2.0**14, "RIn": 2.0**11, "Fade": 2.0**14,
            "Slip": 2.0**14},
    "CTRL": {"PCmd": 2.0**16, "Thr": 2.0**14},
}


class LogError(ValueError):
    """A file that is not a DataFlash log of this writer (the message says why)."""


def read_log(path: str | os.PathLike[str]) -> dict[str, dict[str, np.ndarray]]:
    """Every record type of the log: field -> array, in physical units, and
    "t_s" (TimeUS in seconds). PARM is left out (read_params)."""
    p = Path(path)
    if not p.is_file():
        raise LogError(f"{p}: no such file")
    if p.stat().st_size < 3 or p.read_bytes()[:3] != b"\xa3\x95\x80":
        raise LogError(f"{p}: not a DataFlash .bin log (it does not start with a FMT record)")
    log = DFReader.DFReader_binary(str(p), zero_time_base=True)
    rows: dict[str, list[list[float]]] = {}
    names: dict[str, list[str]] = {}
    while True:
        m = log.recv_msg()
        if m is None:
            break
        kind = m.get_type()
        if kind in ("FMT", "PARM", "MSG", "FMTU", "UNIT", "MULT"):
            continue
        fields = [f for f in m.get_fieldnames() if not isinstance(getattr(m, f), (str, bytes))]
        names.setdefault(kind, fields)
        rows.setdefault(kind, []).append([float(getattr(m, f)) for f in names[kind]])
    out: dict[str, dict[str, np.ndarray]] = {}
    for kind, data in rows.items():
        arr = np.asarray(data, dtype=np.float64)
        rec = {f: arr[:, i] / SCALES.get(kind, {}).get(f, 1.0) for i, f in enumerate(names[kind])}
        if "TimeUS" in rec:
            rec["t_s"] = rec["TimeUS"] * 1e-6
        out[kind] = rec
    if "HTO" not in out:
        raise LogError(f"{p}: no HTO records (not a helical flight log, or empty)")
    return out


def read_params(path: str | os.PathLike[str]) -> dict[str, float]:
    """The PARM records: name -> value (the last one of a name)."""
    log = DFReader.DFReader_binary(str(path), zero_time_base=True)
    out: dict[str, float] = {}
    while True:
        m = log.recv_match(type="PARM")
        if m is None:
            return out
        out[str(m.Name)] = float(m.Value)
