"""`python -m helical_sil serve` with real ground-station clients (issue 15):
pymavlink reads and sets parameters, uploads, flies and downloads a mission,
switches modes and measures the telemetry rates; MAVProxy connects as a user
would; malformed frames are dropped and counted by the firmware's link.

ctest runs this file as sil_mavlink (sil/CMakeLists.txt), not in sil_pytest.
HT_MAVLINK_TRANSCRIPT=FILE writes the main session's transcript and rates
(and FILE.gain: the roll-in with and without the gain set on the link).
"""

from __future__ import annotations

import math
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path
from typing import Iterator

import pytest

pytest.importorskip("pymavlink")

from mavlink_client import (MAV, SIL_DIR, GroundStation, distance_m,  # noqa: E402
                            offset_deg, param_id)

from helical_sil.config import params  # noqa: E402
from helical_sil.config.scenario import load_scenario  # noqa: E402
from helical_sil.live.serve import Flight, parse_endpoint, ServeError  # noqa: E402
from helical_sil.sim.board import table_values  # noqa: E402

SCENARIO = SIL_DIR / "scenarios" / "c172p_level_hold.toml"
# HEARTBEAT custom_mode of each flight mode (docs/mavlink.md)
CUSTOM_MODE = {"manual": 0, "fbw": 5, "waypoint": 10, "rth": 11}
SPEED = 10.0  # x real time: the whole module stays well under a minute and a half


def _link_defaults() -> dict[str, float]:
    return {p.name: p.default for p in params.TABLE if p.group == "LINK"}


def expected_values(board_lib: str) -> dict[str, float]:
    """Every parameter's value as serve configures the board: the scenario's
    aircraft gains, trims and mode tables (the same Flight serve builds), the
    link's rows at the table's defaults; as the board stores them (rounded to
    the row's format)."""
    fl = Flight(load_scenario(SCENARIO), board_lib, "fbw")
    groups = table_values(fl.board_config)
    values = {"LINK": _link_defaults()}
    for key, group, _rows in params.BOARD_GROUPS:
        values[group] = groups[key]
    out = {}
    for p in params.TABLE:
        out[param_id(p)] = p.raw(values[p.group][p.name]) / p.fmt.scale
    return out


@pytest.fixture(scope="module")
def gs(board_lib: str, tmp_path_factory: pytest.TempPathFactory) -> Iterator[GroundStation]:
    """One serve session at SPEED x real time, shared by the tests below in
    file order (parameters, modes, mission, rates)."""
    g = GroundStation(board_lib, SCENARIO, SPEED, 900.0, tmp_path_factory.mktemp("serve"))
    g.wait("HEARTBEAT", timeout_s=30.0)  # pymavlink answers the address it heard from
    yield g
    out = g.finish()
    path = os.environ.get("HT_MAVLINK_TRANSCRIPT")
    if path:
        Path(path).write_text("\n".join(g.transcript) + "\n\nserve's output:\n" + out)


def test_heartbeat_says_fixed_wing_in_its_mode(gs: GroundStation) -> None:
    hb = gs.heartbeat()
    assert hb.type == MAV.MAV_TYPE_FIXED_WING
    assert hb.base_mode & MAV.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED
    assert hb.custom_mode == CUSTOM_MODE["fbw"]  # serve's default switch position
    assert hb.get_srcSystem() == 1 and hb.get_srcComponent() == 1


def test_the_parameter_list_is_the_table(gs: GroundStation, board_lib: str) -> None:
    """Every row of params.def, once, under its id, at the value serve gave it."""
    count, got = gs.read_all_params()
    assert count == len(params.TABLE)
    want = expected_values(board_lib)
    assert set(got) == set(want)
    assert sorted(m.param_index for m in got.values()) == list(range(count))
    for pid, v in want.items():
        assert math.isclose(got[pid].param_value, v, rel_tol=1e-6, abs_tol=1e-9), \
            (pid, got[pid].param_value, v)
    gs.note(f"parameters match the table: e.g. LAW_KP_AILERON = "
            f"{got['LAW_KP_AILERON'].param_value:g}, LNK_ATTITUDE_HZ = "
            f"{got['LNK_ATTITUDE_HZ'].param_value:g}")


