"""The parameter table (include/helical/params.def) as the harness reads it,
against the table compiled into the board library, and every Python place
that takes names, defaults, bounds or frame layouts from it.

Worked values (the formats of params.def): kp_aileron max 64 -> Q16
4194304; v_ref 327.67 m/s -> 32767 cm/s; max_tilt min 2^-16 -> 1;
gyro_limit default 34.9 rad/s -> 2287206 (34.9 * 65536 = 2287206.4);
gps_min_speed 3 m/s -> 300; the SIL's gyro_bias_max_deg_s bound is
1 rad/s = 57.2958 deg/s.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from helical_sil.config import params
from helical_sil.config.scenario import (ESTIMATOR_KEYS, GAIN_BOUNDS, GAIN_DEFAULTS, LAW_PARAMS,
                                         ScenarioError, load_scenario)
from helical_sil.live import pil
from helical_sil.sim.board import Board, BoardError, compiled_table

SIL_DIR = Path(__file__).resolve().parents[1]


def test_the_table_parses_with_the_worked_values() -> None:
    assert [p.name for p in params.LAW][:3] == ["kp_aileron", "kp_elevator", "kp_rudder"]
    assert len(params.LAW) >= 14 and len(params.ESTIMATOR) >= 12  # and any row added since
    kp = params.LAW_BY_NAME["kp_aileron"]
    assert (kp.min_raw, kp.max_raw, kp.default_raw, kp.fmt.name) == (0, 4194304, 65536, "Q16")
    v = params.LAW_BY_NAME["v_ref"]
    assert (v.c_field, v.unit, v.max_raw, v.default_raw) == ("v_ref_cm_s", "m/s", 32767, 1500)
    assert params.LAW_BY_NAME["max_tilt"].min_raw == 1
    assert params.ESTIMATOR_BY_NAME["gyro_limit"].default_raw == 2287206
    assert params.ESTIMATOR_BY_NAME["gps_min_speed"].default_raw == 300


def test_python_reads_the_table_as_the_compiler_did(board_lib: str) -> None:
    """Every row: name, unit, format, stored bounds, default, scale and width
    as compiled into the board library (sil_param_info) - the two readers of
    params.def agree, and a row the C side lacks (or adds) fails here."""
    c = compiled_table(board_lib)
    assert len(params.GUIDANCE) >= 5
    assert (len(params.ALT_HOLD), len(params.SPEED_HOLD)) == (11, 7)
    assert (len(params.MODES), len(params.FBW), len(params.NAV), len(params.AOA)) == \
        (7, 5, 9, 12)
    assert set(c) == {"LAW", "DCM", "GUIDE", "ALT", "SPEED", "MODES", "FBW", "NAV", "AOA"}
    for _key, group, rows in params.BOARD_GROUPS:
        assert [r["name"] for r in c[group]] == [p.name for p in rows]
        for r, p in zip(c[group], rows):
            assert r["unit"] == p.unit and r["format"] == p.fmt.name, p.name
            assert r["description"] == p.description, p.name
            assert (r["min_raw"], r["max_raw"], r["default_raw"]) == \
                (p.min_raw, p.max_raw, p.default_raw), p.name
            assert r["scale"] == int(p.fmt.scale) and r["bytes"] == p.fmt.nbytes, p.name


def _config(**law: float) -> dict[str, object]:
    """A board config: the holds as test_run's, the law's table defaults with
    the given overrides."""
    cfg: dict[str, object] = {name: 0.0 for name in (
        "alt_integral_upright", "alt_integral_inverted",
        "trim_aileron", "trim_elevator", "trim_rudder")}
    cfg.update(control_rate_hz=40, law=law)
    return cfg


def test_the_board_takes_the_table_defaults_and_quotes_the_bounds(board_lib: str) -> None:
    Board(_config(), board_lib)  # every default is legal
    with pytest.raises(BoardError, match=r"kp_rudder = 65 is outside \[0, 64\] "
                                         r"\(per unit error, Q16\)"):
        Board(_config(kp_rudder=65.0), board_lib)
    with pytest.raises(BoardError, match=r"v_min = 0\.5 is outside \[1, 327\.67\] "
                                         r"\(m/s, int32 x100\)"):
        Board(_config(v_min=0.5), board_lib)
    with pytest.raises(BoardError, match=r"schedule = 0\.5 is not a whole number"):
        Board(_config(schedule=0.5), board_lib)
    cfg = _config()
    cfg["estimator"] = {"gps_latency": 501.0}
    with pytest.raises(BoardError, match=r"estimator\.gps_latency = 501 is outside \[0, 500\] "
                                         r"\(ms, uint16\)"):
        Board(cfg, board_lib)
    cfg["estimator"] = {"bogus": 1.0}
    with pytest.raises(BoardError, match="unknown parameter 'bogus'"):
        Board(cfg, board_lib)
    # the edges themselves are accepted
    cfg["estimator"] = {"gps_latency": 500.0, "accel_band": 2.0 ** -16, "kp_yaw": 16.0}
    Board(cfg, board_lib)
    Board(_config(max_tilt=8.0, kp_aileron=64.0), board_lib)
    # the holds, the same way (their names are the [gains] keys)
    cfg = _config()
    cfg["alt_hold"] = {"alt_protect_tau_s": 60.001}
    with pytest.raises(BoardError, match=r"alt_protect_tau_s = 60\.001 is outside \[0, 60\] "
                                         r"\(s, uint16 x1000\)"):
        Board(cfg, board_lib)
    cfg["alt_hold"] = {}
    cfg["speed_hold"] = {"throttle_max": 1.0001}
    with pytest.raises(BoardError, match=r"throttle_max = 1\.0001 is outside \[0, 1\] "
                                         r"\(throttle, Q14\)"):
        Board(cfg, board_lib)
    # a joint limit is the firmware's own check, naming the field
    cfg["speed_hold"] = {"throttle_min": 0.6, "throttle_max": 0.5}
    with pytest.raises(BoardError, match=r"speed\.throttle_max"):
        Board(cfg, board_lib)
    cfg["speed_hold"] = {}
    cfg["alt_hold"] = {"alt_integral_band_m": 20.0, "alt_max_error_m": 10.0}
    with pytest.raises(BoardError, match=r"alt\.alt_integral_band_m"):
        Board(cfg, board_lib)
    # a key that is not the board's is refused, not ignored
    cfg = _config()
    cfg["alt_kp_pitch_per_m"] = 0.1
    with pytest.raises(BoardError, match="unknown key 'alt_kp_pitch_per_m'"):
        Board(cfg, board_lib)
    # the edges themselves are accepted
    cfg = _config()
    cfg["alt_hold"] = {"alt_protect_tau_s": 60.0, "alt_max_pitch": 2.0 ** -16,
                       "alt_max_error_m": 10000.0, "alt_integral_band_m": 10000.0}
    cfg["speed_hold"] = {"throttle_min": 1.0, "throttle_max": 1.0, "spd_kff_pitch": 64.0}
    Board(cfg, board_lib)


def test_the_scenario_takes_names_defaults_and_bounds_from_the_table() -> None:
    assert LAW_PARAMS == tuple(p.name for p in params.LAW if p.name != "pitch_mode")
    for p in params.LAW:
        if p.name in LAW_PARAMS:
            assert GAIN_DEFAULTS[p.name] == p.default
            assert GAIN_BOUNDS[p.name] == (p.min, p.max)
    for p in params.HOLDS:  # the holds' rows are [gains] keys under their own names
        assert GAIN_BOUNDS[p.name] == (p.min, p.max)
        assert GAIN_DEFAULTS.get(p.name, p.default) == p.default
    assert "throttle_trim" not in GAIN_DEFAULTS  # absent: JSBSim's trim throttle
    # [estimator] keys: the table's rows the SIL does not derive, older spellings kept
    assert ESTIMATOR_KEYS["kp_rollpitch"] == ("kp_rollpitch", 1.0)
    assert ESTIMATOR_KEYS["gps_latency_s"] == ("gps_latency", 1000.0)
    assert ESTIMATOR_KEYS["gyro_bias_max_deg_s"] == ("gyro_bias_max", math.pi / 180.0)
    assert not {"imu_rate_hz", "gyro_limit", "accel_limit"} & set(ESTIMATOR_KEYS)


def _scenario(tmp_path: Path, extra: str) -> Path:
    text = (SIL_DIR / "scenarios" / "pil" / "default_short.toml").read_text()
    p = tmp_path / "s.toml"
    p.write_text(text + "\n" + extra)
    return p


@pytest.mark.parametrize("extra,message", [
    ("[gains]\nkp_aileron = 65",
     "'gains.kp_aileron' = 65 is outside [0, 64] (per unit error, Q16)"),
    ("[gains]\nmax_tilt = 0",
     "'gains.max_tilt' = 0 is outside [1.52588e-05, 8] (tilt ratio, Q16)"),
    ("[gains]\nv_ref = 400",
     "'gains.v_ref' = 400 is outside [1, 327.67] (m/s, int32 x100)"),
    ("[estimator]\nkp_yaw = 17",
     "'estimator.kp_yaw' = 17 is outside [0, 16] (1/s, Q16)"),
    ("[estimator]\ngps_latency_s = 0.6",
     "'estimator.gps_latency_s' = 0.6 is outside [0, 0.5] (s; the table's gps_latency in "
     "[0, 500] (ms, uint16))"),
    ("[estimator]\ncentripetal = 1.5", "'estimator.centripetal' = 1.5 is not a whole number"),
    ("[guidance]\nturn_trim_max = 0.6",
     "'guidance.turn_trim_max' = 0.6 is outside [0, 0.5] (ratio, Q16)"),
    ("[guidance]\nturn_trim = 2", "'guidance.turn_trim' = 2 is outside [0, 1] (0/1, uint8)"),
    ("[guidance]\nturn_trim_gain = 1", "turn_trim_gain"),
    ("[gains]\nalt_max_pitch = 0",
     "'gains.alt_max_pitch' = 0 is outside [1.52588e-05, 4] (pitch ratio, Q16)"),
    ("[gains]\nalt_protect_tau_s = 61",
     "'gains.alt_protect_tau_s' = 61 is outside [0, 60] (s, uint16 x1000)"),
    ("[gains]\nspd_max_integral = 1.5",
     "'gains.spd_max_integral' = 1.5 is outside [0, 1] (throttle, Q14)"),
])
def test_scenario_errors_quote_the_tables_bounds(tmp_path: Path, extra: str,
                                                 message: str) -> None:
    text = (SIL_DIR / "scenarios" / "pil" / "default_short.toml").read_text()
    if extra.split("\n")[0] in text:
        pytest.skip("the base scenario already has that table")
    with pytest.raises(ScenarioError) as e:
        load_scenario(_scenario(tmp_path, extra))
    assert message in str(e.value), str(e.value)


@pytest.mark.parametrize("table,key,value,message", [
    ("modes", "blend_ticks", 0,
     "'modes.blend_ticks' = 0 is outside [1, 10000] (control steps, uint16)"),
    ("modes", "turn_slew_deg_s2", 90.5,
     "'modes.turn_slew_deg_s2' = 90.5 is not a whole number (deg/s^2, int16)"),
    ("nav", "l1_m", 601, "'nav.l1_m' = 601 is outside [5, 600] (m, uint16)"),
    ("fbw", "pitch_max", 4.5,
     "'fbw.pitch_max' = 4.5 is outside [1.52588e-05, 4] (pitch ratio, Q16)"),
    ("aoa", "trim_inverted", -1.5,
     "'aoa.trim_inverted' = -1.5 is outside [-1, 1] (elevator, Q14)"),
])
def test_mode_tables_quote_the_tables_bounds(table: str, key: str, value: float,
                                             message: str) -> None:
    """[modes], [nav], [fbw], [aoa] (of a scenario or an aircraft file) take
    their bounds from the table's rows."""
    from helical_sil.config import scenario
    with pytest.raises(ScenarioError) as e:
        scenario._parse_mode_tables(Path("a.toml"), {table: {key: value}},
                                    scenario.ModesConfig())
    assert message in str(e.value), str(e.value)
    mc = scenario.ModesConfig()  # and the defaults are the table's
    assert (mc.rc_loss_ticks, mc.l1_m, mc.fbw_pitch_max) == (20, 60.0, 0.5)


