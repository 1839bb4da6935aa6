#!/usr/bin/env python3
"""The C tree's architecture, checked from the sources (docs/architecture.md).

    arch_check.py layers  [--root DIR] [--config FILE]
    arch_check.py circles [--root DIR] [--config FILE]
    arch_check.py mirror  [--root DIR]

layers   every project #include goes down the layer order of tools/arch/layers.toml
         (a file may include its own layer and the layers it `uses`)
circles  no circle among the C modules (x.c with x.h is one module): module A
         depends on B if A includes B's header or calls a function B defines;
         a strongly connected component of two or more modules is a circle
mirror   src/<concern>/ and include/helical/<concern>/ name the same concerns

Exit status: 0 clean, 1 a finding (each printed with the files and the edge),
2 bad usage or an unreadable configuration.
"""

from __future__ import annotations

import argparse
import re
import sys
import tomllib
from collections import defaultdict
from dataclasses import dataclass, field
from pathlib import Path

INCLUDE_RE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)
IDENT_RE = re.compile(r"[A-Za-z_]\w*")
# the keywords that look like calls: `if (`, `sizeof (` ...
NOT_CALLS = frozenset(
    "if while for switch return sizeof _Alignof alignof defined _Static_assert "
    "static_assert _Generic do else case".split())


@dataclass
class CFile:
    path: str  # relative to the root, with '/'
    text: str
    includes: list[str] = field(default_factory=list)  # resolved project paths
    defines: set[str] = field(default_factory=set)  # external function definitions
    calls: set[str] = field(default_factory=set)


def strip_code(text: str) -> str:
    """The text without comments, string and character literals, preprocessor lines."""
    out: list[str] = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(" 0 ")
            i = j + 1
        else:
            out.append(c)
            i += 1
    lines = "".join(out).split("\n")
    kept: list[str] = []
    cont = False
    for line in lines:
        is_pp = cont or line.lstrip().startswith("#")
        cont = is_pp and line.rstrip().endswith("\\")
        kept.append("" if is_pp else line)
    return "\n".join(kept)


def functions(code: str) -> tuple[set[str], set[str]]:
    """(external function definitions, identifiers called inside bodies)."""
    defines: set[str] = set()
    calls: set[str] = set()
    depth = 0
    decl = ""  # the text at depth 0 since the last ';' or '}'
    i, n = 0, len(code)
    while i < n:
        c = code[i]
        if c == "{":
            if depth == 0:
                m = re.search(r"([A-Za-z_]\w*)\s*\([^{}]*\)\s*$", decl)
                if m and not re.search(r"\bstatic\b", decl) and "=" not in decl:
                    defines.add(m.group(1))
            depth += 1
            decl = ""
        elif c == "}":
            depth = max(0, depth - 1)
            decl = ""
        elif depth == 0:
            decl = "" if c == ";" else decl + c
        i += 1
    for m in re.finditer(r"([A-Za-z_]\w*)\s*\(", code):
        if m.group(1) not in NOT_CALLS:
            calls.add(m.group(1))
    return defines, calls - defines


def project_files(root: Path, roots: list[str]) -> list[Path]:
    found: list[Path] = []
    for r in roots:
        base = root / r
        if not base.is_dir():
            continue
        for p in sorted(base.rglob("*")):
            if p.suffix not in (".c", ".h", ".def") or not p.is_file():
                continue
            parts = p.relative_to(root).parts
            if "tests" in parts or "build" in parts[:1]:
                continue
            found.append(p)
    return found


def load(root: Path, roots: list[str]) -> dict[str, CFile]:
    files = {p.relative_to(root).as_posix(): CFile(p.relative_to(root).as_posix(),
                                                   p.read_text(errors="replace"))
             for p in project_files(root, roots)}
    by_name: dict[str, list[str]] = defaultdict(list)
    for rel in files:
        by_name[rel.rsplit("/", 1)[-1]].append(rel)
    search = ["include", "src", "firmware"]
    for f in files.values():
        here = f.path.rsplit("/", 1)[0] if "/" in f.path else ""
        for inc in INCLUDE_RE.findall(f.text):
            cands = [f"{here}/{inc}" if here else inc] + [f"{s}/{inc}" for s in search]
            hit = next((c for c in (Path(x).as_posix() for x in cands) if c in files), None)
            if hit is None and "/" not in inc and len(by_name.get(inc, [])) == 1:
                hit = by_name[inc][0]  # a board's flat include ("stm32f4_regs.h")
            if hit is None and "/" not in inc:
                # several headers of that name: the one nearest the includer
                near = sorted(by_name.get(inc, []),
                              key=lambda c: -len(_common_prefix(c, f.path)))
                hit = near[0] if near else None
            if hit is not None and hit != f.path:
                f.includes.append(hit)
        if f.path.endswith(".c"):
            f.defines, f.calls = functions(strip_code(f.text))
    return files


def _common_prefix(a: str, b: str) -> str:
    pa, pb = a.split("/"), b.split("/")
    k = 0
    while k < min(len(pa), len(pb)) and pa[k] == pb[k]:
        k += 1
    return "/".join(pa[:k])


def module_of(path: str) -> str:
    """x.c and x.h are one module; a .def file belongs to its .h."""
    return path.rsplit(".", 1)[0]