def test_a_set_out_of_range_is_refused_and_a_good_one_applied(gs: GroundStation) -> None:
    before = gs.set_param("NAV_ARRIVAL_RADS", 50.0)  # unchanged, echoed
    assert before.param_value == 50.0
    # kp_aileron's bounds are [0, 64]: 100 is refused, the value stays
    m = gs.set_param("LAW_KP_AILERON", 100.0)
    assert m.param_value <= 64.0


def test_modes_follow_the_ground_station(gs: GroundStation) -> None:
    for name, via in (("manual", "set_mode"), ("fbw", "command"), ("rth", "command"),
                      ("fbw", "set_mode")):
        hb = gs.set_mode(CUSTOM_MODE[name], name, via)
        assert hb.custom_mode == CUSTOM_MODE[name]


def test_mission_uploaded_flown_and_downloaded(gs: GroundStation) -> None:
    """Four waypoints laid out from the aircraft: a 1500 m x 1000 m box, ahead
    and to the right, back to where it started; downloaded back as sent;
    flown in waypoint mode: the track (GLOBAL_POSITION_INT) passes each in
    order, and the firmware reports each reached (MISSION_ITEM_REACHED)."""
    pos = gs.wait("GLOBAL_POSITION_INT")
    lat0, lon0, alt_m = pos.lat / 1e7, pos.lon / 1e7, pos.alt / 1000.0
    hdg = math.radians(pos.hdg / 100.0)
    box = ((1500.0, 0.0), (1500.0, 1000.0), (0.0, 1000.0), (0.0, 0.0))  # ahead, right
    wps = []
    for ahead, right in box:
        n = ahead * math.cos(hdg) - right * math.sin(hdg)
        e = ahead * math.sin(hdg) + right * math.cos(hdg)
        wps.append((*offset_deg(lat0, lon0, n, e), round(alt_m)))
    gs.upload_mission(wps)
    down = gs.download_mission()
    assert len(down) == 4
    for it, (lat, lon, alt) in zip(down, wps):
        assert (it.x, it.y) == (int(round(lat * 1e7)), int(round(lon * 1e7)))
        assert it.z == pytest.approx(alt, abs=0.01)
        assert it.command == MAV.MAV_CMD_NAV_WAYPOINT
    gs.set_mode(CUSTOM_MODE["waypoint"], "waypoint")
    start = len(gs.seen)
    # The c172p's arrival radius is 50 m, or the waypoint is passed abeam
    # (nav.h): 60 m for the track at 5 Hz (10 m between fixes)
    tol_m = 60.0
    closest = [math.inf] * 4
    t_close = [0.0] * 4
    reached: list[int] = []
    end = time.monotonic() + 60.0
    while len(reached) < 4 or reached[-1] != 3:
        assert time.monotonic() < end, f"reached {reached}, closest {closest}"
        m = gs.wait(("GLOBAL_POSITION_INT", "MISSION_ITEM_REACHED"))
        if m.get_type() == "MISSION_ITEM_REACHED":
            reached.append(m.seq)
            gs.note(f"<- MISSION_ITEM_REACHED {m.seq}")
            continue
        for i, (lat, lon, _alt) in enumerate(wps):
            d = distance_m(m.lat / 1e7, m.lon / 1e7, lat, lon)
            if d < closest[i] and (i == 0 or t_close[i - 1] > 0.0):
                closest[i], t_close[i] = d, m.time_boot_ms / 1000.0
    gs.run_for(2.0)  # the fixes just after the last waypoint
    for s in gs.seen[start:]:
        if s.msg.get_type() == "GLOBAL_POSITION_INT":
            d = distance_m(s.msg.lat / 1e7, s.msg.lon / 1e7, wps[3][0], wps[3][1])
            if d < closest[3]:
                closest[3], t_close[3] = d, s.msg.time_boot_ms / 1000.0
    assert reached[:4] == [0, 1, 2, 3], reached
    assert t_close == sorted(t_close), t_close
    assert max(closest) <= tol_m, closest
    gs.note(f"the track passed the four waypoints in order: closest "
            f"{', '.join(f'{c:.0f}' for c in closest)} m at t = "
            f"{', '.join(f'{t:.1f}' for t in t_close)} s")


