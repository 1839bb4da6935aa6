"""Processor-in-the-loop (issue 8): the HIL firmware image under QEMU against
the host SIL, step by step.

The QEMU tests need qemu-system-arm and the HIL image; they run under the
ctest entry `pil_short` (label pil), which builds the image and sets
HT_PIL_ELF (and HT_PIL_REQUIRE=1: a missing piece is then a failure, not a
skip). The protocol tests at the top run everywhere.
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import numpy as np
import pytest

from helical_sil.analysis import metrics as met
from helical_sil.config import params
from helical_sil.config.scenario import load_scenario
from helical_sil.live import pil
from helical_sil.sim import lockstep

SIL_DIR = Path(__file__).resolve().parents[1]
SHORT = SIL_DIR / "scenarios" / "pil" / "default_short.toml"  # [attitude] source = "truth"
SHORT_ESTIMATE = SIL_DIR / "scenarios" / "pil" / "estimate_short.toml"  # source = "estimate"
SURFACES = ("aileron", "elevator", "rudder", "throttle")


# --- the host side of the protocol (no QEMU) -----------------------------------

def test_crc_and_frame_layout() -> None:
    assert pil.crc16(b"123456789") == 0x29B1
    f = pil.encode(0x20, bytes(range(3)))
    assert f[:4] == bytes((0xA5, 0x5A, 3, 0x20)) and len(f) == 3 + 6
    c = pil.crc16(f[2:-2])
    assert f[-2:] == bytes((c & 0xFF, c >> 8))


def test_decoder_resynchronises_and_counts() -> None:
    d = pil.Decoder({0xA0: 2, 0x81: 0})
    good = pil.encode(0xA0, b"\x01\x02")
    bad_crc = bytearray(good)
    bad_crc[4] ^= 1
    wrong_len = pil.encode(0xA0, b"\x01")
    unknown = pil.encode(0x55, b"")
    stream = b"\x00\xa5\xa5" + bytes(bad_crc) + wrong_len + unknown + good + pil.encode(0x81)
    frames = []
    for i in range(len(stream)):  # byte by byte, as a socket may deliver it
        frames += d.feed(stream[i: i + 1])
    assert frames == [(0xA0, b"\x01\x02"), (0x81, b"")]
    assert d.bad == 3


def test_fixed_point_rounds_like_llround() -> None:
    assert pil._llround(2.5) == 3 and pil._llround(-2.5) == -3
    assert pil._llround(0.49999999999999994) == 0
    assert pil.q14(0.5 / 16384) == 1 and pil.q14(-0.5 / 16384) == -1
    assert pil.q14(2.5) == 32767 and pil.q14(-9.0) == -32768 and pil.q14(float("nan")) == 0
    assert pil.cm32(1e12) == 2 ** 31 - 1
    assert pil.to_fixed(0.013, 500.0, -500, 500) == 7  # 6.5 -> 7 (away from zero)


def test_config_frames_have_the_documented_lengths() -> None:
    cfg = {k: 0.0 for k in ("alt_integral_upright", "alt_integral_inverted", "trim_aileron",
                            "trim_elevator", "trim_rudder")}
    cfg.update(control_rate_hz=40, law={"schedule": 1})
    frames = pil.config_frames(cfg)
    # protocol 8 (docs/hil-protocol.md): CFG_LAW 63 (issue 17's options),
    # CFG_ALT 52, CFG_SPD 22, CFG_EST 60 with today's table
    assert [f[2] for f in frames] == [63, 52, 22, 58, 60]
    assert [f[3] for f in frames] == [0x10, 0x11, 0x12, 0x13, 0x15]


def test_cfg_alt_and_cfg_spd_follow_the_table() -> None:
    """The documented offsets of protocol 7 (hil_cfg_alt/spd_parse)."""
    cfg = {"control_rate_hz": 50, "alt_integral_upright": 0.25, "alt_integral_inverted": -0.5,
           "trim_aileron": 0.0, "trim_elevator": 0.0, "trim_rudder": 0.0,
           "alt_hold": {"alt_kp": 0.5, "alt_max_error_m": 123.45, "alt_protect_m_s": 60.0,
                        "alt_kv": 2.0, "alt_protect_tau_s": 1.5},
           "speed_hold": {"throttle_trim": 0.25, "spd_kff_pitch": 1.5,
                          "spd_max_integral": 0.75}}
    frames = pil.config_frames(cfg)
    a, s = frames[1][4:-2], frames[2][4:-2]
    i32 = lambda p, o: int.from_bytes(p[o:o + 4], "little", signed=True)  # noqa: E731
    u16 = lambda p, o: int.from_bytes(p[o:o + 2], "little")  # noqa: E731
    assert i32(a, 0) == 32768 and i32(a, 20) == 12345 and i32(a, 24) == 1000
    assert i32(a, 28) == 6000 and i32(a, 36) == 131072 and u16(a, 40) == 1500
    assert u16(a, 42) == 50 and i32(a, 44) == 262144 and i32(a, 48) == -524288
    assert int.from_bytes(s[0:2], "little", signed=True) == 4096
    assert int.from_bytes(s[4:6], "little", signed=True) == 16384  # throttle_max default 1
    assert i32(s, 14) == 98304 and int.from_bytes(s[18:20], "little") == 12288
    assert u16(s, 20) == 50


def test_cfg_law_and_cfg_est_follow_the_table() -> None:
    """The documented offsets of protocol 6, from the table's order and widths:
    each value lands where hil_fw.c's generated parser reads it."""
    law = {"kp_aileron": 2.0, "kd_rudder": 0.5, "v_ref": 110.0, "v_min": 30.0,
           "schedule": 1, "max_tilt": 2.5, "pitch_mode": 1,
           "roll_in": 1, "roll_in_rate_max": 0.5, "kp_sideslip": 1.5, "vertical_fade": 0.25}
    p = pil.cfg_law_payload({"control_rate_hz": 40, "law": law})
    i32 = lambda o: int.from_bytes(p[o:o + 4], "little", signed=True)  # noqa: E731
    assert i32(0) == 2 * 65536 and i32(4) == 65536 and i32(32) == 32768
    assert i32(36) == 11000 and i32(40) == 3000
    assert p[44] == 1 and i32(45) == int(2.5 * 65536) and p[49] == 1
    # protocol 8: the law options of issue 17 (roll_in u8, then roll_in_rate_max,
    # kp_sideslip, vertical_fade Q16)
    assert p[50] == 1 and i32(51) == 32768 and i32(55) == 98304 and i32(59) == 16384
    assert len(p) == 63
    est = {"imu_rate_hz": 120, "gyro_bias_max": 0.1, "gps_min_speed": -1.5, "gps_latency": 80}
    guide = {"turn_trim": 0, "turn_trim_tau": 7.5, "turn_trim_hold": 3}
    p = pil.cfg_est_payload({"control_rate_hz": 40, "estimator": est, "guidance": guide})
    assert int.from_bytes(p[0:2], "little") == 120
    assert int.from_bytes(p[2:6], "little", signed=True) == 26214  # kp_rollpitch 0.4
    assert int.from_bytes(p[18:22], "little", signed=True) == 6554  # 0.1 rad/s
    assert int.from_bytes(p[34:36], "little", signed=True) == -150
    assert p[36] == 2 and int.from_bytes(p[37:39], "little") == 80
    assert int.from_bytes(p[39:41], "little") == 3 and int.from_bytes(p[41:43], "little") == 24
    # the guidance's rows after the timing: turn_trim 0, tau 7.5 s, max 0.1 (the
    # default), min_rate 0.035 rad/s (the default), hold 3 s
    i32 = lambda o: int.from_bytes(p[o:o + 4], "little", signed=True)  # noqa: E731
    assert p[43] == 0 and i32(44) == int(7.5 * 65536) and i32(48) == 6554
    assert i32(52) == 2294 and i32(56) == 3 * 65536 and len(p) == 60
    # every row of the table is in the frame, in order: offsets are the running sum
    assert pil.LEN_CFG_LAW == sum(q.fmt.nbytes for q in params.LAW)
    assert pil.LEN_CFG_EST == (sum(q.fmt.nbytes for q in params.ESTIMATOR) + 4
                               + sum(q.fmt.nbytes for q in params.GUIDANCE))


