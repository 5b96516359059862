#!/usr/bin/env python3
"""ff-cyclemodel: exact instruction counts and modelled MK66 cycles of every
traced call of ff-m4trace.elf (HapticPipeline::tick and ::set_condition).

Runs the harness under qemu mps2-an386 with one instruction per translation
block (-singlestep -d exec,nochain, -icount shift=0: deterministic), streams
the execution log through a pipe, and costs each call from its entry to its
return with tools/cyclemodel/model.py under the best and the worst
assumptions. Writes calls.csv (one row per call) and cycles.csv (per scene:
percentiles of the stroke's ticks, the worst tick, the events, preparation);
with --breakdown also breakdown.csv: the worst case of each scene's event
ticks and of its worst stroke tick, split by function.

Exit codes: 0 ok, 1 the harness failed or a check failed, 2 bad usage/input.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile
import threading
from fractions import Fraction
from pathlib import Path

sys.path[:0] = [str(Path(__file__).resolve().parent), str(Path(__file__).resolve().parent.parent / "common")]

import ff_files  # noqa: E402
from disassembly import disassemble, symbols  # noqa: E402
from model import CORE_HZ, ISR_BEST, ISR_WORST, TICK_BUDGET_CYCLES, CodeMap  # noqa: E402
from exec_log import executed_addresses, measure_calls  # noqa: E402

TICK_SYMBOL = "_ZN2ff14HapticPipeline4tickEm"
PREPARE_SYMBOL = "_ZN2ff14HapticPipeline13set_conditionERKNS_9ConditionE"
EVENTS = ("swap", "mailbox-full", "mailbox-drain", "lift-off", "no-finger", "touch-down", "after-touch-down")


class UsageError(Exception):
    pass


def percentile(values, p):
    """Nearest rank: the smallest value with at least p % of values at or below it."""
    ordered = sorted(values)
    # p as written in decimal, not its binary float: 99.9 / 100 * 1000 is 999.0000000000001 in floats.
    rank = max(1, math.ceil(Fraction(str(p)) * len(ordered) / 100))
    return ordered[rank - 1]


def run_qemu(elf, mode, log_path, semihosting_path, timeout):
    args = "arg=ff-m4trace," + ",".join(f"arg={word}" for word in mode.split())
    command = ["qemu-system-arm", "-M", "mps2-an386", "-nographic", "-monitor", "none", "-serial", "none",
               "-chardev", f"file,id=semihosting,path={semihosting_path}",
               "-semihosting-config", f"enable=on,target=native,chardev=semihosting,{args}",
               "-icount", "shift=0", "-singlestep", "-d", "exec,nochain", "-D", log_path, "-kernel", elf]
    return subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)


def trace_calls(elf, mode, timeout=1800, by_function=False):
    """(calls, harness lines): the costed calls and the harness's own output."""
    instructions = disassemble(elf)
    table = symbols(elf)
    for name in (TICK_SYMBOL, PREPARE_SYMBOL):
        if name not in table:
            raise UsageError(f"{elf} has no symbol {name}: not an ff-m4trace build")
    entries = {table[TICK_SYMBOL][0]: "tick", table[PREPARE_SYMBOL][0]: "prepare"}
    ram = (table.get("__fastrun_start", (0, 0))[0], table.get("__fastrun_end", (0, 0))[0])
    code_map = CodeMap(*ram)
    with tempfile.TemporaryDirectory() as tmp:
        fifo = os.path.join(tmp, "exec.fifo")
        os.mkfifo(fifo)
        output = os.path.join(tmp, "semihosting.txt")
        qemu = run_qemu(elf, mode, fifo, output, timeout)
        timer = threading.Timer(timeout, qemu.kill)
        timer.start()
        try:
            with open(fifo, "r", buffering=1 << 20) as log:
                calls = list(measure_calls(executed_addresses(log), instructions, entries, code_map,
                                           by_function))
            qemu.wait()
        finally:
            timer.cancel()
        harness = Path(output).read_text() if os.path.exists(output) else ""
    if qemu.returncode != 0 or "done,0" not in harness.splitlines():
        raise RuntimeError(f"ff-m4trace failed (qemu exit {qemu.returncode}):\n{harness[-2000:]}")
    return calls, harness, code_map


