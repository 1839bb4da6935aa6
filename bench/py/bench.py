#!/usr/bin/env python3
"""The helical-turn benchmark (tracker issue 6): builds, emulates, times, prints.

What it does, in order:
  1. writes the fixed, seeded input set (realistic steps + edge cases),
  2. builds the library and the bench harness for x86-64 and runs the host
     figures (ns/step, steps/s, callgrind instructions/step) and the
     reference dump every emulator run is checked against,
  3. builds one harness ELF per Cortex-M core and optimisation level with
     arm-none-eabi-gcc and runs it in Unicorn, counting the instructions of
     every call (ht_step, step + output stage, the primitives, the float and
     double law) and a per-function profile,
  4. prints Markdown tables (and writes them, with JSON, to the output dir).

It is a benchmark, not a test: it never fails on a figure, only on breakage
(a build that fails, an emulated call that faults, a result that differs
from the host build's bits). Run it through scripts/bench.sh.
"""
from __future__ import annotations

import argparse
import bisect
import datetime
import json
import math
import os
import random
import re
import shutil
import statistics
import struct
import subprocess
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Optional

ROOT = Path(__file__).resolve().parents[2]
BENCH = ROOT / "bench"
CDIR = BENCH / "c"

ARM_CC = "arm-none-eabi-gcc"
STRICT = ["-std=c11", "-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wshadow", "-Werror"]
# The library is compiled with its own warnings but never -Werror here: it is
# the lead's code and may be in flux; its warnings are counted and reported.
LIB_WARN = ["-std=c11", "-Wall", "-Wextra"]
CORE_SOURCES = ("q14.c", "param_rows.c", "ht_params.c", "helical_turn.c")
OS_SOURCES = ("mixer.c", "output_stage.c")

FLASH_BASE = 0x08000000
FLASH_SIZE = 1 << 20
RAM_BASE = 0x20000000
RAM_SIZE = 256 << 10
STACK_TOP = RAM_BASE + RAM_SIZE
STACK_PAINT = 8 << 10  # bytes below STACK_TOP painted to measure stack depth
PAINT_WORD = 0xA5C3E1F0
MAX_INSNS = 5_000_000  # per call; a runaway call is breakage


@dataclass(frozen=True)
class Core:
    name: str
    flags: tuple[str, ...]
    model: str  # unicorn.arm_const UC_CPU_ARM_* name
    fpu: bool
    note: str


CORES: dict[str, Core] = {
    "M0": Core("M0", ("-mcpu=cortex-m0", "-mthumb", "-mfloat-abi=soft"),
               "UC_CPU_ARM_CORTEX_M0", False, "ARMv6-M, no divide, 32x32->32 MUL only"),
    "M3": Core("M3", ("-mcpu=cortex-m3", "-mthumb", "-mfloat-abi=soft"),
               "UC_CPU_ARM_CORTEX_M3", False, "ARMv7-M, SDIV, SMULL"),
    "M4": Core("M4", ("-mcpu=cortex-m4", "-mthumb", "-mfloat-abi=soft"),
               "UC_CPU_ARM_CORTEX_M4", False, "ARMv7E-M (DSP), float in software"),
    "M4F": Core("M4F", ("-mcpu=cortex-m4", "-mthumb", "-mfpu=fpv4-sp-d16", "-mfloat-abi=hard"),
                "UC_CPU_ARM_CORTEX_M4", True, "ARMv7E-M + FPv4-SP single-precision FPU"),
}

# Workloads measured per step, with their display names.
STEP_WORKLOADS = ("step", "step_os", "f32", "f64", "q14", "q14_os")
WL_NAMES = {"step": "ht_step (fixed)", "step_os": "ht_step + output stage (fixed)",
            "f32": "float law", "f64": "double law", "q14": "16-bit law",
            "q14_os": "16-bit law + output stage"}


class BenchError(Exception):
    """Breakage: the benchmark cannot produce a trustworthy figure."""


def log(msg: str) -> None:
    print(f"[bench] {msg}", file=sys.stderr, flush=True)


def run(cmd: list[str], cwd: Optional[Path] = None, check: bool = True,
        capture: bool = True) -> subprocess.CompletedProcess[str]:
    p = subprocess.run(cmd, cwd=cwd, text=True, capture_output=capture)
    if check and p.returncode != 0:
        raise BenchError(f"command failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr}{p.stdout}")
    return p


# --------------------------------------------------------------------------
# Inputs
# --------------------------------------------------------------------------

INPUT_FMT = "<hhhhihhhhBxhh2x"  # ht_input_t, 28 bytes (checked by _Static_assert)
F32_FMT = "<9fi"
F64_FMT = "<9dii"
OUTPUT_FMT = "<h2xi15hB1x"  # ht_output_t's first 40 bytes (the seed's fields; 48 in all)
Q14_OUTPUT_FMT = "<6h"  # law_q14_output_t, 12 bytes

# Columns of host_bench's dump (one row per input).
REF_HT = slice(0, 18)  # every ht_output_t field
REF_PULSES = slice(18, 23)
REF_F64 = (23, 24, 25)  # double law surfaces, bench set: aileron, elevator, rudder
REF_Q14 = slice(26, 32)  # law_q14_output_t: aileron, elevator, rudder, tilt x, y, z
REF_Q14_PULSES = slice(32, 37)
REF_C172P = (37, 46)  # ht_step (3), 16-bit law (3), double law (3) surfaces, c172p set
REF_COLS = 46


def q(v: float, one: int, lo: int, hi: int) -> int:
    return max(lo, min(hi, int(math.floor(v * one + 0.5))))


def q14(v: float) -> int:
    return q(v, 16384, -32768, 32767)


def q11(v: float) -> int:
    return q(v, 2048, -32768, 32767)


def q16(v: float) -> int:
    return q(v, 65536, -(2 ** 31), 2 ** 31 - 1)


# x, y, z, turn, pitch, airspeed, gyro x/y/z, inverted, and the options'
# inputs turn_accel (Q11 rad/s^2), accel_lat (Q14 g): 0 unless --options.
Input = tuple[int, ...]

# --options (docs/control-law.md "Extensions beyond the seed"): the law's
# options on in bench_setup (-DBENCH_OPTIONS=1) and their inputs drawn in the
# realistic set, to measure what they cost. The float and double laws do not
# have them: their agreement with the fixed law is then not checked.
BENCH_DEFS: list[str] = []


def with_option_inputs(inputs: list[tuple[int, ...]], seed: int) -> list[Input]:
    """The options' inputs: 0 (the default), or with --options a turn
    acceleration (half the steps, U(-3, 3) rad/s^2) and a lateral specific
    force (N(0, 0.05) g) on every realistic step; edge cases at the ends."""
    if not BENCH_DEFS:
        return [(*i, 0, 0) for i in inputs]
    rng = random.Random(seed + 17)
    out: list[Input] = []
    for i in inputs:
        ta = q11(rng.uniform(-3.0, 3.0)) if rng.random() < 0.5 else 0
        out.append((*i, ta, q14(rng.gauss(0.0, 0.05))))
    return out


def realistic_inputs(n: int, seed: int) -> list[Input]:
    """Flight-like steps: mostly moderate attitudes and demands, some upsets,
    a little DCM drift, occasional inverted flight and low airspeed."""
    rng = random.Random(seed)
    out: list[Input] = []
    for _ in range(n):
        upset = rng.random() < 0.05
        roll = math.radians(rng.uniform(-180, 180) if upset else rng.gauss(0, 25))
        pitch = math.radians(rng.uniform(-85, 85) if upset else rng.gauss(0, 10))
        inverted = 1 if rng.random() < 0.02 else 0
        if inverted:
            roll = math.pi - roll
        drift = 1.0 + rng.gauss(0, 0.003)  # the DCM row is used as given
        x = -math.sin(roll) * math.cos(pitch) * drift
        y = -math.sin(pitch) * drift
        z = math.cos(roll) * math.cos(pitch) * drift
        turn = 0.0 if rng.random() < 0.2 else rng.uniform(-0.8, 0.8)
        pr = 0.0 if rng.random() < 0.3 else rng.gauss(0, 0.15)
        speed = rng.uniform(3.0, 8.0) if rng.random() < 0.05 else rng.uniform(9.0, 30.0)
        gyro = [rng.gauss(0, 0.4) for _ in range(3)]
        out.append((q14(x), q14(y), q14(z), q11(turn), q16(pr), int(round(speed * 100)),
                    q11(gyro[0]), q11(gyro[1]), q11(gyro[2]), inverted))
    return out


