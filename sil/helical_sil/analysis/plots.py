"""PNG plots of a run: attitude, turn rate vs command, altitude, surfaces,
ground track.

The number of artists does not grow with the number of commands: segment
boundaries are one LineCollection per axis (and left out beyond
MAX_SEGMENT_MARKS, where they would be a grey band), and the ground track's
scatter is decimated to MAX_SCATTER_POINTS. A 10 000-command scenario once
made 100 000 axvline artists (61 s, 709 MB of plotting)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


from helical_sil.sim.lockstep import RunResult  # noqa: E402

PLOT_FILES = ("attitude.png", "turn_rate.png", "altitude.png", "surfaces.png",
              "ground_track.png")
# More boundaries than this in a plot about 800 pixels wide would be closer
# than 4 pixels apart: they are left out and a note says how many there are.
MAX_SEGMENT_MARKS = 200
# The ground track colours every point by altitude; beyond this many points
# (1000 s at 40 Hz) every k-th point is drawn, which a 6-inch plot cannot tell.
MAX_SCATTER_POINTS = 40000


def _break_wraps(values: np.ndarray) -> np.ndarray:
    """An angle in degrees with NaN where it wraps (a jump over 180 deg), so
    that a bank near +-180 or a heading through north is not drawn as a
    vertical line across the plot."""
    v = np.asarray(values, dtype=float).copy()
    jumps = np.abs(np.diff(v)) > 180.0
    v[1:][jumps] = np.nan
    return v


def _marks(ax: plt.Axes, res: RunResult) -> None:
    """The segment boundaries: one artist, however many segments."""
    ts = [s.t0 for s in res.segments[1:]]
    if not ts:
        return
    if len(ts) > MAX_SEGMENT_MARKS:
        ax.text(0.99, 0.02, f"{len(ts) + 1} segments (boundaries not drawn)",
                transform=ax.transAxes, ha="right", va="bottom", fontsize=7, color="0.3",
                bbox={"facecolor": "white", "alpha": 0.8, "edgecolor": "none", "pad": 1})
        return
    ax.vlines(ts, 0.0, 1.0, transform=ax.get_xaxis_transform(), colors="0.7", lw=0.8,
              linestyles=":")


def _every(n: int, limit: int) -> slice:
    """A slice keeping at most limit of n points, evenly spaced."""
    return slice(None, None, max(1, -(-n // limit)))


def build_figures(res: RunResult) -> dict[str, plt.Figure]:
    """The figures of write_plots, by file name (the caller closes them)."""
    figs: dict[str, plt.Figure] = {}
    try:
        _build(res, figs)
    except BaseException:
        for f in figs.values():
            plt.close(f)
        raise
    return figs


def write_plots(res: RunResult, out: Path) -> list[Path]:
    title = f"{res.scenario.name} ({res.scenario.aircraft.name})"
    files: list[Path] = []
    figs = build_figures(res)
    try:
        for name, fig in figs.items():
            fig.suptitle(title)
            fig.tight_layout()
            p = out / name
            fig.savefig(p, dpi=90, metadata={"Software": None})
            files.append(p)
    finally:
        for fig in figs.values():
            plt.close(fig)
    return files


def _build(res: RunResult, figs: dict[str, plt.Figure]) -> None:
    tel = res.telemetry
    t = tel["t_s"]

    def save(fig: plt.Figure, name: str) -> None:
        figs[name] = fig

    # sideslip has its own panel: on the heading axis (0-360 deg) a few
    # degrees of sideslip were a flat line at zero
    fig, axs = plt.subplots(4, 1, figsize=(9, 8.5), sharex=True)
    for ax, k, lab in zip(axs, ("phi_deg", "theta_deg", "psi_deg", "beta_deg"),
                          ("bank φ (deg)", "pitch θ (deg)", "heading ψ (deg)",
                           "sideslip β (deg)")):
        ax.plot(t, _break_wraps(tel[k]) if k in ("phi_deg", "psi_deg") else tel[k], lw=1)
        ax.set_ylabel(lab)
        ax.grid(alpha=0.3)
        _marks(ax, res)
    axs[3].axhline(0.0, color="0.5", lw=0.6)
    axs[-1].set_xlabel("t (s)")
    save(fig, "attitude.png")

    fig, ax = plt.subplots(figsize=(9, 4))
    ax.plot(t, tel["turn_rate_deg_s"], lw=1, label="actual (about earth vertical)")
    ax.plot(t, tel["cmd_turn_rate_deg_s"], lw=1.2, ls="--", label="command")
    if res.scenario.modes is not None:
        ax.plot(t, tel["turn_target_deg_s"], lw=0.8, ls="-.",
                label="mode target (nav / stick, before the slew)")
    ax.plot(t, tel["turn_rate_used_deg_s"], lw=0.8, ls=":", label="used by the law")
    ax.set_ylabel("turn rate (deg/s)")
    ax.set_xlabel("t (s)")
    ax.grid(alpha=0.3)
    ax.legend(loc="best")
    _marks(ax, res)
    save(fig, "turn_rate.png")

    fig, axs = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    axs[0].plot(t, tel["altitude_m"], lw=1, label="altitude")
    axs[0].plot(t, tel["cmd_altitude_m"], lw=1, ls="--", label="command (hold)")
    axs[0].set_ylabel("altitude (m)")
    axs[0].legend(loc="best")
    axs[1].plot(t, tel["airspeed_m_s"], lw=1, label="airspeed")
    axs[1].plot(t, tel["cmd_airspeed_m_s"], lw=1, ls="--", label="command")
    axs[1].set_ylabel("airspeed (m/s)")
    axs[1].legend(loc="best")
    axs[1].set_xlabel("t (s)")
    for ax in axs:
        ax.grid(alpha=0.3)
        _marks(ax, res)
    save(fig, "altitude.png")

    fig, axs = plt.subplots(4, 1, figsize=(9, 8), sharex=True)
    for ax, k in zip(axs, ("aileron", "elevator", "rudder", "throttle")):
        ax.plot(t, tel[k], lw=1, label="servo")
        if k != "throttle":
            ax.plot(t, tel["law_" + k], lw=0.8, ls=":", label="law (before trim)")
        ax.set_ylabel(k)
        ax.set_ylim(-1.05 if k != "throttle" else -0.05, 1.05)
        ax.grid(alpha=0.3)
        _marks(ax, res)
    axs[0].legend(loc="upper right")
    axs[-1].set_xlabel("t (s)")
    save(fig, "surfaces.png")

    fig, ax = plt.subplots(figsize=(6, 6))
    dec = _every(len(t), MAX_SCATTER_POINTS)
    sc = ax.scatter(tel["east_m"][dec], tel["north_m"][dec], c=tel["altitude_m"][dec], s=2,
                    cmap="viridis")
    ax.plot(tel["east_m"][:1], tel["north_m"][:1], "k^", label="start")
    mc = res.scenario.modes
    if mc is not None and mc.waypoints:
        # the planned path: legs from the start point through the list (and back
        # round when looping), waypoints with their arrival circles
        wn = [0.0] + [w[0] for w in mc.waypoints] + ([mc.waypoints[0][0]] if mc.loop else [])
        we = [0.0] + [w[1] for w in mc.waypoints] + ([mc.waypoints[0][1]] if mc.loop else [])
        ax.plot(we, wn, color="tab:red", lw=1, ls="--", label="planned legs")
        for i, w in enumerate(mc.waypoints):
            ax.add_patch(plt.Circle((w[1], w[0]), mc.arrival_radius_m, fill=False,
                                    color="tab:red", lw=0.6))
            ax.annotate(str(i), (w[1], w[0]), textcoords="offset points", xytext=(4, 4),
                        fontsize=8, color="tab:red")
    if mc is not None and (tel["failsafe"] > 0.5).any():
        ax.add_patch(plt.Circle((0.0, 0.0), mc.loiter_radius_m, fill=False, color="tab:orange",
                                lw=0.8, ls=":"))
        fs = tel["failsafe"] > 0.5
        ax.plot(tel["east_m"][fs], tel["north_m"][fs], ".", ms=1, color="tab:orange",
                label="failsafe (RTH, loiter)")
    fig.colorbar(sc, ax=ax, label="altitude (m)")
    ax.set_xlabel("east (m)")
    ax.set_ylabel("north (m)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(alpha=0.3)
    ax.legend(loc="best")
    save(fig, "ground_track.png")


