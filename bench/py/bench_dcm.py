"""The estimator's benchmark: instructions per ht_dcm_update and per
ht_dcm_output on Cortex-M0 and M4 (Unicorn, the same emulator, cores and
counting as bench.py, whose functions it reuses), and the CPU load of the
whole firmware: the estimator at the IMU rate plus the law, the output stage
and one ht_dcm_output at the control rate.

    bench/.venv/bin/python bench/py/bench_dcm.py [--samples N] [--opt O2]

(scripts/bench.sh --dcm runs it in the bench's venv.) The law's share is the
last scripts/bench.sh run's (bench/out/results.json, or --law-results; exit 2
without one). Prints a Markdown table and writes bench/out/dcm.json;
--update-doc also writes docs/generated/cpu-load.md, the figures the docs quote. Exits non-zero only on breakage (a build, a
fault, a call that does not return, a setup that fails).
"""
from __future__ import annotations

import argparse
import contextlib
import io
import json
import statistics
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench as B  # noqa: E402  (the main benchmark: builds, disassembly, emulator)

# Instructions per control step of ht_step + output stage (mix + 5 pulses):
# the medians of the last bench.py run (its results.json, options off, the
# same -O level), not a figure typed here (issue 32: a copy went stale).
LAW_RESULTS = B.BENCH / "out" / "results.json"
DOC = B.ROOT / "docs" / "generated" / "cpu-load.md"


def law_os_insns(path: Path, opt: str) -> tuple[dict[str, float], str]:
    """{core: median instructions of ht_step + output stage} and where they come from."""
    if not path.is_file():
        raise B.BenchError(f"{path}: no bench.py results: run scripts/bench.sh (the law's "
                           "cost per control step) first, or give --law-results")
    try:
        doc = json.loads(path.read_text())
        meta = doc["meta"]
        if meta.get("options"):
            raise B.BenchError(f"{path}: a --options run; the load figure takes the law with "
                               "its options off: run scripts/bench.sh")
        got = {r["core"]: float(r["workloads"]["step_os"]["all"]["med"])
               for r in doc["results"] if r["opt"] == opt and r["core"] in ("M0", "M4")}
    except (KeyError, TypeError, ValueError) as e:
        raise B.BenchError(f"{path}: not a bench.py results.json ({e!r})") from None
    if set(got) != {"M0", "M4"}:
        raise B.BenchError(f"{path}: no -{opt} ht_step + output stage figures for M0 and M4")
    run = "quick run" if meta.get("quick") else "full run"
    return got, f"bench.py {run} at {meta.get('commit', '?')}, {meta.get('date', '?')}"
# Clock and cycles per instruction assumed for the load figure (stated in the
# output): the M4 at 168 MHz (STM32F405) ~1 cycle per instruction, the M0 at
# 48 MHz ~1.3 (its 32x32 multiply is 1 cycle on the fast-multiplier option;
# loads, stores and taken branches take 2-3).
CLOCK_HZ = {"M0": 48e6, "M4": 168e6}
CPI = {"M0": 1.3, "M4": 1.0}


# the estimator's sources (src/): the ARM build checks they compiled, the
# host build compiles them
DCM_SOURCES = ("estimator/dcm.c", "estimator/dcm_gps_accel.c", "estimator/dcm_wind.c",
               "estimator/dcm_params.c", "estimator/dcm_trig.c", "math/q14.c", "params/param_rows.c")


