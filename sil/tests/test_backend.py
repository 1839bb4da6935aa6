"""The backends of batch, upsets and tune (helical_sil/campaigns/backend.py): the local
process pool and Ray give the same results, bit for bit, in the inputs'
order. The Ray test starts a local Ray (marker `ray`: ctest runs it as
sil_ray_backend)."""

from __future__ import annotations

import hashlib
from pathlib import Path

import pytest

from helical_sil.campaigns.backend import BackendError, map_ordered
from helical_sil.cli import main


def _square(x: int) -> int:
    return x * x


def test_local_results_come_back_in_order_with_progress() -> None:
    seen: list[int] = []
    got = map_ordered(_square, list(range(7)), jobs=2,
                      progress=lambda k, _r: seen.append(k))
    assert got == [x * x for x in range(7)]
    assert sorted(seen) == list(range(1, 8))
    assert map_ordered(_square, [3], jobs=1) == [9]
    with pytest.raises(BackendError, match="unknown backend 'slurm'"):
        map_ordered(_square, [1], backend="slurm")
    with pytest.raises(BackendError, match="jobs must be at least 1"):
        map_ordered(_square, [1], jobs=0)


def _digests(out: Path) -> dict[str, str]:
    return {str(p.relative_to(out)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(out.rglob("telemetry.csv"))}


@pytest.mark.ray
def test_ray_and_local_fly_the_same_upsets_bit_for_bit(tmp_path: Path, board_lib: str) -> None:
    """Four seeded c172p upsets through a local Ray (2 CPUs) and through the
    local pool: every telemetry.csv is byte-identical, and so is the summary
    the campaign writes (but for the output folder's own path)."""
    pytest.importorskip("ray")
    outs = {}
    for backend in ("local", "ray"):
        out = tmp_path / backend
        rc = main(["--board-lib", board_lib, "upsets", "--aircraft", "c172p", "--count", "4",
                   "--seed", "3", "--duration-s", "12", "--out", str(out), "--jobs", "2",
                   "--backend", backend])
        assert rc in (0, 1)
        outs[backend] = out
    a, b = _digests(outs["local"]), _digests(outs["ray"])
    assert len(a) == 4 and a == b
    # the summaries differ only by their own folder's name in the file paths
    summary = {k: (o / "summary.json").read_text().replace(str(o), "OUT")
               for k, o in outs.items()}
    assert summary["local"] == summary["ray"]


def test_a_ray_cluster_that_is_not_there_is_a_clear_error(tmp_path: Path, board_lib: str,
                                                         capsys: pytest.CaptureFixture[str]
                                                         ) -> None:
    pytest.importorskip("ray")
    rc = main(["--board-lib", board_lib, "upsets", "--aircraft", "c172p", "--count", "1",
               "--out", str(tmp_path / "o"), "--backend", "ray", "--address",
               "127.0.0.1:1"])
    assert rc == 3
    assert "Ray did not start (127.0.0.1:1)" in capsys.readouterr().err