def label_calls(calls, harness):
    """Pairs each costed call with the harness's "call,kind,scene,index" line."""
    notes = [line.split(",") for line in harness.splitlines() if line.startswith("call,")]
    if len(notes) != len(calls):
        raise RuntimeError(f"{len(calls)} calls traced but the harness announced {len(notes)}")
    rows = []
    for note, call in zip(notes, calls):
        _, kind, scene, index = note
        expected = "prepare" if kind == "prepare" else "tick"
        if call.function != expected:
            raise RuntimeError(f"trace order differs from the harness's: {call.function} where {kind} was announced")
        rows.append({"kind": kind, "scene": scene, "index": int(index), "function": call.function,
                     "instructions": call.instructions, "cycles_best": call.best, "cycles_worst": call.worst,
                     "flash_lines": call.flash_lines, "functions": call.functions})
    return rows


def demangle(names):
    """Readable C++ names (c++filt), in the same order."""
    try:
        result = subprocess.run(["arm-none-eabi-c++filt"], input="\n".join(names), capture_output=True,
                                text=True, check=True)
        readable = result.stdout.splitlines()
        return readable if len(readable) == len(names) else list(names)
    except (OSError, subprocess.CalledProcessError):
        return list(names)


def breakdown(rows):
    """Per scene, its event ticks and its worst stroke tick split by function
    (worst assumptions), most expensive function first."""
    picked = []
    for scene in dict.fromkeys(r["scene"] for r in rows if r["kind"] not in ("warm-up", "prepare")):
        mine = [r for r in rows if r["scene"] == scene and r["function"] == "tick"]
        stroke = [r for r in mine if r["kind"] == "stroke"]
        picked += [r for r in mine if r["kind"] not in ("stroke", "after-touch-down")]
        if stroke:
            picked.append(max(stroke, key=lambda r: r["cycles_worst"]))
    names = sorted({f for r in picked for f in (r["functions"] or {})})
    readable = dict(zip(names, demangle(names)))
    out = []
    for r in picked:
        for function, (instructions, cycles, misses) in sorted((r["functions"] or {}).items(),
                                                               key=lambda item: -item[1][1]):
            out.append({"scene": r["scene"], "kind": r["kind"], "index": r["index"],
                        "function": readable[function], "instructions": instructions,
                        "cycles_worst": cycles, "flash_misses_worst": misses,
                        "tick_cycles_worst": r["cycles_worst"]})
    return out


def summarise(rows):
    """Per scene: stroke percentiles, the worst tick, events, preparation."""
    scenes = []
    for row in rows:
        if row["scene"] not in scenes and row["kind"] != "warm-up":
            scenes.append(row["scene"])
    summary = []
    for scene in scenes:
        mine = [r for r in rows if r["scene"] == scene]
        stroke = [r for r in mine if r["kind"] == "stroke"]
        ticks = [r for r in mine if r["function"] == "tick"]
        prepare = [r for r in mine if r["kind"] == "prepare"]
        entry = {"scene": scene, "stroke_ticks": len(stroke)}
        for column in ("instructions", "cycles_best", "cycles_worst"):
            values = [r[column] for r in stroke]
            entry[f"{column}_mean"] = sum(values) / len(values)
            for name, p in (("p50", 50), ("p99", 99), ("p99.9", 99.9)):
                entry[f"{column}_{name}"] = percentile(values, p)
            entry[f"{column}_max"] = max(r[column] for r in ticks)
        worst = max(ticks, key=lambda r: r["cycles_worst"])
        entry["worst_tick_kind"] = worst["kind"]
        for event in EVENTS:
            events = [r for r in mine if r["kind"] == event]
            if events:
                entry[f"{event}_instructions"] = max(r["instructions"] for r in events)
                entry[f"{event}_cycles_worst"] = max(r["cycles_worst"] for r in events)
        if prepare:
            entry["prepare_instructions"] = prepare[0]["instructions"]
            entry["prepare_cycles_best"] = prepare[0]["cycles_best"]
            entry["prepare_cycles_worst"] = prepare[0]["cycles_worst"]
            entry["prepare_ms_best"] = prepare[0]["cycles_best"] / CORE_HZ * 1e3
            entry["prepare_ms_worst"] = prepare[0]["cycles_worst"] / CORE_HZ * 1e3
        entry["isr_best"] = ISR_BEST
        entry["isr_worst"] = ISR_WORST
        entry["worst_tick_budget_percent"] = 100.0 * (entry["cycles_worst_max"] + ISR_WORST) / TICK_BUDGET_CYCLES
        summary.append(entry)
    return summary


