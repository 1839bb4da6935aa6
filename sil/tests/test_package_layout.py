"""The layout of the helical_sil package (issue 27): no import cycles between
its modules and every import going down the layers.

The import graph is read from the source with ast, not by importing: every
`import helical_sil...` and `from helical_sil... import` / `from . import`
anywhere in a module counts, inside functions too (a lazy import is still a
dependency: it only moves the cycle from import time to run time).
"""

from __future__ import annotations

import ast
from pathlib import Path

PKG_DIR = Path(__file__).resolve().parents[1] / "helical_sil"
ROOT = "helical_sil"

# The layers, lowest first. A module may import the modules of its own group
# (its subpackage; a top-level module is a group of its own) and those of a
# LOWER layer; never a higher layer's, nor another group of its own layer
# (campaigns and live do not know each other). The root package's
# __init__.py is below every layer (it imports nothing).
LAYERS: tuple[tuple[str, ...], ...] = (
    ("sensors",),            # frames, the ideal sensors, the sensor error models and their config
    ("config",),             # the parameter table, scenario and aircraft files
    ("sim",),                # the board (ctypes), the faults, the lockstep flight loop
    ("analysis",),           # metrics and plots of a flight
    ("campaigns", "live"),   # many flights (runner, backend, batch pieces, upsets, tune,
                             # options, roll limit); live (serve: MAVLink, pil: QEMU)
    ("cli",),                # the command line
    ("__main__",),           # python -m helical_sil
)


# --- the graph ------------------------------------------------------------------

