"""Bad inputs of the harness answered at load time with exit 2, the file and
the key named, no traceback, nothing flown or overwritten (issue 33, item 10).
Each case below was, on main before issue 33: a hang growing memory (a GPS at
1e9 Hz), a traceback (an integer beyond double range), an error at fly time
naming another key in another unit (latency 1e300 s), JSBSim given a path
("../../etc/passwd"), an aircraft file linked from outside flown, a linked
telemetry.csv's target overwritten, and serve --stats-json on a folder failing
after the whole flight."""

from __future__ import annotations

import os
import time
from pathlib import Path

import pytest

from helical_sil import cli
from helical_sil.config.scenario import ScenarioError, load_scenario

SCENARIO = """
aircraft = "c172p"
duration_s = 0.5
[initial]
altitude_m = 1000
airspeed_m_s = 45
[[command]]
t_s = 0
turn_rate_deg_s = 0
"""


def _write(tmp_path: Path, text: str, name: str = "s.toml") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


@pytest.mark.parametrize("table, key, words", [
    ("[sensor_model.gps]\nrate_hz = 1e9\n", "'sensor_model.gps.rate_hz'", "Hz"),
    ("[sensor_model.gps]\nrate_hz = 121\n", "'sensor_model.gps.rate_hz'", "(0, 120] Hz"),
    ("[sensor_model.imu]\nrate_hz = 1e7\n", "'sensor_model.imu.rate_hz'", "Hz"),
    ("[sensor_model.gps]\npos_sigma_h_m = 1" + "0" * 400 + "\n",
     "'sensor_model.gps.pos_sigma_h_m'", "finite"),
    ("[sensor_model.gps]\nlatency_s = 1e300\n", "'sensor_model.gps.latency_s'", "[0, 0.5] s"),
    ("[sensor_model.gps]\nlatency_s = 0.6\n", "'sensor_model.gps.latency_s'", "[0, 0.5] s"),
])
def test_sensor_model_bounded_at_load(tmp_path: Path, table: str, key: str, words: str,
                                      capsys: pytest.CaptureFixture[str]) -> None:
    path = _write(tmp_path, SCENARIO + table)
    t0 = time.monotonic()
    with pytest.raises(ScenarioError) as e:
        load_scenario(path)
    assert key in str(e.value) and words in str(e.value) and str(path) in str(e.value)
    # through the command: exit 2, the message, no traceback, nothing written
    out = tmp_path / "out"
    assert cli.main(["run", str(path), "--out", str(out), "--no-plots"]) == 2
    err = capsys.readouterr().err
    assert key in err and "Traceback" not in err
    assert not out.exists()
    assert time.monotonic() - t0 < 20.0  # refused, not flown


def test_a_longer_true_latency_is_flown_when_the_estimator_is_told(tmp_path: Path) -> None:
    text = SCENARIO + "[sensor_model.gps]\nlatency_s = 0.8\n[estimator]\ngps_latency_s = 0.1\n"
    sc = load_scenario(_write(tmp_path, text))
    assert sc.sensor_model["gps"]["latency_s"] == 0.8


@pytest.mark.parametrize("model", ["../../etc/passwd", "/etc/passwd", "..", ".hidden",
                                   "c172p/../../x", "a" * 65])
def test_model_names_cannot_leave_the_aircraft_root(tmp_path: Path, model: str) -> None:
    (tmp_path / "aircraft").mkdir()
    (tmp_path / "aircraft" / "mine.toml").write_text(
        f'model = "{model}"\n[gains]\nv_ref = 30\n')
    path = _write(tmp_path, SCENARIO.replace('"c172p"', '"mine"'))
    with pytest.raises(ScenarioError) as e:
        load_scenario(path)
    assert "'model'" in str(e.value) and "mine.toml" in str(e.value)
    assert "not a JSBSim model name" in str(e.value)


def test_an_aircraft_linked_from_outside_is_not_flown(tmp_path: Path) -> None:
    outside = tmp_path / "elsewhere"
    outside.mkdir()
    (outside / "evil.toml").write_text('model = "c172p"\n[gains]\nv_ref = 30\n')
    (tmp_path / "aircraft").mkdir()
    os.symlink(outside / "evil.toml", tmp_path / "aircraft" / "evil.toml")
    path = _write(tmp_path, SCENARIO.replace('"c172p"', '"evil"'))
    with pytest.raises(ScenarioError) as e:
        load_scenario(path)
    assert "outside the aircraft folder" in str(e.value) and "'aircraft'" in str(e.value)
    # a link inside the folder is the folder's own file: flown
    (tmp_path / "aircraft" / "real.toml").write_text('model = "c172p"\n[gains]\nv_ref = 30\n')
    os.symlink(tmp_path / "aircraft" / "real.toml", tmp_path / "aircraft" / "alias.toml")
    assert load_scenario(_write(tmp_path, SCENARIO.replace('"c172p"', '"alias"'),
                                "t.toml")).aircraft.name == "alias"


def test_run_never_overwrites_a_linked_output(tmp_path: Path,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    path = _write(tmp_path, SCENARIO)
    target = tmp_path / "precious.txt"
    target.write_text("keep me\n")
    out = tmp_path / "out"
    out.mkdir()
    os.symlink(target, out / "telemetry.csv")
    assert cli.main(["run", str(path), "--out", str(out), "--no-plots"]) == 2
    err = capsys.readouterr().err
    assert "telemetry.csv" in err and "symbolic link" in err and "Traceback" not in err
    assert target.read_text() == "keep me\n"
    assert not (out / "metrics.json").exists()


@pytest.mark.parametrize("kind", ["folder", "link", "no_parent"])
def test_serve_stats_json_refused_before_flying(tmp_path: Path, kind: str,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    path = _write(tmp_path, SCENARIO)
    if kind == "folder":
        stats = tmp_path / "stats"
        stats.mkdir()
    elif kind == "link":
        (tmp_path / "precious.json").write_text("{}\n")
        stats = tmp_path / "stats.json"
        os.symlink(tmp_path / "precious.json", stats)
    else:
        stats = tmp_path / "missing" / "stats.json"
    t0 = time.monotonic()
    rc = cli.main(["serve", str(path), "--fast", "--duration", "30", "--stats-json", str(stats),
                   "--mavlink", "udpout:127.0.0.1:9"])
    assert rc == 2
    err = capsys.readouterr().err
    assert "--stats-json" in err and "Traceback" not in err
    assert time.monotonic() - t0 < 5.0  # before the 30 s flight
    if kind == "link":
        assert (tmp_path / "precious.json").read_text() == "{}\n"
