"""Processor-in-the-loop: the STM32F405 firmware image flies JSBSim under QEMU.

`run ... --target pil` flies a scenario exactly as the SIL does (the same
lockstep loop of sim/lockstep.py), except that each control step is computed by the
HIL firmware image (`ht_stm32f4_hil.elf`, firmware/hil/hil_main.c) running
in `qemu-system-arm -M netduinoplus2`: the host converts the raw sensor
samples, the truth solution and the command into the firmware's fixed-point
formats (the conversions of boards/sil/sil_board.c, rounding to nearest with
ties away from zero), sends one control step's frames (STEP, TRUTH, IMU...,
SENSORS) over the emulated USART1 (QEMU's -serial #0, a TCP socket with
nodelay=on), and flies the pulses the firmware answers with: the values it
read back from its timers' compare registers; the rest of the telemetry (the
estimate, the solution flown) is the firmware's STATE answer. Both attitude
sources work. Protocol: docs/hil-protocol.md.

The host board library still runs beside it, step for step on the same
inputs, as a shadow: every step whose firmware answer differs from the host
step in any bit is counted (`mismatch_steps`, expected 0).

Every wait is bounded (connect, banner, each frame), and QEMU is killed on
exit, also on errors and Ctrl-C.
"""

from __future__ import annotations

import contextlib
import ctypes
import json
import math
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterator

from helical_sil.config import params
from helical_sil.sim import lockstep
from helical_sil.sim.board import Board, BoardError, SilActuators, table_values

# --- the protocol (docs/hil-protocol.md) -------------------------------------

SYNC = b"\xa5\x5a"
PAYLOAD_MAX = 64
PROTOCOL_VERSION = 8  # 3: raw sensor samples, CFG_EST, STATE; 4: CFG_EST latency;
#                        5: CFG_LAW and CFG_EST laid out by the parameter table;
#                        6: CFG_EST ends with the guidance's rows;
#                        7: CFG_ALT and CFG_SPD laid out by the parameter table;
#                        8: CFG_LAW grows by the law options of issue 17 (63 bytes)

ID_HELLO, ID_CFG_LAW, ID_CFG_ALT, ID_CFG_SPD, ID_CFG_OUT, ID_START, ID_CFG_EST = (
    0x01, 0x10, 0x11, 0x12, 0x13, 0x14, 0x15)
ID_SENSORS, ID_STEP, ID_TRUTH, ID_IMU = 0x20, 0x21, 0x22, 0x23
ID_READY, ID_NAK, ID_ACK, ID_OUTPUT, ID_STATE = 0x81, 0x8E, 0x94, 0xA0, 0xA1
FW_LENGTHS = {ID_READY: 24, ID_NAK: 2, ID_ACK: 4, ID_OUTPUT: 40, ID_STATE: 55}
LEN_STEP, LEN_TRUTH, LEN_IMU, LEN_SENSORS = 52, 42, 24, 28
# the configuration frames of the parameter table's rows (hil_fw.h): CFG_LAW
# the law's rows in order, CFG_EST the estimator's, then divider and timeout
LEN_CFG_LAW = params.payload_length(params.LAW)
LEN_CFG_EST = params.payload_length(params.ESTIMATOR) + 4 + params.payload_length(params.GUIDANCE)
# the holds' rows, then u16 rate_hz (and for CFG_ALT two i32 Q20 integrators)
LEN_CFG_ALT = params.payload_length(params.ALT_HOLD) + 10
LEN_CFG_SPD = params.payload_length(params.SPEED_HOLD) + 2
IMU_MAX = 32  # samples per control step (HIL_IMU_MAX = SIL_IMU_MAX)
# The firmware's receive ring holds 255 bytes: a step's frames beyond this
# many bytes are sent after a HELLO/READY round trip (the firmware has then
# taken everything before it).
RX_BUDGET = 224

SF_ALTITUDE_HOLD, SF_SPEED_HOLD, SF_INVERTED, SF_TILT_CROSS = 0x01, 0x02, 0x04, 0x08
SF_USE_TRUTH = 0x10
SF_ALIGN = 0x20  # align the estimator to the TRUTH frame before the step's samples
FRESH_GPS, FRESH_AIRSPEED, FRESH_BARO = 0x01, 0x02, 0x04
ST_CONTROL_RAN, ST_FAILSAFE, ST_GUARD_ENGAGED = 0x01, 0x02, 0x04

