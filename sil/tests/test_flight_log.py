"""The SIL's flight log (flight.bin, docs/flight-log.md) read by pymavlink's
own DFReader, compared with telemetry.csv of the same flight: the same
control steps, the same numbers to each record's resolution, and every PARM
equal to the parameter row in force (the scenario's value, rounded to the
row's format, as binary32)."""

from __future__ import annotations

import math
import os
import subprocess
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from pymavlink import DFReader

from helical_sil.config import params as ptable
from helical_sil.config.scenario import load_scenario
from helical_sil.sim import lockstep
from helical_sil.sim.board import MODES_CONFIG_DEFAULTS, table_values

SCENARIOS = Path(__file__).resolve().parents[1] / "scenarios"
Q14, Q11, Q16 = 16384.0, 2048.0, 65536.0
LINK_PREFIX = {"LAW": "LAW_", "DCM": "DCM_", "GUIDE": "GDE_", "ALT": "ALT_", "SPEED": "SPD_",
               "MODES": "MOD_", "FBW": "FBW_", "NAV": "NAV_", "AOA": "AOA_", "LINK": "LNK_"}


def _read(path: Path) -> dict[str, list[Any]]:
    log = DFReader.DFReader_binary(str(path), zero_time_base=True)
    out: dict[str, list[Any]] = {}
    while True:
        m = log.recv_msg()
        if m is None:
            break
        out.setdefault(m.get_type(), []).append(m)
    return out


@pytest.fixture(scope="module")
def flight(tmp_path_factory: pytest.TempPathFactory, board_lib: str) -> tuple[Any, Any, dict, Path]:
    """The RC-loss circuit cut to 75 s (the loss at 60 s): modes, a failsafe."""
    sc = load_scenario(SCENARIOS / "c172p_circuit_rc_loss.toml")
    sc.duration_s = 75.0
    sc.criteria = []
    out = tmp_path_factory.mktemp("log")
    res = lockstep.run(sc, board_lib, log_path=out / "flight.bin")
    lockstep.write_csv(res, out / "telemetry.csv")
    tel = np.genfromtxt(out / "telemetry.csv", delimiter=",", names=True)
    return res, tel, _read(out / "flight.bin"), out / "flight.bin"


def _col(msgs: list[Any], field: str) -> np.ndarray:
    return np.array([getattr(m, field) for m in msgs], dtype=np.float64)


def test_every_control_step_is_logged_once_with_its_time(flight: tuple) -> None:
    res, tel, log, _path = flight
    n = len(tel["t_s"])
    assert n == 75 * res.scenario.control_rate_hz
    for kind in ("IMU", "GPS", "BARO", "ARSP", "ATT", "HTIN", "HTO", "CTRL", "RCOU"):
        assert len(log[kind]) == n, kind
    # TimeUS is the step's clock: the IMU samples so far, the first step's
    # after its samples (one control period)
    t_us = _col(log["HTO"], "TimeUS")
    np.testing.assert_array_equal(t_us, np.round((tel["t_s"] + 1.0 / 40.0) * 1e6))
    assert log["MSG"][0].Message.startswith("helical flight log")


