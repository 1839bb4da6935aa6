"""PNG plots of a run: attitude, turn rate vs command, altitude, surfaces,
ground track."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


from helical_sil.sim import RunResult  # noqa: E402


def _break_wraps(values: np.ndarray) -> np.ndarray:
    """An angle in degrees with NaN where it wraps (a jump over 180 deg), so
    that a bank near +-180 or a heading through north is not drawn as a
    vertical line across the plot."""
    v = np.asarray(values, dtype=float).copy()
    jumps = np.abs(np.diff(v)) > 180.0
    v[1:][jumps] = np.nan
    return v


def _marks(ax: plt.Axes, res: RunResult) -> None:
    for s in res.segments[1:]:
        ax.axvline(s.t0, color="0.7", lw=0.8, ls=":")


def write_plots(res: RunResult, out: Path) -> list[Path]:
    tel = res.telemetry
    t = tel["t_s"]
    title = f"{res.scenario.name} ({res.scenario.aircraft.name})"
    files: list[Path] = []

    def save(fig: plt.Figure, name: str) -> None:
        fig.suptitle(title)
        fig.tight_layout()
        p = out / name
        fig.savefig(p, dpi=90, metadata={"Software": None})
        plt.close(fig)
        files.append(p)

    fig, axs = plt.subplots(3, 1, figsize=(9, 7), sharex=True)
    for ax, k, lab in zip(axs, ("phi_deg", "theta_deg", "psi_deg"),
                          ("bank φ (deg)", "pitch θ (deg)", "heading ψ (deg)")):
        ax.plot(t, _break_wraps(tel[k]) if k != "theta_deg" else tel[k], lw=1)
        ax.set_ylabel(lab)
        ax.grid(alpha=0.3)
        _marks(ax, res)
    axs[2].plot(t, tel["beta_deg"], lw=0.8, label="sideslip β (deg)")
    axs[2].legend(loc="upper right")
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
    sc = ax.scatter(tel["east_m"], tel["north_m"], c=tel["altitude_m"], s=2, cmap="viridis")
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
    return files


