"""The standard plots of a run (analysis/plots.py: attitude, turn rate,
altitude, surfaces, ground track) drawn from a flight log alone, board or
SIL: `python -m helical_sil plot LOG`. A log holds the firmware's view (the
estimate, the law's command, the sensors), not JSBSim's truth, so "actual"
here is what the firmware measured and estimated."""

from __future__ import annotations

import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from helical_sil.analysis.log_read import read_log  # noqa: E402

LOG_PLOT_FILES = ("attitude.png", "turn_rate.png", "altitude.png", "surfaces.png",
                  "ground_track.png")
EARTH_RADIUS_M = 6371000.0


def _unwrapped_deg(rad: np.ndarray) -> np.ndarray:
    """An angle through +-180 (or 0/360) drawn as a continuous line."""
    return np.degrees(np.unwrap(rad))


def _roll_pitch(x: np.ndarray, y: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Bank and pitch (rad) of a body-frame down vector (X left wing, Y
    forward, Z down): a right bank tips the down vector to the right wing
    (-X), nose up tips it to the tail (-Y)."""
    n = np.sqrt(x * x + y * y + z * z)
    n[n == 0.0] = 1.0
    return np.arctan2(-x, z), np.arcsin(np.clip(-y / n, -1.0, 1.0))


def plot_log(path: str | os.PathLike[str], out: str | os.PathLike[str]) -> list[Path]:
    """Write LOG_PLOT_FILES into out (created); returns their paths."""
    d = read_log(path)
    out_p = Path(out)
    out_p.mkdir(parents=True, exist_ok=True)
    att, hin, hto, ctrl = d["ATT"], d["HTIN"], d["HTO"], d["CTRL"]
    t = hto["t_s"]
    figs: dict[str, plt.Figure] = {}

    fig, axs = plt.subplots(3, 1, sharex=True, figsize=(9, 7))
    roll_cmd, pitch_cmd = _roll_pitch(hto["TX"], hto["TY"], hto["TZ"])
    roll, pitch = _roll_pitch(hin["X"], hin["Y"], hin["Z"])
    axs[0].plot(t, _unwrapped_deg(roll), lw=1, label="flown (the law's input)")
    axs[0].plot(t, _unwrapped_deg(roll_cmd), lw=1, ls="--", label="command (target tilt)")
    axs[0].set_ylabel("bank (deg, unwrapped)")
    axs[1].plot(t, np.degrees(pitch), lw=1, label="flown")
    axs[1].plot(t, np.degrees(pitch_cmd), lw=1, ls="--", label="command (target tilt)")
    axs[1].set_ylabel("pitch (deg)")
    axs[2].plot(att["t_s"], _unwrapped_deg(np.radians(att["Yaw"])), lw=1, label="estimate")
    axs[2].set_ylabel("heading (deg, unwrapped)")
    axs[2].set_xlabel("time (s)")
    for ax in axs:
        ax.legend(loc="upper right", fontsize=8)
        ax.grid(True, alpha=0.3)
    figs["attitude.png"] = fig

    fig, ax = plt.subplots(figsize=(9, 4))
    # the rate about the earth vertical: the body rates along the down vector
    n = np.sqrt(hin["X"] ** 2 + hin["Y"] ** 2 + hin["Z"] ** 2)
    n[n == 0.0] = 1.0
    turn = (hin["GX"] * hin["X"] + hin["GY"] * hin["Y"] + hin["GZ"] * hin["Z"]) / n
    ax.plot(t, np.degrees(turn), lw=1, label="measured (gyros along the down vector)")
    ax.plot(t, np.degrees(hin["Turn"]), lw=1.2, ls="--", label="command")
    ax.plot(t, np.degrees(hto["TrnU"]), lw=0.8, ls=":", label="used by the law (tilt limit)")
    ax.set_ylabel("turn rate (deg/s, + right)")
    ax.set_xlabel("time (s)")
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(True, alpha=0.3)
    figs["turn_rate.png"] = fig

    fig, axs = plt.subplots(2, 1, sharex=True, figsize=(9, 6))
    if "BARO" in d:
        axs[0].plot(d["BARO"]["t_s"], d["BARO"]["Alt"], lw=1, label="baro")
    if "GPS" in d:
        axs[0].plot(d["GPS"]["t_s"], d["GPS"]["Alt"], lw=0.8, ls=":", label="GPS")
    axs[0].set_ylabel("altitude (m MSL)")
    axs[1].plot(t, hin["Asp"], lw=1, label="airspeed the law used")
    if "ARSP" in d:
        axs[1].plot(d["ARSP"]["t_s"], d["ARSP"]["Airspeed"], lw=0.8, ls=":", label="pitot")
    axs[1].set_ylabel("airspeed (m/s)")
    axs[1].set_xlabel("time (s)")
    for ax in axs:
        ax.legend(loc="upper right", fontsize=8)
        ax.grid(True, alpha=0.3)
    figs["altitude.png"] = fig

    fig, axs = plt.subplots(5, 1, sharex=True, figsize=(9, 9))
    for ax, (k, label) in zip(axs, (("Ail", "aileron"), ("Elv", "elevator"), ("Rud", "rudder"))):
        ax.plot(t, hto[k], lw=1, label="law")
        ax.set_ylabel(f"{label} [-1, 1]")
    axs[3].plot(ctrl["t_s"], ctrl["Thr"], lw=1, label="throttle")
    axs[3].set_ylabel("throttle [0, 1]")
    if "RCOU" in d:
        for c in ("C1", "C2", "C3", "C4"):
            axs[4].plot(d["RCOU"]["t_s"], d["RCOU"][c], lw=0.8, label=c)
    axs[4].set_ylabel("pulse (us)")
    axs[4].set_xlabel("time (s)")
    for ax in axs:
        ax.legend(loc="upper right", fontsize=7)
        ax.grid(True, alpha=0.3)
    figs["surfaces.png"] = fig

    fig, ax = plt.subplots(figsize=(7, 7))
    if "GPS" in d and (d["GPS"]["Status"] >= 3).any():
        g = d["GPS"]
        fix = g["Status"] >= 3
        lat0, lon0 = g["Lat"][fix][0], g["Lng"][fix][0]
        north = np.radians(g["Lat"][fix] - lat0) * EARTH_RADIUS_M
        east = np.radians(g["Lng"][fix] - lon0) * EARTH_RADIUS_M * np.cos(np.radians(lat0))
        sc = ax.scatter(east, north, c=g["Alt"][fix], s=2, cmap="viridis")
        fig.colorbar(sc, ax=ax, label="GPS altitude (m)")
        ax.plot(east[:1], north[:1], "k^", label="first fix")
        ax.legend(loc="upper right", fontsize=8)
    else:
        ax.text(0.5, 0.5, "no 3-D GPS fix in the log", ha="center", transform=ax.transAxes)
    ax.set_xlabel("east (m)")
    ax.set_ylabel("north (m)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    figs["ground_track.png"] = fig

    files: list[Path] = []
    try:
        for name, f in figs.items():
            f.suptitle(Path(path).name)
            f.tight_layout()
            p = out_p / name
            f.savefig(p, dpi=90, metadata={"Software": None})
            files.append(p)
    finally:
        for f in figs.values():
            plt.close(f)
    return files
