"""`python -m helical_sil serve`: the SIL as a live aircraft on a MAVLink link.

JSBSim flies the scenario's aircraft with the firmware on the board library,
in its own flight modes (fly-by-wire, waypoint, return-to-home, manual), paced
at N x real time, while a ground station (QGroundControl, MAVProxy, pymavlink)
talks to the board over UDP. The firmware's link (firmware/link/fw_link.h, called by
the board after each control step) builds and parses every MAVLink message;
this module only moves bytes between the socket and the board.

The pilot is a steady transmitter: sticks centred, throttle at the trim, the
mode switch where --mode puts it. A ground station's mode command (SET_MODE,
COMMAND_LONG) then selects the mode, and an uploaded mission is what waypoint
mode flies.
"""

from __future__ import annotations

import contextlib
import copy
import json
import math
import select
import signal
import socket
import sys
import time
from collections import deque
from dataclasses import dataclass, field
from pathlib import Path
from types import FrameType
from typing import Any, Callable, Iterator

import numpy as np

from helical_sil.config import scenario as scn
from helical_sil.config.scenario import ModesConfig, Scenario
from helical_sil.sensors import frames
from helical_sil.sensors import models as sensors_mod
from helical_sil.sim import lockstep
from helical_sil.sim.board import Board
from helical_sil.sim.faults import SensorFaults

FT = frames.FT
MODES = tuple(scn.MODE_PULSES_US)  # manual, fbw, waypoint, rth
# the most bytes the board's link is asked for at once (one datagram: frames
# may straddle two datagrams; a MAVLink parser reads a byte stream)
TX_CHUNK = 8192
# behind the pacing by more than this, the clock is reset instead of catching up
MAX_LAG_S = 0.5


class ServeError(ValueError):
    """A bad --mavlink endpoint or option (exit 2)."""


@dataclass(frozen=True)
class Endpoint:
    """udpout: send to a ground station listening at host:port and hear only
    datagrams from that address; udpin: listen at host:port, answer whoever
    sent last."""
    kind: str
    host: str
    port: int

    def __str__(self) -> str:
        return f"{self.kind}:{self.host}:{self.port}"


def parse_endpoint(text: str) -> Endpoint:
    """"udpout:HOST:PORT" or "udpin:HOST:PORT" (HOST may be empty for udpin: every address)."""
    parts = text.split(":")
    if len(parts) != 3 or parts[0] not in ("udpout", "udpin"):
        raise ServeError(f"--mavlink {text!r}: expected udpout:HOST:PORT or udpin:HOST:PORT")
    kind, host, port_s = parts
    try:
        port = int(port_s)
    except ValueError:
        raise ServeError(f"--mavlink {text!r}: the port {port_s!r} is not a number") from None
    if not 1 <= port <= 65535:
        raise ServeError(f"--mavlink {text!r}: the port {port} is outside [1, 65535]")
    if kind == "udpout" and not host:
        raise ServeError(f"--mavlink {text!r}: udpout needs the ground station's host")
    return Endpoint(kind, host or "0.0.0.0", port)


@dataclass
class LinkStats:
    datagrams_in: int = 0
    bytes_in: int = 0
    datagrams_out: int = 0
    bytes_out: int = 0
    send_errors: int = 0  # nobody listening (ICMP port unreachable), no route
    bytes_unsent: int = 0  # udpin before any ground station spoke: no address yet
    datagrams_foreign: int = 0  # udpout: from another address than the configured peer, dropped


class UdpLink:
    """A non-blocking UDP socket that moves datagrams as bytes."""

    def __init__(self, ep: Endpoint) -> None:
        self.endpoint = ep
        self.stats = LinkStats()
        self._sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self._sock.setblocking(False)
        self._peer: tuple[str, int] | None = None
        try:
            if ep.kind == "udpin":
                self._sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
                self._sock.bind((ep.host, ep.port))
            else:
                self._peer = (socket.gethostbyname(ep.host), ep.port)
        except OSError as e:
            self._sock.close()
            raise ServeError(f"--mavlink {ep}: {e}") from None

    @property
    def peer(self) -> tuple[str, int] | None:
        return self._peer

    def receive(self) -> Iterator[bytes]:
        """Every datagram waiting. udpin: the sender becomes the address answers go
        to. udpout: only the configured peer is heard; a datagram from any other
        address is dropped (counted), so no local process can redirect the telemetry
        or command the aircraft (issue 33 item 9)."""
        while True:
            try:
                data, addr = self._sock.recvfrom(65535)
            except (BlockingIOError, InterruptedError):
                return
            except OSError:  # e.g. ECONNREFUSED from an earlier send: nothing to read
                self.stats.send_errors += 1
                continue
            if self.endpoint.kind == "udpin":
                self._peer = (addr[0], addr[1])
            elif (addr[0], addr[1]) != self._peer:
                self.stats.datagrams_foreign += 1
                continue
            self.stats.datagrams_in += 1
            self.stats.bytes_in += len(data)
            yield data

    def send(self, data: bytes) -> None:
        if not data:
            return
        if self._peer is None:
            self.stats.bytes_unsent += len(data)
            return
        try:
            self._sock.sendto(data, self._peer)
        except OSError:
            self.stats.send_errors += 1
            return
        self.stats.datagrams_out += 1
        self.stats.bytes_out += len(data)

    def wait(self, timeout_s: float) -> bool:
        """Until a datagram arrives or timeout_s passes; True if one is waiting."""
        r, _w, _x = select.select([self._sock], [], [], max(0.0, timeout_s))
        return bool(r)

    def close(self) -> None:
        self._sock.close()