def test_telemetry_rates_are_the_configured_ones(gs: GroundStation) -> None:
    """Messages per second of sim time over 20 s, per type, against the
    LNK_*_HZ rows (the aircraft's clock: time_boot_ms)."""
    seen = gs.run_for(20.0)
    t0, t1 = seen[0].t_ms, seen[-1].t_ms
    span_s = (t1 - t0) / 1000.0
    counts: dict[str, int] = {}
    for s in seen:
        k = s.msg.get_type()
        if k == "DEBUG_VECT":  # the law's state: two vectors, by name
            k = f"{k} {s.msg.name}"
        counts[k] = counts.get(k, 0) + 1
    rates = {k: v / span_s for k, v in counts.items()}
    d = _link_defaults()
    want = {"HEARTBEAT": d["heartbeat_hz"], "SYS_STATUS": d["sys_status_hz"],
            "MISSION_CURRENT": d["sys_status_hz"], "ATTITUDE": d["attitude_hz"],
            "GLOBAL_POSITION_INT": d["position_hz"], "VFR_HUD": d["vfr_hud_hz"],
            "SERVO_OUTPUT_RAW": d["servo_hz"], "RC_CHANNELS": d["rc_hz"],
            "DEBUG_VECT HT_TILT": d["law_hz"], "DEBUG_VECT HT_ERR": d["law_hz"]}
    gs.note(f"telemetry over {span_s:.1f} s of sim time (messages/s, configured): " +
            ", ".join(f"{k} {rates.get(k, 0.0):.2f} ({v:g})" for k, v in want.items()))
    for k, hz in want.items():
        # +-1 message over the window: the window's ends cut a period
        assert abs(counts.get(k, 0) - hz * span_s) <= 1.0 + 0.02 * hz * span_s, (k, rates.get(k))


def test_a_rate_set_on_the_link_is_the_rate_flown(gs: GroundStation) -> None:
    gs.set_param("LNK_ATTITUDE_HZ", 20.0)
    gs.run_for(1.0)
    seen = gs.run_for(10.0)
    n = sum(1 for s in seen if s.msg.get_type() == "ATTITUDE")
    span_s = (seen[-1].t_ms - seen[0].t_ms) / 1000.0
    gs.note(f"LNK_ATTITUDE_HZ = 20: {n / span_s:.2f} ATTITUDE/s over {span_s:.1f} s")
    assert abs(n - 20.0 * span_s) <= 1.5
    gs.set_param("LNK_ATTITUDE_HZ", 10.0)


def test_the_mission_is_cleared(gs: GroundStation) -> None:
    gs.conn.mav.mission_clear_all_send(1, 1, MAV.MAV_MISSION_TYPE_MISSION)
    ack = gs.wait("MISSION_ACK")
    assert ack.type == MAV.MAV_MISSION_ACCEPTED
    gs.note("-> MISSION_CLEAR_ALL; <- MISSION_ACK ACCEPTED")
    assert gs.download_mission() == []


def _rth_roll_in(board_lib: str, tmp: Path, kp_scale: float | None) -> tuple[float, str]:
    """Serve, [scale LAW_KP_AILERON on the link], switch to return-to-home
    (home is behind: a turn back at the nav's 10 deg/s, about 42 deg of
    bank); the sim time from the mode command to 30 deg of bank (s)."""
    g = GroundStation(board_lib, SCENARIO, SPEED, 300.0, tmp)
    try:
        g.heartbeat()
        g.wait("GLOBAL_POSITION_INT")
        g.run_for(3.0)
        note = "the aircraft file's gains"
        if kp_scale is not None:
            g.conn.mav.param_request_read_send(1, 1, b"LAW_KP_AILERON", -1)
            kp = g.wait("PARAM_VALUE", lambda m: m.param_id == "LAW_KP_AILERON").param_value
            m = g.set_param("LAW_KP_AILERON", kp * kp_scale)
            assert m.param_value == pytest.approx(kp * kp_scale, rel=1e-4)
            note = f"LAW_KP_AILERON {kp:g} -> {m.param_value:g}"
        g.set_mode(CUSTOM_MODE["rth"], "rth")
        t0 = g.t_mode_ms
        seen = g.run_for(20.0)
        t30 = next((s.t_ms - t0 for s in seen if s.msg.get_type() == "ATTITUDE"
                    and abs(math.degrees(s.msg.roll)) >= 30.0), None)
        assert t30 is not None, f"{note}: the turn back never reached 30 deg of bank"
        return t30 / 1000.0, note
    finally:
        g.finish()