def module_name(path: Path, pkg_dir: Path = PKG_DIR) -> str:
    """helical_sil/sim/lockstep.py -> helical_sil.sim.lockstep; a package's
    __init__.py is the package."""
    rel = path.relative_to(pkg_dir.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _known(name: str, known: set[str]) -> str | None:
    """The longest prefix of a dotted name that is a module of the package."""
    parts = name.split(".")
    for n in range(len(parts), 0, -1):
        cand = ".".join(parts[:n])
        if cand in known:
            return cand
    return None


def imports_of(source: str, module: str, is_package: bool, known: set[str]) -> set[str]:
    """The package's modules that one module imports, wherever the import
    statement is (module level, function, class, `if TYPE_CHECKING:`).
    `from X import Y` depends on X.Y when that is a module, else on X."""
    out: set[str] = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name == ROOT or a.name.startswith(ROOT + "."):
                    dep = _known(a.name, known)
                    if dep is not None:
                        out.add(dep)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = module if is_package else module.rpartition(".")[0]
                for _ in range(node.level - 1):
                    base = base.rpartition(".")[0]
                if node.module:
                    base = f"{base}.{node.module}"
            else:
                base = node.module or ""
            if base != ROOT and not base.startswith(ROOT + "."):
                continue
            for a in node.names:
                dep = _known(f"{base}.{a.name}", known)
                if dep is not None:
                    out.add(dep)
    return out


def import_graph(pkg_dir: Path = PKG_DIR) -> dict[str, set[str]]:
    files = {module_name(p, pkg_dir): p for p in sorted(pkg_dir.rglob("*.py"))}
    known = set(files)
    return {m: imports_of(p.read_text(encoding="utf-8"), m, p.name == "__init__.py", known)
            for m, p in files.items()}


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One import cycle [a, b, ..., a's importer] (a imports b, ..., the last
    imports a), or None; depth-first, in sorted order (deterministic)."""
    WHITE, GREY, BLACK = 0, 1, 2
    colour = {n: WHITE for n in graph}
    for start in sorted(graph):
        if colour[start] != WHITE:
            continue
        path = [start]
        stack = [iter(sorted(graph[start]))]
        colour[start] = GREY
        while stack:
            nxt = next(stack[-1], None)
            if nxt is None:
                colour[path.pop()] = BLACK
                stack.pop()
                continue
            c = colour.get(nxt, BLACK)  # a name outside the graph imports nothing here
            if c == GREY:
                return path[path.index(nxt):]
            if c == WHITE:
                colour[nxt] = GREY
                path.append(nxt)
                stack.append(iter(sorted(graph.get(nxt, ()))))
    return None


def group_of(module: str) -> str:
    """helical_sil.sim.lockstep -> sim; helical_sil.cli -> cli; the root -> ''."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def rank_of(group: str, layers: tuple[tuple[str, ...], ...] = LAYERS) -> int | None:
    if group == "":
        return -1
    for r, groups in enumerate(layers):
        if group in groups:
            return r
    return None


def layer_violations(graph: dict[str, set[str]],
                     layers: tuple[tuple[str, ...], ...] = LAYERS) -> list[str]:
    """Every import that does not go down the layers (or stay in its group)."""
    bad = []
    for m in sorted(graph):
        gm = group_of(m)
        rm = rank_of(gm, layers)
        for d in sorted(graph[m]):
            gd = group_of(d)
            rd = rank_of(gd, layers)
            if gd == gm:
                continue
            if rm is None or rd is None or rd >= rm:
                bad.append(f"{m} ({gm or 'root'}) imports {d} ({gd or 'root'})")
    return bad


# --- the package ------------------------------------------------------------------

def test_the_graph_sees_the_package_and_its_lazy_imports() -> None:
    g = import_graph()
    assert len(g) > 25 and "helical_sil.sim.lockstep" in g
    # cli imports upsets, tune and serve inside its functions only: seen all the same
    assert {"helical_sil.campaigns.upsets", "helical_sil.campaigns.tune",
            "helical_sil.live.serve"} <= g["helical_sil.cli"]
    assert "helical_sil.sim.lockstep" in g["helical_sil.campaigns.runner"]  # lazy too


def test_no_import_cycles() -> None:
    cycle = find_cycle(import_graph())
    assert cycle is None, "import cycle: " + " -> ".join(cycle + cycle[:1])


def test_imports_go_down_the_layers() -> None:
    assert layer_violations(import_graph()) == []


def test_every_module_is_in_a_layer() -> None:
    missing = sorted(m for m in import_graph() if rank_of(group_of(m)) is None)
    assert missing == [], f"not in LAYERS (add the subpackage to a layer): {missing}"


def test_every_subpackage_says_what_it_owns_and_imports_nothing() -> None:
    """Each subpackage's __init__.py is its docstring only (what it owns, what
    it may import, what imports it): an import there would run whenever any
    module of the subpackage is imported, an edge the graph above leaves out."""
    subs = sorted(p.parent for p in PKG_DIR.glob("*/__init__.py"))
    assert {p.name for p in subs} >= {g for layer in LAYERS for g in layer
                                      if (PKG_DIR / g).is_dir()}
    for d in subs:
        tree = ast.parse((d / "__init__.py").read_text(encoding="utf-8"))
        doc = ast.get_docstring(tree)
        assert doc and len(doc.split()) >= 10, f"{d.name}/__init__.py: no docstring"
        assert all(isinstance(n, ast.Expr) for n in tree.body), \
            f"{d.name}/__init__.py: only its docstring (no imports, no code)"


# --- the checks check (each of them can fail) ----------------------------------------

def test_find_cycle_finds_a_cycle() -> None:
    g = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert find_cycle(g) == ["a", "b", "c"]
    assert find_cycle({"x": {"x"}}) == ["x"]
    assert find_cycle({"p": {"q", "r"}, "q": {"s"}, "r": {"s"}, "s": set()}) is None
    # the package's own graph with one edge back up (the old upsets -> cli) has one
    real = import_graph()
    real["helical_sil.campaigns.upsets"] = real["helical_sil.campaigns.upsets"] | {
        "helical_sil.cli"}
    cycle = find_cycle(real)
    assert cycle is not None and {"helical_sil.cli", "helical_sil.campaigns.upsets"} <= set(cycle)


def test_imports_of_reads_lazy_relative_and_absolute_imports() -> None:
    known = {"helical_sil", "helical_sil.cli", "helical_sil.config", "helical_sil.config.params",
             "helical_sil.sim", "helical_sil.sim.lockstep", "helical_sil.campaigns",
             "helical_sil.campaigns.tune", "helical_sil.campaigns.fake",
             "helical_sil.sensors", "helical_sil.sensors.frames"}
    src = """
import json
import helical_sil.sensors.frames
from typing import TYPE_CHECKING
from . import tune
from ..sim import lockstep
from helical_sil.config.params import LAW
if TYPE_CHECKING:
    from helical_sil import config
def f():
    from helical_sil.cli import main
"""
    assert imports_of(src, "helical_sil.campaigns.fake", False, known) == {
        "helical_sil.sensors.frames", "helical_sil.campaigns.tune", "helical_sil.sim.lockstep",
        "helical_sil.config.params", "helical_sil.config", "helical_sil.cli"}
    # in a package's __init__.py, "." is the package itself
    assert imports_of("from . import tune\n", "helical_sil.campaigns", True, known) == {
        "helical_sil.campaigns.tune"}


def test_layer_violations_flags_up_and_sideways_imports() -> None:
    ok = {"helical_sil.cli": {"helical_sil.sim.lockstep"},
          "helical_sil.sim.lockstep": {"helical_sil.sim.board", "helical_sil.config.params"},
          "helical_sil.sim.board": set()}
    assert layer_violations(ok) == []
    up = {"helical_sil.sim.lockstep": {"helical_sil.cli"}}
    assert layer_violations(up) == ["helical_sil.sim.lockstep (sim) imports helical_sil.cli (cli)"]
    sideways = {"helical_sil.live.serve": {"helical_sil.campaigns.tune"}}
    assert len(layer_violations(sideways)) == 1
    unknown = {"helical_sil.extra.x": {"helical_sil.sim.lockstep"}}
    assert len(layer_violations(unknown)) == 1
