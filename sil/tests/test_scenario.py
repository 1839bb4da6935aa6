"""Scenario files: every shipped one parses, and bad ones name the key."""

from __future__ import annotations

from pathlib import Path

import pytest

from helical_sil.config.scenario import ScenarioError, load_scenario

from conftest import SCENARIOS

GOOD = """
aircraft = "c172p"
duration_s = 20
seed = 3
[initial]
altitude_m = 1000
airspeed_m_s = 45
heading_deg = 90
trim = true
[gains]
kp_aileron = 2.5
[wind]
north_m_s = 3
turbulence = "light"
[sensors]
gyro_noise_rad_s = 0.01
latency_steps = 1
[[command]]
t_s = 0
label = "a"
turn_rate_deg_s = 5
[[command]]
t_s = 5
label = "b"
pitch = 0.1
inverted = true
pitch_mode = "tilt_cross"
[[pass]]
segment = "a"
metric = "turn_rate_error_pct"
max = 5
"""


def _write(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "s.toml"
    p.write_text(text)
    return p


@pytest.mark.parametrize("path", sorted(SCENARIOS.glob("*.toml")), ids=lambda p: p.stem)
def test_shipped_scenarios_parse(path: Path) -> None:
    sc = load_scenario(path)
    assert sc.commands or (sc.modes is not None and sc.modes.rc), "a scenario without commands"
    assert sc.criteria, "every scenario states pass criteria"


def test_good_scenario_values(tmp_path: Path) -> None:
    sc = load_scenario(_write(tmp_path, GOOD))
    assert sc.aircraft.model == "c172p"
    assert sc.gains["kp_aileron"] == 2.5
    assert sc.gains["kp_elevator"] == 6.0  # the aircraft's default
    assert sc.turbulence == "light" and sc.latency_steps == 1
    assert sc.commands[1].pitch == 0.1 and sc.commands[1].inverted is True
    assert sc.commands[1].pitch_mode == "tilt_cross"
    assert sc.altitude_m == 1000 and sc.heading_deg == 90


@pytest.mark.parametrize("old,new,key", [
    ('seed = 3', 'seed = 3\nbogus = 1', "'bogus'"),
    ('duration_s = 20', 'duration_s = "20"', "'duration_s'"),
    ('aircraft = "c172p"', 'aircraft = "b52x"', "'aircraft'"),
    ('kp_aileron = 2.5', 'kp_ailerons = 2.5', "'gains.kp_ailerons'"),
    ('kp_aileron = 2.5', 'kp_aileron = -1', "'gains.kp_aileron'"),
    ('kp_aileron = 2.5', 'kp_aileron = true', "'gains.kp_aileron'"),
    ('trim = true', 'trim = 1', "'initial.trim'"),
    ('altitude_m = 1000', 'altitude = 1000', "'initial.altitude'"),
    ('turbulence = "light"', 'turbulence = "wild"', "'wind.turbulence'"),
    ('latency_steps = 1', 'latency_steps = 1.5', "'sensors.latency_steps'"),
    ('gyro_noise_rad_s = 0.01', 'gyro_noise = 0.01', "'sensors.gyro_noise'"),
    ('turn_rate_deg_s = 5', 'turn_rate = 5', "'command[0].turn_rate'"),
    ('turn_rate_deg_s = 5', 'turn_rate_deg_s = "fast"', "'command[0].turn_rate_deg_s'"),
    ('pitch = 0.1', 'pitch = 0.1\naltitude_m = 100', "'command[1].pitch'"),
    ('inverted = true', 'inverted = "yes"', "'command[1].inverted'"),
    ('pitch_mode = "tilt_cross"', 'pitch_mode = "body"', "'command[1].pitch_mode'"),
    ('t_s = 5', 't_s = 50', "'command[1].t_s'"),
    ('metric = "turn_rate_error_pct"', 'metric = "happiness"', "'pass[0].metric'"),
    ('segment = "a"', 'segment = "zz"', "'pass[0].segment'"),
    ('label = "b"', 'label = "a"', "'command[1].label'"),
])
def test_bad_scenario_names_the_key(tmp_path: Path, old: str, new: str, key: str) -> None:
    assert old in GOOD
    p = _write(tmp_path, GOOD.replace(old, new, 1))
    with pytest.raises(ScenarioError) as e:
        load_scenario(p)
    assert key in str(e.value), str(e.value)
    assert str(p) in str(e.value)


def test_missing_required_keys(tmp_path: Path) -> None:
    with pytest.raises(ScenarioError, match="'aircraft'"):
        load_scenario(_write(tmp_path, "duration_s = 5\n"))
    with pytest.raises(ScenarioError, match="'duration_s'"):
        load_scenario(_write(tmp_path, 'aircraft = "T37"\n'))
    with pytest.raises(ScenarioError, match=r"'command\[0\].t_s'"):
        load_scenario(_write(tmp_path, 'aircraft = "T37"\nduration_s = 5\n[[command]]\nlabel="x"\n'))


def test_not_toml_and_missing_file(tmp_path: Path) -> None:
    with pytest.raises(ScenarioError, match="not valid TOML"):
        load_scenario(_write(tmp_path, "aircraft = \n"))
    with pytest.raises(ScenarioError, match="no such file"):
        load_scenario(tmp_path / "nope.toml")


@pytest.mark.parametrize("aircraft,message", [
    ('description = "no model"\n[gains]\nv_ref = 30\n',
     "'model': missing (required): the JSBSim model to fly"),
    ('model = "c172p"\n', "'gains': missing (required): the [gains] table"),
    ('model = "c172p"\n[gains]\nkp_aileron = 2\n',
     "'gains.v_ref': missing (required): the airspeed the gains are tuned at, [1, 327.67] "
     "(m/s, int32 x100)"),
    ('model = "c172p"\n[gains]\nv_ref = 30\nv_min = 40\n',
     "'gains.v_min' = 40 (this file) must not exceed 'gains.v_ref' = 30 (this file)"),
    ('model = "c172p"\n[gains]\nv_ref = 30\n[envelope]\nstall_alpha_deg = 60\n',
     "'envelope.stall_alpha_deg'"),
    ('model = "c172p"\n[gains]\nv_ref = 30\nalt_kp = 65\n',
     "'gains.alt_kp' = 65 is outside [0, 64] (pitch ratio per m, Q16)"),
])
def test_aircraft_files_have_no_silent_defaults(tmp_path: Path, aircraft: str,
                                                message: str) -> None:
    """model, [gains] and gains.v_ref are required; every bound is the table's;
    an order between two keys names both and the file."""
    (tmp_path / "aircraft").mkdir()
    (tmp_path / "aircraft" / "mine.toml").write_text(aircraft)
    text = GOOD.replace('aircraft = "c172p"', 'aircraft = "mine"')
    with pytest.raises(ScenarioError) as e:
        load_scenario(_write(tmp_path, text))
    assert message in str(e.value), str(e.value)
    assert "mine.toml" in str(e.value)
