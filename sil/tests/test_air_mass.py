"""The air-mass metrics (fault campaign, issue 7): the wind columns of the
telemetry, the air-relative altitude, the unavoidable sink of an ideal
aircraft and the altitude error net of it; and the c172p's severe-turbulence
seed 8 (a long downdraft) flown with the airspeed protection of the hold."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest

from helical_sil.analysis import metrics
from helical_sil.config.scenario import ScenarioError, load_scenario
from helical_sil.sim import lockstep

from conftest import SCENARIOS

DT = 0.025  # 40 Hz
BASE = """
aircraft = "c172p"
duration_s = 4
seed = 1
[[command]]
t_s = 0
label = "a"
turn_rate_deg_s = 0
altitude_m = 1500
"""


def _write(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "f.toml"
    p.write_text(text)
    return p


def _res(h: np.ndarray, air_down: np.ndarray, target: float = 1500.0,
         capability: float | None = 5.0) -> Any:
    """A stand-in RunResult: what air_mass_metrics reads."""
    n = h.size
    w = np.gradient(air_down, DT)
    tel = {"t_s": np.arange(n) * DT, "altitude_m": h, "cmd_altitude_m": np.full(n, target),
           "air_down_m": air_down, "wind_down_m_s": w}
    sc = SimpleNamespace(climb_capability_m_s=capability, control_rate_hz=40)
    return SimpleNamespace(telemetry=tel, scenario=sc)


# --- unavoidable_sink -------------------------------------------------------

def test_unavoidable_sink_calm_air_and_weak_or_rising_air_is_zero() -> None:
    n = 400
    tgt = np.full(n, 1500.0)
    assert not metrics.unavoidable_sink(np.zeros(n), tgt, 5.0, DT).any()
    weak = 4.9 * DT * np.arange(n)  # sinking air slower than the climb capability
    assert not metrics.unavoidable_sink(weak, tgt, 5.0, DT).any()
    rising = -8.0 * DT * np.arange(n)
    assert not metrics.unavoidable_sink(rising, tgt, 5.0, DT).any()


def test_unavoidable_sink_grows_beyond_the_capability_and_recovers_at_it() -> None:
    # 12 m/s down for 20 s (800 steps), then still air
    w = np.r_[np.full(800, 12.0), np.zeros(1200)]
    air = np.r_[0.0, np.cumsum(w[:-1] * DT)]
    u = metrics.unavoidable_sink(air, np.full(w.size, 1500.0), 5.0, DT)
    # (12 - 5) m/s for 20 s = 140 m, then back at 5 m/s: 28 s to recover
    assert u.max() == pytest.approx(140.0, abs=1e-9)
    assert int(np.argmax(u)) == 800
    assert u[800 + 560] == pytest.approx(70.0, abs=1e-9)
    assert u[800 + 1120] == pytest.approx(0.0, abs=1e-9)
    assert np.allclose(u[800 + 1120:], 0.0, atol=1e-9)
    assert (u >= 0.0).all()


def test_unavoidable_sink_counts_a_rising_target_and_restarts_when_the_hold_is_off() -> None:
    n = 401
    target = 1500.0 + 7.0 * DT * np.arange(n)  # the target climbs at 7 m/s, calm air
    u = metrics.unavoidable_sink(np.zeros(n), target, 5.0, DT)
    assert u[-1] == pytest.approx(2.0 * 10.0, abs=1e-9)  # (7 - 5) m/s for 10 s
    target[200] = np.nan  # hold off for one step: the ideal aircraft starts again
    u = metrics.unavoidable_sink(np.zeros(n), target, 5.0, DT)
    assert u[200] == 0.0 and u[201] == 0.0
    assert u[-1] == pytest.approx(2.0 * 199 * DT, abs=1e-9)


# --- air_mass_metrics -------------------------------------------------------

def test_carried_down_by_the_air_is_net_of_the_unavoidable_part() -> None:
    # 12 m/s down for 20 s; the aircraft climbs through the air at 5 m/s:
    # 140 m low, all of it unavoidable
    n = 800
    air = 12.0 * DT * np.arange(n)
    h = 1500.0 - 7.0 * DT * np.arange(n)
    idx = np.arange(n)
    out = metrics.air_mass_metrics(_res(h, air), idx, np.ones(n, dtype=bool))
    assert out["unavoidable_sink_max_m"] == pytest.approx(7.0 * DT * (n - 1), abs=1e-9)
    assert out["altitude_error_net_of_air_max_m"] == pytest.approx(0.0, abs=1e-9)
    # the air-relative altitude rose by the climb through the air
    assert out["air_relative_altitude_error_max_m"] == pytest.approx(5.0 * DT * (n - 1))
    assert out["air_down_m"] == pytest.approx(12.0 * DT * (n - 1))
    assert out["wind_down_max_m_s"] == pytest.approx(12.0)
    assert out["wind_up_max_m_s"] == 0.0


def test_a_stall_in_the_downdraft_is_not_excused() -> None:
    # the same air; the aircraft sinks 2 m/s through it (stalled): 2 + 12 m/s down
    n = 800
    air = 12.0 * DT * np.arange(n)
    h = 1500.0 - 14.0 * DT * np.arange(n)
    out = metrics.air_mass_metrics(_res(h, air), np.arange(n), np.ones(n, dtype=bool))
    # 14 m/s lost, 7 m/s of it unavoidable: the other 7 m/s count
    assert out["altitude_error_net_of_air_max_m"] == pytest.approx(7.0 * DT * (n - 1))


def test_min_altitude_net_of_air_raises_each_step_by_its_unavoidable_sink() -> None:
    # 12 m/s down for 20 s, then still air; the aircraft climbs through the
    # air at 5 m/s, then back up at 5 m/s: its lowest point is all unavoidable
    n = 1600
    half = n // 2
    air = np.concatenate([12.0 * DT * np.arange(half), np.full(n - half, 12.0 * DT * (half - 1))])
    h = np.concatenate([1500.0 - 7.0 * DT * np.arange(half),
                        1500.0 - 7.0 * DT * (half - 1) + 5.0 * DT * np.arange(1, n - half + 1)])
    h = np.minimum(h, 1500.0)
    out = metrics.min_altitude_net_of_air(_res(h, air))
    assert out["min_altitude_net_of_air_m"] == pytest.approx(1500.0, abs=1e-6)
    # sinking 2 m/s faster than the air forces: that part stays
    h2 = 1500.0 - 14.0 * DT * np.arange(n)
    air2 = 12.0 * DT * np.arange(n)
    out2 = metrics.min_altitude_net_of_air(_res(h2, air2))
    assert out2["min_altitude_net_of_air_m"] == pytest.approx(1500.0 - 7.0 * DT * (n - 1))
    # no climb capability: no figure
    assert metrics.min_altitude_net_of_air(_res(h, air, capability=None)) == {}


def test_above_the_target_counts_in_full_and_the_steady_mask_applies() -> None:
    n = 400
    h = np.full(n, 1500.0)
    h[100] = 1530.0  # 30 m high once, in still air
    h[300] = 1520.0
    steady = np.arange(n) >= 200
    out = metrics.air_mass_metrics(_res(h, np.zeros(n)), np.arange(n), steady)
    assert out["altitude_error_net_of_air_max_m"] == pytest.approx(20.0)
    assert out["unavoidable_sink_max_m"] == 0.0


def test_holding_the_altitude_while_the_air_moves_is_air_relative_error() -> None:
    # why air_relative_altitude_error_max_m is reported, not a criterion: a hold
    # that keeps its altitude exactly through 3 m/s of sinking air (within the
    # capability) shows the air's whole displacement there
    n = 800
    air = 3.0 * DT * np.arange(n)
    out = metrics.air_mass_metrics(_res(np.full(n, 1500.0), air), np.arange(n),
                                   np.ones(n, dtype=bool))
    assert out["air_relative_altitude_error_max_m"] == pytest.approx(3.0 * DT * (n - 1))
    assert out["altitude_error_net_of_air_max_m"] == pytest.approx(0.0)


def test_without_a_climb_capability_only_the_air_figures() -> None:
    n = 100
    out = metrics.air_mass_metrics(_res(np.full(n, 1500.0), np.zeros(n), capability=None),
                                   np.arange(n), np.ones(n, dtype=bool))
    assert "altitude_error_net_of_air_max_m" not in out
    assert "unavoidable_sink_max_m" not in out
    assert out["air_relative_altitude_error_max_m"] == 0.0


# --- scenario keys ------------------------------------------------------------

def test_climb_capability_key(tmp_path: Path) -> None:
    sc = load_scenario(_write(tmp_path, BASE + "[metrics]\nclimb_capability_m_s = 4.9\n"))
    assert sc.climb_capability_m_s == 4.9
    assert load_scenario(_write(tmp_path, BASE)).climb_capability_m_s is None
    with pytest.raises(ScenarioError, match="'metrics.climb_capability_m_s'"):
        load_scenario(_write(tmp_path, BASE + "[metrics]\nclimb_capability_m_s = -1\n"))


def test_net_criterion_needs_the_climb_capability(tmp_path: Path) -> None:
    crit = '[[pass]]\nsegment = "a"\nmetric = "altitude_error_net_of_air_max_m"\nmax = 50\n'
    with pytest.raises(ScenarioError, match="needs metrics.climb_capability_m_s"):
        load_scenario(_write(tmp_path, BASE + crit))
    sc = load_scenario(_write(tmp_path, BASE + "[metrics]\nclimb_capability_m_s = 4.9\n" + crit))
    assert sc.criteria[0].metric == "altitude_error_net_of_air_max_m"


# --- the flown telemetry ------------------------------------------------------

def test_telemetry_logs_the_turbulence_and_integrates_it(tmp_path: Path, board_lib: str) -> None:
    sc = load_scenario(_write(tmp_path, BASE + '[wind]\nturbulence = "severe"\n'))
    tel = lockstep.run(sc, board_lib).telemetry
    w = tel["wind_down_m_s"]
    assert np.std(w) > 1.0 and np.std(tel["wind_north_m_s"]) > 1.0
    assert tel["air_down_m"][0] == 0.0
    # air_down_m integrates the down wind of every sim frame: over a control
    # step it moves by about the wind logged at that step
    rate = np.diff(tel["air_down_m"]) / DT
    assert float(np.sqrt(np.mean((rate - w[:-1]) ** 2))) < 0.5
    calm = lockstep.run(load_scenario(_write(tmp_path, BASE)), board_lib).telemetry
    # calm air (JSBSim's trim leaves a wind of order 1e-14 m/s)
    assert np.allclose(calm["air_down_m"], 0.0, atol=1e-9)
    assert np.allclose(calm["wind_down_m_s"], 0.0, atol=1e-9)


def test_the_steady_wind_is_applied_after_the_trim_and_ramped_in(tmp_path: Path,
                                                                  board_lib: str) -> None:
    """JSBSim's run_ic and trim reset atmosphere/wind-*-fps: the harness sets
    the steady wind in its loop, ramped in over WIND_RAMP_S (a step would be a
    gust of the full wind speed on the trimmed aircraft)."""
    text = BASE.replace("duration_s = 4", "duration_s = 8")
    text += "[wind]\nnorth_m_s = -4\neast_m_s = 10\ndown_m_s = 0.5\n"
    tel = lockstep.run(load_scenario(_write(tmp_path, text)), board_lib).telemetry
    t = tel["t_s"]
    half = int(np.argmin(np.abs(t - lockstep.WIND_RAMP_S / 2)))
    assert tel["wind_east_m_s"][half] == pytest.approx(5.0, abs=0.1)
    late = t >= lockstep.WIND_RAMP_S
    assert np.allclose(tel["wind_east_m_s"][late], 10.0, atol=1e-6)
    assert np.allclose(tel["wind_north_m_s"][late], -4.0, atol=1e-6)
    assert np.allclose(tel["wind_down_m_s"][late], 0.5, atol=1e-6)
    assert np.all(np.diff(tel["wind_east_m_s"][~late]) >= 0.0)  # a ramp, no step


def test_severe_turbulence_seed8_downdraft_is_beyond_the_climb_and_does_not_stall(
        board_lib: str) -> None:
    """The campaign's seed 8: from 48 s the air sinks at 10-16 m/s to the end;
    with the airspeed protection the c172p trades altitude for airspeed
    instead of stalling (without it: 17 m/s, alpha 39 deg, 305 m lost). The
    subject is the hold's protection, so the law flies on JSBSim's attitude:
    on the estimate the 10-16 m/s downdraft puts up to 9 degrees into its
    pitch (its air-relative climb is the GPS's), a known limit
    (docs/estimator.md "Limits")."""
    base = load_scenario(SCENARIOS / "faults" / "c172p_turbulence_severe.toml")
    res = lockstep.run(dataclasses.replace(base, seed=8, attitude_source="truth"), board_lib)
    tel = res.telemetry
    down = tel["t_s"] >= 48.0
    assert np.mean(tel["wind_down_m_s"][down]) > 10.0
    m = metrics.run_metrics(res)
    rev = next(s for s in m["segments"] if s["label"] == "fault_reverse")
    assert rev["altitude_error_max_m"] > 150.0       # inertial: the air took it down ...
    assert rev["unavoidable_sink_max_m"] > 150.0     # ... beyond any 4.9 m/s climber
    assert rev["altitude_error_net_of_air_max_m"] <= 50.0
    assert float(np.max(tel["alpha_deg"][tel["t_s"] >= 15.0])) < 20.0
    assert all(c["ok"] for c in metrics.evaluate(m, res.scenario.criteria))