def test_the_estimate_and_the_law_equal_the_telemetry(flight: tuple) -> None:
    _res, tel, log, _path = flight
    att, hto, hin, ctrl = log["ATT"], log["HTO"], log["HTIN"], log["CTRL"]
    # centidegrees ('c'): the estimator's own telemetry angles
    np.testing.assert_allclose(_col(att, "Roll"), tel["est_roll_deg"], atol=0.005 + 1e-9)
    np.testing.assert_allclose(_col(att, "Pitch"), tel["est_pitch_deg"], atol=0.005 + 1e-9)
    # raw Q14 / Q11 / Q16 fields: exact
    np.testing.assert_array_equal(_col(att, "DX") / Q14, tel["est_x"])
    np.testing.assert_array_equal(_col(att, "DZ") / Q14, tel["est_z"])
    np.testing.assert_array_equal(_col(hto, "Ail") / Q14, tel["law_aileron"])
    np.testing.assert_array_equal(_col(hto, "Elv") / Q14, tel["law_elevator"])
    np.testing.assert_array_equal(_col(hto, "Rud") / Q14, tel["law_rudder"])
    np.testing.assert_array_equal(_col(hto, "REr") / Q14, tel["roll_error"])
    np.testing.assert_array_equal(_col(hto, "PEr") / Q14, tel["pitch_error"])
    np.testing.assert_allclose(np.degrees(_col(hto, "TrnU") / Q11), tel["turn_rate_used_deg_s"],
                               rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(_col(ctrl, "PCmd") / Q16, tel["pitch_cmd"])
    np.testing.assert_array_equal(_col(hin, "Asp") / 100.0, tel["law_airspeed_m_s"])
    np.testing.assert_array_equal(_col(hin, "Inv"), tel["inverted"])
    # the law moved: a test on constants could not fail
    assert np.ptp(tel["law_aileron"]) > 0.1 and np.ptp(tel["est_roll_deg"]) > 10.0


def test_pulses_are_the_surfaces_the_aircraft_got(flight: tuple) -> None:
    _res, tel, log, _path = flight
    rcou = log["RCOU"]
    # the SIL's servos: centre 1500 us, travel 500 us; throttle idle 1000, travel 1000
    np.testing.assert_allclose((_col(rcou, "C1") - 1500.0) / 500.0, tel["aileron"], atol=1e-12)
    np.testing.assert_allclose((_col(rcou, "C2") - 1500.0) / 500.0, tel["elevator"], atol=1e-12)
    np.testing.assert_allclose((_col(rcou, "C3") - 1500.0) / 500.0, tel["rudder"], atol=1e-12)
    np.testing.assert_allclose((_col(rcou, "C4") - 1000.0) / 1000.0, tel["throttle"], atol=1e-12)
    np.testing.assert_array_equal(_col(rcou, "C5"), 0.0)  # no fifth channel


def test_mode_changes_and_the_failsafe_event(flight: tuple) -> None:
    _res, tel, log, _path = flight
    modes = [(m.TimeUS, m.Mode, m.Rsn) for m in log["MODE"]]
    mode = tel["mode"]
    changes = [0] + [k for k in range(1, len(mode)) if mode[k] != mode[k - 1]]
    want = [(round((tel["t_s"][k] + 0.025) * 1e6), int(mode[k]), int(tel["failsafe"][k]))
            for k in changes]
    assert modes == want
    assert any(m[1] == 3 and m[2] == 1 for m in modes)  # RTH for the RC loss
    ev = [(m.TimeUS, m.Id) for m in log["EV"]]
    k_fs = int(np.argmax(tel["failsafe"] > 0))
    assert (round((tel["t_s"][k_fs] + 0.025) * 1e6), 3) in ev


def test_every_parm_is_the_row_in_force(flight: tuple) -> None:
    res, _tel, log, _path = flight
    sc = res.scenario
    cfg: dict[str, Any] = dict(lockstep.board_config(sc, res.trims))
    cfg.update(lockstep.modes_board_config(sc))
    values = table_values({**MODES_CONFIG_DEFAULTS, **cfg})
    rows: list[tuple[str, float]] = []
    for key, _g, group_rows in ptable.BOARD_GROUPS:
        for p in group_rows:
            rows.append((LINK_PREFIX[p.group], p.raw(values[key][p.name]) / p.fmt.scale))
    for p in ptable.TABLE:
        if p.group == "LINK":
            rows.append(("LNK_", p.raw(p.default) / p.fmt.scale))
    parms = log["PARM"]
    assert len(parms) == len(rows) > 90  # every row of params.def
    names = [m.Name for m in parms]
    assert len(set(names)) == len(names)
    for m, (prefix, value) in zip(parms, rows):
        assert m.Name.startswith(prefix), m.Name
        assert m.Value == float(np.float32(value)), (m.Name, m.Value, value)
    # a value the scenario sets away from its default is there
    kp = [m.Value for m in parms if m.Name == "LAW_KP_AILERON"]
    assert kp == [float(np.float32(sc.gains["kp_aileron"]))]
    assert not math.isnan(sum(m.Value for m in parms))


def test_plot_draws_the_standard_plots_from_the_log(flight: tuple, tmp_path: Path) -> None:
    from helical_sil.analysis.log_plots import LOG_PLOT_FILES
    from helical_sil.analysis.log_read import read_log
    from helical_sil.cli import main

    _res, tel, _log, path = flight
    assert main(["plot", str(path), "--out", str(tmp_path / "p")]) == 0
    for name in LOG_PLOT_FILES:
        assert (tmp_path / "p" / name).stat().st_size > 10000, name
    # the reader's units: the law's aileron in [-1, 1], the airspeed in m/s
    d = read_log(path)
    np.testing.assert_array_equal(d["HTO"]["Ail"], tel["law_aileron"])
    np.testing.assert_array_equal(d["HTIN"]["Asp"], tel["law_airspeed_m_s"])


def test_plot_refuses_what_is_not_a_log(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from helical_sil.cli import main

    bad = tmp_path / "telemetry.csv"
    bad.write_text("t_s\n0\n")
    assert main(["plot", str(bad), "--out", str(tmp_path / "p")]) == 2
    err = capsys.readouterr().err
    assert "not a DataFlash .bin log" in err and "Traceback" not in err
    assert main(["plot", str(tmp_path / "none.bin")]) == 2
    assert "no such file" in capsys.readouterr().err


def _replay_bin(board_lib: str) -> Path:
    """ht_replay of the same build tree ($HT_REPLAY_BIN under ctest)."""
    env = os.environ.get("HT_REPLAY_BIN")
    p = Path(env) if env else Path(board_lib).resolve().parents[2] / "tools" / "ht_replay"
    if not p.is_file():
        if os.environ.get("HT_SIL_REQUIRE_BOARD") == "1":
            pytest.fail(f"ht_replay not built: {p}")
        pytest.skip(f"ht_replay not built: {p}")
    return p


def _replay(binary: Path, log: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(binary), "--log", str(log)], capture_output=True, text=True,
                          timeout=60, check=False)


def _offsets(data: bytes, name: bytes) -> list[int]:
    """Byte offsets of every record of a type, walking the log by its FMTs."""
    lengths = {0x80: 89}
    type_of: dict[bytes, int] = {}
    out, off = [], 0
    while off + 3 <= len(data):
        t = data[off + 2]
        if t == 0x80:
            lengths[data[off + 3]] = data[off + 4]
            type_of[data[off + 5:off + 9].rstrip(b"\0")] = data[off + 3]
        elif t == type_of.get(name):
            out.append(off)
        off += lengths[t]
    return out


def test_ht_replay_replays_the_law_bit_for_bit(flight: tuple, board_lib: str,
                                               tmp_path: Path) -> None:
    _res, tel, _log, path = flight
    binary = _replay_bin(board_lib)
    r = _replay(binary, path)
    assert r.returncode == 0, r.stderr
    assert f"{len(tel['t_s'])} steps replayed, every law output equal" in r.stdout
    data = path.read_bytes()
    # one aileron count changed in one HTO record (the 1000th): found, named
    hto = _offsets(data, b"HTO")[999]
    ail = hto + 3 + 8 + 2 + 4 + 2 * 5  # TimeUS, TrnU, Tilt, TX TY TZ REr PEr
    bad = bytearray(data)
    bad[ail] ^= 1
    (tmp_path / "ail.bin").write_bytes(bytes(bad))
    r = _replay(binary, tmp_path / "ail.bin")
    assert r.returncode == 1
    assert "step 1000): HTO.Ail logged" in r.stderr
    # a different roll gain in the PARM header: the replayed law differs
    parm = next(o for o in _offsets(data, b"PARM") if data[o + 11:o + 25] == b"LAW_KP_AILERON")
    bad = bytearray(data)
    bad[parm + 27:parm + 31] = np.float32(2.5).tobytes()
    (tmp_path / "kp.bin").write_bytes(bytes(bad))
    r = _replay(binary, tmp_path / "kp.bin")
    assert r.returncode == 1 and "HTO." in r.stderr
    # a log cut in the middle of a record, and a file that is no log
    (tmp_path / "cut.bin").write_bytes(data[:hto + 10])
    r = _replay(binary, tmp_path / "cut.bin")
    assert r.returncode == 1 and "cut short" in r.stderr
    (tmp_path / "csv.bin").write_bytes(b"t_s,x\n0,1\n")
    r = _replay(binary, tmp_path / "csv.bin")
    assert r.returncode == 1 and "byte 0: not a record header" in r.stderr
