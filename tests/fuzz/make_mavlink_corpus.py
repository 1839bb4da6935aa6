#!/usr/bin/env python3
"""Writes the record-mode seeds of fuzz_mavlink_rx (tests/fuzz/corpus/mavlink_rx/rec_*):
sequences of messages packed by pymavlink's own encoder that reach the paths a raw
byte stream rarely completes - a whole mission upload (frames 0, 3, 5, 6, the legacy
MISSION_ITEM), its conversion and refusal by frame, latitude, longitude, altitude and
range, PREFLIGHT_STORAGE at rest, U16 / U8 / INT32 / REAL32 rows with right and wrong
param_type, commands by COMMAND_INT.

A record is (selector, length, payload): selector = the index of the message id in
the target's ids[] (bit 7 clear: addressed to the link), payload = the MAVLink 2
payload as pymavlink packs it. The first byte of a file is the mode: 0x01 records,
0x03 records with the aircraft at rest.

Usage: .venv/bin/python tests/fuzz/make_mavlink_corpus.py [OUT_DIR]
"""
from __future__ import annotations

import struct
import sys
from pathlib import Path

from pymavlink.dialects.v20 import common as mav

# the order of ids[] in tests/fuzz/fuzz_mavlink_rx.c
IDS = [
    mav.MAVLINK_MSG_ID_PARAM_REQUEST_LIST, mav.MAVLINK_MSG_ID_PARAM_REQUEST_READ,
    mav.MAVLINK_MSG_ID_PARAM_SET, mav.MAVLINK_MSG_ID_MISSION_COUNT,
    mav.MAVLINK_MSG_ID_MISSION_ITEM_INT, mav.MAVLINK_MSG_ID_MISSION_REQUEST_LIST,
    mav.MAVLINK_MSG_ID_MISSION_REQUEST_INT, mav.MAVLINK_MSG_ID_MISSION_REQUEST,
    mav.MAVLINK_MSG_ID_MISSION_CLEAR_ALL, mav.MAVLINK_MSG_ID_MISSION_SET_CURRENT,
    mav.MAVLINK_MSG_ID_MISSION_ACK, mav.MAVLINK_MSG_ID_COMMAND_LONG,
    mav.MAVLINK_MSG_ID_SET_MODE, mav.MAVLINK_MSG_ID_HEARTBEAT,
    mav.MAVLINK_MSG_ID_COMMAND_INT, mav.MAVLINK_MSG_ID_MISSION_ITEM,
]
LINK = mav.MAVLink(None, srcSystem=255, srcComponent=190)
HOME = (470000000, 80000000)  # the target's home
T = (1, 1)


def rec(msg: mav.MAVLink_message) -> bytes:
    frame = msg.pack(LINK)
    assert frame[0] == 0xFD
    n = frame[1]
    return bytes([IDS.index(msg.id), n]) + frame[10:10 + n]


def item(seq: int, lat: int, lon: int, z: float, frame: int = mav.MAV_FRAME_GLOBAL_RELATIVE_ALT,
         cmd: int = mav.MAV_CMD_NAV_WAYPOINT) -> bytes:
    return rec(mav.MAVLink_mission_item_int_message(*T, seq, frame, cmd, 0, 1, 0, 0, 0, 0, lat, lon,
                                                    z, 0))


def upload(items: list[bytes]) -> bytes:
    return rec(mav.MAVLink_mission_count_message(*T, len(items), 0)) + b"".join(items)


def pset(pid: str, value: float, ptype: int) -> bytes:
    return rec(mav.MAVLink_param_set_message(*T, pid.encode(), value, ptype))


def cmd_long(c: int, *p: float) -> bytes:
    p7 = list(p) + [0.0] * (7 - len(p))
    return rec(mav.MAVLink_command_long_message(*T, c, 0, *p7))


def cmd_int(c: int, *p: float) -> bytes:
    p4 = list(p) + [0.0] * (4 - len(p))
    return rec(mav.MAVLink_command_int_message(*T, 0, c, 0, 0, *p4, 0, 0, 0.0))


def bytewise_int(v: int) -> float:
    """an integer put into the float field byte-wise (PX4's encoding)"""
    return struct.unpack("<f", struct.pack("<i", v))[0]


