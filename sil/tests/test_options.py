"""Issue 17: the metrics of the law-options campaign on synthetic data with
known answers, the campaign's argument parsing and table building, a tiny
campaign end to end, and the upset campaign's vertical grid."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest

from helical_sil import cli
from helical_sil.analysis import metrics
from helical_sil.campaigns import options, upsets
from helical_sil.campaigns.roll_limit import FullAileron, coordinated_bank_deg, first_crossing
from helical_sil.config.scenario import load_scenario

# --- the metrics -------------------------------------------------------------------


def test_bank_entry_is_the_first_time_at_90_percent_of_the_bank_change() -> None:
    ts = np.arange(0.0, 3.0, 0.025)
    phi = np.minimum(ts / 1.5, 1.0) * 45.0          # 30 deg/s up to 45 deg at 1.5 s
    # 90 % of 45 = 40.5 deg, reached at 1.35 s (the first sample at or past it)
    assert metrics.bank_entry_s(ts, phi, 45.0) == pytest.approx(1.35, abs=1e-9)
    # the same roll to the left
    assert metrics.bank_entry_s(ts, -phi, -45.0) == pytest.approx(1.35, abs=1e-9)
    # a target never reached
    assert metrics.bank_entry_s(ts, 0.5 * phi, 45.0) is None
    # from a bank back to level (an exit): 90 % of -45 from 45 is 4.5 deg
    assert metrics.bank_entry_s(ts, 45.0 - phi, 0.0) == pytest.approx(1.35, abs=1e-9)
    # through +-180: from 170 to -170 is a 20 deg roll to the right
    roll = 170.0 + np.minimum(ts, 1.0) * 20.0
    wrapped = (roll + 180.0) % 360.0 - 180.0
    assert metrics.bank_entry_s(ts, wrapped, -170.0) == pytest.approx(0.9, abs=1e-9)


def test_first_crossing_interpolates_between_samples() -> None:
    t = np.array([0.0, 1.0, 2.0, 3.0])
    y = np.array([0.0, 10.0, 20.0, 30.0])
    assert first_crossing(t, y, 15.0) == pytest.approx(1.5)
    assert first_crossing(t, y, 0.0) == 0.0
    assert first_crossing(t, y, 30.5) is None


def test_full_aileron_times_each_way_and_the_coordinated_bank() -> None:
    t = np.linspace(0.0, 2.0, 241)
    fa = FullAileron(t, 60.0 * t, -30.0 * t, 50.0, True)  # 60 deg/s right, 30 deg/s left
    assert fa.time_to_bank(30.0) == pytest.approx(0.5, abs=1e-9)
    assert fa.time_to_bank(-30.0) == pytest.approx(1.0, abs=1e-9)
    assert fa.time_to_bank(0.0) == 0.0
    assert fa.time_to_bank(-90.0) is None
    # atan(omega V / g): 10 deg/s at 50 m/s
    w = math.radians(10.0) * 50.0 / 9.80665
    assert coordinated_bank_deg(10.0, 50.0) == pytest.approx(math.degrees(math.atan(w)), 1e-12)
    assert coordinated_bank_deg(10.0, 50.0) == pytest.approx(41.6649, abs=1e-4)


def test_roll_in_rate_is_the_rows_reachable_bank_rate() -> None:
    t = np.linspace(0.0, 2.0, 241)
    d = {"t_s": t.tolist(), "right": (60.0 * t).tolist(), "left": (-30.0 * t).tolist(),
         "airspeed_m_s": 50.0, "trimmed": True}
    # 30 deg in 1.0 s the slower way (left): 0.524 rad/s
    assert options.reachable_roll_rate(d) == pytest.approx(round(math.radians(30.0), 3))
    assert options.reachable_roll_rate(None) is None
    assert options.reachable_roll_rate({"error": "trim failed"}) is None
    slow = {**d, "left": (-10.0 * t).tolist()}  # never reaches -30 deg in 2 s
    assert options.reachable_roll_rate(slow) is None
    on = {"roll_in": 1.0, "kp_sideslip": 0.0}
    assert options.with_roll_in_rate(on, d, fixed=False)["roll_in_rate_max"] == pytest.approx(0.524)
    assert "roll_in_rate_max" not in options.with_roll_in_rate(on, d, fixed=True)
    assert "roll_in_rate_max" not in options.with_roll_in_rate({"roll_in": 0.0}, d, fixed=False)
    assert options.with_roll_in_rate(on, slow, fixed=False) == on


def test_near_vertical_aileron_activity() -> None:
    n = 200
    dt = 0.025
    tel = {"dcm_x": np.full(n, 0.02), "dcm_z": np.full(n, 0.03),
           "law_aileron": np.where(np.arange(n) % 2 == 0, 1.0, -1.0)}
    m = metrics.near_vertical_metrics(tel, dt)
    # a +-1 bang-bang every step: total variation 2 per step, 80 per second at 40 Hz
    assert m["near_vertical_s"] == pytest.approx(n * dt)
    assert m["near_vertical_aileron_tv_per_s"] == pytest.approx(2.0 / dt)
    tel["law_aileron"] = np.full(n, 0.3)
    assert metrics.near_vertical_metrics(tel, dt)["near_vertical_aileron_tv_per_s"] == 0.0
    # only the steps near the vertical count: half the run near it, a ramp there
    tel = {"dcm_x": np.concatenate([np.full(100, 0.5), np.zeros(100)]), "dcm_z": np.zeros(n),
           "law_aileron": np.concatenate([np.zeros(100), np.linspace(0.0, 1.0, 100)])}
    m = metrics.near_vertical_metrics(tel, dt)
    assert m["near_vertical_s"] == pytest.approx(100 * dt)
    assert m["near_vertical_aileron_tv_per_s"] == pytest.approx(1.0 / (99 * dt))
    tel["dcm_x"] = np.full(n, 0.5)
    assert metrics.near_vertical_metrics(tel, dt) == {}


# --- the campaign's arguments and tables -----------------------------------------------


def test_overrides_are_table_rows_within_their_bounds() -> None:
    assert options.parse_set(["turn_trim=0", "kp_sideslip=1.5"]) == {"turn_trim": 0.0,
                                                                     "kp_sideslip": 1.5}
    assert options.row_of("turn_trim")[0] == "guidance"
    assert options.row_of("roll_in")[0] == "law"
    with pytest.raises(options.OptionsError, match=r"kp_sideslip = 65 is outside \[0, 64\]"):
        options.parse_set(["kp_sideslip=65"])
    with pytest.raises(options.OptionsError, match="expected KEY=VALUE"):
        options.parse_set(["roll_in"])
    with pytest.raises(options.OptionsError, match="not a number"):
        options.parse_set(["roll_in=yes"])
    with pytest.raises(options.OptionsError, match="not a row"):
        options.parse_set(["pitch_mode=1"])
    with pytest.raises(options.OptionsError, match="not a row"):
        options.parse_set(["kp_ailerons=1"])


def test_variants_are_the_seed_law_each_option_alone_and_the_combination() -> None:
    on = {"roll_in": 1.0, "kp_sideslip": 2.0, "turn_trim": 1.0, "vertical_fade": 0.1}
    vs = options.variants(on, ["roll_in", "turn_trim"], {"turn_trim_tau": 5.0},
                          ["roll_in", "kp_sideslip", "turn_trim", "vertical_fade"])
    assert [v.name for v in vs] == ["seed", "roll_in", "kp_sideslip", "turn_trim",
                                    "vertical_fade", "combo"]
    zero = {"roll_in": 0.0, "kp_sideslip": 0.0, "turn_trim": 0.0, "vertical_fade": 0.0,
            "turn_trim_tau": 5.0}
    assert vs[0].overrides == zero
    assert vs[2].overrides == {**zero, "kp_sideslip": 2.0}
    assert vs[5].overrides == {**zero, "roll_in": 1.0, "turn_trim": 1.0}
    sc = load_scenario(Path(__file__).parents[1] / "scenarios" / "c172p_turn_entry_ff.toml")
    s2 = options.copy_scenario_overrides(sc, vs[5].overrides)
    assert s2.gains["roll_in"] == 1.0 and s2.guidance["turn_trim"] == 1.0
    assert s2.gains["kp_sideslip"] == 0.0 and s2.guidance["turn_trim_tau"] == 5.0
    assert "turn_trim" not in sc.guidance  # the loaded scenario is unchanged


def _seg(label: str, cmd: float, **kw: float | None) -> dict[str, object]:
    return {"label": label, "turn_rate_cmd_deg_s": cmd, "inverted": False, **kw}


def test_row_metrics_against_a_known_full_aileron_limit() -> None:
    t = np.linspace(0.0, 3.0, 361)
    limit = {"t_s": t.tolist(), "right": (40.0 * t).tolist(), "left": (-50.0 * t).tolist(),
             "airspeed_m_s": 50.0, "trimmed": True}
    m = {"run": {}, "segments": [
        _seg("level", 0.0, entry_altitude_loss_m=None),
        _seg("right", 10.0, bank_target_deg=40.0, turn_entry_s=1.5, bank_entry_s=1.08,
             turn_rate_error_pct=2.5, steady_sideslip_rms_deg=0.4, bank_overshoot_deg=3.0,
             entry_altitude_loss_m=2.0, turn_rate_rmse_deg_s=0.1),
        _seg("reverse", -10.0, bank_target_deg=-40.0, turn_entry_s=3.0, bank_entry_s=2.0,
             turn_rate_error_pct=-1.0, steady_sideslip_rms_deg=0.7, bank_overshoot_deg=1.0,
             entry_altitude_loss_m=5.0, turn_rate_rmse_deg_s=0.2),
        _seg("out", 0.0, turn_entry_s=1.0, entry_altitude_loss_m=1.0),
        _seg("left", -10.0, bank_target_deg=-40.0, turn_entry_s=1.2, bank_entry_s=0.54,
             turn_rate_error_pct=0.5, steady_sideslip_rms_deg=0.2, turn_rate_rmse_deg_s=0.1)]}
    m2 = {"run": {}, "segments": [_seg("right", 10.0, turn_rate_rmse_deg_s=1.5)]}
    r = options.row_metrics(m, m2, limit)
    # entries from straight flight only: right 1.5 / (40 / 40) = 1.5, left 1.2 / 0.8 = 1.5;
    # bank: right 1.08 / 0.9 = 1.2, left 0.54 / 0.72 = 0.75 (the reversal is no entry)
    assert r["entry_ratio"] == pytest.approx(1.5, abs=1e-3)
    assert r["bank_ratio"] == pytest.approx(1.2, abs=1e-3)
    assert r["turn_rate_error_pct"] == 2.5 and r["steady_sideslip_rms_deg"] == 0.7
    assert r["bank_overshoot_deg"] == 3.0 and r["entry_altitude_loss_m"] == 5.0
    # 2x: 1.5 > 0.5 and > 2 x 0.2: a limit cycle
    assert r["rmse_2x_deg_s"] == 1.5 and r["limit_cycle_2x"] is True
    m2["segments"][0]["turn_rate_rmse_deg_s"] = 0.35
    assert options.row_metrics(m, m2, limit)["limit_cycle_2x"] is False
    # an entry never reached is infinitely slow
    m["segments"][4]["turn_entry_s"] = None
    assert math.isinf(options.row_metrics(m, None, limit)["entry_ratio"])


def test_helps_and_hurts_against_the_seed() -> None:
    seed = {"entry_ratio": 2.0, "turn_rate_error_pct": 3.0, "steady_sideslip_rms_deg": 0.5,
            "bank_overshoot_deg": 2.0}
    helps, hurts = options.compare(seed, {"entry_ratio": 1.4, "turn_rate_error_pct": 3.1,
                                          "steady_sideslip_rms_deg": 0.8,
                                          "bank_overshoot_deg": 2.0})
    assert helps == ["entry_ratio"] and hurts == ["steady_sideslip_rms_deg"]
    helps, hurts = options.compare(seed, {**seed, "entry_ratio": math.inf,
                                          "limit_cycle_2x": True})
    assert helps == [] and hurts == ["entry_ratio", "limit_cycle_2x"]
    # beyond the absolute tolerance but within 5 % of a large value: no effect
    big = {"cross_track_max_m": 300.0, "entry_altitude_loss_m": 40.0}
    assert options.compare(big, {"cross_track_max_m": 314.0,
                                 "entry_altitude_loss_m": 38.5}) == ([], [])
    assert options.compare(big, {"cross_track_max_m": 316.0,
                                 "entry_altitude_loss_m": 37.9}) == (
        ["entry_altitude_loss_m"], ["cross_track_max_m"])
    table = {"a": {"seed": seed, "x": {**seed, "entry_ratio": 1.0}},
             "b": {"seed": seed, "x": dict(seed)}}
    v = options.verdicts(table, ["x"])
    assert v["x"] == {"helps": ["a:entry_ratio"], "hurts": [], "keep": True}
    table["b"]["x"]["bank_overshoot_deg"] = 4.0
    assert options.verdicts(table, ["x"])["x"]["keep"] is False


def test_tables_of_a_tiny_campaign(tmp_path: Path) -> None:
    table = {"r1": {"seed": {"entry_ratio": 2.0, "turn_rate_error_pct": 3.0,
                             "limit_cycle_2x": False},
                    "roll_in": {"entry_ratio": math.inf, "turn_rate_error_pct": 1.0,
                                "limit_cycle_2x": True}}}
    md = options.markdown(table, ["seed", "roll_in"], options.verdicts(table, ["roll_in"]),
                          "T", "cmd")
    assert "| r1 | 2.00 | never |" in md
    assert "| turn_rate_error_pct | <= 2 | 0/1 | 1/1 |" in md
    assert "| limit cycles at 2x gains | 0 | 0 | 1 |" in md
    assert "| r1 | ok | LC |" in md
    options.write_csv(table, ["seed", "roll_in"], tmp_path / "t.csv")
    rows = list(csv.reader((tmp_path / "t.csv").open()))
    assert rows[0][:3] == ["row", "variant", "entry_ratio"] and len(rows) == 3
    assert rows[2][:2] == ["r1", "roll_in"] and rows[2][2] == "inf"


TINY = """aircraft = "c172p"
duration_s = 14
seed = 1
[metrics]
steady_after_s = 6
[[command]]
t_s = 0
label = "level"
turn_rate_deg_s = 0
[[command]]
t_s = 2
label = "right"
turn_rate_deg_s = 10
"""


def test_a_tiny_campaign_end_to_end(tmp_path: Path, board_lib: str) -> None:
    scen = tmp_path / "tiny.toml"
    scen.write_text(TINY)
    out = tmp_path / "out"
    rc = cli.main(["--board-lib", board_lib, "options", str(scen), "--out", str(out),
                   "--no-margin", "--no-recommend", "--combo", "roll_in", "turn_trim",
                   "--set", "turn_trim_hold=1", "--on", "kp_sideslip=2"])
    assert rc == 0
    r = json.loads((out / "result.json").read_text())
    names = [v["name"] for v in r["variants"]]
    assert names == ["seed", "roll_in", "kp_sideslip", "turn_trim", "vertical_fade", "combo"]
    assert r["variants"][2]["overrides"]["kp_sideslip"] == 2.0
    assert all(v["overrides"]["turn_trim_hold"] == 1.0 for v in r["variants"])
    row = r["table"]["tiny"]["seed"]
    # the c172p at 50 m/s: full aileron banks 41.7 deg in well under 2 s, the
    # law's entry comes after it
    assert 0.3 < row["full_aileron_s"] < 2.0 and row["entry_ratio"] > 1.0
    assert row["steady_sideslip_rms_deg"] is not None
    assert (out / "options.png").stat().st_size > 1000
    assert "| tiny |" in (out / "table.md").read_text()
    # a bad override is exit 2, nothing flown
    assert cli.main(["options", str(scen), "--out", str(tmp_path / "o2"),
                     "--set", "kp_sideslip=100"]) == 2
    assert cli.main(["options", str(scen), "--out", str(tmp_path / "o3"),
                     "--combo", "roll"]) == 2


# --- the upsets' vertical grid --------------------------------------------------------


def test_the_vertical_grid_reaches_pitch_90_both_ways(tmp_path: Path) -> None:
    g = upsets.vertical_grid("c172p")
    assert len(g) == 32
    assert {u.pitch_deg for u in g} == {90.0, 85.0, -85.0, -90.0}
    assert {u.roll_deg for u in g} == {0.0, 90.0, 180.0, -90.0}
    assert {u.calibrated_airspeed_m_s for u in g} == {26.0, 50.0}
    both = upsets.upset_list("c172p", 6, 1, "both")
    assert both[:6] == upsets.generate("c172p", 6, 1) and both[6:] == g
    assert upsets.upset_list("c172p", 6, 1, "vertical") == g
    # the file of a vertical upset loads, with the campaign's override
    p = tmp_path / "aircraft"
    p.mkdir()
    text = upsets.scenario_toml("c172p", g[0], 0, 1, 2500.0, 45.0, 300.0, 50.0,
                                overrides={"vertical_fade": 0.1, "turn_trim": 0.0})
    f = tmp_path / "u.toml"
    f.write_text(text)
    sc = load_scenario(f)
    assert sc.upset is not None and sc.upset.pitch_deg == 90.0
    assert sc.gains["vertical_fade"] == 0.1 and sc.guidance["turn_trim"] == 0.0