# --- the firmware under QEMU -----------------------------------------------------

@pytest.fixture(scope="module")
def elf() -> str:
    required = os.environ.get("HT_PIL_REQUIRE") == "1"
    path = os.environ.get("HT_PIL_ELF")
    why = None
    if not path or not Path(path).is_file():
        why = f"HIL image not found (HT_PIL_ELF={path!r})"
    elif not (os.environ.get("HT_QEMU") or shutil.which("qemu-system-arm")):
        why = "qemu-system-arm not found"
    if why:
        if required:
            pytest.fail(why)
        pytest.skip(why + ": the PIL tests run under ctest -L pil")
    assert path is not None
    return path


def _strip(d: object) -> object:
    """metrics.json without the two wall-clock numbers."""
    if isinstance(d, dict):
        return {k: _strip(v) for k, v in d.items() if k not in ("sim_speed_x_realtime", "wall_s")}
    if isinstance(d, list):
        return [_strip(x) for x in d]
    return d


def test_step_frames_carry_the_host_boards_integers() -> None:
    """One step's frames: STEP, TRUTH only when flown, imu_count - 1 IMU
    frames, SENSORS with the last sample; values as sil_board.c converts."""
    s, c = _Sensors(), _Command()
    s.imu_count = 3
    s.gyro_rad_s = [[0.5 / 65536, -1.5 / 65536, 40.0]] * 3
    s.accel_g = [[0.0, 0.25, -1.0]] * 2 + [[1e9, float("nan"), -1e9]]
    frames = pil.step_frames(7, s, c)
    assert [f[3] for f in frames] == [pil.ID_STEP, pil.ID_TRUTH, pil.ID_IMU, pil.ID_IMU,
                                      pil.ID_SENSORS]
    assert [f[2] for f in frames] == [52, 42, 24, 24, 28]
    last = frames[-1][4:-2]
    assert int.from_bytes(last[0:4], "little") == 7
    vals = [int.from_bytes(last[4 + 4 * i: 8 + 4 * i], "little", signed=True) for i in range(6)]
    assert vals == [1, -2, 40 * 65536, 2 ** 31 - 1, 0, -(2 ** 31)]  # ties away, clamps, NaN
    step = frames[0][4:-2]
    assert step[4] == pil.SF_USE_TRUTH and step[5] == 3 and step[6] == 3 and step[7] == 7
    assert int.from_bytes(step[8:12], "little", signed=True) == 470000001  # 47.0000001 deg
    s.use_truth, s.imu_count = 0, 0
    frames = pil.step_frames(8, s, c)
    assert [f[3] for f in frames] == [pil.ID_STEP, pil.ID_SENSORS]
    assert frames[-1][8:-2] == bytes(24)


