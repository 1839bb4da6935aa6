"""A pymavlink ground station for the serve tests (test_serve_mavlink.py):
starts `python -m helical_sil serve` against a socket it listens on, and
speaks the parameter, mission and mode protocols as a ground station does.

Every frame the aircraft sends is kept (with the sim time of the newest time
stamp seen), so that a test can measure rates and tracks afterwards; every
protocol step is written to a transcript (the closing note quotes one).
"""

from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

os.environ.setdefault("MAVLINK20", "1")  # before pymavlink is imported: MAVLink 2 frames

from pymavlink import mavutil  # noqa: E402

from helical_sil.config import params  # noqa: E402

SIL_DIR = Path(__file__).resolve().parents[1]
MAV = mavutil.mavlink
TARGET = (1, 1)  # the aircraft: system 1, autopilot component
EARTH_R_M = 6378137.0

# params.def's groups as the link names them (firmware/link/fw_link_param_table.c)
GROUP_PREFIX = {"LAW": "LAW_", "DCM": "DCM_", "GUIDE": "GDE_", "ALT": "ALT_", "SPEED": "SPD_",
                "MODES": "MOD_", "FBW": "FBW_", "NAV": "NAV_", "AOA": "AOA_", "LINK": "LNK_"}


def param_id(p: params.Param) -> str:
    """The MAVLink param_id of a row (docs/mavlink.md): the group's prefix and
    the row's ID column; while longer than 16 characters, the last vowel of
    the ID that does not begin a word goes; none left: the ID is cut to 12."""
    body = list(p.id)
    while 4 + len(body) > 16:
        i = len(body)
        while i > 1 and not (body[i - 1] in "AEIOU" and body[i - 2] != "_"):
            i -= 1
        if i <= 1:
            body = body[:12]
        else:
            del body[i - 1]
    return GROUP_PREFIX[p.group] + "".join(body)


def offset_deg(lat_deg: float, lon_deg: float, north_m: float,
               east_m: float) -> tuple[float, float]:
    """A point north_m, east_m from (lat, lon) on a sphere (short distances)."""
    lat = lat_deg + math.degrees(north_m / EARTH_R_M)
    lon = lon_deg + math.degrees(east_m / (EARTH_R_M * math.cos(math.radians(lat_deg))))
    return lat, lon


def distance_m(lat1: float, lon1: float, lat2: float, lon2: float) -> float:
    n = math.radians(lat2 - lat1) * EARTH_R_M
    e = math.radians(lon2 - lon1) * EARTH_R_M * math.cos(math.radians(0.5 * (lat1 + lat2)))
    return math.hypot(n, e)


@dataclass
class Seen:
    """One frame from the aircraft and the sim time (ms) it came at."""
    t_ms: int
    msg: Any


