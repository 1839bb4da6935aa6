"""The SIL gives the firmware what the board's pitot gives it, the INDICATED
airspeed, and the firmware makes it true with the baro (issue 33, item 13):
a level 10 deg/s turn, its turn-rate trim off so the
law alone answers, flies the commanded rate at 3 000 m as at 1 500 m (the T37:
the c172p does not trim at 3 000 m). On main the SIL fed JSBSim's true
airspeed, so the board's difference (14 % at 3 000 m) never showed."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from helical_sil.config.scenario import load_scenario
from helical_sil.sim import lockstep

TURN = """
aircraft = "T37"
duration_s = 30
seed = 1
[initial]
altitude_m = {alt}
airspeed_m_s = 110.0
[guidance]
turn_trim = 0
[[command]]
t_s = 0
label = "straight"
turn_rate_deg_s = 0
[[command]]
t_s = 8
label = "right_10"
turn_rate_deg_s = 10
"""


def _isa_sigma(h_m: float) -> float:
    theta = 1.0 - 0.0065 * h_m / 288.15
    return theta ** (9.80665 / (287.05287 * 0.0065) - 1.0)


def _fly(tmp_path: Path, board_lib: str, monkeypatch: pytest.MonkeyPatch,
         alt_m: int) -> tuple[float, float, float, float]:
    """(indicated / true as fed, law / true, mean altitude, steady turn rate)"""
    p = tmp_path / f"turn{alt_m}.toml"
    p.write_text(TURN.replace("{alt}", str(alt_m)))
    fed: list[tuple[float, float]] = []  # (what the board was given, JSBSim's true airspeed)
    raw = lockstep._board_seam  # the seam of every control step (the SIL loop's)

    def spy(sc, sens, model, state, t, *rest):  # type: ignore[no-untyped-def]
        raw(sc, sens, model, state, t, *rest)
        fed.append((sens.pitot_m_s, state.vt_m_s))

    monkeypatch.setattr(lockstep, "_board_seam", spy)
    t = lockstep.run(load_scenario(p), board_lib).telemetry
    assert len(fed) > 1000, "the spy saw no control step: is _board_seam still the seam?"
    monkeypatch.setattr(lockstep, "_board_seam", raw)
    seg = (t["t_s"] > 18.0) & (t["cmd_turn_rate_deg_s"] > 9.0)
    return (float(np.mean([f / v for f, v in fed])),
            float(np.mean(t["law_airspeed_m_s"] / t["airspeed_m_s"])),
            float(np.mean(t["altitude_m"])), float(np.mean(t["turn_rate_deg_s"][seg])))


def test_turn_rate_unchanged_at_3000_m(tmp_path: Path, board_lib: str,
                                       monkeypatch: pytest.MonkeyPatch) -> None:
    low = _fly(tmp_path, board_lib, monkeypatch, 1500)
    high = _fly(tmp_path, board_lib, monkeypatch, 3000)
    for ias_per_tas, law_per_tas, alt, rate in (low, high):
        print(f"{alt:.0f} m: indicated/true fed {ias_per_tas:.4f} (ISA "
              f"{math.sqrt(_isa_sigma(alt)):.4f}), law/true {law_per_tas:.4f}, "
              f"turn {rate:.3f} deg/s for 10")
        # the SIL fed the board the indicated airspeed: sqrt(sigma) x true
        assert abs(ias_per_tas / math.sqrt(_isa_sigma(alt)) - 1.0) < 0.01
        # the law flew the true airspeed the firmware made of it
        assert abs(law_per_tas - 1.0) < 0.01
        assert abs(rate - 10.0) < 0.5  # the shipped scenarios' 5 %
    assert high[0] < 0.88  # 14 % below true at 3 000 m: the law would see it
    # the same turn at both heights: the density is the firmware's business
    assert abs(high[3] - low[3]) < 0.1, f"{low[3]:.3f} at 1500 m, {high[3]:.3f} at 3000 m"