@pytest.mark.parametrize("scenario", [SHORT, SHORT_ESTIMATE], ids=["truth", "estimate"])
def test_pil_flies_like_the_sil_step_by_step(elf: str, board_lib: str, tmp_path: Path,
                                             scenario: Path) -> None:
    sc = load_scenario(scenario)
    ref = lockstep.run(sc, board_lib)
    r = pil.run(sc, board_lib, elf)
    got = r.result
    n = len(ref.telemetry["t_s"])
    assert len(got.telemetry["t_s"]) == n == int(sc.duration_s * sc.control_rate_hz)
    surf_ref = np.column_stack([ref.telemetry[c] for c in SURFACES])
    surf_pil = np.column_stack([got.telemetry[c] for c in SURFACES])
    mismatching = int(np.count_nonzero(np.any(surf_ref != surf_pil, axis=1)))
    differing_columns = [c for c in lockstep.COLUMNS
                         if not np.array_equal(ref.telemetry[c], got.telemetry[c],
                                               equal_nan=True)]
    m_ref, m_pil = met.run_metrics(ref), met.run_metrics(got)
    s = r.summary()
    report = {"scenario": scenario.name, "attitude_source": sc.attitude_source,
              "steps": n, "mismatching_surface_steps": mismatching,
              "differing_columns": differing_columns,
              "mismatch_steps_vs_host_step": s["mismatch_steps_vs_host_step"],
              "frames_per_s_link": s["frames_per_s_link"],
              "frames_per_s_loop": s["frames_per_s_loop"],
              "frames_sent": s["frames_sent"],
              "frames_sent_per_s_link": s["frames_sent_per_s_link"],
              "pil_wall_s": got.wall_s, "sil_wall_s": ref.wall_s,
              "firmware": s["firmware_counters_end"], "sil_run": m_ref["run"],
              "pil_run": m_pil["run"]}
    print(json.dumps(report, indent=1))
    (tmp_path / "pil_check.json").write_text(json.dumps(report, indent=1))
    assert mismatching == 0
    assert differing_columns == []
    assert s["mismatch_steps_vs_host_step"] == 0
    assert s["readback_mismatch_steps"] == 0
    assert _strip(m_ref) == _strip(m_pil)
    fw = s["firmware_counters_end"]
    assert fw["steps"] == n
    assert fw["bad_crc"] == fw["bad_length"] == fw["unknown_id"] == fw["naks"] == 0
    assert fw["link_errors"] == 0


