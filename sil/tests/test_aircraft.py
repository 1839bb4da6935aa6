"""`aircraft list`: which JSBSim models are flyable, and JSBSim's own trim."""

from __future__ import annotations

from helical_sil.cli import main
from helical_sil.config import aircraft as acm


def _by_name() -> dict[str, acm.ModelInfo]:
    return {m.name: m for m in acm.find_models()}


def test_the_installed_models_are_classified() -> None:
    m = _by_name()
    for name in ("c172p", "T37", "f16", "737", "J3Cub"):
        assert m[name].fixed_wing, name
    assert m["ah1s"].why_not == "rotorcraft"
    assert m["sgs233"].why_not.startswith("no engine")     # a glider
    assert m["weather-balloon"].why_not.startswith("airship or balloon")
    assert m["ZLT-NT"].why_not.startswith("airship or balloon")
    assert m["J246"].why_not == "launch vehicle"
    assert m["c172p"].engines == 1 and 16.0 < m["c172p"].wing_area_m2 < 16.5  # 174 ft^2


def test_the_trim_is_jsbsims() -> None:
    c172 = _by_name()["c172p"]
    acm.trim_sweep(c172, speeds=(50.0, 25.0))  # cruise trims; 25 m/s is below its stall
    assert c172.trims_at == [50.0]
    assert c172.trim_error.startswith("Trim Failed") and "(at 25 m/s)" in c172.trim_error
    assert "trim = false" not in acm.explain(c172)  # it trims: nothing to explain
    c172.trims_at = []
    assert acm.explain(c172).startswith("JSBSim: \"Trim Failed\" at every speed of the sweep")
    assert "[initial] trim = false" in acm.explain(c172)


def test_aircraft_list_help() -> None:
    import pytest
    with pytest.raises(SystemExit) as e:
        main(["aircraft", "list", "--help"])
    assert e.value.code == 0
    assert main(["aircraft", "list", "--jobs", "0"]) == 2


def test_a_model_with_output_directives_writes_nothing_here(tmp_path, monkeypatch) -> None:
    """global5000 logs to global5000.csv in the working directory at run_ic:
    the sweep runs it in a scratch directory."""
    monkeypatch.chdir(tmp_path)
    g = _by_name()["global5000"]
    acm.trim_sweep(g, speeds=(100.0,))
    assert g.trims_at == [100.0]
    assert list(tmp_path.iterdir()) == []


def test_aircraft_new_writes_a_file_the_loader_takes(tmp_path) -> None:
    """The c172p's starter: v_ref at cruise power near its tuned 50 m/s, v_min
    the slowest trim, roll gains near the tuned ones (it is the reference);
    the file loads as an aircraft of a scenario."""
    from pathlib import Path

    from helical_sil.config.scenario import load_scenario
    (tmp_path / "aircraft").mkdir()
    out = tmp_path / "aircraft" / "mine.toml"
    assert main(["aircraft", "new", "c172p", "--out", str(out)]) == 0
    text = out.read_text()
    assert 'model = "c172p"' in text and "stability augmentation" not in text
    # the c172p's FCS: 15 deg of aileron, 23 of elevator (down), 16 of rudder
    assert "surface travel at full command (deg; - = not written by the model's FCS): " \
        "aileron 15, elevator 23, rudder 16" in text
    sc = load_scenario(_scenario(tmp_path, "mine"))
    g = sc.gains
    assert 45.0 < g["v_ref"] < 56.0 and 24.0 < g["v_min"] < 30.0
    assert 0.6 < g["throttle_trim"] < 0.75
    assert 4.0 < g["kp_aileron"] < 6.0 and g["kp_elevator"] == 6.0
    # its envelope: the c172p's <alphalimits> (0.28 rad) and its fastest level trim
    assert sc.aircraft.envelope["stall_alpha_deg"] == 16.0
    assert 60.0 < sc.aircraft.envelope["max_airspeed_m_s"] < 70.0
    assert main(["aircraft", "new", "c172p", "--out", str(out)]) == 2  # exists: not overwritten
    assert main(["aircraft", "new", "sgs233", "--out", str(tmp_path / "g.toml")]) == 2  # glider
    assert not Path(tmp_path / "g.toml").exists()


def test_aircraft_new_names_the_models_own_yaw_damper(tmp_path) -> None:
    out = tmp_path / "t38.toml"
    assert main(["aircraft", "new", "T38", "--out", str(out)]) == 0
    text = out.read_text()
    assert "own stability augmentation" in text and "yaw damper" in text.lower()


def _scenario(tmp_path, aircraft: str):
    p = tmp_path / "s.toml"
    p.write_text(f'aircraft = "{aircraft}"\nduration_s = 5\n[[command]]\nt_s = 0\nlabel = "a"\n'
                 'turn_rate_deg_s = 0\n[[pass]]\nsegment = "a"\nmetric = "turn_rate_rmse_deg_s"\n'
                 "max = 1\n")
    return p


def test_aircraft_new_for_a_model_that_does_not_trim(tmp_path) -> None:
    """JSBSim's pa28 trims at no speed here: the file says so, with JSBSim's
    message and the trim = false path, and still loads."""
    from helical_sil.config.scenario import load_scenario
    (tmp_path / "aircraft").mkdir()
    out = tmp_path / "aircraft" / "pa.toml"
    assert main(["aircraft", "new", "pa28", "--out", str(out)]) == 0
    text = out.read_text()
    assert 'NO TRIM: JSBSim trims this model at no speed of the sweep ("Trim Failed")' in text
    assert "[initial] trim = false" in text
    assert load_scenario(_scenario(tmp_path, "pa")).gains["v_ref"] == 50.0


def test_a_model_that_diverges_is_a_clear_runtime_error(tmp_path, capsys) -> None:
    """JSBSim's paraglider goes to NaN rates within 0.2 s of its release: the
    run stops with exit 3 and says the model diverged (not a traceback)."""
    (tmp_path / "aircraft").mkdir()
    out = tmp_path / "aircraft" / "pg.toml"
    assert main(["aircraft", "new", "paraglider", "--out", str(out)]) == 0
    sc = _scenario(tmp_path, "pg")
    sc.write_text(sc.read_text().replace("duration_s = 5\n",
                                         "duration_s = 5\n[initial]\ntrim = false\n"))
    rc = main(["run", str(sc), "--no-plots", "--out", str(tmp_path / "o")])
    assert rc == 3
    assert "(the model diverged)" in capsys.readouterr().err