def serve_modes(sc: Scenario) -> ModesConfig:
    """The flight modes the served aircraft flies with: the scenario's own
    ([modes], [nav], its waypoints), else its aircraft's mode tables with no
    waypoints (a ground station uploads a mission)."""
    if sc.modes is not None:
        return copy.deepcopy(sc.modes)
    mc = ModesConfig()
    scn._parse_mode_tables(sc.path, sc.aircraft.mode_tables, mc)
    mc.cruise_m_s = sc.airspeed_m_s
    mc.home_alt_m = sc.altitude_m
    mc.rc = [scn.RcEntry(t_s=0.0, label="serve", mode_us=scn.MODE_PULSES_US["fbw"])]
    return mc


def default_mode(sc: Scenario) -> str:
    """The scenario's first [[rc]] mode, else fly-by-wire."""
    if sc.modes is not None:
        for e in sc.modes.rc:
            if e.mode_us is not None:
                return lockstep.mode_of_pulse(e.mode_us)
    return "fbw"


@dataclass
class Flight:
    """JSBSim and the board, one control step at a time (the lockstep of
    lockstep.run without its log): the firmware flies the scenario's aircraft on
    its estimate (or the truth, as the scenario says) in its flight modes."""
    sc: Scenario
    board_lib: str | None = None
    mode: str = "fbw"
    sysid: int = 1
    k: int = 0
    trims: dict[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        sc = copy.copy(self.sc)
        sc.modes = serve_modes(self.sc)
        self.sc = sc
        if self.mode not in MODES:
            raise ServeError(f"--mode {self.mode!r}: one of {', '.join(MODES)}")
        self.fdm = lockstep.make_fdm(sc)
        fdm = self.fdm
        self.n_engines = fdm.get_propulsion().get_num_engines()
        ail, elev, rud = frames.surfaces_from_jsbsim(
            fdm["fcs/aileron-cmd-norm"], fdm["fcs/elevator-cmd-norm"], fdm["fcs/rudder-cmd-norm"])
        self.trims = {"aileron": float(ail), "elevator": float(elev), "rudder": float(rud),
                      "throttle": float(fdm["fcs/throttle-cmd-norm[0]"])}
        cfg: dict[str, Any] = dict(lockstep.board_config(sc, self.trims))
        cfg.update(lockstep.modes_board_config(sc))
        cfg["link_sysid"] = self.sysid
        self.board_config = cfg
        self.board = Board(cfg, self.board_lib)
        rng = np.random.Generator(np.random.PCG64(sc.seed))
        bias = sc.gyro_bias_rad_s * rng.choice(np.array([-1.0, 1.0]), size=3)
        self._imu_bias = bias if sc.gyro_bias_rad_s > 0.0 else np.zeros(3)
        self._imu_rng = np.random.Generator(np.random.PCG64([sc.seed, 0x1A1]))
        self._faults = SensorFaults(sc)
        self._model = lockstep.sensor_model(sc)
        self._n_sub = sc.sim_rate_hz // sc.control_rate_hz
        self.dt_s = 1.0 / sc.control_rate_hz
        self._imu_batch = [self._model.imu(sensors_mod.read_fdm_state(fdm), 0.0)] * self._n_sub
        self._imu_fifo: deque[Any] = deque()
        self._north = self._east = 0.0
        self._steady_wind = any(w != 0.0 for w in (sc.wind_north_m_s, sc.wind_east_m_s,
                                                   sc.wind_down_m_s))
        # the steady transmitter: sticks centred, throttle at the trim
        rc = lockstep.RcState(mode_us=scn.MODE_PULSES_US[self.mode],
                         throttle_us=int(round(1000 + 1000 * self.trims["throttle"])))
        cmd = self.board.command
        for i, us in enumerate(rc.pulses()):
            cmd.rc_us[i] = us
        cmd.rc_fresh = 1
        cmd.speed_hold = 1
        cmd.airspeed_m_s = sc.airspeed_m_s
        cmd.throttle = self.trims["throttle"]

    @property
    def t_s(self) -> float:
        return self.k * self.dt_s

    def step(self) -> Any:
        """One control step: the sensors of now into the board, its servos into
        JSBSim, JSBSim to the next step. Raises lockstep.SimError at ground contact."""
        sc, fdm, b = self.sc, self.fdm, self.board
        t = self.t_s
        sens = b.sensors
        phi, theta, psi = (fdm[f"attitude/{a}-rad"] for a in ("phi", "theta", "psi"))
        p, q, r = (fdm[f"velocities/{a}-rad_sec"] for a in ("p", "q", "r"))
        x, y, z = frames.dcm_bottom_row(phi, theta)
        gx, gy, gz = frames.body_rates_lib(p, q, r)
        (sens.dcm_x, sens.dcm_y, sens.dcm_z, sens.gyro_x, sens.gyro_y, sens.gyro_z) = (
            x, y, z, gx, gy, gz)
        sens.airspeed_m_s = fdm["velocities/vt-fps"] * FT
        sens.altitude_m = fdm["position/h-sl-ft"] * FT
        sens.climb_m_s = fdm["velocities/h-dot-fps"] * FT
        vn = fdm["velocities/v-north-fps"] * FT
        ve = fdm["velocities/v-east-fps"] * FT
        sens.north_m, sens.east_m, sens.vel_north_m_s, sens.vel_east_m_s = (
            self._north, self._east, vn, ve)
        sens.heading_rad = psi
        sens.use_truth = int(sc.attitude_source == "truth")
        sens.align_to_truth = int(self.k == 0)
        lockstep._raw_sensors(sc, sens, self._model, sensors_mod.read_fdm_state(fdm), t,
                         self._imu_batch, self._imu_fifo, self._faults, self._imu_bias,
                         self._imu_rng)
        a = b.step()
        ail, elev, rud = frames.surfaces_to_jsbsim(a.aileron, a.elevator, a.rudder)
        fdm["fcs/aileron-cmd-norm"] = ail
        fdm["fcs/elevator-cmd-norm"] = elev
        fdm["fcs/rudder-cmd-norm"] = rud
        for e in range(self.n_engines):
            fdm[f"fcs/throttle-cmd-norm[{e}]"] = a.throttle
        if self._steady_wind:
            ramp = min(1.0, (t + self.dt_s) / lockstep.WIND_RAMP_S)
            fdm["atmosphere/wind-north-fps"] = ramp * sc.wind_north_m_s / FT
            fdm["atmosphere/wind-east-fps"] = ramp * sc.wind_east_m_s / FT
            fdm["atmosphere/wind-down-fps"] = ramp * sc.wind_down_m_s / FT
        batch = []
        for j in range(self._n_sub):
            if not fdm.run():
                raise lockstep.SimError(
                    f"JSBSim stopped at t = {fdm['simulation/sim-time-sec']:.2f} s")
            try:
                batch.append(self._model.imu(sensors_mod.read_fdm_state(fdm),
                                             t + (j + 1) / sc.sim_rate_hz))
            except ValueError as e:
                raise lockstep.SimError(f"JSBSim's state is not finite at t = "
                                   f"{fdm['simulation/sim-time-sec']:.2f} s: {e}") from None
        self._imu_batch = batch
        self._north += vn * self.dt_s
        self._east += ve * self.dt_s
        self.k += 1
        agl = fdm["position/h-agl-ft"] * FT
        if agl < lockstep.GROUND_CONTACT_M:
            raise lockstep.SimError(f"ground contact at t = {self.t_s:.2f} s")
        return a


@dataclass
class ServeResult:
    sim_s: float
    wall_s: float
    end_reason: str
    link: LinkStats
    counters: dict[str, int]

    def as_dict(self) -> dict[str, Any]:
        return {"sim_s": self.sim_s, "wall_s": self.wall_s,
                "speed_x_realtime": self.sim_s / self.wall_s if self.wall_s > 0 else math.inf,
                "end_reason": self.end_reason, "udp": vars(self.link),
                "board_link": self.counters}


class _Stop:
    """SIGTERM / SIGINT end the flight at the next control step (the counters
    are still printed)."""

    def __init__(self) -> None:
        self.reason = ""

    def __call__(self, signum: int, _frame: FrameType | None) -> None:
        self.reason = signal.Signals(signum).name


@contextlib.contextmanager
def _signals(stop: _Stop) -> Iterator[None]:
    saved = {}
    for s in (signal.SIGTERM, signal.SIGINT):
        try:
            saved[s] = signal.signal(s, stop)
        except ValueError:  # not the main thread: no signals
            pass
    try:
        yield
    finally:
        for s, h in saved.items():
            signal.signal(s, h)


def serve(flight: Flight, link: UdpLink, speed: float, duration_s: float | None,
          on_start: Callable[[], None] | None = None) -> ServeResult:
    """Fly until duration_s of sim time (None: until SIGINT / SIGTERM), paced
    at speed x real time (0: as fast as possible), moving bytes between the
    socket and the board's link before and after every control step."""
    board = flight.board
    stop = _Stop()
    steps = None if duration_s is None else int(round(duration_s / flight.dt_s))
    end = "duration"

    def drain() -> None:
        while out := board.link_tx(TX_CHUNK):
            link.send(out)

    def pump() -> None:
        # the answers of each datagram leave before the next is parsed: the
        # firmware's transmit queue is small (FW_LINK_TX_BYTES), like a UART's
        for d in link.receive():
            board.link_rx(d)
            drain()
        drain()

    with _signals(stop):
        if on_start is not None:
            on_start()
        t_start = t0 = time.perf_counter()
        k0 = 0
        while steps is None or flight.k < steps:
            if stop.reason:
                end = stop.reason
                break
            pump()
            try:
                flight.step()
            except lockstep.SimError as e:
                end = str(e)
                break
            pump()
            if speed > 0.0:
                due = t0 + (flight.k - k0) * flight.dt_s / speed
                now = time.perf_counter()
                if now > due + MAX_LAG_S:  # the host cannot keep up: no burst to catch up
                    t0, k0 = now, flight.k
                while (rem := due - time.perf_counter()) > 0.0 and not stop.reason:
                    if link.wait(rem):
                        pump()
        wall = time.perf_counter() - t_start
    return ServeResult(flight.t_s, wall, end, link.stats, board.link_counters())


def format_result(r: ServeResult) -> str:
    d = r.as_dict()
    lines = [f"served {r.sim_s:.1f} s of flight in {r.wall_s:.1f} s "
             f"({d['speed_x_realtime']:.1f}x real time); end: {r.end_reason}",
             "udp: " + ", ".join(f"{k} {v}" for k, v in vars(r.link).items()),
             "board link: " + ", ".join(f"{k} {v}" for k, v in r.counters.items())]
    return "\n".join(lines)


def run_serve(scenario_path: Path, endpoint: str, speed: float, duration_s: float | None,
              mode: str | None, board_lib: str | None, sysid: int,
              stats_json: Path | None) -> int:
    """The serve subcommand: 0 when the flight ended by --duration or a signal."""
    ep = parse_endpoint(endpoint)
    if not (speed >= 0.0 and math.isfinite(speed)):
        raise ServeError(f"--speed {speed}: a finite number >= 0 (0: as fast as possible)")
    if duration_s is not None and not (duration_s > 0.0 and math.isfinite(duration_s)):
        raise ServeError(f"--duration {duration_s}: a positive number of seconds")
    if not 1 <= sysid <= 255:
        raise ServeError(f"--sysid {sysid}: within [1, 255]")
    sc = scn.load_scenario(scenario_path)
    chosen = mode if mode is not None else default_mode(sc)
    link = UdpLink(ep)
    try:
        with lockstep._quiet_stdout():
            flight = Flight(sc, board_lib, chosen, sysid)

        def started() -> None:
            pace = "as fast as possible" if speed == 0.0 else f"{speed:g}x real time"
            print(f"serve: {sc.aircraft.name} ({sc.name}) in {chosen} mode on {ep}, {pace}, "
                  f"MAVLink system {sysid}; "
                  + (f"{duration_s:g} s" if duration_s else "until Ctrl-C"), flush=True)

        res = serve(flight, link, speed, duration_s, started)
    finally:
        link.close()
    print(format_result(res), flush=True)
    if stats_json is not None:
        stats_json.write_text(json.dumps(res.as_dict(), indent=2) + "\n")
    ok = res.end_reason in ("duration", "SIGINT", "SIGTERM")
    if not ok:
        print(f"error: the flight ended early: {res.end_reason}", file=sys.stderr)
    return 0 if ok else 3