def module_graph(files: dict[str, CFile]) -> dict[str, dict[str, str]]:
    """module -> {module it depends on: why (the first edge seen)}."""
    definers: dict[str, set[str]] = defaultdict(set)
    for f in files.values():
        for name in f.defines:
            definers[name].add(module_of(f.path))
    graph: dict[str, dict[str, str]] = defaultdict(dict)
    for f in files.values():
        a = module_of(f.path)
        graph.setdefault(a, {})
        for inc in f.includes:
            b = module_of(inc)
            if b != a:
                graph[a].setdefault(b, f"{f.path} includes {inc}")
        for name in sorted(f.calls):
            for b in sorted(definers.get(name, ())):
                if b != a:
                    graph[a].setdefault(b, f"{f.path} calls {name}()")
    return graph


def strongly_connected(graph: dict[str, dict[str, str]]) -> list[list[str]]:
    """Tarjan's algorithm, iterative (no recursion limit on a deep tree)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    out: list[list[str]] = []
    counter = 0
    nodes = set(graph) | {b for deps in graph.values() for b in deps}
    for start in sorted(nodes):
        if start in index:
            continue
        work = [(start, iter(sorted(graph.get(start, {}))))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            v, it = work[-1]
            advanced = False
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(graph.get(w, {})))))
                    advanced = True
                    break
                if w in on_stack:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp: list[str] = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return out


def layer_of(path: str, layers: dict[str, list[str]]) -> str | None:
    best, best_len = None, -1
    for name, prefixes in layers.items():
        for pre in prefixes:
            if (path == pre or (pre.endswith("/") and path.startswith(pre))) and len(pre) > best_len:
                best, best_len = name, len(pre)
    return best


def check_layers(files: dict[str, CFile], cfg: dict) -> list[str]:
    layers = {k: v["paths"] for k, v in cfg["layers"].items()}
    uses = {k: set(v.get("uses", [])) for k, v in cfg["layers"].items()}
    bad: list[str] = []
    for f in sorted(files.values(), key=lambda x: x.path):
        la = layer_of(f.path, layers)
        if la is None:
            continue
        for inc in f.includes:
            lb = layer_of(inc, layers)
            if lb is None or lb == la or lb in uses[la]:
                continue
            bad.append(f"{f.path} ({la}) includes {inc} ({lb}): {la} may use "
                       f"{', '.join(sorted(uses[la])) or 'nothing else'}")
    return bad


def check_mirror(root: Path) -> list[str]:
    def folders(d: Path) -> set[str]:
        return {p.name for p in d.iterdir() if p.is_dir()} if d.is_dir() else set()
    src, inc = folders(root / "src"), folders(root / "include/helical")
    return ([f"src/{d}/ has no include/helical/{d}/" for d in sorted(src - inc)] +
            [f"include/helical/{d}/ has no src/{d}/" for d in sorted(inc - src)])


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="\n".join(__doc__.split("\n")[2:]))
    ap.add_argument("check", choices=["layers", "circles", "mirror"])
    ap.add_argument("--root", type=Path, default=Path(__file__).resolve().parents[2],
                    help="the tree to check (default: this checkout)")
    ap.add_argument("--config", type=Path, default=None,
                    help="layer table (default: ROOT/tools/arch/layers.toml, else ROOT/layers.toml)")
    args = ap.parse_args(argv)
    cfg_path = args.config or args.root / "tools/arch/layers.toml"
    if args.config is None and not cfg_path.exists():
        cfg_path = args.root / "layers.toml"  # a test fixture's tree
    try:
        cfg = tomllib.loads(cfg_path.read_text())
        roots = cfg["circles"]["roots"]
        for name, layer in cfg["layers"].items():
            if not isinstance(layer.get("paths"), list):
                raise KeyError(f"layers.{name}.paths")
            for u in layer.get("uses", []):
                if u not in cfg["layers"]:
                    raise KeyError(f"layers.{name}.uses names an unknown layer {u!r}")
    except (OSError, tomllib.TOMLDecodeError, KeyError, TypeError) as e:
        print(f"arch_check: {cfg_path}: {e}", file=sys.stderr)
        return 2

    if args.check == "mirror":
        bad = check_mirror(args.root)
        for b in bad:
            print(f"MIRROR {b}")
        print(f"arch_check mirror: {'OK' if not bad else f'{len(bad)} finding(s)'}")
        return 1 if bad else 0

    files = load(args.root, roots)
    if args.check == "layers":
        bad = check_layers(files, cfg)
        for b in bad:
            print(f"LAYER {b}")
        n_inc = sum(len(f.includes) for f in files.values())
        print(f"arch_check layers: {len(files)} files, {n_inc} project includes, "
              f"{len(cfg['layers'])} layers: {'OK' if not bad else f'{len(bad)} finding(s)'}")
        return 1 if bad else 0

    graph = module_graph(files)
    comps = strongly_connected(graph)
    for comp in comps:
        print(f"CIRCLE among {len(comp)} modules: {', '.join(comp)}")
        members = set(comp)
        for a in comp:
            for b, why in sorted(graph.get(a, {}).items()):
                if b in members:
                    print(f"    {a} -> {b}: {why}")
    n_edges = sum(len(v) for v in graph.values())
    print(f"arch_check circles: {len(graph)} modules, {n_edges} dependencies: "
          f"{'OK, no circle' if not comps else f'{len(comps)} circle(s)'}")
    return 1 if comps else 0


if __name__ == "__main__":
    sys.exit(main())