# output-stage functions (include/helical/output/mixer.h) of the SIL's four channels
OS_FN_AILERON, OS_FN_ELEVATOR, OS_FN_RUDDER, OS_FN_THROTTLE = 1, 3, 4, 5
SIL_CHANNELS = (OS_FN_AILERON, OS_FN_ELEVATOR, OS_FN_RUDDER, OS_FN_THROTTLE)

_SIM_RUN = lockstep.run  # the SIL loop itself, also while as_sim_target() has replaced lockstep.run

DEFAULT_ELF = (Path(__file__).resolve().parents[3] / "build" / "stm32f4" / "boards" / "stm32f4"
               / "ht_stm32f4_hil.elf")


class PilError(BoardError):
    """QEMU, the link or the firmware failed (exit status 3 in the CLI)."""


def crc16(data: bytes, crc: int = 0xFFFF) -> int:
    """CRC-16/CCITT-FALSE (check value of b'123456789': 0x29B1)."""
    for b in data:
        crc ^= b << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1021) & 0xFFFF if crc & 0x8000 else (crc << 1) & 0xFFFF
    return crc


def encode(msg_id: int, payload: bytes = b"") -> bytes:
    if len(payload) > PAYLOAD_MAX:
        raise ValueError("payload over 64 bytes")
    body = bytes((len(payload), msg_id)) + payload
    c = crc16(body)
    return SYNC + body + bytes((c & 0xFF, c >> 8))


class Decoder:
    """Frames out of a byte stream; resynchronises on the next A5 5A after any
    bad frame (bad length, CRC, or an unknown id or length), counting it."""

    def __init__(self, lengths: dict[int, int]):
        self.lengths = lengths
        self.buf = bytearray()
        self.bad = 0

    def feed(self, data: bytes) -> list[tuple[int, bytes]]:
        self.buf += data
        out: list[tuple[int, bytes]] = []
        while True:
            i = self.buf.find(SYNC)
            if i < 0:
                keep = 1 if self.buf[-1:] == SYNC[:1] else 0
                del self.buf[: len(self.buf) - keep]
                return out
            del self.buf[:i]
            if len(self.buf) < 4:
                return out
            n = self.buf[2]
            if n > PAYLOAD_MAX:
                self.bad += 1
                del self.buf[:1]
                continue
            if len(self.buf) < n + 6:
                return out
            body = bytes(self.buf[2: 4 + n])
            crc = self.buf[4 + n] | (self.buf[5 + n] << 8)
            msg_id = self.buf[3]
            if crc != crc16(body) or self.lengths.get(msg_id) != n:
                self.bad += 1
                del self.buf[:1]
                continue
            del self.buf[: n + 6]
            out.append((msg_id, body[2:]))


# --- fixed point, exactly as boards/sil/sil_board.c converts -----------------

I16 = (-32768, 32767)
I32 = (-(2 ** 31), 2 ** 31 - 1)


def _llround(s: float) -> int:
    """C's llround: to nearest, ties away from zero (exact for |s| < 2**52)."""
    a = abs(s)
    f = math.floor(a)
    r = f + 1 if a - f >= 0.5 else f
    return int(r) if s >= 0 else -int(r)


def to_fixed(v: float, scale: float, lo: int, hi: int) -> int:
    """round(v * scale) saturated to [lo, hi]; NaN gives 0 (sil_board.c to_fixed)."""
    if v != v:
        return 0
    s = float(v) * scale
    if s <= lo:
        return lo
    if s >= hi:
        return hi
    return _llround(s)


def q14(v: float) -> int:
    return to_fixed(v, 16384.0, *I16)


def q11(v: float) -> int:
    return to_fixed(v, 2048.0, *I16)


def q16(v: float) -> int:
    return to_fixed(v, 65536.0, *I32)


def cm16(v: float) -> int:
    return to_fixed(v, 100.0, *I16)


def cm32(v: float) -> int:
    return to_fixed(v, 100.0, *I32)


def _i16(v: int) -> bytes:
    return v.to_bytes(2, "little", signed=True)


def _i32(v: int) -> bytes:
    return v.to_bytes(4, "little", signed=True)


def _u16(v: int) -> bytes:
    return v.to_bytes(2, "little")


