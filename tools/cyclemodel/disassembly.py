"""Instructions of an ELF as arm-none-eabi-objdump prints them, classified for
the Cortex-M4 cycle model: size, kind, registers, literal-pool address."""
import re
import subprocess
from dataclasses import dataclass, field

_CONDITIONS = ("eq", "ne", "cs", "hs", "cc", "lo", "mi", "pl", "vs", "vc",
               "hi", "ls", "ge", "lt", "gt", "le", "al")

# Base mnemonics the model distinguishes; anything else is a 1-cycle
# data-processing instruction. Longest match first.
_BASES = sorted([
    "b", "bl", "blx", "bx", "cbz", "cbnz", "tbb", "tbh", "it",
    "ldr", "ldrb", "ldrh", "ldrsb", "ldrsh", "ldrd", "ldrex", "ldm", "ldmia", "ldmdb", "ldmfd",
    "str", "strb", "strh", "strd", "strex", "stm", "stmia", "stmdb", "stmea",
    "push", "pop", "vldr", "vstr", "vldm", "vldmia", "vldmdb", "vstm", "vstmia", "vstmdb",
    "vpush", "vpop", "vmov", "vmrs", "vmsr",
    "vmla", "vmls", "vnmla", "vnmls", "vfma", "vfms", "vfnma", "vfnms", "vdiv", "vsqrt",
    "mul", "mla", "mls", "smull", "umull", "smlal", "umlal", "sdiv", "udiv",
    "dmb", "dsb", "isb", "bkpt",
], key=len, reverse=True)

_LINE = re.compile(r"^\s*([0-9a-f]+):\t([0-9a-f]{4}(?: [0-9a-f]{4})?)\s*\t(\S+)\s*(.*)$")
_FUNCTION = re.compile(r"^([0-9a-f]+) <(.+)>:$")
_REGISTER_LIST = re.compile(r"\{([^}]*)\}")
_LITERAL = re.compile(r"\[pc, #(-?\d+)\]")


@dataclass
class Instruction:
    address: int
    size: int            # bytes: 2 or 4
    mnemonic: str        # as printed, e.g. "vmlage.f32"
    base: str            # e.g. "vmla", "ldr", "alu"
    operands: str
    function: str
    conditional: bool = False    # a condition code on the mnemonic (IT block or branch)
    registers: int = 0           # registers moved by ldm/stm/push/pop/vldm/vstm/vpush/vpop
    writes_pc: bool = False      # pop {.., pc}, ldr pc, ldm {.., pc}, bx, mov pc
    literal: int | None = None   # address a PC-relative load reads
    dest: str = ""               # first operand register
    base_register: str = ""      # address register of a load/store
    extra: dict = field(default_factory=dict)


def _split_mnemonic(mnemonic):
    """('vmlage.f32') -> ('vmla', True)."""
    head = mnemonic.split(".")[0]
    if head[:1] == "b" and head[1:] in _CONDITIONS:  # bls, bhi, ... (not bl + s)
        return "b", True
    for base in _BASES:
        if head == base:
            return base, False
        if head.startswith(base):
            rest = head[len(base):]
            if rest in _CONDITIONS:
                return base, True
            if rest == "s" or (rest.startswith("s") and rest[1:] in _CONDITIONS):
                return base, rest != "s"
    # it, ite, itte ...: the IT family.
    if re.fullmatch(r"it[te]{0,3}", head):
        return "it", False
    for cond in _CONDITIONS:
        if head.endswith(cond) and len(head) > len(cond) + 1:  # b<cond> was found above
            return "alu", True
    return "alu", False


def _count_registers(operands, double_width):
    match = _REGISTER_LIST.search(operands)
    if not match:
        return 0
    count = 0
    for part in match.group(1).split(","):
        part = part.strip()
        if "-" in part:
            lo, hi = part.split("-")
            count += int(hi.strip()[1:]) - int(lo.strip()[1:]) + 1
        elif part:
            count += 1
    return count * (2 if double_width else 1)


def classify(address, size, mnemonic, operands, function):
    base, conditional = _split_mnemonic(mnemonic)
    ins = Instruction(address, size, mnemonic, base, operands, function, conditional)
    ops = operands.split("@")[0].split(";")[0].strip()
    ins.dest = ops.split(",")[0].strip().rstrip("!")
    if base in ("ldm", "ldmia", "ldmdb", "ldmfd", "stm", "stmia", "stmdb", "stmea", "push", "pop"):
        ins.registers = _count_registers(ops, False)
        ins.writes_pc = base not in ("stm", "stmia", "stmdb", "stmea", "push") and "pc" in ops.split("{")[-1]
    elif base in ("vldm", "vldmia", "vldmdb", "vstm", "vstmia", "vstmdb", "vpush", "vpop"):
        ins.registers = _count_registers(ops, "{d" in ops.replace(" ", ""))
    elif base in ("ldr",) and ins.dest == "pc":
        ins.writes_pc = True
    elif base == "bx":
        ins.writes_pc = True
    elif base == "alu" and mnemonic.startswith("mov") and ins.dest == "pc":
        ins.writes_pc = True
    bracket = re.search(r"\[(\w+)", ops)
    if bracket:
        ins.base_register = bracket.group(1)
    literal = _LITERAL.search(ops)
    if literal and base in ("ldr", "ldrb", "ldrh", "ldrsb", "ldrsh", "ldrd", "vldr"):
        ins.literal = ((address + 4) & ~3) + int(literal.group(1))
    if base == "vmov":
        # vmov r0, r1, d0 / vmov d0, r0, r1 / vmov s0, s1, r0, r1: two transfers.
        regs = [r.strip() for r in ops.split(",")]
        ins.extra["transfers"] = 2 if len(regs) >= 3 else 1
    return ins


def parse_objdump(text):
    """Address -> Instruction for every instruction objdump printed (not data)."""
    instructions = {}
    function = "?"
    for line in text.splitlines():
        fmatch = _FUNCTION.match(line)
        if fmatch:
            function = fmatch.group(2)
            continue
        match = _LINE.match(line)
        if not match:
            continue
        address = int(match.group(1), 16)
        raw, mnemonic, operands = match.group(2), match.group(3), match.group(4)
        if mnemonic.startswith("."):  # .word, .short: literal pool data
            continue
        size = 4 if " " in raw.strip() else 2
        instructions[address] = classify(address, size, mnemonic, operands, function)
    return instructions


def disassemble(elf, objdump="arm-none-eabi-objdump"):
    result = subprocess.run([objdump, "-d", elf], capture_output=True, text=True, check=True)
    return parse_objdump(result.stdout)


def symbols(elf, nm="arm-none-eabi-nm"):
    """Name -> (address, size) of every function and object symbol."""
    result = subprocess.run([nm, "-S", elf], capture_output=True, text=True, check=True)
    table = {}
    for line in result.stdout.splitlines():
        parts = line.split()
        if len(parts) == 4:
            table[parts[3]] = (int(parts[0], 16) & ~1, int(parts[1], 16))
        elif len(parts) == 3:
            table.setdefault(parts[2], (int(parts[0], 16) & ~1, 0))
    return table