def edge_inputs() -> list[Input]:
    """The corners: every branch of the law and the extreme values."""
    e: list[Input] = []
    one = 16384
    e.append((0, 0, one, 0, 0, 1500, 0, 0, 0, 0))  # level, nothing asked
    e.append((0, 0, one, 1024, 13107, 1500, 0, 0, 0, 0))  # worked case
    e.append((0, 0, one, 32767, 0, 3000, 0, 0, 0, 0))  # tilt limit +
    e.append((0, 0, one, -32768, 0, 3000, 0, 0, 0, 0))  # tilt limit -
    e.append((0, 0, one, 1024, 0, 0, 0, 0, 0, 0))  # airspeed 0 -> floored
    e.append((0, 0, one, 1024, 0, -32768, 0, 0, 0, 0))  # negative airspeed
    e.append((0, 0, one, 1024, 0, 32767, 0, 0, 0, 0))  # max airspeed
    e.append((0, one, 0, 512, 0, 1500, 0, 0, 0, 0))  # fuselage vertical, nose down
    e.append((0, -one, 0, 512, 0, 1500, 0, 0, 0, 0))  # fuselage vertical, nose up
    e.append((0, 0, 0, 0, 0, 1500, 0, 0, 0, 0))  # zero row
    e.append((0, 1638, -16302, 0, 0, 1500, 0, 0, 0, 1))  # inverted target, nose low
    e.append((one, 1638, 0, 0, 0, 1500, 0, 0, 0, 0))  # 90 deg bank
    e.append((0, 0, -one, 0, 0, 1500, 0, 0, 0, 0))  # upside down, upright target
    e.append((0, 0, -one, 0, 0, 1500, 0, 0, 0, 1))  # upside down, inverted target
    e.append((0, 0, one, 0, 2 ** 31 - 1, 1500, 0, 0, 0, 0))  # pitch ratio max
    e.append((0, 0, one, 0, -(2 ** 31), 1500, 0, 0, 0, 0))  # pitch ratio min
    e.append((0, 0, one, 0, 0, 1500, 32767, 32767, 32767, 0))  # gyro max
    e.append((0, 0, one, 0, 0, 1500, -32768, -32768, -32768, 0))  # gyro min
    e.append((32767, 32767, 32767, 32767, 2 ** 31 - 1, 32767, 32767, 32767, 32767, 1))
    e.append((-32768, -32768, -32768, -32768, -(2 ** 31), -32768, -32768, -32768, -32768, 1))
    e.append((-32768, 0, 0, 0, 0, 1500, 0, 0, 0, 0))
    e.append((0, 0, 32767, 1, 1, 500, 1, 1, 1, 0))  # tiny values at v_min
    e.append((11585, 0, 11585, -2048, -65536, 1000, 2048, -2048, 2048, 0))  # 45 deg left, diving
    e.append((-11585, 0, -11585, 2048, 65536, 2500, 0, 0, 0, 0))  # upset, roll_dot < 0
    e.append((1, 0, -1, 0, 0, 1500, 0, 0, 0, 0))  # a ~ 0, not exactly
    return e


def pack_inputs(inputs: list[Input]) -> bytes:
    return b"".join(struct.pack(INPUT_FMT, *i) for i in inputs)


def to_real(i: Input) -> tuple[float, ...]:
    x, y, z, w, p, s, gx, gy, gz, inv = i[:10]
    return (x / 16384.0, y / 16384.0, z / 16384.0, w / 2048.0, p / 65536.0, s / 100.0,
            gx / 2048.0, gy / 2048.0, gz / 2048.0, 1 if inv else 0)


def primitive_inputs(n: int, seed: int) -> dict[str, list[tuple[int, ...]]]:
    rng = random.Random(seed + 1)
    d: dict[str, list[tuple[int, ...]]] = {}
    d["q14_mul"] = [(rng.randint(-32768, 32767), rng.randint(-32768, 32767)) for _ in range(n)]
    shifts = (14, 16, 20, 24, 28, 30, 32, 35)
    d["q_mul32"] = [(rng.randint(-(2 ** 30), 2 ** 30), rng.randint(-(2 ** 30), 2 ** 30),
                     rng.choice(shifts)) for _ in range(n)]
    # the step's own form: the caller's proof that the result fits (|a|, |b| <= 2^27)
    d["q_mul32_fit"] = [(rng.randint(-(2 ** 27), 2 ** 27), rng.randint(-(2 ** 27), 2 ** 27),
                         rng.choice((24, 28, 30, 32, 35))) for _ in range(n)]
    d["q_isqrt32"] = [(int(2 ** rng.uniform(0, 32)) & 0xFFFFFFFF,) for _ in range(n)]
    d["q_rsqrt_norm_q28"] = [(max(1, int(2 ** rng.uniform(0, 32)) & 0xFFFFFFFF),)
                             for _ in range(n)]
    d["q_recip_q30"] = [(max(1, int(2 ** rng.uniform(0, 31)) & 0x7FFFFFFF),) for _ in range(n)]
    d["q_unit2_q28"] = [(rng.randint(-(2 ** 20), 2 ** 20), rng.randint(-(2 ** 20), 2 ** 20))
                        for _ in range(n)]
    d["q_unit3_q28"] = [tuple(rng.randint(-(2 ** 28), 2 ** 28) for _ in range(3)) for _ in range(n)]
    d["q14_normalize3"] = [tuple(rng.randint(-16384, 16384) for _ in range(3)) for _ in range(n)]
    return d


PRIMITIVES = ("q14_mul", "q_mul32", "q_mul32_fit", "q_isqrt32", "q_rsqrt_norm_q28", "q_recip_q30",
              "q_unit2_q28", "q_unit3_q28", "q14_normalize3")


# --------------------------------------------------------------------------
# Builds
# --------------------------------------------------------------------------

@dataclass
class LibBuild:
    objects: list[Path]
    core_objects: list[Path]
    have_os: bool
    failed: dict[str, str]
    warnings: int


def lib_sources() -> list[Path]:
    """Every library source: each concern's folder of src/."""
    return sorted((ROOT / "src").glob("*/*.c"))


def build_library(cc: str, flags: list[str], outdir: Path) -> LibBuild:
    """Compile every src/*/*.c that builds; the core must, the rest may not."""
    outdir.mkdir(parents=True, exist_ok=True)
    objs: list[Path] = []
    core: list[Path] = []
    failed: dict[str, str] = {}
    warnings = 0
    for src in lib_sources():
        obj = outdir / (src.stem + ".o")
        base = [cc, *LIB_WARN, *flags, "-I", str(ROOT / "include"), "-I", str(ROOT / "src"),
                "-fstack-usage", "-c", str(src), "-o", str(obj)]
        p = run(base, check=False)
        if p.returncode != 0:
            failed[src.name] = p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "failed"
            continue
        warnings += p.stderr.count("warning:")
        objs.append(obj)
        if src.name in CORE_SOURCES:
            core.append(obj)
    for name in CORE_SOURCES:
        if name in failed:
            raise BenchError(f"library core file {name} does not build ({' '.join(flags)}): "
                             f"{failed[name]}")
    names = {s.name for s in lib_sources()}
    have_os = all(n not in failed and n in names for n in OS_SOURCES)
    return LibBuild(objs, core, have_os, failed, warnings)


@dataclass
class ArmBuild:
    core: str
    opt: str
    elf: Path
    lib: LibBuild
    outdir: Path


def build_arm(core: Core, opt: str, outroot: Path) -> ArmBuild:
    outdir = outroot / f"arm-{core.name}-{opt}"
    if outdir.exists():
        shutil.rmtree(outdir)
    flags = [*core.flags, f"-{opt}", "-ffunction-sections", "-fdata-sections", "-g"]
    lib = build_library(ARM_CC, flags, outdir / "lib")
    bflags = [*STRICT, *flags, *BENCH_DEFS, "-fno-math-errno",
              f"-DBENCH_HAVE_OS={1 if lib.have_os else 0}",
              "-I", str(ROOT / "include"), "-I", str(CDIR), "-fstack-usage"]
    hobjs: list[Path] = []
    for name in ("bench_common.c", "arm_harness.c", "law_f32.c", "law_f64.c", "law_q14.c"):
        obj = outdir / (Path(name).stem + ".o")
        run([ARM_CC, *bflags, "-c", str(CDIR / name), "-o", str(obj)])
        hobjs.append(obj)
    elf = outdir / "bench.elf"
    run([ARM_CC, *flags, "-nostartfiles", "-nostdlib", "-T", str(CDIR / "bench.ld"),
         "-Wl,--gc-sections", f"-Wl,-Map={outdir / 'bench.map'}",
         *[str(o) for o in hobjs], *[str(o) for o in lib.objects],
         "-lm", "-lc", "-lgcc", "-o", str(elf)])
    return ArmBuild(core.name, opt, elf, lib, outdir)


# --------------------------------------------------------------------------
# Disassembly: instruction boundaries, symbols, the cycle model
# --------------------------------------------------------------------------

# The Cortex-M4 cycle model (an estimate; Unicorn has no timing). Stated in
# bench/README.md: VSQRT/VDIV 14; SDIV/UDIV 12 (the worst case of 2-12, so the
# fixed-point figure is not flattered); MUL/MLA/SMULL/UMLAL/SMULxy/VFP
# arithmetic 1 (VMLA/VMLS/VFMA/VFNMA 3); single loads and stores 2 (LDRD/STRD
# 3); LDM/STM/PUSH/POP/VLDM/VSTM/VPUSH/VPOP 1+N; B/BL/BX/BLX 3 (1 + a
# pipeline refill of 2); conditional branches and CBZ/CBNZ 2 (taken 3, not
# taken 1: an average); POP/LDM into PC 1+N+2; IT 1; everything else 1.
_REGLIST = re.compile(r"\{([^}]*)\}")


