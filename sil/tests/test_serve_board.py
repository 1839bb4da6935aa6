"""The board's side of serve, without a socket (issue 15): the link's bytes
after a few control steps are MAVLink 2 frames a client parses, bytes given
to the board reach the firmware's parser and its counters; serve's choice of
flight modes for a scenario. Quick: it runs in sil_pytest."""

from __future__ import annotations

import os

import pytest

from helical_sil.config.scenario import load_scenario
from helical_sil.live.serve import Flight, default_mode, serve_modes
from helical_sil.sim.board import Board

os.environ.setdefault("MAVLINK20", "1")
mavutil = pytest.importorskip("pymavlink.mavutil")

from conftest import SCENARIOS  # noqa: E402

COUNTERS = ["rx_ok", "rx_dropped", "rx_bad_crc", "rx_garbled", "rx_unknown_id",
            "rx_wrong_target", "rx_bad_content", "tx_frames", "tx_overflow"]


def _parse(data: bytes) -> list[object]:
    mav = mavutil.mavlink.MAVLink(None)
    out = mav.parse_buffer(data) or []
    return list(out)


def test_a_second_of_flight_is_a_second_of_telemetry(board_lib: str) -> None:
    fl = Flight(load_scenario(SCENARIOS / "c172p_level_hold.toml"), board_lib, "fbw")
    b: Board = fl.board
    assert list(b.link_counters()) == COUNTERS
    fl.step()  # the first step sends every stream (and the mission's state) once
    b.link_tx()
    tx0 = b.link_counters()["tx_frames"]
    data = b""
    for _ in range(40):  # then 1 s at 40 Hz
        fl.step()
        data += b.link_tx()
    msgs = _parse(data)
    kinds = [m.get_type() for m in msgs]
    assert kinds.count("HEARTBEAT") == 1 and kinds.count("ATTITUDE") == 10, kinds
    hb = msgs[kinds.index("HEARTBEAT")]
    assert hb.type == mavutil.mavlink.MAV_TYPE_FIXED_WING and hb.custom_mode == 5  # FBW ("FBWA")
    assert b.link_counters()["tx_frames"] - tx0 == len(msgs)
    assert b.link_tx() == b""  # drained


def test_bytes_given_to_the_board_reach_the_firmware(board_lib: str) -> None:
    fl = Flight(load_scenario(SCENARIOS / "c172p_level_hold.toml"), board_lib, "fbw")
    b: Board = fl.board
    fl.step()
    b.link_tx()
    mav = mavutil.mavlink.MAVLink(None, srcSystem=255, srcComponent=190)
    req = mav.param_request_read_encode(1, 1, b"LAW_KP_AILERON", -1).pack(mav)
    broken = req[:-1] + bytes([req[-1] ^ 0x55])
    b.link_rx(broken)
    b.link_rx(req[:5])  # any split: a frame spans two calls
    b.link_rx(req[5:])
    got = [m for m in _parse(b.link_tx()) if m.get_type() == "PARAM_VALUE"]
    assert [(m.param_id, m.param_value) for m in got] == [("LAW_KP_AILERON", 5.0)]
    c = b.link_counters()
    assert (c["rx_ok"], c["rx_bad_crc"], c["rx_dropped"]) == (1, 1, 1), c


def test_serve_flies_the_scenarios_modes_or_its_aircrafts() -> None:
    circuit = load_scenario(SCENARIOS / "c172p_circuit_l1.toml")
    assert default_mode(circuit) == "waypoint"
    assert len(serve_modes(circuit).waypoints) == 4
    level = load_scenario(SCENARIOS / "c172p_level_hold.toml")
    assert level.modes is None and default_mode(level) == "fbw"
    mc = serve_modes(level)
    assert mc.waypoints == [] and mc.cruise_m_s == level.airspeed_m_s
    assert mc.loiter_radius_m == 400.0  # the c172p file's [nav], not the table's 60 m


def test_serve_has_help(capsys: pytest.CaptureFixture[str]) -> None:
    from helical_sil.cli import main
    with pytest.raises(SystemExit) as e:
        main(["serve", "--help"])
    assert e.value.code == 0
    out = capsys.readouterr().out
    assert "--mavlink" in out and "udpin:HOST:PORT" in out and "--speed" in out
