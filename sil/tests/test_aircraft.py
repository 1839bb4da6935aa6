"""`aircraft list`: which JSBSim models are flyable, and JSBSim's own trim."""

from __future__ import annotations

from helical_sil import aircraft as acm
from helical_sil.cli import main


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