def test_firmware_drops_bad_frames_on_the_wire(elf: str) -> None:
    with pil.Target(elf) as t:
        before = t.status()
        good = pil.step_payload(0, _Sensors(), _Command())
        bad_crc = bytearray(pil.encode(pil.ID_STEP, good))
        bad_crc[10] ^= 0x40
        t.send(b"\x00\x13\xa5" + bytes(bad_crc) + pil.encode(0x33, b"xyz")
               + pil.encode(pil.ID_STEP, good[:-1]))
        # nothing may come back for those: only the READY asked for next
        after = t.status()
        assert after["bad_crc"] == before["bad_crc"] + 1
        assert after["unknown_id"] == before["unknown_id"] + 2  # unknown id, wrong length
        assert after["steps"] == before["steps"] == 0
        assert not t.pending
        # a step before START: refused (NAK), not stepped
        t.send(pil.encode(pil.ID_STEP, good))
        with pytest.raises(pil.PilError, match="refused"):
            t.expect(pil.ID_OUTPUT, timeout_s=2.0)
        assert t.status()["naks"] == before["naks"] + 1


class _Sensors:
    imu_count = 0
    gyro_rad_s: list[list[float]] = []
    accel_g: list[list[float]] = []
    gps_fresh, gps_fix, gps_lat_deg, gps_lon_deg, gps_alt_m = 1, 3, 47.0000001, 8.0, 1500.0
    gps_vel_ned_m_s = (110.0, 0.0, 0.0)
    airspeed_fresh, pitot_m_s, baro_fresh, baro_alt_m = 1, 110.0, 1, 1500.0
    use_truth = 1
    align_to_truth = 0
    dcm_x, dcm_y, dcm_z = 0.0, 0.0, 1.0
    gyro_x = gyro_y = gyro_z = 0.0
    airspeed_m_s, altitude_m, climb_m_s = 110.0, 1500.0, 0.0
    north_m = east_m = vel_east_m_s = heading_rad = 0.0
    vel_north_m_s = 110.0


class _Command:
    turn_rate_rad_s = pitch_ratio = 0.0
    altitude_m, airspeed_m_s, throttle = 1500.0, 110.0, 0.5
    altitude_hold = speed_hold = inverted = pitch_mode = 0


def test_qemu_is_gone_after_close(elf: str) -> None:
    t = pil.Target(elf)
    proc = t.proc
    assert proc is not None and proc.poll() is None
    t.close()
    assert proc.poll() is not None
    t.close()  # idempotent