def test_a_law_gain_set_on_the_link_changes_the_flight(board_lib: str, tmp_path: Path) -> None:
    """The same turn back home, flown with the aircraft's roll gain and with a
    tenth of it set over the link: the roll-in takes seconds longer (measured:
    0.8 s and 3.8 s to 30 deg of bank)."""
    base, _ = _rth_roll_in(board_lib, tmp_path, None)
    low, note = _rth_roll_in(board_lib, tmp_path, 0.1)
    assert base < 2.0, base
    assert low > base + 2.0, (base, low)
    path = os.environ.get("HT_MAVLINK_TRANSCRIPT")
    if path:
        Path(path + ".gain").write_text(f"turn back home (RTH), from the mode command to 30 deg of bank: "
                              f"{base:.1f} s with the aircraft file's gains, {low:.1f} s after "
                              f"{note} (PARAM_SET on the link)\n")


def test_malformed_frames_are_dropped_and_counted(board_lib: str, tmp_path: Path) -> None:
    """PARAM_REQUEST_READ frames broken four ways (CRC, an id common.xml
    lacks, addressed to system 7, cut short) and line noise: none is
    answered, the board's counters say why each was dropped; then the good
    frame is answered. A byte stream, as on a UART: the cut frame swallows the
    start of the next one, so the good frame goes three times."""
    g = GroundStation(board_lib, SCENARIO, SPEED, 300.0, tmp_path)
    try:
        g.heartbeat()
        msg = g.conn.mav.param_request_read_encode(1, 1, b"LAW_KP_AILERON", -1)
        good = bytes(msg.pack(g.conn.mav))
        bad_crc = good[:-1] + bytes([good[-1] ^ 0xFF])
        unknown = bytearray(good)
        unknown[7:10] = (60000).to_bytes(3, "little")  # no such message id
        other = g.conn.mav.param_request_read_encode(7, 1, b"LAW_KP_AILERON", -1)
        wrong_target = bytes(other.pack(g.conn.mav))
        noise = bytes(range(0x20, 0x7F))  # no 0xFD: nothing starts a frame
        for frame in (bad_crc, noise, bytes(unknown), wrong_target, good[:-4]):
            g.send_raw(frame)
        g.run_for(1.0)
        assert not any(s.msg.get_type() == "PARAM_VALUE" for s in g.seen)
        for _ in range(3):
            g.send_raw(good)
        g.wait("PARAM_VALUE", lambda m: m.param_id == "LAW_KP_AILERON")
        g.run_for(1.0)
        answers = sum(1 for s in g.seen if s.msg.get_type() == "PARAM_VALUE")
    finally:
        g.finish()
    c = g.stats()["board_link"]
    g.note(f"malformed frames: {c}")
    print(f"\nboard link after the malformed frames: {c}, PARAM_VALUE answers {answers}")
    assert answers == c["rx_ok"] and answers in (2, 3), (answers, c)  # one good frame eaten
    assert c["rx_bad_crc"] >= 2  # the broken CRC, the cut frame (with the next one's start)
    assert c["rx_unknown_id"] == 1 and c["rx_wrong_target"] == 1, c
    assert c["rx_dropped"] == (c["rx_bad_crc"] + c["rx_garbled"] + c["rx_unknown_id"] +
                               c["rx_wrong_target"] + c["rx_bad_content"])