def _nregs(ops: str) -> int:
    m = _REGLIST.search(ops)
    if not m:
        return 1
    n = 0
    for part in m.group(1).split(","):
        part = part.strip()
        if "-" in part:
            a, b = part.split("-")
            na, nb = re.sub(r"\D", "", a), re.sub(r"\D", "", b)
            n += int(nb) - int(na) + 1 if na and nb else 1
        elif part:
            n += 1
    return n


_COND = ("eq", "ne", "cs", "cc", "hs", "lo", "mi", "pl", "vs", "vc", "hi", "ls", "ge", "lt",
         "gt", "le", "al")


def cycles_of(mnem: str, ops: str) -> int:
    m = mnem.lower().split(".")[0]
    fp = mnem.lower().startswith("v")
    if m in ("vsqrt", "vdiv"):
        return 14
    if m in ("sdiv", "udiv"):
        return 12
    if m in ("vmla", "vmls", "vnmla", "vnmls", "vfma", "vfms", "vfnma", "vfnms"):
        return 3
    if m in ("vpush", "vpop", "vldmia", "vldmdb", "vstmia", "vstmdb", "vldm", "vstm"):
        return 1 + _nregs(ops)
    if m in ("vldr", "vstr"):
        return 2
    if fp:
        return 1
    if m.startswith("push") or m.startswith("stm"):
        return 1 + _nregs(ops)
    if m.startswith("pop") or m.startswith("ldm"):
        return 1 + _nregs(ops) + (2 if "pc" in ops else 0)
    if m.startswith("ldrd") or m.startswith("strd"):
        return 3
    if m.startswith("ldr") or m.startswith("str") or m.startswith("ldrex") or m.startswith("strex"):
        return 2 + (2 if ops.split(",")[0].strip() == "pc" else 0)
    if m in ("b", "bl", "bx", "blx"):
        return 3
    if m in ("cbz", "cbnz") or (m.startswith("b") and m[1:] in _COND):
        return 2
    if m.startswith("it"):
        return 1
    return 1


@dataclass
class Disasm:
    addrs: list[int]
    cycles: list[int]
    sym_of: list[int]  # index into syms
    syms: list[str]
    sym_start: dict[int, int]  # address -> sym index, function entries
    calls: dict[str, set[str]]  # static call graph (bl / b to other symbols)
    mnems: list[str]
    in_it: list[int]  # 1 where the instruction is inside an IT block


def disassemble(elf: Path) -> Disasm:
    p = run(["arm-none-eabi-objdump", "-d", "--no-show-raw-insn", str(elf)])
    addrs: list[int] = []
    cycles: list[int] = []
    sym_of: list[int] = []
    mnems: list[str] = []
    in_it: list[int] = []
    it_left = 0
    syms: list[str] = []
    sym_start: dict[int, int] = {}
    calls: dict[str, set[str]] = {}
    cur = -1
    fn_re = re.compile(r"^([0-9a-f]+) <([^>]+)>:$")
    ins_re = re.compile(r"^\s*([0-9a-f]+):\s+(\S+)\s*(.*)$")
    tgt_re = re.compile(r"^[0-9a-f]+ <([^>+]+)>")
    for line in p.stdout.splitlines():
        m = fn_re.match(line)
        if m:
            syms.append(m.group(2))
            cur = len(syms) - 1
            sym_start[int(m.group(1), 16)] = cur
            calls.setdefault(m.group(2), set())
            continue
        m = ins_re.match(line)
        if not m or cur < 0:
            continue
        mnem, ops = m.group(2), m.group(3).split("@")[0].split(";")[0].strip()
        if mnem.startswith("."):
            continue  # literal pools (.word)
        addrs.append(int(m.group(1), 16))
        in_it.append(1 if it_left > 0 else 0)
        it_left = max(0, it_left - 1)
        if re.fullmatch(r"it[te]{0,3}", mnem.lower()):
            it_left = len(mnem) - 1
        cycles.append(cycles_of(mnem, ops))
        sym_of.append(cur)
        mnems.append(mnem)
        base = mnem.lower().split(".")[0]
        if base in ("bl", "b", "blx") or (base.startswith("b") and base[1:] in _COND):
            t = tgt_re.match(ops)
            if t and t.group(1) != syms[cur]:
                calls[syms[cur]].add(t.group(1))
    return Disasm(addrs, cycles, sym_of, syms, sym_start, calls, mnems, in_it)


# --------------------------------------------------------------------------
# The emulator
# --------------------------------------------------------------------------