def cfg_est_payload(c: dict[str, Any]) -> bytes:
    """CFG_EST: the estimator's rows of the parameter table in order, as
    sil_board_init converts them, then the IMU timing (divider = imu / control
    rate; timeout = imu rate / 5), then the guidance's rows."""
    v = table_values(c)
    est, guide = v["estimator"], v["guidance"]
    imu, ctl = int(est["imu_rate_hz"]), int(c["control_rate_hz"])
    if ctl < 1 or imu < ctl or imu % ctl != 0 or imu // ctl > IMU_MAX:
        raise PilError(f"imu_rate_hz {imu} is not 1..{IMU_MAX} times control_rate_hz {ctl}")
    p = (params.payload(params.ESTIMATOR, est) + _u16(imu // ctl) + _u16(imu // 5)
         + params.payload(params.GUIDANCE, guide))
    assert len(p) == LEN_CFG_EST
    return p


def cfg_law_payload(c: dict[str, Any]) -> bytes:
    """CFG_LAW: the law's rows of the parameter table in order, as
    sil_board_init converts them."""
    law = table_values(c)["law"]
    p = params.payload(params.LAW, law)
    assert len(p) == LEN_CFG_LAW
    return p


def _channel_default(fn: int) -> dict[str, int]:
    """os_channel_default (src/output/output_stage.c)."""
    thr = fn == OS_FN_THROTTLE
    return {"function": fn, "reversed": 0, "centre_us": 1000 if thr else 1500, "trim_us": 0,
            "travel_us": 1000 if thr else 500, "min_us": 1000, "max_us": 2000,
            "failsafe_us": 1000 if thr else 1500}


def output_channels(config: dict[str, Any]) -> list[dict[str, int]]:
    """The SIL board's four channels with the aircraft's trims (sil_board_init)."""
    chans = [_channel_default(fn) for fn in SIL_CHANNELS]
    for ch, key in zip(chans, ("trim_aileron", "trim_elevator", "trim_rudder")):
        ch["trim_us"] = to_fixed(config[key], float(ch["travel_us"]), -500, 500)
    return chans


def config_frames(config: dict[str, Any]) -> list[bytes]:
    """CFG_LAW, CFG_ALT, CFG_SPD, CFG_OUT, CFG_EST for a board config (lockstep.board_config)."""
    c = config
    rate = int(c["control_rate_hz"])
    law = cfg_law_payload(c)
    v = table_values(c)
    alt = params.payload(params.ALT_HOLD, v["alt_hold"]) + rate.to_bytes(2, "little")
    for k in ("alt_integral_upright", "alt_integral_inverted"):
        alt += to_fixed(c[k], 1048576.0, *I32).to_bytes(4, "little", signed=True)
    spd = params.payload(params.SPEED_HOLD, v["speed_hold"]) + rate.to_bytes(2, "little")
    out = bytes((len(SIL_CHANNELS), 0))
    for ch in output_channels(c):
        out += bytes((ch["function"], ch["reversed"]))
        out += ch["centre_us"].to_bytes(2, "little")
        out += ch["trim_us"].to_bytes(2, "little", signed=True)
        for k in ("travel_us", "min_us", "max_us", "failsafe_us"):
            out += ch[k].to_bytes(2, "little")
    assert (len(alt), len(spd), len(out)) == (LEN_CFG_ALT, LEN_CFG_SPD, 58)
    return [encode(ID_CFG_LAW, law), encode(ID_CFG_ALT, alt), encode(ID_CFG_SPD, spd),
            encode(ID_CFG_OUT, out), encode(ID_CFG_EST, cfg_est_payload(c))]


def imu_count(s: Any) -> int:
    """The samples sil_board_step takes: imu_count clamped to [0, IMU_MAX]."""
    return min(max(int(s.imu_count), 0), IMU_MAX)


def imu_payload(s: Any, i: int) -> bytes:
    """Sample i of a SilSensors: gyro rad/s and specific force g, Q16."""
    return (b"".join(_i32(q16(s.gyro_rad_s[i][k])) for k in range(3))
            + b"".join(_i32(q16(s.accel_g[i][k])) for k in range(3)))


def step_payload(seq: int, s: Any, c: Any) -> bytes:
    """STEP from a SilSensors and a SilCommand (sil_board_step's slow_sensors
    and guided_command conversions)."""
    thr = c.throttle
    thr = 0.0 if thr < 0.0 else (1.0 if thr > 1.0 else thr)
    flags = ((SF_ALTITUDE_HOLD if c.altitude_hold else 0) | (SF_SPEED_HOLD if c.speed_hold else 0)
             | (SF_INVERTED if c.inverted else 0) | (SF_TILT_CROSS if c.pitch_mode else 0)
             | (SF_USE_TRUTH if s.use_truth else 0) | (SF_ALIGN if s.align_to_truth else 0))
    fresh = ((FRESH_GPS if s.gps_fresh else 0) | (FRESH_AIRSPEED if s.airspeed_fresh else 0)
             | (FRESH_BARO if s.baro_fresh else 0))
    p = (seq & 0xFFFFFFFF).to_bytes(4, "little")
    p += bytes((flags, imu_count(s), to_fixed(s.gps_fix, 1.0, 0, 3), fresh))
    p += _i32(to_fixed(s.gps_lat_deg, 1.0e7, -900000000, 900000000))
    p += _i32(to_fixed(s.gps_lon_deg, 1.0e7, -1800000000, 1800000000))
    p += _i32(cm32(s.gps_alt_m))
    p += b"".join(_i32(cm32(s.gps_vel_ned_m_s[k])) for k in range(3))
    p += _i16(cm16(s.pitot_m_s)) + _i32(cm32(s.baro_alt_m))
    p += _i16(q11(c.turn_rate_rad_s)) + _i32(q16(c.pitch_ratio)) + _i32(cm32(c.altitude_m))
    p += _i16(cm16(c.airspeed_m_s)) + _i16(q14(thr))
    assert len(p) == LEN_STEP
    return p


def truth_payload(s: Any) -> bytes:
    """TRUTH: JSBSim's state as sil_board.c's truth_solution converts it."""
    p = b"".join(_i16(q14(v)) for v in (s.dcm_x, s.dcm_y, s.dcm_z))
    p += b"".join(_i16(q11(v)) for v in (s.gyro_x, s.gyro_y, s.gyro_z))
    p += _i16(cm16(s.airspeed_m_s))
    p += b"".join(_i32(cm32(v)) for v in (s.altitude_m, s.climb_m_s, s.north_m, s.east_m,
                                          s.vel_north_m_s, s.vel_east_m_s))
    p += _i16(q14(math.cos(s.heading_rad))) + _i16(q14(math.sin(s.heading_rad)))
    assert len(p) == LEN_TRUTH
    return p


def step_frames(seq: int, s: Any, c: Any) -> list[bytes]:
    """One control step's frames: STEP, TRUTH (when the truth is flown), an
    IMU frame per sample but the last, SENSORS (seq and the last sample)."""
    n = imu_count(s)
    frames = [encode(ID_STEP, step_payload(seq, s, c))]
    if s.use_truth or s.align_to_truth:
        frames.append(encode(ID_TRUTH, truth_payload(s)))
    frames += [encode(ID_IMU, imu_payload(s, i)) for i in range(n - 1)]
    last = imu_payload(s, n - 1) if n > 0 else bytes(LEN_IMU)
    frames.append(encode(ID_SENSORS, (seq & 0xFFFFFFFF).to_bytes(4, "little") + last))
    return frames


@dataclass
class State:
    """STATE: the estimate and the solution the control flew on."""
    seq: int
    flags: int
    est_row: tuple[int, int, int]
    roll_cdeg: int
    pitch_cdeg: int
    yaw_cdeg: int
    bias_q16: tuple[int, int, int]
    est_flags: int
    nav_row: tuple[int, int, int]
    nav_airspeed_cm_s: int
    nav_altitude_cm: int
    nav_climb_cm_s: int
    nav_north_cm: int
    nav_east_cm: int

    @classmethod
    def parse(cls, p: bytes) -> State:
        def i16(o: int) -> int:
            return int.from_bytes(p[o: o + 2], "little", signed=True)

        def i32(o: int) -> int:
            return int.from_bytes(p[o: o + 4], "little", signed=True)

        return cls(int.from_bytes(p[0:4], "little"), p[4], (i16(5), i16(7), i16(9)), i16(11),
                   i16(13), int.from_bytes(p[15:17], "little"), (i32(17), i32(21), i32(25)),
                   int.from_bytes(p[29:31], "little"), (i16(31), i16(33), i16(35)), i16(37),
                   i32(39), i32(43), i32(47), i32(51))


@dataclass
class Output:
    seq: int
    ccr_us: tuple[int, ...]
    pulse_us: tuple[int, ...]
    law_aileron: int
    law_elevator: int
    law_rudder: int
    pitch_cmd: int
    throttle: int
    turn_rate_used: int
    roll_error: int
    pitch_error: int
    flags: int

    @classmethod
    def parse(cls, p: bytes) -> Output:
        def u16(o: int) -> int:
            return int.from_bytes(p[o: o + 2], "little")

        def i16(o: int) -> int:
            return int.from_bytes(p[o: o + 2], "little", signed=True)

        return cls(int.from_bytes(p[0:4], "little"), tuple(u16(4 + 2 * i) for i in range(4)),
                   tuple(u16(12 + 2 * i) for i in range(4)), i16(20), i16(22), i16(24),
                   int.from_bytes(p[26:30], "little", signed=True), i16(30), i16(32), i16(34),
                   i16(36), u16(38))


def parse_ready(p: bytes) -> dict[str, int]:
    def u16(o: int) -> int:
        return int.from_bytes(p[o: o + 2], "little")

    return {"magic_ok": int(p[0:2] == b"HT"), "version": p[2], "started": p[3],
            "servo_count": p[4], "frames_ok": u16(6), "bad_crc": u16(8), "bad_length": u16(10),
            "unknown_id": u16(12), "skipped_bytes": u16(14), "naks": u16(16),
            "steps": int.from_bytes(p[18:22], "little"), "link_errors": u16(22)}


# --- QEMU ---------------------------------------------------------------------


def find_qemu() -> str:
    q = os.environ.get("HT_QEMU") or shutil.which("qemu-system-arm")
    if not q:
        raise PilError("qemu-system-arm not found (apt-get install --no-install-recommends "
                       "qemu-system-arm, or set HT_QEMU)")
    return q


def find_elf(explicit: str | os.PathLike[str] | None = None) -> Path:
    p = Path(explicit or os.environ.get("HT_PIL_ELF") or DEFAULT_ELF)
    if not p.is_file():
        raise PilError(f"HIL firmware image not found: {p} (build it: cmake --workflow "
                       "--preset stm32f4, or pass --elf / set HT_PIL_ELF)")
    return p


def _die_with_parent() -> None:
    """In the QEMU child (Linux): SIGTERM when the harness dies, even by SIGKILL."""
    with contextlib.suppress(Exception):
        ctypes.CDLL(None, use_errno=True).prctl(1, int(signal.SIGTERM))  # PR_SET_PDEATHSIG


class Target:
    """One QEMU netduinoplus2 running the HIL image, its USART1 on a TCP socket."""

    def __init__(self, elf: str | os.PathLike[str] | None = None, timeout_s: float = 5.0,
                 start_timeout_s: float = 20.0):
        self.elf = find_elf(elf)
        self.qemu = find_qemu()
        self.timeout_s = timeout_s
        self.proc: subprocess.Popen[bytes] | None = None
        self._err: Any = None  # QEMU's stderr, a temporary file (a pipe could fill up)
        self.sock: socket.socket | None = None
        self.dec = Decoder(FW_LENGTHS)
        self.pending: list[tuple[int, bytes]] = []
        self.ready: dict[str, int] = {}
        self.frames = 0  # control steps answered
        self.frames_sent = 0  # frames sent for them (STEP, TRUTH, IMU, SENSORS)
        self.link_s = 0.0
        self._start(start_timeout_s)

    def _start(self, start_timeout_s: float) -> None:
        deadline = time.monotonic() + start_timeout_s
        for _attempt in range(5):  # the free port may be taken between probe and bind
            with socket.socket() as probe:
                probe.bind(("127.0.0.1", 0))
                port = probe.getsockname()[1]
            self._err = tempfile.TemporaryFile()
            self.proc = subprocess.Popen(
                [self.qemu, "-M", "netduinoplus2", "-nographic", "-monitor", "none",
                 "-serial", f"tcp:127.0.0.1:{port},server=on,wait=off,nodelay=on",
                 "-kernel", str(self.elf)],
                stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=self._err,
                preexec_fn=_die_with_parent if sys.platform.startswith("linux") else None)
            while time.monotonic() < deadline and self.proc.poll() is None:
                try:
                    self.sock = socket.create_connection(("127.0.0.1", port), timeout=0.5)
                    break
                except OSError:
                    time.sleep(0.02)
            if self.sock is not None:
                break
            err = self._stop_qemu()
            if time.monotonic() >= deadline:
                raise PilError(f"QEMU did not open its serial socket in {start_timeout_s:.0f} s"
                               + (f": {err}" if err else ""))
        if self.sock is None:
            raise PilError("QEMU did not start (port clashes?)")
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        # The banner went out when the USART came up, probably before we were
        # connected (wait=off): ask with HELLO until a READY comes back.
        while True:
            self.send(encode(ID_HELLO))
            try:
                self.ready = parse_ready(self.expect(ID_READY, timeout_s=0.2))
                break
            except TimeoutError:
                if time.monotonic() >= deadline:
                    self.close()
                    raise PilError("no READY banner from the firmware in "
                                   f"{start_timeout_s:.0f} s") from None
        if not self.ready["magic_ok"] or self.ready["version"] != PROTOCOL_VERSION:
            self.close()
            raise PilError(f"unexpected READY from the firmware: {self.ready}")
        # An earlier HELLO may still be answered: drain the READYs until the
        # link has been quiet for 0.1 s (at most 1 s), so that no stale READY
        # is taken for the answer to a later HELLO (status()).
        drain_end = time.monotonic() + 1.0
        while time.monotonic() < drain_end:
            try:
                self.expect(ID_READY, timeout_s=0.1)
            except TimeoutError:
                break
        self.pending.clear()

    def send(self, data: bytes) -> None:
        assert self.sock is not None
        self.sock.sendall(data)

    def expect(self, msg_id: int, timeout_s: float | None = None) -> bytes:
        """The next frame of this id (others are kept aside); TimeoutError."""
        assert self.sock is not None
        deadline = time.monotonic() + (self.timeout_s if timeout_s is None else timeout_s)
        while True:
            for i, (fid, payload) in enumerate(self.pending):
                if fid == msg_id:
                    del self.pending[i]
                    return payload
                if fid == ID_NAK:
                    del self.pending[i]
                    raise PilError(f"the firmware refused frame 0x{payload[0]:02x} "
                                   f"(reason {payload[1]})")
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError(f"no frame 0x{msg_id:02x} from the firmware")
            self.sock.settimeout(left)
            try:
                data = self.sock.recv(4096)
            except socket.timeout:
                continue
            if not data:
                raise PilError("QEMU closed the serial socket")
            self.pending.extend(self.dec.feed(data))

    def configure(self, config: dict[str, Any]) -> None:
        for f in config_frames(config):
            self.send(f)
        self.send(encode(ID_START))
        try:
            ack = self.expect(ID_ACK)
        except TimeoutError:
            raise PilError("no ACK to START from the firmware") from None
        if ack[0] != 0:
            what = {1: "missing block", 2: "refused"}.get(ack[0], f"status {ack[0]}")
            raise PilError(f"the firmware's configuration check: {what} 0x{ack[1]:02x}, "
                           f"detail {ack[2]}")

    def step(self, seq: int, frames: list[bytes]) -> tuple[State, Output]:
        """Send one control step's frames; its STATE and OUTPUT."""
        t0 = time.perf_counter()
        chunk = b""
        for f in frames:
            if chunk and len(chunk) + len(f) > RX_BUDGET:
                self.send(chunk)  # more than the firmware's ring: wait until it took these
                chunk = b""
                self.status()
            chunk += f
        self.send(chunk)
        try:
            st = State.parse(self.expect(ID_STATE))
            out = Output.parse(self.expect(ID_OUTPUT))
        except TimeoutError:
            raise PilError(f"no STATE and OUTPUT for step {seq} within {self.timeout_s} s") from None
        self.link_s += time.perf_counter() - t0
        self.frames += 1
        self.frames_sent += len(frames)
        if out.seq != seq & 0xFFFFFFFF or st.seq != out.seq:
            raise PilError(f"OUTPUT for step {out.seq} (STATE {st.seq}), expected {seq}")
        return st, out

    def status(self) -> dict[str, int]:
        """The firmware's counters (HELLO -> READY; one frame in flight)."""
        self.pending = [f for f in self.pending if f[0] != ID_READY]
        self.send(encode(ID_HELLO))
        return parse_ready(self.expect(ID_READY))

    def _stop_qemu(self) -> str:
        err = ""
        if self.proc is not None:
            if self.proc.poll() is None:
                self.proc.terminate()
                try:
                    self.proc.wait(timeout=3)
                except subprocess.TimeoutExpired:
                    self.proc.kill()
                    self.proc.wait(timeout=3)
            self.proc = None
        if self._err is not None:
            with contextlib.suppress(OSError):
                self._err.seek(0)
                err = self._err.read().decode(errors="replace").strip()
                self._err.close()
            self._err = None
        return err

    def close(self) -> None:
        if self.sock is not None:
            with contextlib.suppress(OSError):
                self.sock.close()
            self.sock = None
        self._stop_qemu()

    def __enter__(self) -> Target:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


# --- the board the lockstep loop sees ------------------------------------------

# every field of the actuators: the shadow comparison covers them all (the
# flight modes' are zero on both sides: PIL flies guided scenarios only)
ACT_FIELDS = tuple(f[0] for f in SilActuators._fields_)


def _field(a: SilActuators, name: str) -> Any:
    v = getattr(a, name)
    return tuple(v) if isinstance(v, ctypes.Array) else v


@dataclass
class PilStats:
    steps: int = 0
    mismatch_steps: int = 0
    readback_mismatch_steps: int = 0  # CCR read back != the output stage's pulse
    first_mismatches: list[dict[str, Any]] = field(default_factory=list)


class PilBoard:
    """Board's interface (sensors, command, step()) with the step done by the
    firmware under QEMU; the host board runs alongside as a shadow."""

    def __init__(self, config: dict[str, Any], lib_path: str | None, target: Target,
                 stats: PilStats):
        if int(config.get("modes_enabled", 0)) != 0:
            raise PilError("PIL: flight-mode scenarios (RC pilot, navigation) are not in the "
                           "HIL protocol yet; fly them with the SIL target")
        self.host = Board(config, lib_path)  # checks every parameter, names a refused one
        self.target = target
        self.stats = stats
        self.chans = output_channels(config)
        target.configure(config)
        self._act = SilActuators()

    @property
    def sensors(self) -> Any:
        return self.host.sensors

    @property
    def command(self) -> Any:
        return self.host.command

    def _deflection(self, i: int, pulse: int) -> float:
        ch = self.chans[i]
        d = (float(pulse) - float(ch["centre_us"])) / float(ch["travel_us"])
        return -d if ch["reversed"] else d

    def step(self) -> SilActuators:
        k = self.stats.steps
        st, out = self.target.step(k, step_frames(k, self.host.sensors, self.host.command))
        a = self._act
        ctypes.memset(ctypes.addressof(a), 0, ctypes.sizeof(a))
        if st.flags & ST_CONTROL_RAN:  # else zeros, as the host board answers
            self._fill(a, st, out)
            if out.ccr_us != out.pulse_us:
                self.stats.readback_mismatch_steps += 1
        h = self.host.step()  # the shadow: the host board on the same inputs
        diff = {f: (_field(a, f), _field(h, f)) for f in ACT_FIELDS
                if _field(a, f) != _field(h, f)}
        if diff:
            self.stats.mismatch_steps += 1
            if len(self.stats.first_mismatches) < 5:
                self.stats.first_mismatches.append({"step": k, "pil_vs_sil": diff})
        self.stats.steps += 1
        return a

    def _fill(self, a: SilActuators, st: State, out: Output) -> None:
        """The actuators from the firmware's answer, converted as sil_board.c's
        actuators() converts the step's output."""
        a.control_ran = 1
        # the surfaces flown are the pulses read back from the timers (CCRx)
        a.aileron = self._deflection(0, out.ccr_us[0])
        a.elevator = self._deflection(1, out.ccr_us[1])
        a.rudder = self._deflection(2, out.ccr_us[2])
        a.throttle = self._deflection(3, out.ccr_us[3])
        a.law_aileron = out.law_aileron / 16384.0
        a.law_elevator = out.law_elevator / 16384.0
        a.law_rudder = out.law_rudder / 16384.0
        a.pitch_cmd = out.pitch_cmd / 65536.0
        a.turn_rate_used_rad_s = out.turn_rate_used / 2048.0
        a.roll_error = out.roll_error / 16384.0
        a.pitch_error = out.pitch_error / 16384.0
        a.flags = out.flags
        a.est_x, a.est_y, a.est_z = (v / 16384.0 for v in st.est_row)
        a.est_roll_deg = st.roll_cdeg / 100.0
        a.est_pitch_deg = st.pitch_cdeg / 100.0
        a.est_yaw_deg = st.yaw_cdeg / 100.0
        for k in range(3):
            a.est_bias_rad_s[k] = st.bias_q16[k] / 65536.0
        a.est_flags = st.est_flags
        a.nav_x, a.nav_y, a.nav_z = (v / 16384.0 for v in st.nav_row)
        a.nav_airspeed_m_s = st.nav_airspeed_cm_s / 100.0
        a.nav_altitude_m = st.nav_altitude_cm / 100.0
        a.nav_climb_m_s = st.nav_climb_cm_s / 100.0
        a.nav_north_m = st.nav_north_cm / 100.0
        a.nav_east_m = st.nav_east_cm / 100.0
        a.guard_engaged = 1 if st.flags & ST_GUARD_ENGAGED else 0


@dataclass
class PilResult:
    result: lockstep.RunResult
    stats: PilStats
    frames: int
    link_s: float
    ready_start: dict[str, int]
    ready_end: dict[str, int]
    frames_sent: int = 0

    def summary(self) -> dict[str, Any]:
        wall = self.result.wall_s
        return {
            "target": "pil", "machine": "qemu-system-arm -M netduinoplus2",
            "frames": self.frames,
            "frames_sent": self.frames_sent,  # all host -> firmware frames of the steps
            "frames_per_s_link": self.frames / self.link_s if self.link_s > 0 else None,
            "frames_per_s_loop": self.frames / wall if wall > 0 else None,
            "frames_sent_per_s_link": (self.frames_sent / self.link_s if self.link_s > 0
                                       else None),
            "mismatch_steps_vs_host_step": self.stats.mismatch_steps,
            "readback_mismatch_steps": self.stats.readback_mismatch_steps,
            "first_mismatches": self.stats.first_mismatches,
            "firmware_counters_end": self.ready_end,
        }


@contextlib.contextmanager
def board_factory(target: Target, stats: PilStats) -> Iterator[None]:
    """lockstep.run builds its board with lockstep.Board(config, lib); for the duration
    of this block that is a PilBoard on `target`."""
    saved = lockstep.Board

    def make(config: dict[str, Any], lib_path: str | None = None) -> PilBoard:
        return PilBoard(config, lib_path, target, stats)

    lockstep.Board = make  # type: ignore[assignment,misc]
    try:
        yield
    finally:
        lockstep.Board = saved  # type: ignore[misc]


def run(sc: Any, board_lib: str | None = None, elf: str | None = None,
        timeout_s: float = 5.0) -> PilResult:
    """Fly one scenario with the firmware under QEMU; QEMU is stopped on return."""
    stats = PilStats()
    with Target(elf, timeout_s=timeout_s) as target:
        ready0 = dict(target.ready)
        with board_factory(target, stats):
            res = _SIM_RUN(sc, board_lib)
        try:
            ready1 = target.status()
        except (TimeoutError, PilError):
            ready1 = {}
        return PilResult(res, stats, target.frames, target.link_s, ready0, ready1,
                         target.frames_sent)


@contextlib.contextmanager
def as_sim_target(elf: str | None = None, timeout_s: float = 5.0) -> Iterator[list[PilResult]]:
    """For the CLI: within this block lockstep.run flies the firmware (pil.run);
    the PilResult of each run is appended to the yielded list."""
    saved = lockstep.run
    results: list[PilResult] = []

    def pil_run(sc: Any, board_lib: str | None = None) -> lockstep.RunResult:
        r = run(sc, board_lib, elf, timeout_s)
        results.append(r)
        return r.result

    lockstep.run = pil_run  # type: ignore[assignment]
    try:
        yield results
    finally:
        lockstep.run = saved  # type: ignore[assignment]


def report(r: PilResult, out: Path) -> int:
    """Print the PIL numbers and write pil.json beside metrics.json; 1 when a
    step differed from the host step or a read-back differed."""
    s = r.summary()
    out.mkdir(parents=True, exist_ok=True)
    with (out / "pil.json").open("w") as f:
        json.dump(s, f, indent=2)
        f.write("\n")
    fw = s["firmware_counters_end"]
    print(f"PIL: {s['frames']} frames, {s['frames_per_s_link'] or 0:.0f} frames/s on the link, "
          f"{s['frames_per_s_loop'] or 0:.0f} steps/s with JSBSim; steps differing from the host "
          f"step: {s['mismatch_steps_vs_host_step']}; CCR read-back differing: "
          f"{s['readback_mismatch_steps']}; firmware: {fw.get('frames_ok', '?')} frames ok, "
          f"{fw.get('bad_crc', '?')} bad CRC, {fw.get('bad_length', '?')} bad length, "
          f"{fw.get('unknown_id', '?')} unknown id, {fw.get('naks', '?')} refused")
    return 0 if s["mismatch_steps_vs_host_step"] == 0 and s["readback_mismatch_steps"] == 0 else 1