def build(core: B.Core, opt: str, outroot: Path) -> Path:
    outdir = outroot / f"dcm-{core.name}-{opt}"
    outdir.mkdir(parents=True, exist_ok=True)
    flags = [*core.flags, f"-{opt}", "-ffunction-sections", "-fdata-sections", "-g"]
    lib = B.build_library(B.ARM_CC, flags, outdir / "lib")
    need = {Path(n).name for n in DCM_SOURCES}
    missing = need & set(lib.failed)
    if missing:
        raise B.BenchError(f"estimator sources do not build: {sorted(missing)}")
    obj = outdir / "dcm_harness.o"
    B.run([B.ARM_CC, *B.STRICT, *flags, "-I", str(B.ROOT / "include"), "-c",
           str(B.CDIR / "dcm_harness.c"), "-o", str(obj)])
    elf = outdir / "dcm.elf"
    B.run([B.ARM_CC, *flags, "-nostartfiles", "-nostdlib", "-T", str(B.CDIR / "bench.ld"),
           "-Wl,--gc-sections", f"-Wl,-Map={outdir / 'dcm.map'}", str(obj),
           *[str(o) for o in lib.objects], "-lc", "-lgcc", "-o", str(elf)])
    return elf


def measure(core: B.Core, elf: Path, samples: int, host: str) -> dict[str, Any]:
    dis = B.disassemble(elf)
    emu = B.Emulator(elf, core, dis)
    r0, _, _ = emu.call("dcm_bench_setup")
    if r0 != 0:
        raise B.BenchError(f"{core.name}: dcm_bench_setup returned {r0}")
    upd: list[int] = []
    out: list[int] = []
    emu.paint_stack()
    for k in range(samples):
        emu.call("dcm_bench_prepare", k)
        _, n, _ = emu.call("dcm_bench_update")
        upd.append(n)
        if k % 5 == 0:
            _, n, _ = emu.call("dcm_bench_output")
            out.append(n)
    # ht_dcm_state_t: r, bias, omega_corr, rate_rad_s (72 bytes), then flags
    flags = int.from_bytes(emu.read("dcm_bench_s", 74)[72:74], "little")
    state = emu.read("dcm_bench_s", len(host) // 2).hex()
    if state != host:
        raise B.BenchError(f"{core.name}: the estimator's state after {samples} samples differs "
                           f"from the host's:\n  {state}\n  {host}")
    return {"update": {"min": min(upd), "median": statistics.median(upd), "max": max(upd)},
            "output": {"min": min(out), "median": statistics.median(out), "max": max(out)},
            "stack_bytes": emu.stack_used(), "final_flags": flags}


def host_state(outroot: Path, samples: int) -> str:
    """The host build's final state after the same flight, as hex."""
    outdir = outroot / "dcm-host"
    outdir.mkdir(parents=True, exist_ok=True)
    lib = [str(B.ROOT / "src" / n) for n in DCM_SOURCES]
    exe = outdir / "dcm_host"
    B.run(["gcc", *B.STRICT, "-O2", "-I", str(B.ROOT / "include"), "-I", str(B.ROOT / "src"),
           str(B.CDIR / "dcm_harness.c"), str(B.CDIR / "dcm_host_main.c"), *lib, "-o", str(exe)])
    return B.run([str(exe), str(samples)]).stdout.strip()


def load(core: str, upd: float, outp: float, law_os: float, imu_hz: int,
         ctl_hz: int) -> dict[str, float]:
    insns_s = upd * imu_hz + (outp + law_os) * ctl_hz
    return {"insns_per_s": insns_s, "percent": 100.0 * insns_s * CPI[core] / CLOCK_HZ[core],
            "estimator_percent": 100.0 * upd * imu_hz * CPI[core] / CLOCK_HZ[core]}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=2000, help="IMU samples flown (default 2000)")
    ap.add_argument("--opt", default="O2", help="optimisation level (default O2)")
    ap.add_argument("--imu-hz", type=int, default=200)
    ap.add_argument("--control-hz", type=int, default=40)
    ap.add_argument("--out", type=Path, default=B.BENCH / "out")
    ap.add_argument("--update-doc", action="store_true",
                    help="also write the tables to docs/generated/cpu-load.md")
    ap.add_argument("--law-results", type=Path, default=LAW_RESULTS,
                    help="bench.py's results.json for the law's cost (default: the last run's)")
    a = ap.parse_args(argv)
    try:
        law, law_src = law_os_insns(a.law_results, a.opt)
    except B.BenchError as ex:
        print(f"bench_dcm: {ex}", file=sys.stderr)
        return 2
    res: dict[str, Any] = {"samples": a.samples, "opt": a.opt, "imu_hz": a.imu_hz,
                           "control_hz": a.control_hz, "law_os_insns": law,
                           "law_os_source": law_src,
                           "clock_hz": CLOCK_HZ, "cpi": CPI, "cores": {}}
    try:
        host = host_state(a.out, a.samples)
        for name in ("M0", "M4"):
            core = B.CORES[name]
            elf = build(core, a.opt, a.out)
            m = measure(core, elf, a.samples, host)
            m["load"] = load(name, m["update"]["median"], m["output"]["median"], law[name],
                             a.imu_hz, a.control_hz)
            m["load_worst"] = load(name, m["update"]["max"], m["output"]["max"], law[name],
                                   a.imu_hz, a.control_hz)
            res["cores"][name] = m
    except B.BenchError as ex:
        print(f"bench_dcm: {ex}", file=sys.stderr)
        return 1
    a.out.mkdir(parents=True, exist_ok=True)
    (a.out / "dcm.json").write_text(json.dumps(res, indent=1))
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        tables(res, a)
    sys.stdout.write(buf.getvalue())
    if a.update_doc:
        DOC.parent.mkdir(parents=True, exist_ok=True)
        DOC.write_text("<!-- generated by scripts/bench.sh --dcm --update-doc: do not edit by "
                       "hand -->\n# Estimator cost and CPU load (generated)\n\nWritten by "
                       f"`scripts/bench.sh --dcm {' '.join(sys.argv[1:])}`.\n\n"
                       + buf.getvalue())
        print(f"bench_dcm: wrote {DOC.relative_to(B.ROOT)}", file=sys.stderr)
    return 0


