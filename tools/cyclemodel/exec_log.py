"""Calls in qemu's per-instruction execution log (-singlestep -d exec,nochain):
every instruction from a function's entry up to the return to its caller,
costed as it streams past (the log of a full run is gigabytes)."""
from dataclasses import dataclass

from model import BEST, WORST, CallCost


@dataclass
class CallResult:
    function: str
    instructions: int
    best: int
    worst: int
    flash_lines: int
    functions: dict | None = None  # function -> [instructions, worst cycles, worst flash misses]


def executed_addresses(lines):
    """Guest PCs of "Trace 0: 0x... [cs_base/pc/flags/cflags] symbol" lines."""
    for line in lines:
        if not line.startswith("Trace"):
            continue
        bracket = line.find("[")
        if bracket < 0:
            continue
        yield int(line[bracket + 10:bracket + 18], 16)


def measure_calls(addresses, instructions, entries, code_map, by_function=False):
    """Yields a CallResult per call of the functions in entries (address ->
    name), in execution order. The return address is the one the most recent
    BL/BLX left (a wrapper's tail call keeps its caller's). by_function: also
    split the worst case by the function each instruction belongs to."""
    last_return = None
    active = None  # (name, return address, best, worst)
    previous = None
    for address in addresses:
        if active is not None:
            name, return_address, best, worst = active
            best.add(previous, address)
            worst.add(previous, address)
            if address == return_address:
                yield CallResult(name, best.instructions, best.total(), worst.total(), len(worst.flash_lines),
                                 worst.functions)
                active = None
        ins = instructions.get(address)
        if ins is None:
            raise ValueError(f"executed address 0x{address:x} is not an instruction in the disassembly")
        if active is None and address in entries:
            if last_return is None:
                raise ValueError(f"{entries[address]} entered without a call")
            active = (entries[address], last_return, CallCost(BEST, code_map), CallCost(WORST, code_map, by_function))
        if ins.base in ("bl", "blx"):
            last_return = address + ins.size
        previous = ins
