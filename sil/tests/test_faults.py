"""The fault campaign (issue 7): sensor-fault keys, [upset], the upset
generator, the recovery metrics and the `upsets` subcommand."""

from __future__ import annotations

import json
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from helical_sil import cli
from helical_sil.analysis import metrics
from helical_sil.campaigns import upsets
from helical_sil.config.scenario import ScenarioError, Upset, load_scenario
from helical_sil.sim import faults

from conftest import SCENARIOS

FAULTS = SCENARIOS / "faults"

BASE = """
aircraft = "c172p"
duration_s = 20
seed = 4
[[command]]
t_s = 0
label = "a"
turn_rate_deg_s = 5
"""


def _write(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "f.toml"
    p.write_text(text)
    return p


@pytest.mark.parametrize("path", sorted(FAULTS.glob("*.toml")) +
                         sorted((FAULTS / "known_defects").glob("*.toml")), ids=lambda p: p.stem)
def test_fault_scenarios_parse(path: Path) -> None:
    sc = load_scenario(path)
    assert sc.criteria, "every fault scenario states its bounds"
    assert any(c.metric == "min_altitude_m" for c in sc.criteria)


def test_sensor_fault_keys(tmp_path: Path) -> None:
    sc = load_scenario(_write(tmp_path, BASE + """
[sensors]
fault_start_s = 5
airspeed_stuck_m_s = 0
airspeed_spike_m_s = 30
airspeed_spike_rate_hz = 2
gyro_saturation_rad_s = 2.0
"""))
    assert sc.fault_start_s == 5.0 and sc.airspeed_stuck_m_s == 0.0
    assert sc.airspeed_spike_m_s == 30.0 and sc.airspeed_spike_rate_hz == 2.0
    assert sc.gyro_saturation_rad_s == 2.0 and sc.upset is None
    plain = load_scenario(_write(tmp_path, BASE))
    assert plain.airspeed_stuck_m_s is None and plain.gyro_saturation_rad_s is None
    assert not faults.active(plain)


@pytest.mark.parametrize("extra, key", [
    ("[sensors]\nairspeed_spike_m_s = 30\n", "sensors.airspeed_spike_rate_hz"),
    ("[sensors]\ngyro_saturation_rad_s = 20\n", "sensors.gyro_saturation_rad_s"),
    ("[sensors]\nairspeed_stuck_m_s = 'zero'\n", "sensors.airspeed_stuck_m_s"),
    ("[sensors]\nfault_start_s = 30\n", "sensors.fault_start_s"),
    ("[sensors]\nairspeed_stuk_m_s = 0\n", "sensors.airspeed_stuk_m_s"),
    ("[upset]\npitch_deg = 10\n", "upset.roll_deg"),
    ("[upset]\nroll_deg = 10\npitch_deg = 95\n", "upset.pitch_deg"),
    ("[upset]\nroll_deg = 10\npitch_deg = 5\nyaw_deg = 3\n", "upset.yaw_deg"),
    ("[initial]\ntrim = false\n[upset]\nroll_deg = 10\npitch_deg = 5\n", "initial.trim"),
])
def test_fault_errors_name_the_key(tmp_path: Path, extra: str, key: str) -> None:
    with pytest.raises(ScenarioError, match=f"'{key}'"):
        load_scenario(_write(tmp_path, BASE + extra))


def test_upset_table(tmp_path: Path) -> None:
    sc = load_scenario(_write(tmp_path, BASE + """
[upset]
roll_deg = -170
pitch_deg = 60
calibrated_airspeed_m_s = 30
q_deg_s = 10
"""))
    assert sc.upset == Upset(-170.0, 60.0, 0.0, 30.0, 0.0, 10.0, 0.0)


def test_generate_is_seeded_and_in_range() -> None:
    a = upsets.generate("T37", 60, 1)
    assert a == upsets.generate("T37", 60, 1)
    assert a != upsets.generate("T37", 60, 2)
    assert a[4:] != upsets.generate("c172p", 60, 1)[4:]
    assert a[:4] == upsets.generate("T37", 4, 99)  # the fixed corners
    assert upsets.generate("T37", 10, 1) == a[:10]  # a short campaign is a prefix
    lo, hi = upsets.SPEED_RANGE_M_S["T37"]
    for u in a:
        assert -180.0 <= u.roll_deg <= 180.0 and -80.0 <= u.pitch_deg <= 80.0
        assert lo <= u.calibrated_airspeed_m_s <= hi
        assert max(abs(u.p_deg_s), abs(u.q_deg_s), abs(u.r_deg_s)) <= upsets.RATE_MAX_DEG_S
    assert sum(abs(u.roll_deg) > 90.0 for u in a) >= 15  # inverted ones are there


def test_upset_scenario_round_trip(tmp_path: Path) -> None:
    for i, up in enumerate(upsets.generate("c172p", 8, 3)):
        p = tmp_path / f"u{i}.toml"
        p.write_text(upsets.scenario_toml("c172p", up, i, 3, 2500.0, 45.0, 300.0, 50.0))
        sc = load_scenario(p)
        assert sc.upset == up and sc.altitude_m == 2500.0 and sc.commands[0].altitude_m == 2500.0
        assert {c.metric for c in sc.criteria} == {"recovery_time_s", "min_altitude_m"}


def test_parse_known() -> None:
    assert upsets.parse_known(["T37:2", "c172p:02"], ["T37", "c172p"], 10) == ["T37:2", "c172p:2"]
    for bad in ("T37", "T37:10", "b52:1", "T37:x"):
        with pytest.raises(ValueError, match="known-failures"):
            upsets.parse_known([bad], ["T37", "c172p"], 10)


def _scenario(tmp_path: Path, extra: str):  # type: ignore[no-untyped-def]
    return load_scenario(_write(tmp_path, BASE + extra))


def test_sensor_faults_apply(tmp_path: Path) -> None:
    meas = (0.0, 0.0, 1.0, 3.0, -3.0, 0.5, 50.0, 1000.0, 0.0)
    f = faults.SensorFaults(_scenario(tmp_path, """
[sensors]
fault_start_s = 1
airspeed_stuck_m_s = 0
gyro_saturation_rad_s = 2
"""))
    assert f.apply(0.5, meas) == meas
    assert f.apply(1.0, meas) == (0.0, 0.0, 1.0, 2.0, -2.0, 0.5, 0.0, 1000.0, 0.0)
    # spikes: about rate * time of them, each +-size, deterministic
    sc = _scenario(tmp_path, "[sensors]\nairspeed_spike_m_s = 30\nairspeed_spike_rate_hz = 4\n")
    outs = [faults.SensorFaults(sc) for _ in range(2)]
    vals = [[o.apply(k / 40.0, meas)[6] for k in range(4000)] for o in outs]
    assert vals[0] == vals[1]
    v = np.asarray(vals[0])
    assert set(np.unique(v)) <= {20.0, 50.0, 80.0}
    assert 300 < outs[0].spikes < 500  # 4/s over 100 s


def _fake_run(dcm: np.ndarray, pitch: np.ndarray, h: np.ndarray) -> SimpleNamespace:
    n = len(h)
    tel = {"t_s": np.arange(n) / 40.0, "dcm_x": dcm[:, 0], "dcm_y": dcm[:, 1],
           "dcm_z": dcm[:, 2], "pitch_cmd": pitch, "turn_rate_used_deg_s": np.zeros(n),
           "sens_airspeed_m_s": np.full(n, 50.0), "law_airspeed_m_s": np.full(n, 50.0),
           "inverted": np.zeros(n),
           "altitude_m": h, "phi_deg": np.zeros(n), "airspeed_m_s": np.full(n, 50.0)}
    sc = SimpleNamespace(gains={"v_min": 5.0, "max_tilt": 4.0}, control_rate_hz=40)
    return SimpleNamespace(telemetry=tel, scenario=sc)


def test_recovery_metrics() -> None:
    n = 40 * 20
    ang = np.radians(np.where(np.arange(n) < 200, 150.0, 3.0))  # inverted 5 s, then 3 deg off
    dcm = np.column_stack([-np.sin(ang), np.zeros(n), np.cos(ang)])
    res = _fake_run(dcm, np.zeros(n), np.linspace(2500.0, 2400.0, n))
    err = metrics.tilt_error_deg(res)  # type: ignore[arg-type]
    assert err[0] == pytest.approx(150.0) and err[-1] == pytest.approx(3.0)
    r = metrics.recovery_metrics(res)  # type: ignore[arg-type]
    assert r["recovery_time_s"] == pytest.approx(5.0)
    assert r["tilt_error_end_deg"] == pytest.approx(3.0)
    assert r["min_altitude_m"] == pytest.approx(2400.0)
    # the target follows the pitch ratio: level tilt against pitch 0.3 is 16.7 deg off
    res2 = _fake_run(np.tile([0.0, 0.0, 1.0], (n, 1)), np.full(n, 0.3), np.full(n, 2500.0))
    assert metrics.tilt_error_deg(res2)[0] == pytest.approx(np.degrees(np.arctan(0.3)))  # type: ignore[arg-type]
    assert metrics.recovery_metrics(res2)["recovery_time_s"] is None  # type: ignore[arg-type]


def test_upsets_help(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as e:
        cli.main(["upsets", "--help"])
    assert e.value.code == 0
    out = capsys.readouterr().out
    for opt in ("--aircraft", "--count", "--seed", "--out", "--known-failures", "--pitch-mode"):
        assert opt in out


def test_upsets_bad_arguments(tmp_path: Path) -> None:
    assert cli.main(["upsets", "--count", "0", "--out", str(tmp_path)]) == 2
    assert cli.main(["upsets", "--count", "2", "--known-failures", "T37:5",
                     "--out", str(tmp_path)]) == 2


def test_upsets_cli_runs(tmp_path: Path, board_lib: str) -> None:
    out = tmp_path / "u"
    rc = cli.main(["--board-lib", board_lib, "upsets", "--aircraft", "T37", "--count", "2",
                   "--seed", "1", "--out", str(out)])
    assert rc == 0
    s = json.loads((out / "summary.json").read_text())
    t37 = s["aircraft"]["T37"]
    assert t37["count"] == 2 and t37["recovered"] == 2 and t37["fraction_recovered"] == 1.0
    assert 0.0 < t37["recovery_time_worst_s"] < upsets.RECOVERY_MAX_S
    assert (out / "T37" / "upset_001.toml").is_file()
    assert (out / "T37" / "upset_001" / "telemetry.csv").is_file()
    assert "| T37" in (out / "summary.md").read_text()
    # a known failure that passes is an error (strict)
    assert cli.main(["--board-lib", board_lib, "upsets", "--aircraft", "T37", "--count", "1",
                     "--known-failures", "T37:0", "--out", str(tmp_path / "k")]) == 1


def test_batch_seeds(tmp_path: Path, board_lib: str) -> None:
    out = tmp_path / "b"
    rc = cli.main(["--board-lib", board_lib, "batch", str(FAULTS), "--only", "c172p_gyro_bias",
                   "--seeds", "3", "4", "--no-plots", "--out", str(out)])
    assert rc == 0
    s = json.loads((out / "summary.json").read_text())
    assert set(s) == {"c172p_gyro_bias_seed3", "c172p_gyro_bias_seed4"}
    m3 = json.loads((out / "c172p_gyro_bias_seed3" / "metrics.json").read_text())
    m4 = json.loads((out / "c172p_gyro_bias_seed4" / "metrics.json").read_text())
    assert m3["seed"] == 3 and m4["seed"] == 4
    assert m3["run"]["sideslip_rms_deg"] != m4["run"]["sideslip_rms_deg"]  # the bias signs differ
