"""Flight-mode scenarios (issue 5): the [modes]/[nav]/[fbw]/[aoa]/[[waypoint]]/
[[rc]] schema (errors name the key), the RC pulse helpers, and a short run
through the C modes (ABI 6)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from helical_sil.analysis import metrics as met
from helical_sil.config.scenario import ScenarioError, load_scenario
from helical_sil.sim import lockstep

GOOD = """
aircraft = "c172p"
duration_s = 40
seed = 1
[modes]
cruise_m_s = 48
rc_loss_ticks = 10
[nav]
law = "l1"
l1_m = 180
home_alt_m = 1550
loop = false
[fbw]
turn_rate_max_deg_s = 30
[aoa]
enabled = true
[[waypoint]]
north_m = 1000
east_m = 0
[[waypoint]]
north_m = 1000
east_m = 800
alt_m = 1520
[[rc]]
t_s = 0
label = "fbw"
mode = "fbw"
turn_rate_deg_s = 6
[[rc]]
t_s = 10
label = "auto"
mode = "waypoint"
aileron = 0
[[rc]]
t_s = 25
label = "lost"
link = false
[[pass]]
segment = "auto"
metric = "cross_track_rms_m"
max = 1000
[[pass]]
metric = "failsafe_entry_s"
max = 1
"""


def _write(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "m.toml"
    p.write_text(text)
    return p


def test_good_modes_file_parses(tmp_path: Path) -> None:
    sc = load_scenario(_write(tmp_path, GOOD))
    mc = sc.modes
    assert mc is not None
    assert mc.law == "l1" and mc.l1_m == 180 and mc.loop is False
    assert mc.cruise_m_s == 48 and mc.rc_loss_ticks == 10 and mc.home_alt_m == 1550
    assert mc.fbw_turn_rate_max_deg_s == 30
    # aircraft defaults survive where the scenario is silent
    assert mc.arrival_radius_m == 50 and mc.nav_turn_rate_max_deg_s == 10
    assert mc.aoa["enabled"] == 1.0 and mc.aoa["aoa_normal_slope_deg"] == pytest.approx(2.13)
    # a waypoint without alt_m gets the initial altitude
    assert mc.waypoints == [(1000, 0, sc.altitude_m), (1000, 800, 1520)]
    assert [e.label for e in mc.rc] == ["fbw", "auto", "lost"]
    assert mc.rc[0].turn_rate_deg_s == 6 and mc.rc[2].link is False


@pytest.mark.parametrize("edit, key", [
    (('law = "l1"', 'law = "pure"'), "'nav.law'"),
    (("l1_m = 180", "l1_m = 2"), "'nav.l1_m'"),
    (("l1_m = 180", "l1_m = 180\nwobble = 1"), "'nav.wobble'"),
    (("cruise_m_s = 48", "cruise_m_s = 'fast'"), "'modes.cruise_m_s'"),
    (("rc_loss_ticks = 10", "rc_loss_ticks = 0"), "'modes.rc_loss_ticks'"),
    (("enabled = true", "enabled = 1"), "'aoa.enabled'"),
    (("north_m = 1000\neast_m = 0", "east_m = 0"), "'waypoint[0].north_m'"),
    (('mode = "fbw"', 'mode = "acro"'), "'rc[0].mode'"),
    (('mode = "fbw"', 'mode = "fbw"\nmode_us = 1500'), "'rc[0].mode_us'"),
    (("turn_rate_deg_s = 6", "turn_rate_deg_s = 45"), "'rc[0].turn_rate_deg_s'"),
    (("t_s = 25", "t_s = 5"), "'rc[2].t_s'"),
    (("link = false", "link = 0"), "'rc[2].link'"),
    (('label = "lost"', 'label = "auto"'), "'rc[2].label'"),
    (("aileron = 0", "aileron = 1.5"), "'rc[1].aileron'"),
])
def test_bad_modes_key_is_named(tmp_path: Path, edit: tuple[str, str], key: str) -> None:
    with pytest.raises(ScenarioError) as e:
        load_scenario(_write(tmp_path, GOOD.replace(*edit, 1)))
    assert key in str(e.value)


def test_modes_and_commands_are_exclusive(tmp_path: Path) -> None:
    with pytest.raises(ScenarioError, match="'command'"):
        load_scenario(_write(tmp_path, GOOD + "[[command]]\nt_s = 0\n"))
    plain = 'aircraft = "c172p"\nduration_s = 5\n[[waypoint]]\nnorth_m = 1\neast_m = 1\n'
    with pytest.raises(ScenarioError, match="'waypoint'"):
        load_scenario(_write(tmp_path, plain))
    with pytest.raises(ScenarioError, match="'rc'"):
        load_scenario(_write(tmp_path, 'aircraft = "c172p"\nduration_s = 5\n[modes]\n'))


def test_stick_pulses_round_trip() -> None:
    for db in (0.0, 8.0, 30.0):
        for stick in (-1.0, -0.5, -0.1, 0.0, 0.2, 0.7, 1.0):
            us = lockstep.stick_pulse_us(stick, db)
            assert abs(lockstep.stick_of_pulse(us, db) - stick) <= 1.0 / (500 - db)
    assert [lockstep.mode_of_pulse(u) for u in (1000, 1500, 2000, 2150)] == \
        ["manual", "fbw", "waypoint", "rth"]


def test_modes_run_through_the_c_board(tmp_path: Path, board_lib: str) -> None:
    sc = load_scenario(_write(tmp_path, GOOD))
    res = lockstep.run(sc, board_lib)
    tel = res.telemetry
    t = tel["t_s"]
    # the C modes followed the switch, then the failsafe took over
    assert np.all(tel["mode"][(t > 1) & (t < 10)] == 1)
    assert np.all(tel["mode"][(t > 11) & (t < 25)] == 2)
    assert np.all(tel["failsafe"][t > 26] == 1) and np.all(tel["mode"][t > 26] == 3)
    # FBW: 6 deg/s from the stick, flown
    fbw = (t > 6) & (t < 10)
    assert np.mean(tel["turn_rate_deg_s"][fbw]) == pytest.approx(6.0, abs=0.6)
    m = met.run_metrics(res)
    assert m["run"]["failsafe_entry_s"] == pytest.approx(10 / 40, abs=0.03)
    seg = {s["label"]: s for s in m["segments"]}
    assert seg["fbw"]["turn_rate_error_pct"] < 10
    assert seg["auto"]["mode"] == "waypoint"
    assert "turn_rate_error_pct" not in seg["auto"]
    assert seg["auto"]["cross_track_rms_m"] is not None