def test_the_estimator_config_is_in_table_units(tmp_path: Path) -> None:
    from helical_sil.sim import lockstep
    sc = load_scenario(_scenario(tmp_path, "[estimator]\ngyro_bias_max_deg_s = 10\n"
                                           "gps_latency_s = 0.05\nkp_yaw = 1.5"))
    est = lockstep.estimator_config(sc)
    assert set(est) == set(params.ESTIMATOR_BY_NAME)
    assert est["gyro_bias_max"] == pytest.approx(10 * math.pi / 180)
    assert est["gps_latency"] == pytest.approx(50.0) and est["kp_yaw"] == 1.5
    assert est["imu_rate_hz"] == sc.sim_rate_hz
    assert est["ki_yaw"] == params.ESTIMATOR_BY_NAME["ki_yaw"].default


def test_hil_frames_carry_every_row() -> None:
    """A row added to the table is a field of its configuration frame."""
    law = pil.cfg_law_payload({"control_rate_hz": 40})
    assert law == params.payload(params.LAW, params.law_defaults())
    off = 0
    for p in params.LAW:  # each default at the running offset
        raw = int.from_bytes(law[off:off + p.fmt.nbytes], "little", signed=p.fmt.signed)
        assert raw == p.default_raw, p.name
        off += p.fmt.nbytes
    assert off == len(law) == pil.LEN_CFG_LAW
    # the holds: their rows, then the rate (and the altitude hold's integrators)
    frames = pil.config_frames({"control_rate_hz": 40, "alt_integral_upright": 0.0,
                                "alt_integral_inverted": 0.0, "trim_aileron": 0.0,
                                "trim_elevator": 0.0, "trim_rudder": 0.0,
                                "speed_hold": {"spd_kp": 0.25}})
    alt, spd = frames[1][4:-2], frames[2][4:-2]  # sync, length, id ... CRC
    assert alt[:-10] == params.payload(params.ALT_HOLD, {})
    assert alt[-10:] == (40).to_bytes(2, "little") + bytes(8)
    assert spd[:-2] == params.payload(params.SPEED_HOLD, {"spd_kp": 0.25})
    assert int.from_bytes(spd[6:10], "little") == 16384  # spd_kp 0.25 in Q16 at offset 6
    assert (len(alt), len(spd)) == (pil.LEN_CFG_ALT, pil.LEN_CFG_SPD) == (52, 22)


