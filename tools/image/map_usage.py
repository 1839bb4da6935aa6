#!/usr/bin/env python3
"""map_usage.py MAP_FILE [ARCHIVE_NAME]

Flash and RAM that each object of ARCHIVE_NAME (default libhelical.a)
contributes to a linked image, from the GNU ld map file: the part of the
library the image really uses after --gc-sections, which `size` of the
archive cannot tell. Flash = .text + .rodata + .data (its load copy);
RAM = .data + .bss.
"""
import re
import sys

# An input section, whitespace collapsed: name, address, size, source file.
ENTRY = re.compile(r'^ (\.(?:text|rodata|data|bss)\S*) 0x([0-9a-f]+) 0x([0-9a-f]+) (\S+)$')


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    archive = argv[2] if len(argv) > 2 else "libhelical.a"
    with open(argv[1], encoding="utf-8", errors="replace") as f:
        lines = f.read().splitlines()
    # join "name\n   addr size file" pairs
    joined = []
    i = 0
    while i < len(lines):
        line = lines[i]
        if re.match(r'^ \.\S+$', line) and i + 1 < len(lines):
            joined.append(line + " " + lines[i + 1].strip())
            i += 2
            continue
        joined.append(line)
        i += 1
    started = False
    per = {}
    for line in joined:
        if line.startswith("Linker script and memory map"):
            started = True
            continue
        if not started:
            continue
        m = ENTRY.match(re.sub(r'\s+', ' ', line.rstrip()))
        if not m:
            continue
        name, _, size, src = m.groups()
        if archive not in src:
            continue
        obj = src[src.find("(") + 1:-1] if "(" in src else src
        flash, ram = per.get(obj, (0, 0))
        n = int(size, 16)
        if name.startswith((".text", ".rodata")):
            flash += n
        elif name.startswith(".data"):
            flash += n
            ram += n
        elif name.startswith(".bss"):
            ram += n
        per[obj] = (flash, ram)
    if not per:
        print("map_usage: nothing from %s in %s" % (archive, argv[1]))
        return 1
    total_f = total_r = 0
    print("%-28s %8s %8s" % (archive + " member", "flash", "RAM"))
    for obj in sorted(per):
        f, r = per[obj]
        total_f += f
        total_r += r
        print("%-28s %8d %8d" % (obj, f, r))
    print("%-28s %8d %8d" % ("total linked", total_f, total_r))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