def write_csv(path, rows, metadata):
    def write(f):
        f.write(f"# {metadata}\n")
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()), extrasaction="ignore")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
    ff_files.write_whole(path, write)


def print_summary(summary):
    print(f"{'scene':22} {'instr mean/p99.9/max':>22} {'cycles worst p99.9/max (+isr)':>32} {'prep ms':>12}")
    for s in summary:
        prep = f"{s.get('prepare_ms_best', 0):.3f}-{s.get('prepare_ms_worst', 0):.3f}"
        print(f"{s['scene']:22} {s['instructions_mean']:8.0f}/{s['instructions_p99.9']:6}/{s['instructions_max']:6} "
              f"{s['cycles_worst_p99.9']:12}/{s['cycles_worst_max']:6} (+{s['isr_worst']}) "
              f"{s['worst_tick_budget_percent']:5.2f} % {prep:>14}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     epilog="Model and validation: docs/cycle-model.md.")
    parser.add_argument("elf", help="ff-m4trace.elf (cortex-m4 preset)")
    parser.add_argument("--out", default="build/benchmarks", help="folder for calls.csv and cycles.csv")
    parser.add_argument("--smoke", action="store_true", help="one scene, a short stroke (scripts/m4-smoke)")
    parser.add_argument("--timeout", type=float, default=1800, help="seconds before qemu is stopped")
    parser.add_argument("--metadata", default="", help="text for the CSV files' first line")
    parser.add_argument("--breakdown", action="store_true",
                        help="also write breakdown.csv: event ticks and each scene's worst stroke tick by function")
    args = parser.parse_args(argv)
    try:
        if not os.path.isfile(args.elf):
            raise UsageError(f"{args.elf} does not exist (cmake --build --preset cortex-m4)")
        calls, harness, code_map = trace_calls(args.elf, "trace smoke" if args.smoke else "trace", args.timeout,
                                               args.breakdown)
        rows = label_calls(calls, harness)
        summary = summarise(rows)
        os.makedirs(args.out, exist_ok=True)
        metadata = (f"ff-cyclemodel {os.path.basename(args.elf)}; FASTRUN 0x{code_map.ram_start:x}-"
                    f"0x{code_map.ram_end:x}; {args.metadata}")
        if args.breakdown:
            write_csv(os.path.join(args.out, "breakdown.csv"), breakdown(rows), metadata)
        for row in rows:
            del row["functions"]
        write_csv(os.path.join(args.out, "calls.csv"), rows, metadata)
        write_csv(os.path.join(args.out, "cycles.csv"), summary, metadata)
        print_summary(summary)
    except UsageError as e:
        print(f"ff-cyclemodel: {e}", file=sys.stderr)
        return 2
    except (RuntimeError, ValueError, OSError, subprocess.CalledProcessError) as e:
        print(f"ff-cyclemodel: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