def tables(res: dict[str, Any], a: argparse.Namespace) -> None:
    """The Markdown tables of one run, on stdout."""
    law, law_src = res["law_os_insns"], res["law_os_source"]
    print(f"Estimator, arm-none-eabi-gcc -{a.opt}, {a.samples} samples of a synthetic flight "
          f"(min / median / max instructions):\n")
    print("| | Cortex-M0 | Cortex-M4 |\n| --- | --- | --- |")
    c = res["cores"]
    for key, label in (("update", "`ht_dcm_update`"), ("output", "`ht_dcm_output`")):
        cells = [f"{c[n][key]['min']} / {c[n][key]['median']:.0f} / {c[n][key]['max']}"
                 for n in ("M0", "M4")]
        print(f"| {label} | {cells[0]} | {cells[1]} |")
    print(f"| state after the flight equals the host's (x86-64, int64 products) | bit for bit | "
          f"bit for bit |")
    print(f"| stack of the deepest call, bytes | {c['M0']['stack_bytes']} | "
          f"{c['M4']['stack_bytes']} |")
    print(f"\nCPU load: estimator at {a.imu_hz} Hz + (`ht_step` + output stage "
          f"[{law['M0']:.0f} / {law['M4']:.0f} instructions, median, {law_src}] + "
          f"`ht_dcm_output`) at {a.control_hz} Hz; assumed 1.3 cycles per instruction on a "
          f"48 MHz M0, 1.0 on a 168 MHz M4:\n")
    print("| | Cortex-M0 @ 48 MHz | Cortex-M4 @ 168 MHz |\n| --- | --- | --- |")
    for key, label in (("load", "median"), ("load_worst", "worst sample")):
        print(f"| {label}: whole firmware | {c['M0'][key]['percent']:.2f} % | "
              f"{c['M4'][key]['percent']:.3f} % |")
        print(f"| {label}: estimator alone | {c['M0'][key]['estimator_percent']:.2f} % | "
              f"{c['M4'][key]['estimator_percent']:.3f} % |")


if __name__ == "__main__":
    sys.exit(main())