def test_malformed_rows_are_refused() -> None:
    head = "#define HT_PARAMS_LAW(X) \\\n"
    good = 'X(A, a, a, "u", Q16, 0, 1, 0, "d")\n'
    assert params.parse(head + good)[0].name == "a"
    for bad, why in (('X(A, a, a, "u", Q17, 0, 1, 0, "d")', "unknown format"),
                     ('X(A, a, a, "u", Q16, 0, 1 + 1, 0, "d")', "plain decimal"),
                     ('X(A, a, a, "u", Q16, 0, 1, 2, "d")', "default 2 outside"),
                     ('X(A, a, a, "u", U8, 0, 300, 0, "d")', "does not fit"),
                     ('X(A, a, a, "u", Q16, 0, 1, 0)', "9 columns")):
        with pytest.raises(params.TableError, match=why):
            params.parse(head + bad + "\n")


def test_the_guidance_reaches_the_board_and_its_refusal_names_the_row(tmp_path: Path,
                                                                      board_lib: str) -> None:
    """[guidance] values go to the board in the table's units; the board
    itself refuses a value beyond a row, quoting it."""
    from helical_sil.sim import lockstep
    sc = load_scenario(_scenario(tmp_path, "[guidance]\nturn_trim = 0\nturn_trim_tau = 9\n"))
    cfg = dict(lockstep.board_config(sc, {"aileron": 0.0, "elevator": 0.0, "rudder": 0.0,
                                     "throttle": 0.5}))
    assert cfg["guidance"] == {"turn_trim": 0.0, "turn_trim_tau": 9.0}
    Board(cfg, board_lib)  # accepted
    cfg["guidance"] = {"turn_trim_hold": 11.0}
    with pytest.raises(BoardError) as e:
        Board(cfg, board_lib)
    assert "guidance.turn_trim_hold = 11 is outside [0, 10] (s, Q16)" in str(e.value)