def seeds() -> dict[str, bytes]:
    lat, lon = HOME
    square = [item(0, lat + 10000, lon - 15000, 120.0, mav.MAV_FRAME_GLOBAL_RELATIVE_ALT_INT),
              item(1, lat + 10000, lon + 15000, 620.0, mav.MAV_FRAME_GLOBAL),
              item(2, lat - 10000, lon + 15000, 120.0, mav.MAV_FRAME_GLOBAL_RELATIVE_ALT),
              item(3, lat - 10000, lon - 15000, 620.0, mav.MAV_FRAME_GLOBAL_INT)]
    legacy = [rec(mav.MAVLink_mission_item_message(*T, i, mav.MAV_FRAME_GLOBAL_RELATIVE_ALT,
                                                   mav.MAV_CMD_NAV_WAYPOINT, 0, 1, 0, 0, 0, 0,
                                                   47.001 - 0.002 * i, 8.001, 100.0, 0))
              for i in range(2)]
    listing = (rec(mav.MAVLink_mission_request_list_message(*T, 0)) +
               b"".join(rec(mav.MAVLink_mission_request_int_message(*T, i, 0)) for i in range(4)))
    return {
        "rec_mission_upload_frames": b"\x01" + upload(square) + listing,
        "rec_mission_legacy_item": b"\x01" + upload(legacy) + listing,
        "rec_mission_refused_range": b"\x01" + upload(square) + upload(
            [item(0, lat, lon, 100.0), item(1, -470000000, -1720000000, 100.0)]) + listing,
        "rec_mission_refused_alt": b"\x01" + upload(square) + upload(
            [item(0, lat, lon, 99999.0)]) + upload([item(0, lat, lon, float("nan"))]),
        "rec_mission_refused_fields": b"\x01" + upload(square) +
        upload([item(0, 910000000, lon, 100.0)]) + upload([item(0, lat, 1810000000, 100.0)]) +
        upload([item(0, lat, lon, 100.0, mav.MAV_FRAME_LOCAL_NED)]) +
        upload([item(0, lat, lon, 100.0, cmd=mav.MAV_CMD_NAV_LAND)]) +
        rec(mav.MAVLink_mission_set_current_message(*T, 2)) +
        rec(mav.MAVLink_mission_clear_all_message(*T, 0)),
        "rec_storage_at_rest": b"\x03" + cmd_long(mav.MAV_CMD_PREFLIGHT_STORAGE, 1.0) * 3 +
        cmd_long(mav.MAV_CMD_PREFLIGHT_STORAGE, 0.0) + cmd_int(mav.MAV_CMD_PREFLIGHT_STORAGE, 1.0),
        "rec_storage_flying": b"\x01" + rec(mav.MAVLink_heartbeat_message(6, 8, 0, 0, 4, 3)) +
        cmd_long(mav.MAV_CMD_PREFLIGHT_STORAGE, 1.0),
        "rec_param_types": b"\x01" +
        pset("NAV_L1", 200.0, mav.MAV_PARAM_TYPE_UINT16) +         # U16, its own type
        pset("NAV_L1", 200.5, mav.MAV_PARAM_TYPE_REAL32) +         # rounded
        pset("NAV_L1", 200.5, mav.MAV_PARAM_TYPE_UINT16) +         # not an integer
        pset("NAV_L1", 601.0, mav.MAV_PARAM_TYPE_REAL32) +         # out of range
        pset("NAV_ARRIVAL_RADIUS", 5000.0, mav.MAV_PARAM_TYPE_UINT16) +
        pset("LNK_ATTITUDE_HZ", bytewise_int(3), mav.MAV_PARAM_TYPE_UINT8) +
        pset("LNK_ATTITUDE_HZ", 3.0, mav.MAV_PARAM_TYPE_INT32) +
        pset("LNK_ATTITUDE_HZ", 3.0, 0) + pset("LNK_ATTITUDE_HZ", 3.0, 255) +
        pset("NAV_HOME_ALT", -100000.0, mav.MAV_PARAM_TYPE_INT32) +
        pset("LAW_V_MIN", bytewise_int(3), mav.MAV_PARAM_TYPE_INT32) +
        pset("LAW_V_MIN", 5.005, mav.MAV_PARAM_TYPE_REAL32) +
        pset("LAW_V_MIN", 20.0, mav.MAV_PARAM_TYPE_REAL32) +       # joint check
        rec(mav.MAVLink_param_request_read_message(*T, b"NAV_L1", -2)) +
        rec(mav.MAVLink_param_request_read_message(*T, b"NAV_L1", -1)),
        "rec_commands_int": b"\x01" +
        cmd_int(mav.MAV_CMD_DO_SET_MODE, 1.0, 11.0) + cmd_int(mav.MAV_CMD_DO_SET_MODE, 1.0, 10.4) +
        cmd_long(mav.MAV_CMD_DO_SET_MODE, 1.0, 5.0) + cmd_int(mav.MAV_CMD_NAV_RETURN_TO_LAUNCH) +
        cmd_long(mav.MAV_CMD_COMPONENT_ARM_DISARM, 1.0) +
        cmd_long(mav.MAV_CMD_SET_MESSAGE_INTERVAL, 0.0, 2147483648.0) +
        cmd_long(mav.MAV_CMD_SET_MESSAGE_INTERVAL, 0.0, 20000.0) +
        cmd_long(mav.MAV_CMD_SET_MESSAGE_INTERVAL, 30.0, -1.0) +
        cmd_long(mav.MAV_CMD_GET_MESSAGE_INTERVAL, 30.0) +
        cmd_int(mav.MAV_CMD_REQUEST_MESSAGE, 148.0) + cmd_int(mav.MAV_CMD_NAV_LAND) +
        rec(mav.MAVLink_set_mode_message(1, 1, 11)),
    }


def main() -> int:
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).parent / "corpus" / "mavlink_rx"
    out.mkdir(parents=True, exist_ok=True)
    for name, data in seeds().items():
        (out / name).write_bytes(data)
        print(f"{out / name}: {len(data)} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