class Emulator:
    """One harness ELF in Unicorn on one Cortex-M model, counting every
    executed instruction through a basic-block hook."""

    def __init__(self, elf: Path, core: Core, dis: Disasm) -> None:
        import unicorn  # noqa: PLC0415 (only the emulator needs it)
        from unicorn import arm_const
        from elftools.elf.elffile import ELFFile

        self.uc_mod = unicorn
        self.dis = dis
        self.core = core
        with open(elf, "rb") as f:
            e = ELFFile(f)
            symtab = e.get_section_by_name(".symtab")
            if symtab is None:
                raise BenchError(f"{elf}: no symbol table")
            self.sym: dict[str, int] = {}
            for s in symtab.iter_symbols():
                if s.name and s["st_info"]["type"] in ("STT_FUNC", "STT_OBJECT", "STT_NOTYPE"):
                    self.sym.setdefault(s.name, s["st_value"])
            segs = [(s["p_vaddr"], s.data()) for s in e.iter_segments()
                    if s["p_type"] == "PT_LOAD" and s["p_filesz"]]
        # The facts of issue 6, checked by self_check(): plain THUMB mode plus
        # the CPU model set before any memory is mapped (UC_MODE_MCLASS would
        # select a Cortex-M33).
        self.uc = unicorn.Uc(unicorn.UC_ARCH_ARM, unicorn.UC_MODE_THUMB)
        self.uc.ctl_set_cpu_model(getattr(arm_const, core.model))
        self.uc.mem_map(FLASH_BASE, FLASH_SIZE)
        self.uc.mem_map(RAM_BASE, RAM_SIZE)
        for addr, data in segs:
            self.uc.mem_write(addr, data)
        self.R = arm_const
        self.stop = self.sym["bench_stop"] & ~1
        # Per block (key = address << 16 | size): [instructions, cycles,
        # IT-covered instructions, executions since reset_counts()].
        self.block_info: dict[int, list[int]] = {}
        # Per call: [instructions, cycles, IT-covered instructions].
        self.acc = [0, 0, 0]
        # The hook goes in before anything is translated: Unicorn does not
        # instrument blocks translated before a hook was added.
        self.uc.hook_add(unicorn.UC_HOOK_BLOCK, self._make_hook())

    def _info(self, addr: int, size: int) -> list[int]:
        a = self.dis.addrs
        i = bisect.bisect_left(a, addr)
        j = bisect.bisect_left(a, addr + size)
        if i == j or a[i] != addr:
            raise BenchError(f"block at {addr:#x}+{size} is not on an instruction boundary")
        return [j - i, sum(self.dis.cycles[i:j]), sum(self.dis.in_it[i:j]), 0]

    def _make_hook(self) -> Callable[[Any, int, int, Any], None]:
        # A closure over locals: the hook runs once per executed block and is
        # most of the benchmark's run time. It also stops a runaway call
        # (instead of emu_start's count, which slows every instruction).
        info_get = self.block_info.get
        infos = self.block_info
        acc = self.acc
        make = self._info
        limit = MAX_INSNS

        def on_block(uc: Any, addr: int, size: int, _ud: Any) -> None:
            key = (addr << 16) | size
            info = info_get(key)
            if info is None:
                if addr >= RAM_BASE:
                    return  # the self-check's probes run from RAM
                info = make(addr, size)
                infos[key] = info
            acc[0] += info[0]
            acc[1] += info[1]
            acc[2] += info[2]
            info[3] += 1
            if acc[0] > limit:
                uc.emu_stop()

        return on_block

    def reset_counts(self) -> None:
        for info in self.block_info.values():
            info[3] = 0

    @property
    def block_count(self) -> dict[int, int]:
        return {k: v[3] for k, v in self.block_info.items() if v[3]}

    @property
    def it_insns(self) -> int:
        return self.acc[2]

    def addr(self, name: str) -> int:
        if name not in self.sym:
            raise BenchError(f"symbol {name} not in the ELF")
        return self.sym[name]

    def call(self, fn: str, *args: int) -> tuple[int, int, int]:
        """Call fn(args) in r0-r3; returns (r0, instructions, cycles)."""
        R = self.R
        for i, a in enumerate(args):
            self.uc.reg_write(R.UC_ARM_REG_R0 + i, a & 0xFFFFFFFF)
        self.uc.reg_write(R.UC_ARM_REG_SP, STACK_TOP)
        self.uc.reg_write(R.UC_ARM_REG_LR, self.stop | 1)  # a mapped stub, not EXC_RETURN
        acc = self.acc
        acc[0] = acc[1] = acc[2] = 0
        entry = self.addr(fn) | 1  # Thumb: bit 0 set
        try:
            self.uc.emu_start(entry, self.stop)
        except self.uc_mod.UcError as ex:
            pc = self.uc.reg_read(R.UC_ARM_REG_PC)
            raise BenchError(f"{self.core.name}: {fn} faulted at {pc:#x}: {ex}") from ex
        pc = self.uc.reg_read(R.UC_ARM_REG_PC)
        if pc != self.stop:
            raise BenchError(f"{self.core.name}: {fn} did not return (pc {pc:#x}, "
                             f"{acc[0]} instructions)")
        return self.uc.reg_read(R.UC_ARM_REG_R0), acc[0], acc[1]

    def write(self, name: str, data: bytes) -> None:
        self.uc.mem_write(self.addr(name), data)

    def read(self, name: str, n: int) -> bytes:
        return bytes(self.uc.mem_read(self.addr(name), n))

    def paint_stack(self) -> None:
        self.uc.mem_write(STACK_TOP - STACK_PAINT, struct.pack("<I", PAINT_WORD) * (STACK_PAINT // 4))

    def stack_used(self) -> int:
        mem = bytes(self.uc.mem_read(STACK_TOP - STACK_PAINT, STACK_PAINT))
        word = struct.pack("<I", PAINT_WORD)
        for off in range(0, STACK_PAINT, 4):
            if mem[off:off + 4] != word:
                return STACK_PAINT - off
        return 0


def self_check(elf: Path, core: Core, dis: Disasm) -> list[str]:
    """Check, on a fresh emulator of its own (a faulting probe may leave the
    CPU in a handler), that the emulated CPU is the core asked for: UDIV
    faults on the M0 only, VFP faults on the M0 and M3. Raises on failure."""
    import unicorn

    emu = Emulator(elf, core, dis)
    notes: list[str] = []
    scratch = RAM_BASE + RAM_SIZE // 2
    udiv = bytes.fromhex("b0fbf1f07047")  # udiv r0, r0, r1 ; bx lr
    vfp = bytes.fromhex("00ee100a30ee000a10ee100a7047")  # vmov s0,r0; vadd.f32; vmov r0,s0; bx lr
    uc = emu.uc
    R = emu.R

    def probe(code: bytes, r0: int, r1: int, at: int) -> Optional[int]:
        # A fresh address per probe: Unicorn keeps translated blocks.
        uc.mem_write(at, code)
        uc.reg_write(R.UC_ARM_REG_R0, r0)
        uc.reg_write(R.UC_ARM_REG_R1, r1)
        uc.reg_write(R.UC_ARM_REG_SP, STACK_TOP)
        uc.reg_write(R.UC_ARM_REG_LR, emu.stop | 1)
        try:
            uc.emu_start(at | 1, emu.stop, count=100)
        except unicorn.UcError:
            return None
        if uc.reg_read(R.UC_ARM_REG_PC) != emu.stop:
            return None
        return int(uc.reg_read(R.UC_ARM_REG_R0))

    has_div = probe(udiv, 100, 7, scratch) == 14
    has_vfp = probe(vfp, 0x3F800000, 0, scratch + 64) == 0x40000000
    want_div = core.name != "M0"
    want_vfp = core.name in ("M4", "M4F")  # the M4 model has the FPU either way
    if has_div != want_div or has_vfp != want_vfp:
        raise BenchError(f"{core.name}: the emulated CPU is not the model asked for "
                         f"(UDIV {has_div}, VFP {has_vfp})")
    notes.append(f"{core.name}: model checked (UDIV {'yes' if has_div else 'faults'}, "
                 f"VFP {'yes' if has_vfp else 'faults'})")
    return notes


def count_by_code_hook(emu: Emulator, fn: str, args: tuple[int, ...]) -> int:
    """The same call counted one instruction at a time (a cross-check of the
    block arithmetic, on freshly translated code). Unicorn's code hook skips
    the instructions of an IT block whose condition fails; the block count
    includes them (on the core they issue and take their cycle as NOPs), so
    the two must agree up to those: code <= block <= code + IT-covered."""
    import unicorn

    n = [0]

    def on_code(_uc: Any, _a: int, _s: int, _u: Any) -> None:
        n[0] += 1

    emu.uc.ctl_remove_cache(FLASH_BASE, FLASH_BASE + FLASH_SIZE)
    h = emu.uc.hook_add(unicorn.UC_HOOK_CODE, on_code)
    try:
        _, blocks, _ = emu.call(fn, *args)
    finally:
        emu.uc.hook_del(h)
        emu.uc.ctl_remove_cache(FLASH_BASE, FLASH_BASE + FLASH_SIZE)
    if not n[0] <= blocks <= n[0] + emu.it_insns:
        raise BenchError(f"{emu.core.name}: block count {blocks} vs instruction count {n[0]} "
                         f"(IT-covered {emu.it_insns}) for {fn}")
    return n[0]


# --------------------------------------------------------------------------
# One core x opt level in the emulator
# --------------------------------------------------------------------------

@dataclass
class Stats:
    n: int
    mn: int
    med: float
    mx: int
    mean: float

    @staticmethod
    def of(v: list[int]) -> "Stats":
        return Stats(len(v), min(v), statistics.median(v), max(v), statistics.fmean(v))


def emulate_config(job: dict[str, Any]) -> dict[str, Any]:
    """Runs in a worker process: everything for one ELF. Returns plain data."""
    core = CORES[job["core"]]
    elf = Path(job["elf"])
    inputs: list[Input] = [tuple(i) for i in job["inputs"]]
    n_real: int = job["n_real"]
    t0 = time.time()
    dis = disassemble(elf)
    res: dict[str, Any] = {"core": core.name, "opt": job["opt"], "notes": []}
    res["notes"] += self_check(elf, core, dis)
    emu = Emulator(elf, core, dis)
    r0, _, _ = emu.call("bench_setup")
    if r0 != 0:
        raise BenchError(f"{core.name}: bench_setup returned {r0}")

    ctl, inp, out = emu.addr("bench_ctl"), emu.addr("bench_in"), emu.addr("bench_out")
    packed = [struct.pack(INPUT_FMT, *i) for i in inputs]
    # Cross-check the block arithmetic on one input of each kind.
    emu.write("bench_in", packed[0])
    count_by_code_hook(emu, "ht_step", (ctl, inp, out))

    workloads = [w for w in job["workloads"] if w != "step_os" or job["have_os"]]
    per: dict[str, dict[str, Any]] = {}
    outputs: list[tuple[int, ...]] = []
    pulses: list[tuple[int, ...]] = []
    q14_outputs: list[tuple[int, ...]] = []
    q14_pulses: list[tuple[int, ...]] = []
    freal: dict[str, list[tuple[float, float, float]]] = {"f32": [], "f64": []}
    for wl in workloads:
        insns: list[int] = []
        cycles: list[int] = []
        emu.reset_counts()
        emu.paint_stack()
        for k, i in enumerate(inputs):
            if wl == "step":
                emu.write("bench_in", packed[k])
                _, n, c = emu.call("ht_step", ctl, inp, out)
                outputs.append(struct.unpack(OUTPUT_FMT, emu.read("bench_out", 40)))
            elif wl == "step_os":
                emu.write("bench_in", packed[k])
                _, n, c = emu.call("bench_step_output", inp)
                pulses.append(struct.unpack("<5H", emu.read("bench_pulses", 10)))
            elif wl == "q14":
                emu.write("bench_in", packed[k])
                _, n, c = emu.call("law_step_q14", emu.addr("bench_q14_ctl"), inp,
                                   emu.addr("bench_q14_out"))
                q14_outputs.append(struct.unpack(Q14_OUTPUT_FMT, emu.read("bench_q14_out", 12)))
            elif wl == "q14_os":
                emu.write("bench_in", packed[k])
                _, n, c = emu.call("bench_step_output_q14", inp)
                q14_pulses.append(struct.unpack("<5H", emu.read("bench_pulses", 10)))
            else:
                r = to_real(i)
                if wl == "f32":
                    emu.write("bench_in_f32", struct.pack(F32_FMT, *r[:9], r[9]))
                    _, n, c = emu.call("law_step_f32", emu.addr("bench_law_params_f32"),
                                       emu.addr("bench_in_f32"), emu.addr("bench_out_f32"))
                    freal["f32"].append(struct.unpack("<3f", emu.read("bench_out_f32", 12)))
                else:
                    emu.write("bench_in_f64", struct.pack(F64_FMT, *r[:9], r[9], 0))
                    _, n, c = emu.call("law_step_f64", emu.addr("bench_law_params_f64"),
                                       emu.addr("bench_in_f64"), emu.addr("bench_out_f64"))
                    freal["f64"].append(struct.unpack("<3d", emu.read("bench_out_f64", 24)))
            insns.append(n)
            cycles.append(c)
        per[wl] = {
            "all": Stats.of(insns).__dict__,
            "real": Stats.of(insns[:n_real]).__dict__,
            "edge_max": max(insns[n_real:]) if len(insns) > n_real else None,
            "cycles": Stats.of(cycles).__dict__,
            "stack": emu.stack_used(),
            "profile": profile_of(emu, dis, len(inputs)),
            "inline": (inline_profile(emu, dis, elf, len(inputs))
                       if wl in ("step", "step_os", "q14") else None),
        }
    res["workloads"] = per
    res["outputs"] = outputs
    res["pulses"] = pulses
    res["q14_outputs"] = q14_outputs
    res["q14_pulses"] = q14_pulses
    res["freal"] = freal

    prims: dict[str, Any] = {}
    scratch_in, scratch_out = emu.addr("bench_vec_in"), emu.addr("bench_vec_out")
    qv = emu.addr("bench_q14_vec")
    for name, args_list in job["prims"].items():
        counts: list[int] = []
        for a in args_list:
            if name in ("q14_mul", "q_mul32", "q_mul32_fit", "q_isqrt32"):
                _, n, _ = emu.call(name, *a)
            elif name in ("q_rsqrt_norm_q28", "q_recip_q30"):  # (x, &exponent)
                _, n, _ = emu.call(name, a[0], scratch_out)
            elif name == "q_unit2_q28":
                _, n, _ = emu.call(name, a[0], a[1], scratch_out, scratch_out + 4)
            elif name == "q_unit3_q28":
                emu.write("bench_vec_in", struct.pack("<3i", *a))
                _, n, _ = emu.call(name, scratch_in, scratch_out)
            else:
                emu.write("bench_q14_vec", struct.pack("<3h", *a))
                _, n, _ = emu.call(name, qv)
            counts.append(n)
        prims[name] = Stats.of(counts).__dict__
    res["prims"] = prims
    res["static_stack"] = static_stack(Path(job["outdir"]), dis)
    res["seconds"] = time.time() - t0
    return res


def profile_of(emu: Emulator, dis: Disasm, steps: int) -> list[dict[str, Any]]:
    """Instructions per symbol per step, and calls per step (entries into the
    symbol's first instruction)."""
    ins: dict[str, int] = {}
    calls: dict[str, int] = {}
    a = dis.addrs
    for key, cnt in emu.block_count.items():
        addr, size = key >> 16, key & 0xFFFF
        i = bisect.bisect_left(a, addr)
        j = bisect.bisect_left(a, addr + size)
        for k in range(i, j):
            s = dis.syms[dis.sym_of[k]]
            ins[s] = ins.get(s, 0) + cnt
        if addr in dis.sym_start:
            s = dis.syms[dis.sym_start[addr]]
            calls[s] = calls.get(s, 0) + cnt
    rows = []
    for s, v in sorted(ins.items(), key=lambda kv: -kv[1]):
        c = calls.get(s, 0)
        rows.append({"fn": s, "insns_per_step": v / steps, "calls_per_step": c / steps,
                     "insns_per_call": (v / c) if c else None})
    return rows


def inline_profile(emu: Emulator, dis: Disasm, elf: Path, steps: int) -> dict[str, Any]:
    """The same counts attributed through the DWARF line and inline tables
    (addr2line -i): to the innermost source function, inlined or not, and to
    source lines. This names the hot spots inside a step that inlines its
    primitives."""
    per_addr: dict[int, int] = {}
    a = dis.addrs
    for key, cnt in emu.block_count.items():
        addr, size = key >> 16, key & 0xFFFF
        for k in range(bisect.bisect_left(a, addr), bisect.bisect_left(a, addr + size)):
            per_addr[a[k]] = per_addr.get(a[k], 0) + cnt
    if not per_addr:
        return {"functions": [], "lines": []}
    addrs = sorted(per_addr)
    p = run(["arm-none-eabi-addr2line", "-e", str(elf), "-f", "-i", "-a",
             *[f"{x:#x}" for x in addrs]])
    fn_of: dict[int, str] = {}
    line_of: dict[int, str] = {}
    cur: Optional[int] = None
    expect_fn = False
    for line in p.stdout.splitlines():
        if line.startswith("0x"):
            cur = int(line, 16)
            expect_fn = True
            continue
        if cur is None:
            continue
        if expect_fn:
            if cur not in fn_of:
                fn_of[cur] = line.strip()
            expect_fn = False
        else:
            if cur not in line_of:
                path = line.strip().split(" ")[0]
                try:
                    path = str(Path(path.rsplit(":", 1)[0]).resolve().relative_to(ROOT)) + \
                        ":" + path.rsplit(":", 1)[1]
                except (ValueError, IndexError):
                    path = Path(path).name
                line_of[cur] = path
            expect_fn = True
    fns: dict[str, int] = {}
    lines: dict[str, int] = {}
    mix: dict[str, int] = {}
    for x, cnt in per_addr.items():
        mn = dis.mnems[bisect.bisect_left(a, x)].lower().split(".")[0]
        mix[mn] = mix.get(mn, 0) + cnt
        sym = dis.syms[dis.sym_of[bisect.bisect_left(a, x)]]
        f = fn_of.get(x, "??")
        name = f if f == sym or f == "??" else f"{f} (in {sym})"
        fns[name] = fns.get(name, 0) + cnt
        ln = line_of.get(x, "??")
        lines[ln] = lines.get(ln, 0) + cnt
    total = sum(per_addr.values())

    def rows(d: dict[str, int]) -> list[dict[str, Any]]:
        return [{"name": k, "insns_per_step": v / steps, "share": v / total}
                for k, v in sorted(d.items(), key=lambda kv: -kv[1])]

    return {"functions": rows(fns), "lines": rows(lines), "mix": rows(mix)}


def static_stack(outdir: Path, dis: Disasm) -> dict[str, Any]:
    """Worst stack depth from -fstack-usage frames along the static call graph."""
    frames: dict[str, int] = {}
    for su in outdir.rglob("*.su"):
        for line in su.read_text().splitlines():
            parts = line.split("\t")
            if len(parts) >= 2:
                fn = parts[0].rsplit(":", 1)[-1]
                frames[fn] = max(frames.get(fn, 0), int(parts[1]))
    unknown: set[str] = set()

    def depth(fn: str, seen: tuple[str, ...]) -> int:
        if fn in seen:
            return 0
        own = frames.get(fn)
        if own is None:
            unknown.add(fn)
            own = 0
        sub = [depth(c, seen + (fn,)) for c in dis.calls.get(fn, ())]
        return own + (max(sub) if sub else 0)

    out: dict[str, Any] = {}
    for root in ("ht_step", "bench_step_output", "law_step_f32", "law_step_f64", "law_step_q14",
                 "bench_step_output_q14"):
        if root in dis.calls:
            unknown.clear()
            out[root] = {"bytes": depth(root, ()), "no_su": sorted(unknown)}
    return out


# --------------------------------------------------------------------------
# Footprint
# --------------------------------------------------------------------------

def footprint(lib: LibBuild) -> dict[str, Any]:
    def sizes(objs: list[Path]) -> tuple[int, int, int]:
        if not objs:
            return 0, 0, 0
        p = run(["arm-none-eabi-size", "-t", *[str(o) for o in objs]])
        tot = p.stdout.strip().splitlines()[-1].split()
        return int(tot[0]), int(tot[1]), int(tot[2])

    t, d, b = sizes(lib.objects)
    ct, cd, cb = sizes(lib.core_objects)
    return {"text": t, "data": d, "bss": b, "flash": t + d, "ram": d + b,
            "core_flash": ct + cd, "core_ram": cd + cb,
            "files": sorted(o.name for o in lib.objects)}


# --------------------------------------------------------------------------
# Host figures
# --------------------------------------------------------------------------

def build_host(outroot: Path) -> tuple[Path, LibBuild]:
    outdir = outroot / "host"
    if outdir.exists():
        shutil.rmtree(outdir)
    lib = build_library("gcc", ["-O2", "-g"], outdir / "lib")
    objs = []
    for name in ("bench_common.c", "law_f32.c", "law_f64.c", "law_q14.c", "host_bench.c"):
        obj = outdir / (Path(name).stem + ".o")
        run(["gcc", *STRICT, *BENCH_DEFS, "-O2", "-g", f"-DBENCH_HAVE_OS={1 if lib.have_os else 0}",
             "-I", str(ROOT / "include"), "-I", str(CDIR), "-c", str(CDIR / name), "-o", str(obj)])
        objs.append(obj)
    exe = outdir / "host_bench"
    run(["gcc", "-O2", *[str(o) for o in objs], *[str(o) for o in lib.objects], "-lm", "-o",
         str(exe)])
    return exe, lib


def host_figures(exe: Path, inputs_bin: Path, n: int, quick: bool, have_os: bool,
                 outdir: Path) -> dict[str, Any]:
    res: dict[str, Any] = {}
    runs = 3 if quick else 9
    target_steps = 200_000 if quick else 2_000_000
    repeats = max(1, target_steps // n)
    wls = ["step", "step_os"] if have_os else ["step"]
    for wl in wls:
        p = run([str(exe), str(inputs_bin), "time", wl, str(repeats), str(runs)])
        ns = [float(x) for x in p.stdout.split()]
        med = statistics.median(ns)
        res[wl] = {"ns_median": med, "ns_min": min(ns), "ns_max": max(ns),
                   "steps_per_s": 1e9 / med, "runs": runs, "steps_per_run": repeats * n}
        if shutil.which("valgrind"):
            cg = outdir / f"callgrind.{wl}.out"
            toggle = "run_step" if wl == "step" else "bench_step_output"
            run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={cg}",
                 f"--toggle-collect={toggle}", str(exe), str(inputs_bin), "once", wl])
            total = None
            for line in cg.read_text().splitlines():
                if line.startswith("totals:") or line.startswith("summary:"):
                    total = int(line.split()[1])
            if total is None:
                raise BenchError(f"no totals in {cg}")
            res[wl]["callgrind_ir_per_step"] = total / n
        else:
            res[wl]["callgrind_ir_per_step"] = None
    return res


def host_dump(exe: Path, inputs_bin: Path) -> list[list[str]]:
    p = run([str(exe), str(inputs_bin), "dump"])
    return [line.split() for line in p.stdout.splitlines()]


# --------------------------------------------------------------------------
# Checks against the host build
# --------------------------------------------------------------------------

def check_results(res: dict[str, Any], ref: list[list[str]], n_real: int) -> list[str]:
    """Every core must give the host's bits; the float laws must agree with
    the fixed law on the realistic steps. Returns problems (breakage)."""
    probs: list[str] = []
    tag = f"{res['core']} -{res['opt']}"
    # (emulated results, host reference columns, what they are)
    bit_checks = ((res["outputs"], REF_HT, "ht_step output"),
                  (res["pulses"], REF_PULSES, "pulses"),
                  (res["q14_outputs"], REF_Q14, "law_step_q14 output"),
                  (res["q14_pulses"], REF_Q14_PULSES, "16-bit law pulses"))
    for got_list, cols, what in bit_checks:
        for k, got in enumerate(got_list):
            want = [int(x) for x in ref[k][cols]]
            if list(got) != want:
                probs.append(f"{tag}: {what} of input {k} differs from the host build: "
                             f"{list(got)} != {want}")
                break
    for wl in ("f32", "f64"):
        vals = res["freal"][wl]
        if not vals:
            continue
        bad = 0
        for k in range(min(n_real, len(vals))):
            fixed = [int(ref[k][c]) / 16384.0 for c in (14, 15, 16)]
            if max(abs(a - b) for a, b in zip(vals[k], fixed)) > 0.01:
                bad += 1
        res.setdefault("float_agree", {})[wl] = bad
        if bad > max(1, n_real // 100) and not BENCH_DEFS:
            probs.append(f"{tag}: the {wl} law differs from the fixed law by > 0.01 on "
                         f"{bad} of {n_real} realistic steps")
    return probs


def accuracy(ref: list[list[str]], n_real: int) -> dict[str, Any]:
    """Worst |surface - double law surface| in Q14 LSB over the realistic
    steps (the host build; the emulator runs give the same bits), for the
    library and the 16-bit law, on the bench set and on the c172p set."""
    c0 = REF_C172P[0]
    cols = {  # (fixed-law columns, double-law columns), aileron, elevator, rudder
        "bench": {"step": ((14, 15, 16), REF_F64),
                  "q14": ((REF_Q14.start, REF_Q14.start + 1, REF_Q14.start + 2), REF_F64)},
        "c172p": {"step": ((c0, c0 + 1, c0 + 2), (c0 + 6, c0 + 7, c0 + 8)),
                  "q14": ((c0 + 3, c0 + 4, c0 + 5), (c0 + 6, c0 + 7, c0 + 8))},
    }
    out: dict[str, Any] = {}
    for pset, laws in cols.items():
        out[pset] = {}
        for law, (fc, dc) in laws.items():
            per = [0.0, 0.0, 0.0]
            over4 = over8 = over_cent = 0
            for k in range(n_real):
                row = ref[k]
                errs = [abs(int(row[f]) - float(row[d]) * 16384.0) for f, d in zip(fc, dc)]
                for i in range(3):
                    per[i] = max(per[i], errs[i])
                over4 += max(errs) > 4.0
                over8 += max(errs) > 8.0
                over_cent += max(errs) > 0.01 * 16384.0
            out[pset][law] = {"worst": max(per), "per_surface": per, "steps_over_4": over4,
                              "steps_over_8": over8, "steps_over_0.01": over_cent,
                              "steps": n_real}
    return out


# --------------------------------------------------------------------------
# Tables
# --------------------------------------------------------------------------

def workload_cell(w: dict[str, Any], name: str) -> str:
    """min / **median** / max instructions of one workload, or n/a."""
    if name not in w:
        return "n/a"
    st = w[name]["all"]
    return f"{fmt(st['mn'])} / **{fmt(st['med'])}** / {fmt(st['mx'])}"


def fmt(v: Optional[float], nd: int = 0) -> str:
    if v is None:
        return "-"
    if nd == 0:
        return f"{v:,.0f}".replace(",", " ")
    return f"{v:,.{nd}f}".replace(",", " ")


def floor_table(results: list[dict[str, Any]], acc: dict[str, Any], n_real: int) -> list[str]:
    """The 16-bit law (bench/c/law_q14.c) next to the library: instructions
    and the worst surface error against the double law."""
    L: list[str] = []
    L.append("### The floor: a 16-bit law (int16 values, int32 intermediates)")
    L.append("")
    L.append("`bench/c/law_q14.c`: the same law with Q14 int16 values, Q11 rates, Q12 gains, "
             "int32 intermediates and no 64-bit product; one division (v_ref / S), one "
             "table-and-Newton reciprocal square root (up to three calls). Instructions per "
             "step (min / **median** / max over all inputs):")
    L.append("")
    L.append("| core | opt | ht_step | 16-bit law | ht_step / 16-bit | ht_step + output stage "
             "| 16-bit law + output stage |")
    L.append("| --- | --- | --- | --- | --- | --- | --- |")
    for r in results:
        w = r["workloads"]

        def cell(name: str) -> str:
            return workload_cell(w, name)

        ratio = "-"
        if "step" in w and "q14" in w:
            ratio = f"{w['step']['all']['med'] / w['q14']['all']['med']:.2f}"
        L.append(f"| {r['core']} | -{r['opt']} | {cell('step')} | {cell('q14')} | {ratio} | "
                 f"{cell('step_os')} | {cell('q14_os')} |")
    L.append("")
    by = {(r["core"], r["opt"]): r["workloads"] for r in results}

    def tgt(core: str, wl: str, limit: float) -> str:
        w = by.get((core, "O2"))
        if not w or wl not in w:
            return "not measured"
        v = w[wl]["all"]["med"]
        return f"{fmt(v)} ({'met' if v <= limit else 'missed'})"

    def soft(wl: str) -> str:
        w = by.get(("M0", "O2"))
        if not w or "f32" not in w or wl not in w:
            return "not measured"
        rr = w["f32"]["all"]["med"] / w[wl]["all"]["med"]
        return f"{rr:.2f} ({'met' if rr >= 8 else 'missed'})"

    L.append("| target of issue 6 (medians, -O2) | ht_step | 16-bit law |")
    L.append("| --- | --- | --- |")
    L.append(f"| M4 step + output stage <= 600 | {tgt('M4', 'step_os', 600)} | "
             f"{tgt('M4', 'q14_os', 600)} |")
    L.append(f"| M0 step + output stage <= 1 500 | {tgt('M0', 'step_os', 1500)} | "
             f"{tgt('M0', 'q14_os', 1500)} |")
    L.append(f"| M0 soft float / (step + output) >= 8 | {soft('step_os')} | {soft('q14_os')} |")
    L.append("")
    if acc:
        def acell(a: dict[str, Any]) -> str:
            ps = " / ".join(f"{x:.2f}" for x in a["per_surface"])
            return (f"**{a['worst']:.2f}** ({ps}); {a['steps_over_4']} > 4 LSB, "
                    f"{a['steps_over_8']} > 8 LSB")

        L.append(f"Worst \|surface - double law surface\| in Q14 LSB over the {n_real} "
                 "realistic steps (aileron / elevator / rudder; steps with a surface off by more "
                 "than 4 and 8 LSB). Bench set: the parameters above (effective gains up to "
                 "2.5 x 15/5 = 7.5). c172p scheduled: kp aileron/elevator/rudder 3/6/0.3, kff "
                 "0/1/0.5, kd 0.5/1/1, v_ref 50 m/s, v_min 10 m/s, schedule on, max_tilt 4 "
                 "(effective gains up to 6 x 50/10 = 30). Library contract <= 2 LSB; issue 6 "
                 "target <= 8 LSB.")
        L.append("")
        L.append("| law | bench set | c172p scheduled |")
        L.append("| --- | --- | --- |")
        L.append(f"| ht_step (Q28 internal, exact 32x32->64 products) | "
                 f"{acell(acc['bench']['step'])} | {acell(acc['c172p']['step'])} |")
        L.append(f"| 16-bit law (int16 values, int32 intermediates) | "
                 f"{acell(acc['bench']['q14'])} | {acell(acc['c172p']['q14'])} |")
        L.append("")
    return L


def tables(results: list[dict[str, Any]], host: dict[str, Any], meta: dict[str, Any],
           fps: dict[str, dict[str, Any]], acc: Optional[dict[str, Any]] = None) -> str:
    L: list[str] = []
    order = {c: i for i, c in enumerate(CORES)}
    results = sorted(results, key=lambda r: (order[r["core"]], r["opt"] != "O2", r["opt"]))
    L.append(f"Measured {meta['date']} at commit `{meta['commit']}` ({meta['dirty']}), "
             f"{meta['arm_cc']}, host {meta['host_cc']}; {meta['n_real']} realistic steps "
             f"(seed {meta['seed']}) + {meta['n_edge']} edge cases"
             f"{' (--quick)' if meta['quick'] else ''}.")
    L.append("")
    L.append("### Instructions per control step (Unicorn; min / median / max over all inputs)")
    L.append("")
    L.append("| core | opt | ht_step | ht_step + output stage | float law | double law "
             "| float / step | float / (step + output) | double / step |")
    L.append("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in results:
        w = r["workloads"]

        def cell(name: str) -> str:
            return workload_cell(w, name)

        def ratio(a: str, b: str) -> str:
            if a not in w or b not in w:
                return "-"
            return f"{w[a]['all']['med'] / w[b]['all']['med']:.2f}"

        L.append(f"| {r['core']} | -{r['opt']} | {cell('step')} | {cell('step_os')} | "
                 f"{cell('f32')} | {cell('f64')} | {ratio('f32', 'step')} | "
                 f"{ratio('f32', 'step_os')} | {ratio('f64', 'step')} |")
    L.append("")
    L.append("float = the single-precision law (FPU on the M4F, software elsewhere); "
             "ratios are of medians, > 1 means the fixed-point library executes fewer "
             "instructions.")
    L.append("")
    L.append("### Targets of issue 6 (medians, -O2; reported, never enforced)")
    L.append("")
    L.append("| target | measured | |")
    L.append("| --- | --- | --- |")
    by = {(r["core"], r["opt"]): r["workloads"] for r in results}

    def target(core: str, wl: str, limit: float, label: str) -> None:
        w = by.get((core, "O2"))
        if not w or wl not in w:
            L.append(f"| {label} | not measured | |")
            return
        v = w[wl]["all"]["med"]
        L.append(f"| {label} | {fmt(v)} | {'met' if v <= limit else 'missed'} |")

    target("M4", "step_os", 600, "M4 step + output stage <= 600")
    target("M0", "step_os", 1500, "M0 step + output stage <= 1 500")
    w0 = by.get(("M0", "O2"))
    if w0 and "f32" in w0 and "step_os" in w0:
        rr = w0["f32"]["all"]["med"] / w0["step_os"]["all"]["med"]
        L.append(f"| M0 soft float / (step + output) >= 8 | {rr:.2f} | "
                 f"{'met' if rr >= 8 else 'missed'} |")
    L.append("| anchors (issue 6): MatrixPilot integer step 980 (M4) / 4 608 (M0); float law "
             "223 (M4F), 5 582 (M4 soft), 12 401 (M0) | | |")
    L.append("")
    L += floor_table(results, acc or {}, meta["n_real"])
    m4f = [r for r in results if r["core"] == "M4F"]
    if m4f:
        L.append("### Cortex-M4F cycles (cycle model of bench/README.md; median per step)")
        L.append("")
        L.append("| opt | ht_step | ht_step + output stage | float law (FPU) | double law "
                 "| float / fixed, instructions | float / fixed, cycles |")
        L.append("| --- | --- | --- | --- | --- | --- | --- |")
        for r in m4f:
            w = r["workloads"]

            def cyc(name: str) -> str:
                return fmt(w[name]["cycles"]["med"]) if name in w else "n/a"

            ri = rc = "-"
            if "f32" in w and "step" in w:
                ri = f"{w['f32']['all']['med'] / w['step']['all']['med']:.2f}"
                rc = f"{w['f32']['cycles']['med'] / w['step']['cycles']['med']:.2f}"
            L.append(f"| -{r['opt']} | {cyc('step')} | {cyc('step_os')} | {cyc('f32')} | "
                     f"{cyc('f64')} | {ri} | {rc} |")
        L.append("")
    L.append("### Math primitives (instructions per call: min / median / max)")
    L.append("")
    prim_names = list(PRIMITIVES)
    L.append("| core | opt | " + " | ".join(f"`{p}`" for p in prim_names) + " |")
    L.append("| --- | --- | " + " | ".join("---" for _ in prim_names) + " |")
    for r in results:
        cells = []
        for p in prim_names:
            s = r["prims"].get(p)
            cells.append(f"{fmt(s['mn'])} / {fmt(s['med'])} / {fmt(s['mx'])}" if s else "n/a")
        L.append(f"| {r['core']} | -{r['opt']} | " + " | ".join(cells) + " |")
    L.append("")
    L.append("### Footprint of the library (bytes) and stack of the step")
    L.append("")
    L.append("| core | opt | flash (text+data), all src/ | static RAM (data+bss) | flash, core "
             "only | stack ht_step: static / measured | stack step + output: static / measured |")
    L.append("| --- | --- | --- | --- | --- | --- | --- |")
    for r in results:
        fp = fps[f"{r['core']}-{r['opt']}"]
        ss = r["static_stack"]
        w = r["workloads"]

        def st(root: str, wl: str) -> str:
            if root not in ss or wl not in w:
                return "n/a"
            extra = "+libgcc" if any(not f.startswith("bench") for f in ss[root]["no_su"]) else ""
            return f"{ss[root]['bytes']}{extra} / {w[wl]['stack']}"

        L.append(f"| {r['core']} | -{r['opt']} | {fmt(fp['flash'])} | {fmt(fp['ram'])} | "
                 f"{fmt(fp['core_flash'])} | {st('ht_step', 'step')} | "
                 f"{st('bench_step_output', 'step_os')} |")
    L.append("")
    L.append("### Host (x86-64, gcc -O2)")
    L.append("")
    L.append("| workload | ns / step (median of runs) | min - max | steps / s "
             "| callgrind instructions / step |")
    L.append("| --- | --- | --- | --- | --- |")
    for wl, h in host.items():
        L.append(f"| {WL_NAMES[wl]} | {h['ns_median']:.1f} | {h['ns_min']:.1f} - "
                 f"{h['ns_max']:.1f} | {fmt(h['steps_per_s'])} | "
                 f"{fmt(h['callgrind_ir_per_step'], 1)} |")
    L.append("")
    return "\n".join(L)


def profile_tables(results: list[dict[str, Any]], top: int, opt: str) -> str:
    L: list[str] = []
    for wl in ("step", "step_os"):
        for r in results:
            if r["opt"] != opt or wl not in r["workloads"]:
                continue
            prof = r["workloads"][wl]["profile"]
            L.append(f"#### {r['core']} -{r['opt']}: {WL_NAMES[wl]}, top {top} "
                     f"(median step {fmt(r['workloads'][wl]['all']['med'])} instructions)")
            L.append("")
            L.append("| function | instructions / step | calls / step | instructions / call |")
            L.append("| --- | --- | --- | --- |")
            for row in prof[:top]:
                L.append(f"| `{row['fn']}` | {row['insns_per_step']:.1f} | "
                         f"{row['calls_per_step']:.2f} | {fmt(row['insns_per_call'], 1)} |")
            L.append("")
            inl = r["workloads"][wl].get("inline")
            if inl and inl["functions"]:
                L.append("By source function, inlined code attributed to the inlined function "
                         "(DWARF, addr2line -i):")
                L.append("")
                L.append("| source function | instructions / step | share |")
                L.append("| --- | --- | --- |")
                for row in inl["functions"][:top]:
                    L.append(f"| `{row['name']}` | {row['insns_per_step']:.1f} | "
                             f"{100 * row['share']:.1f} % |")
                L.append("")
                L.append("| hottest source lines | instructions / step | share |")
                L.append("| --- | --- | --- |")
                for row in inl["lines"][:top]:
                    L.append(f"| `{row['name']}` | {row['insns_per_step']:.1f} | "
                             f"{100 * row['share']:.1f} % |")
                L.append("")
                L.append("Instruction mix per step: " + ", ".join(
                    f"{row['name']} {row['insns_per_step']:.0f}" for row in inl["mix"][:16]))
                L.append("")
    L.append("#### Where the float, double and 16-bit laws spend (instructions / step, top 6)")
    L.append("")
    for wl in ("f32", "f64", "q14"):
        for r in results:
            if r["opt"] != opt or wl not in r["workloads"]:
                continue
            prof = r["workloads"][wl]["profile"]
            L.append(f"- {r['core']} {WL_NAMES[wl]}: " + ", ".join(
                f"`{row['fn']}` {row['insns_per_step']:.0f} ({row['calls_per_step']:.1f} calls)"
                for row in prof[:6]))
    L.append("")
    return "\n".join(L)


# --------------------------------------------------------------------------
# Main
# --------------------------------------------------------------------------

README = BENCH / "README.md"
BEGIN, END = "<!-- bench:results:begin -->", "<!-- bench:results:end -->"


def update_readme(text: str, prof: str, notes: list[str], agree: str) -> None:
    doc = README.read_text()
    if BEGIN not in doc or END not in doc:
        raise BenchError(f"{README} has no {BEGIN} ... {END} markers")
    body = [BEGIN, "", text, "### Per-function profile (emulator, -O2)", "", prof]
    if notes:
        body += ["### Notes", ""] + [f"- {n}" for n in notes] + [""]
    body += [agree, "", END]
    head, rest = doc.split(BEGIN, 1)
    tail = rest.split(END, 1)[1]
    README.write_text(head + "\n".join(body) + tail)
    log(f"wrote the tables into {README}")


def git(*args: str) -> str:
    p = run(["git", "-C", str(ROOT), *args], check=False)
    return p.stdout.strip() if p.returncode == 0 else "unknown"


def main(argv: Optional[list[str]] = None) -> int:
    ap = argparse.ArgumentParser(
        description="Instruction-count benchmark of the helical-turn library on Cortex-M0/M3/M4 "
                    "(Unicorn), the same law in float and double, host timing and callgrind, "
                    "footprint; prints Markdown tables.")
    ap.add_argument("--quick", action="store_true",
                    help="tiny run for CI: 200 steps, -O2 only, fewer primitive calls")
    ap.add_argument("--steps", type=int, default=None,
                    help="realistic steps (default 10000, --quick 200)")
    ap.add_argument("--seed", type=int, default=6, help="input seed (default 6)")
    ap.add_argument("--opts", default=None, help="comma-separated opt levels (default O2,Os)")
    ap.add_argument("--cores", default=",".join(CORES),
                    help=f"comma-separated cores (default {','.join(CORES)})")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                    help="emulator processes (default: CPU count)")
    ap.add_argument("--out", type=Path, default=BENCH / "out", help="output dir (bench/out)")
    ap.add_argument("--top", type=int, default=10, help="profile rows per core (default 10)")
    ap.add_argument("--options", action="store_true",
                    help="the law's options on (roll_in, kp_sideslip, vertical_fade) with their "
                         "inputs drawn: what they cost (the float laws' agreement is not checked)")
    ap.add_argument("--update-readme", action="store_true",
                    help="also write the tables into bench/README.md (between its "
                         "bench:results markers)")
    args = ap.parse_args(argv)
    if args.options and args.update_readme:
        ap.error("--options measures the options; the README's figures are the seed's")

    quick = args.quick
    n_real = args.steps if args.steps is not None else (200 if quick else 10_000)
    opts = (args.opts or ("O2" if quick else "O2,Os")).split(",")
    cores = [c.strip() for c in args.cores.split(",") if c.strip()]
    for c in cores:
        if c not in CORES:
            ap.error(f"unknown core {c!r} (known: {', '.join(CORES)})")
    for o in opts:
        if o not in ("O0", "O1", "O2", "O3", "Os", "Og", "Oz"):
            ap.error(f"unknown opt level {o!r}")
    if n_real < 1:
        ap.error("--steps must be positive")
    for tool in (ARM_CC, "arm-none-eabi-objdump", "arm-none-eabi-size", "gcc"):
        if shutil.which(tool) is None:
            print(f"bench: {tool} not found on PATH", file=sys.stderr)
            return 2
    try:
        import unicorn  # noqa: F401
        import elftools  # noqa: F401
    except ImportError as ex:
        print(f"bench: {ex}; run through scripts/bench.sh (it makes bench/.venv)", file=sys.stderr)
        return 2

    t_start = time.time()
    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    problems: list[str] = []
    notes: list[str] = []
    try:
        if args.options:
            BENCH_DEFS.append("-DBENCH_OPTIONS=1")
        inputs = (with_option_inputs(realistic_inputs(n_real, args.seed), args.seed) +
                  with_option_inputs(edge_inputs(), args.seed))
        if args.options:
            inputs += [(0, -16384, 0, 1024, 0, 1500, 0, 0, 0, 0, 32767, 32767),
                       (0, 0, 16384, 0, 0, 1500, 0, 0, 0, 0, -32768, -32768)]
        n_edge = len(inputs) - n_real
        inputs_bin = out / "inputs.bin"
        inputs_bin.write_bytes(pack_inputs(inputs))
        prims = primitive_inputs(50 if quick else 1000, args.seed)

        log("host build")
        exe, hlib = build_host(out)
        ref = host_dump(exe, inputs_bin)
        if len(ref) != len(inputs) or any(len(row) != REF_COLS for row in ref):
            raise BenchError("host dump has the wrong number of rows or columns")
        acc = accuracy(ref, n_real)
        # Breakage, like the float laws' check: the 16-bit law must stay
        # within 0.01 of the double law on >= 99 % of the realistic steps.
        for pset, laws in acc.items():
            bad = laws["q14"]["steps_over_0.01"]
            if bad > max(1, n_real // 100):
                problems.append(f"the 16-bit law differs from the double law by > 0.01 on {bad} "
                                f"of {n_real} realistic steps ({pset} set)")
        if hlib.failed:
            notes.append("not built (host): " + "; ".join(f"{k}: {v}" for k, v in hlib.failed.items()))

        log(f"ARM builds: {', '.join(cores)} x {', '.join(opts)}")
        builds: list[ArmBuild] = []
        for c in cores:
            for o in opts:
                builds.append(build_arm(CORES[c], o, out))
        fps = {f"{b.core}-{b.opt}": footprint(b.lib) for b in builds}
        for b in builds:
            if b.lib.failed:
                notes.append(f"{b.core} -{b.opt}: not built: " +
                             "; ".join(f"{k}: {v}" for k, v in b.lib.failed.items()))
            if not b.lib.have_os:
                notes.append(f"{b.core} -{b.opt}: the output stage does not build: step + "
                             f"output stage not measured")
            if b.lib.warnings:
                notes.append(f"{b.core} -{b.opt}: the library compiled with "
                             f"{b.lib.warnings} warning(s) (-Wall -Wextra)")

        jobs: list[dict[str, Any]] = [{"core": b.core, "opt": b.opt, "elf": str(b.elf), "outdir": str(b.outdir),
                 "inputs": inputs, "n_real": n_real, "prims": prims,
                 "have_os": b.lib.have_os, "workloads": STEP_WORKLOADS} for b in builds]
        # Longest first (the soft-float M0 runs) so that both workers stay busy.
        weight = {"M0": 4, "M3": 2, "M4": 2, "M4F": 1}
        jobs.sort(key=lambda j: -weight[str(j["core"])])
        log(f"emulating {len(jobs)} configurations x {len(inputs)} inputs on {args.jobs} "
            f"process(es)")
        results: list[dict[str, Any]] = []
        with ProcessPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            for r in pool.map(emulate_config, jobs):
                log(f"  {r['core']} -{r['opt']}: {r['seconds']:.0f} s")
                results.append(r)
        for r in results:
            problems += check_results(r, ref, n_real)
            notes += [n for n in r["notes"] if n not in notes]

        log("host timing and callgrind")
        host = host_figures(exe, inputs_bin, len(inputs), quick, hlib.have_os, out)

        meta = {
            "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "commit": git("rev-parse", "--short", "HEAD"),
            "dirty": "work tree modified" if git("status", "--porcelain", "--", "src",
                                                  "include") else "clean src/ include/",
            "arm_cc": run([ARM_CC, "--version"]).stdout.splitlines()[0],
            "host_cc": run(["gcc", "--version"]).stdout.splitlines()[0],
            "n_real": n_real, "n_edge": n_edge, "seed": args.seed, "quick": quick,
            # bench_dcm.py takes the law's cost from an options-off run only
            "options": bool(args.options),
        }
        text = tables(results, host, meta, fps, acc)
        prof = profile_tables(results, args.top, opts[0])
        (out / "results.json").write_text(json.dumps(
            {"meta": meta, "host": host, "footprint": fps, "accuracy": acc,
             "results": [{k: v for k, v in r.items()
                          if k not in ("outputs", "pulses", "freal", "q14_outputs", "q14_pulses")}
                         for r in results]}, indent=1))
        (out / "table.md").write_text(text + "\n")
        (out / "profile.md").write_text(prof + "\n")
        print("## helical-turn benchmark\n")
        print(text)
        print("### Per-function profile (emulator)\n")
        print(prof)
        if notes:
            print("### Notes\n")
            for n in notes:
                print(f"- {n}")
            print()
        agree = {f"{r['core']} -{r['opt']}": r.get("float_agree") for r in results}
        agree_text = (f"Float/double law vs fixed (surfaces differing by > 0.01, of {n_real} "
                      f"realistic steps): {agree}")
        print(agree_text + "\n")
        if args.update_readme and not problems:
            update_readme(text, prof, notes, agree_text)
    except BenchError as ex:
        problems.append(str(ex))
    log(f"done in {time.time() - t_start:.0f} s")
    if problems:
        print("### BROKEN\n")
        for p in problems:
            print(f"- {p}")
        print(f"bench: {len(problems)} problem(s)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