class GroundStation:
    """A pymavlink connection listening on a free local UDP port, and the
    serve process that sends to it."""

    def __init__(self, board_lib: str, scenario: Path, speed: float, duration_s: float,
                 workdir: Path, extra: tuple[str, ...] = ()) -> None:
        self.conn = mavutil.mavlink_connection("udpin:127.0.0.1:0", source_system=255,
                                               source_component=190, dialect="common")
        self.port = int(self.conn.port.getsockname()[1])
        self.stats_path = workdir / f"serve_stats_{self.port}.json"
        env = dict(os.environ, HT_SIL_BOARD_LIB=board_lib,
                   PYTHONPATH=os.pathsep.join([str(SIL_DIR), os.environ.get("PYTHONPATH", "")]))
        self.cmd = [sys.executable, "-m", "helical_sil", "serve", str(scenario),
                    "--mavlink", f"udpout:127.0.0.1:{self.port}", "--speed", f"{speed:g}",
                    "--duration", f"{duration_s:g}", "--stats-json", str(self.stats_path),
                    *extra]
        self.proc = subprocess.Popen(self.cmd, env=env, stdout=subprocess.PIPE,
                                     stderr=subprocess.STDOUT, text=True, cwd=SIL_DIR)
        self.seen: list[Seen] = []
        self.t_ms = 0
        self.t_mode_ms = 0
        self.transcript: list[str] = []
        self.output = ""

    # --- receiving ------------------------------------------------------
    def note(self, line: str) -> None:
        self.transcript.append(f"[t = {self.t_ms / 1000.0:7.2f} s] {line}")

    def recv(self, timeout_s: float) -> Any | None:
        m = self.conn.recv_match(blocking=True, timeout=timeout_s)
        if m is None or m.get_type() == "BAD_DATA":
            return None
        if m.get_srcSystem() != TARGET[0]:
            return None
        t = getattr(m, "time_boot_ms", None)
        if t is not None:
            self.t_ms = max(self.t_ms, int(t))
        self.seen.append(Seen(self.t_ms, m))
        return m

    def wait(self, mtype: str | tuple[str, ...], cond: Callable[[Any], bool] = lambda m: True,
             timeout_s: float = 15.0) -> Any:
        """The next frame of the type(s) that satisfies cond; AssertionError
        naming what did not come after timeout_s of wall time."""
        types = (mtype,) if isinstance(mtype, str) else mtype
        end = time.monotonic() + timeout_s
        while (left := end - time.monotonic()) > 0.0:
            if self.proc.poll() is not None:
                raise AssertionError(f"serve ended (exit {self.proc.returncode}) while "
                                     f"waiting for {types}: {self.finish()}")
            m = self.recv(min(left, 0.5))
            if m is not None and m.get_type() in types and cond(m):
                return m
        raise AssertionError(f"no {'/'.join(types)} within {timeout_s} s (sim t = "
                             f"{self.t_ms / 1000:.1f} s)")

    def run_for(self, sim_s: float, timeout_s: float = 60.0) -> list[Seen]:
        """Everything received until the sim clock advanced by sim_s."""
        start = len(self.seen)
        t_end = self.t_ms + int(sim_s * 1000)
        end = time.monotonic() + timeout_s
        while self.t_ms < t_end:
            assert time.monotonic() < end, f"the sim did not advance {sim_s} s in {timeout_s} s"
            assert self.proc.poll() is None, f"serve ended: {self.finish()}"
            self.recv(0.5)
        return self.seen[start:]

    # --- protocols ----------------------------------------------------------
    def heartbeat(self) -> Any:
        hb = self.wait("HEARTBEAT", timeout_s=30.0)
        self.note(f"HEARTBEAT from system {hb.get_srcSystem()} component {hb.get_srcComponent()}"
                  f": type {hb.type}, autopilot {hb.autopilot}, base_mode {hb.base_mode:#x}, "
                  f"custom_mode {hb.custom_mode}, MAVLink {hb.mavlink_version}")
        return hb

    def read_all_params(self, timeout_s: float = 60.0) -> tuple[int, dict[str, Any]]:
        """PARAM_REQUEST_LIST, then single PARAM_REQUEST_READs for any index
        that was lost; returns (param_count, {param_id: PARAM_VALUE})."""
        self.conn.mav.param_request_list_send(*TARGET)
        self.note("-> PARAM_REQUEST_LIST")
        got: dict[int, Any] = {}
        count = -1
        end = time.monotonic() + timeout_s
        asked_again = False
        while count < 0 or len(got) < count:
            left = end - time.monotonic()
            assert left > 0.0, f"{len(got)} of {count} parameters in {timeout_s} s"
            m = self.recv(min(left, 1.0))
            if m is None:
                if count > 0 and not asked_again:
                    for i in range(count):
                        if i not in got:
                            self.conn.mav.param_request_read_send(*TARGET, b"", i)
                    asked_again = True
                continue
            if m.get_type() == "PARAM_VALUE":
                count = m.param_count
                got[m.param_index] = m
        by_id = {m.param_id: m for m in got.values()}
        self.note(f"<- {len(by_id)} PARAM_VALUE of param_count {count}")
        return count, by_id

    def set_param(self, pid: str, value: float) -> Any:
        self.conn.mav.param_set_send(*TARGET, pid.encode(), float(value),
                                     MAV.MAV_PARAM_TYPE_REAL32)
        m = self.wait("PARAM_VALUE", lambda m: m.param_id == pid)
        self.note(f"-> PARAM_SET {pid} = {value:g}; <- PARAM_VALUE {pid} = {m.param_value:g}")
        return m

    def set_mode(self, custom_mode: int, name: str, via: str = "command") -> Any:
        """MAV_CMD_DO_SET_MODE (COMMAND_LONG, acknowledged) or SET_MODE; then
        the first HEARTBEAT that shows the mode."""
        flag = MAV.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED
        if via == "command":
            self.conn.mav.command_long_send(*TARGET, MAV.MAV_CMD_DO_SET_MODE, 0, flag,
                                            custom_mode, 0, 0, 0, 0, 0)
            ack = self.wait("COMMAND_ACK", lambda m: m.command == MAV.MAV_CMD_DO_SET_MODE)
            self.t_mode_ms = self.t_ms  # the mode is in effect from the next step on
            assert ack.result == MAV.MAV_RESULT_ACCEPTED, f"{name}: result {ack.result}"
            sent = f"COMMAND_LONG DO_SET_MODE {custom_mode} ({name}); <- COMMAND_ACK ACCEPTED"
        else:
            self.conn.mav.set_mode_send(TARGET[0], flag, custom_mode)
            sent = f"SET_MODE {custom_mode} ({name})"
        hb = self.wait("HEARTBEAT", lambda m: m.custom_mode == custom_mode, timeout_s=20.0)
        self.note(f"-> {sent}; <- HEARTBEAT custom_mode {hb.custom_mode}")
        return hb

    def upload_mission(self, items: list[tuple[float, float, float]],
                       frame: int = MAV.MAV_FRAME_GLOBAL_INT) -> None:
        """MISSION_COUNT, answer each MISSION_REQUEST(_INT) with its
        MISSION_ITEM_INT (NAV_WAYPOINT), until MISSION_ACK."""
        self.conn.mav.mission_count_send(*TARGET, len(items), MAV.MAV_MISSION_TYPE_MISSION)
        self.note(f"-> MISSION_COUNT {len(items)}")
        while True:
            m = self.wait(("MISSION_REQUEST_INT", "MISSION_REQUEST", "MISSION_ACK"))
            if m.get_type() == "MISSION_ACK":
                assert m.type == MAV.MAV_MISSION_ACCEPTED, f"MISSION_ACK type {m.type}"
                self.note("<- MISSION_ACK ACCEPTED")
                return
            lat, lon, alt = items[m.seq]
            self.conn.mav.mission_item_int_send(
                *TARGET, m.seq, frame, MAV.MAV_CMD_NAV_WAYPOINT, 0, 1, 0, 0, 0, 0,
                int(round(lat * 1e7)), int(round(lon * 1e7)), float(alt),
                MAV.MAV_MISSION_TYPE_MISSION)
            self.note(f"<- {m.get_type()} {m.seq}; -> MISSION_ITEM_INT {m.seq} "
                      f"({lat:.6f}, {lon:.6f}, {alt:.0f} m)")

    def download_mission(self) -> list[Any]:
        self.conn.mav.mission_request_list_send(*TARGET, MAV.MAV_MISSION_TYPE_MISSION)
        count = self.wait("MISSION_COUNT").count
        self.note(f"-> MISSION_REQUEST_LIST; <- MISSION_COUNT {count}")
        items = []
        for i in range(count):
            self.conn.mav.mission_request_int_send(*TARGET, i, MAV.MAV_MISSION_TYPE_MISSION)
            it = self.wait("MISSION_ITEM_INT", lambda m, i=i: m.seq == i)
            items.append(it)
            self.note(f"-> MISSION_REQUEST_INT {i}; <- MISSION_ITEM_INT {i} "
                      f"({it.x / 1e7:.6f}, {it.y / 1e7:.6f}, {it.z:.0f} m, frame {it.frame})")
        self.conn.mav.mission_ack_send(*TARGET, MAV.MAV_MISSION_ACCEPTED,
                                       MAV.MAV_MISSION_TYPE_MISSION)
        return items

    # --- the end ------------------------------------------------------------
    def send_raw(self, data: bytes) -> None:
        """Bytes as they are (malformed frames): one datagram to the aircraft
        (pymavlink's udpin answers every address it has heard from)."""
        assert self.conn.clients, "nothing heard from the aircraft yet"
        self.conn.write(data)

    def finish(self, timeout_s: float = 20.0) -> str:
        """Stop serve (SIGTERM, as Ctrl-C would) and return its output."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
        try:
            out, _ = self.proc.communicate(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            out, _ = self.proc.communicate()
        self.output += out or ""
        self.conn.close()
        return self.output

    def stats(self) -> dict[str, Any]:
        return json.loads(self.stats_path.read_text())
