"""`tune`: the search space, the tuned file, and a short resumable search."""

from __future__ import annotations

import json
from pathlib import Path

from helical_sil.campaigns import tune as tn
from helical_sil.cli import main
from helical_sil.config.scenario import load_aircraft

SIL = Path(__file__).resolve().parents[1]
C172P = SIL / "scenarios" / "aircraft" / "c172p.toml"


def test_the_search_space_stays_in_the_tables_bounds() -> None:
    sp = tn.search_space({"kp_aileron": 40.0, "kd_aileron": 0.7, "kff_aileron": 0.0,
                          "kp_elevator": 6.0, "kd_elevator": 1.0, "kp_rudder": 0.3,
                          "kd_rudder": 1.0, "kff_rudder": 0.5})
    assert sp["kp_aileron"] == (10.0, 64.0, True)     # 40 x 4 capped at the row's 64
    assert sp["kff_aileron"] == (0.0, 2.0, False)     # a zero gain: searched from 0
    assert sp["kp_rudder"] == (0.075, 1.2, True)


def test_the_tuned_file_changes_only_the_gains(tmp_path: Path) -> None:
    text = C172P.read_text()
    out = tn.tuned_toml(text, {"kp_aileron": 7.25, "kff_aileron": 0.125})
    assert "kp_aileron = 7.25  # tuned" in out and "kff_aileron = 0.125  # tuned" in out
    assert out.count("kp_aileron") == 1
    assert "[envelope]" in out and 'model = "c172p"' in out
    (tmp_path / "x.toml").write_text(out)
    ac = load_aircraft("x", [tmp_path], tmp_path / "s.toml")
    assert ac.gains["kp_aileron"] == 7.25 and ac.gains["kp_elevator"] == 6.0


def test_a_short_search_writes_its_report_and_continues(tmp_path: Path, board_lib: str) -> None:
    out = tmp_path / "t"
    args = ["--board-lib", board_lib, "tune", str(C172P), "--out", str(out), "--seed", "2"]
    assert main([*args, "--trials", "3"]) == 0
    r = json.loads((out / "result.json").read_text())
    assert r["trials"] == 3 and r["trimmed"] is True
    assert r["passed_starter"] == r["criteria"] == len(tn.CRITERIA)  # the tuned c172p passes
    assert r["cost_best"] <= r["cost_starter"] + 1e-9 or r["best"] == r["starter"]
    for f in ("report.md", "search.png", "c172p_tuned.toml", "manoeuvres.toml", "study.db"):
        assert (out / f).is_file(), f
    assert (out / "search.png").read_bytes()[:4] == b"\x89PNG"
    # the store keeps the search: asking for 5 in all flies 2 more
    assert main([*args, "--trials", "5"]) == 0
    assert json.loads((out / "result.json").read_text())["trials"] == 5
    assert main([*args, "--trials", "0"]) == 2
