"""Shared fixtures of the SIL harness tests."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from helical_sil.sim.board import BoardError, find_board_library

SIL_DIR = Path(__file__).resolve().parents[1]
SCENARIOS = SIL_DIR / "scenarios"


@pytest.fixture(scope="session")
def board_lib() -> str:
    """The host board library. Skipped when it is not built, except under
    ctest (HT_SIL_REQUIRE_BOARD=1), where its absence is a failure."""
    try:
        return str(find_board_library())
    except BoardError as e:
        if os.environ.get("HT_SIL_REQUIRE_BOARD") == "1":
            pytest.fail(str(e))
        pytest.skip(str(e))