def test_mavproxy_connects_and_reads_the_parameters(board_lib: str, tmp_path: Path) -> None:
    """MAVProxy (from PyPI) on the port serve sends to, as a user starts it."""
    mavproxy = shutil.which("mavproxy.py", path=str(Path(sys.executable).parent))
    if mavproxy is None:
        pytest.skip("mavproxy.py is not installed (sil/requirements-mavlink.lock)")
    import socket
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    proxy = subprocess.Popen(
        [sys.executable, mavproxy, f"--master=udpin:127.0.0.1:{port}", "--non-interactive",
         "--state-basedir", str(tmp_path), "--default-modules", "param,mode,wp,link",
         "--nowait"],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=tmp_path)
    env = dict(os.environ, HT_SIL_BOARD_LIB=board_lib,
               PYTHONPATH=os.pathsep.join([str(SIL_DIR), os.environ.get("PYTHONPATH", "")]))
    serve = subprocess.Popen(
        [sys.executable, "-m", "helical_sil", "serve", str(SCENARIO), "--mavlink",
         f"udpout:127.0.0.1:{port}", "--speed", f"{SPEED:g}", "--duration", "300"],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=SIL_DIR, env=env)
    lines: list[str] = []
    try:
        assert proxy.stdout is not None
        os.set_blocking(proxy.stdout.fileno(), False)
        end = time.monotonic() + 45.0
        want = f"Received {len(params.TABLE)} parameters"
        while time.monotonic() < end and not any(want in ln for ln in lines):
            ln = proxy.stdout.readline()
            if ln:
                lines.append(ln.rstrip())
            else:
                time.sleep(0.05)
    finally:
        serve.terminate()
        proxy.terminate()
        serve_out = serve.communicate(timeout=20)[0]
        try:
            proxy.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            proxy.kill()
    text = "\n".join(lines)
    assert any(want in ln for ln in lines), f"MAVProxy said:\n{text}\nserve said:\n{serve_out}"
    assert "Detected vehicle 1:1" in text or "online system 1" in text, text


def test_serve_listens_with_udpin(board_lib: str) -> None:
    """serve --mavlink udpin: it waits for a ground station to speak first,
    then answers the address it heard from."""
    import socket
    probe = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    probe.bind(("127.0.0.1", 0))
    port = probe.getsockname()[1]
    probe.close()
    env = dict(os.environ, HT_SIL_BOARD_LIB=board_lib,
               PYTHONPATH=os.pathsep.join([str(SIL_DIR), os.environ.get("PYTHONPATH", "")]))
    serve = subprocess.Popen(
        [sys.executable, "-m", "helical_sil", "serve", str(SCENARIO), "--mavlink",
         f"udpin:127.0.0.1:{port}", "--speed", f"{SPEED:g}", "--duration", "120"],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=SIL_DIR, env=env)
    from pymavlink import mavutil
    conn = mavutil.mavlink_connection(f"udpout:127.0.0.1:{port}", source_system=255,
                                      source_component=190, dialect="common")
    try:
        hb = None
        end = time.monotonic() + 30.0
        while hb is None and time.monotonic() < end:
            conn.mav.heartbeat_send(MAV.MAV_TYPE_GCS, MAV.MAV_AUTOPILOT_INVALID, 0, 0, 0)
            hb = conn.recv_match(type="HEARTBEAT", blocking=True, timeout=1.0)
        assert hb is not None and hb.type == MAV.MAV_TYPE_FIXED_WING
    finally:
        serve.terminate()
        out = serve.communicate(timeout=20)[0]
        conn.close()
    assert "board link: rx_ok" in out, out


def test_serve_refuses_a_bad_endpoint() -> None:
    with pytest.raises(ServeError, match="udpout:HOST:PORT"):
        parse_endpoint("tcp:127.0.0.1:5760")
    with pytest.raises(ServeError, match="outside"):
        parse_endpoint("udpin:0.0.0.0:70000")
    assert str(parse_endpoint("udpin::14550")) == "udpin:0.0.0.0:14550"
    r = subprocess.run([sys.executable, "-m", "helical_sil", "serve", str(SCENARIO),
                        "--mavlink", "serial:/dev/ttyS0"], capture_output=True, text=True,
                       cwd=SIL_DIR, env=dict(os.environ, PYTHONPATH=str(SIL_DIR)))
    assert r.returncode == 2 and "udpout:HOST:PORT" in r.stderr
