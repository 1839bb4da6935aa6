#!/usr/bin/env python3
"""stack_depth.py BUILD_DIR[:DIR...] ROOT [ROOT...] [--limit BYTES] [--indirect CALLER=F1,F2]...

Worst-case stack depth of each ROOT function, from the call graphs GCC
writes with -fcallgraph-info=su (one .ci file per object, VCG format; each
defined function carries its frame size from -fstack-usage).

Depth(f) = frame(f) + max(Depth(callee)). A cycle (recursion), an indirect
call or a frame GCC marks "dynamic" (unbounded) makes the depth unknown and
the script fail. Callees defined in no .ci file (libc's memset/memcpy, libgcc
helpers) are listed as external and counted with frame 0: their frames are
small leaf frames, but the report names them so nobody is misled.
BUILD_DIR may list several directories (":"), e.g. one image's objects and
the libraries it links, so that two images' main() are not merged.
--indirect CALLER=F1,F2 names the functions an indirect call inside CALLER
can reach (a bus callback, a decoder's protocol table): each such call then
counts as the deepest of them. Names match a global or a file-static
function ("path:f"). An indirect call without a mapping is a problem.
Exit status: 0 when every root is known and within --limit, 1 otherwise.
"""
import os
import re
import sys

NODE = re.compile(r'node:\s*\{\s*title:\s*"([^"]+)"\s*label:\s*"([^"]*)"')
EDGE = re.compile(r'edge:\s*\{\s*sourcename:\s*"([^"]+)"\s*targetname:\s*"([^"]+)"')
SIZE = re.compile(r'\\n(\d+) bytes \(([^)]*)\)')


def load(build_dir):
    frames, kinds, edges = {}, {}, {}
    for base, _, files in os.walk(build_dir):
        for name in files:
            if not name.endswith(".ci"):
                continue
            with open(os.path.join(base, name), encoding="utf-8", errors="replace") as f:
                text = f.read()
            for title, label in NODE.findall(text):
                m = SIZE.search(label)
                if m:
                    frames[title] = int(m.group(1))
                    kinds[title] = m.group(2)
            for src, dst in EDGE.findall(text):
                edges.setdefault(src, []).append(dst)
    return frames, kinds, edges


def resolve(name, frames):
    if name in frames:
        return name
    # a file-static function is titled "path:func"; calls from its own file
    # already use that title, so a bare name here is a global.
    return None


INDIRECT = {}  # caller title -> resolved --indirect targets


def depth(fn, frames, kinds, edges, stack, memo, externals, problems):
    if fn in memo:
        return memo[fn]
    if fn in stack:
        problems.append("recursion: " + " -> ".join(stack[stack.index(fn):] + [fn]))
        return 0, [fn]
    if "dynamic" in kinds.get(fn, "") and "bounded" not in kinds.get(fn, ""):
        problems.append("unbounded dynamic frame in " + fn)
    best, best_path = 0, []
    for callee in edges.get(fn, []):
        if "__indirect_call" in callee:
            if fn not in INDIRECT:
                problems.append("indirect call in " + fn)
                continue
            for target in INDIRECT[fn]:
                d, p = depth(target, frames, kinds, edges, stack + [fn], memo, externals,
                             problems)
                if d > best:
                    best, best_path = d, ["(indirect)"] + p
            continue
        target = resolve(callee, frames)
        if target is None:
            externals.add(callee)
            continue
        d, p = depth(target, frames, kinds, edges, stack + [fn], memo, externals, problems)
        if d > best:
            best, best_path = d, p
    memo[fn] = (frames[fn] + best, [fn] + [f for f in best_path if f != "(indirect)"])
    return memo[fn]


def short(title):
    return title.rsplit(":", 1)[-1] if ":" in title else title


def main(argv):
    limit = None
    indirect = []
    args = []
    i = 1
    while i < len(argv):
        if argv[i] == "--limit":
            limit = int(argv[i + 1])
            i += 2
        elif argv[i] == "--indirect":
            caller, _, targets = argv[i + 1].partition("=")
            indirect.append((caller, targets.split(",")))
            i += 2
        else:
            args.append(argv[i])
            i += 1
    if len(args) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    frames, kinds, edges = {}, {}, {}
    for d in args[0].split(":"):
        f, k, e = load(d)
        frames.update(f)
        kinds.update(k)
        for src, dsts in e.items():
            edges.setdefault(src, []).extend(dsts)
    if not frames:
        print("stack_depth: no .ci files under " + args[0], file=sys.stderr)
        return 1
    status = 0
    def titles(name):
        return [t for t in frames if t == name or t.endswith(":" + name)]

    for caller, targets in indirect:
        resolved = []
        for name in targets:
            if not titles(name):
                print("stack_depth: indirect target %s is not defined in any .ci file" % name,
                      file=sys.stderr)
                status = 1
            resolved.extend(titles(name))
        for c in titles(caller):
            INDIRECT.setdefault(c, []).extend(resolved)
    for root in args[1:]:
        if root not in frames:
            print("stack_depth: %s is not defined in any .ci file" % root, file=sys.stderr)
            status = 1
            continue
        externals, problems = set(), []
        total, path = depth(root, frames, kinds, edges, [], {}, externals, problems)
        chain = " -> ".join("%s(%d)" % (short(f), frames[f]) for f in path)
        print("worst stack of %s: %d bytes: %s" % (root, total, chain))
        if externals:
            print("  external callees counted as 0: " + ", ".join(sorted(externals)))
        for p in problems:
            print("  PROBLEM: " + p)
            status = 1
        if limit is not None and total > limit:
            print("  OVER LIMIT: %d > %d bytes" % (total, limit))
            status = 1
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
