"""Cortex-M4F cycles of an executed instruction sequence on the MK66 (Teensy
3.6 at 180 MHz), as a range between two sets of assumptions.

Per-instruction cycles: ARM Cortex-M4 Technical Reference Manual (processor
instruction timing table and its load/store notes; FPU instruction timing
table). Flash: the K66 reference manual's flash memory controller (a read
that misses takes between the core-to-flash clock ratio and twice it minus
one core cycles; 180 MHz / 25.7 MHz = 7, so 7 to 13) behind the 8 KiB LMEM
code cache Teensyduino enables at start-up (teensy3/mk20dx128.c writes
LMEM_PCCCR). See docs/cycle-model.md for what the model cannot know.
"""
from dataclasses import dataclass

CORE_HZ = 180_000_000
TICK_BUDGET_CYCLES = 90_000   # one 500 us tick at 180 MHz
FLASH_LINE_BYTES = 16         # the flash is read 128 bits at a time; cache lines are 16 bytes


@dataclass(frozen=True)
class Assumptions:
    name: str
    refill: int              # P, pipeline refill after a taken branch: 1..3 (TRM)
    store_register_offset: int  # STR Rx,[Ry,Rz]: 1 (write buffer) .. 2
    multiply_accumulate: int    # MLA/MLS
    divide: int              # SDIV/UDIV: 2..12 depending on the operands
    it_cycles: int           # IT: 0 when folded into the previous 16-bit instruction, else 1
    barrier: int             # DMB/DSB: 1 with an empty write buffer, more when it drains
    literal_contention: int  # LDR Rx,[PC,#imm] may lose a cycle to the fetch unit
    cold_code_cache: bool    # every flash line a call touches misses once (main loop evicted it)
    flash_miss: int          # core cycles of a flash read that misses: 7..13
    table_load_misses: bool  # loads of constant tables by code in flash (libm) miss every time
    sram_l_contention: int   # per data access by code running from SRAM_L (FASTRUN), stack excepted: 0..1


BEST = Assumptions("best", refill=1, store_register_offset=1, multiply_accumulate=1, divide=2,
                   it_cycles=0, barrier=1, literal_contention=0, cold_code_cache=False,
                   flash_miss=7, table_load_misses=False, sram_l_contention=0)
WORST = Assumptions("worst", refill=3, store_register_offset=2, multiply_accumulate=2, divide=12,
                    it_cycles=1, barrier=2, literal_contention=1, cold_code_cache=True,
                    flash_miss=13, table_load_misses=True, sram_l_contention=1)

# The IntervalTimer interrupt around FirmwareApp::tick -> HapticPipeline::tick,
# estimated from the code (Teensyduino teensy3/IntervalTimer.cpp pit0_isr,
# pins_teensy.c micros(), mk20dx128.c ResetHandler; firmware/src/main.cpp;
# firmware/app/firmware_app.cpp): not traced. Peripheral accesses cross the
# 60 MHz bus (3 core cycles each and more through the bridge).
ISR_WRAPPER = (
    # (piece, best, worst)
    # ResetHandler copies the vectors to _VectorsRam and points SCB_VTOR there:
    # the vector fetch never waits for flash (worst: one SRAM_L contention cycle).
    ("exception entry: 8 words stacked, vector fetch from the RAM vector table", 12, 12 + 1),
    ("lazy FP stacking at the tick's first FP instruction (worst: interrupted code had FP state)", 0, 18),
    ("exception return (worst: FP context restored too)", 10, 10 + 18),
    ("pit0_isr: clear PIT_TFLG0 (bus write), indirect call", 8, 14),
    ("on_tick: micros() (SysTick and ICSR reads, interrupts masked, division by 180)", 20, 40),
    ("FirmwareApp::tick around the pipeline: two DWT reads, heartbeat, atomics, stream ring, statistics", 35, 70),
    ("DAC write: FsAdjustAmplitude::write_code -> Dac12::write -> TeensyDac::do_write (one 16-bit store "
     "to DAC0_DAT0L)", 20, 40),
    # on_tick, FirmwareApp::tick, the DAC write and TeensyBoard::cycles are
    # FF_FASTRUN: only Teensyduino's pit0_isr (~20 bytes with its literals)
    # and micros() (~70 bytes) stay in flash.
    ("flash misses of the wrapper's code in flash (pit0_isr and micros(): about 8 lines, worst: all evicted)",
     0, 8 * 13),
)
ISR_BEST = sum(best for _, best, _ in ISR_WRAPPER)
ISR_WORST = sum(worst for _, _, worst in ISR_WRAPPER)

_LOAD_SINGLE = {"ldr", "ldrb", "ldrh", "ldrsb", "ldrsh", "ldrex", "vldr"}
_STORE_SINGLE = {"str", "strb", "strh", "strex", "vstr"}
_MULTIPLE = {"ldm", "ldmia", "ldmdb", "ldmfd", "stm", "stmia", "stmdb", "stmea", "push", "pop",
             "vldm", "vldmia", "vldmdb", "vstm", "vstmia", "vstmdb", "vpush", "vpop"}
_BRANCH = {"b", "bl", "blx", "bx", "cbz", "cbnz"}
_FP_MAC = {"vmla", "vmls", "vnmla", "vnmls", "vfma", "vfms", "vfnma", "vfnms"}


def stack_access(ins):
    """PUSH/POP/VPUSH/VPOP and loads/stores addressed by SP. The stack is at
    the top of the Teensy's RAM (Teensyduino teensy3/mk66fx1m0.ld: _estack =
    0x1FFF0000 + 256K), in SRAM_U on the system bus: it never competes with
    instruction fetches from SRAM_L (FASTRUN) on the code bus."""
    if ins.base in ("push", "pop", "vpush", "vpop"):
        return True
    if ins.base in _MULTIPLE:
        return ins.dest == "sp"
    return ins.base_register == "sp"


# Functions whose data (besides literal pools) is all in SRAM_U on the Teensy.
# The tracker's member functions read and write only their own object and the
# stack; the firmware's tracker is HapticPipeline's member after its two table
# slots (haptic_pipeline.hpp: slots_ first; 96 KiB each, platformio.ini), so it
# starts at least 192 KiB after RAM's start (0x1FFF0000, teensy3/mk66fx1m0.ld),
# past SRAM_L's 64 KiB: on the system bus, never competing with FASTRUN's
# instruction fetches from SRAM_L on the code bus (K66 reference manual:
# SRAM_L on the code bus, SRAM_U on the system bus).
SRAM_U_FUNCTIONS = ("_ZN2ff7Tracker",)


class CodeMap:
    """Where code and data live on the Teensy: [ram_start, ram_end) is the
    FASTRUN section (zero wait states); every other instruction is in flash.
    table_functions: functions (by name prefix) whose register-based loads
    read constant tables in flash; sram_u_functions: functions (by name
    prefix) whose data accesses other than literal loads go to SRAM_U."""

    def __init__(self, ram_start=0, ram_end=0, table_functions=("__ieee754", "__kernel", "sinf", "cosf",
                                                                 "atan", "atan2f", "sqrtf", "expf", "logf"),
                 sram_u_functions=SRAM_U_FUNCTIONS):
        self.ram_start = ram_start
        self.ram_end = ram_end
        self.table_functions = tuple(table_functions)
        self.sram_u_functions = tuple(sram_u_functions)

    def memory(self, ins):
        """(flash lines the instruction touches, loads a flash table, data access from SRAM_L code),
        computed once per instruction."""
        key = ("memory", id(self))
        cached = ins.extra.get(key)
        if cached is None:
            in_ram = self.in_ram(ins.address)
            lines = set()
            if not in_ram:
                lines.add(ins.address // FLASH_LINE_BYTES)
                lines.add((ins.address + ins.size - 1) // FLASH_LINE_BYTES)
            if ins.literal is not None and not self.in_ram(ins.literal):
                lines.add(ins.literal // FLASH_LINE_BYTES)
            table_load = self.reads_flash_table(ins) and ins.base in _LOAD_SINGLE | {"ldrd", "vldm", "vldmia",
                                                                                     "ldm", "ldmia"}
            data_access = ins.base in _LOAD_SINGLE | _STORE_SINGLE | _MULTIPLE | {"ldrd", "strd"}
            data_in_sram_u = stack_access(ins) or (ins.literal is None and
                                                   ins.function.startswith(self.sram_u_functions))
            cached = (tuple(lines), table_load, in_ram and data_access and not data_in_sram_u)
            ins.extra[key] = cached
        return cached

    def in_ram(self, address):
        return self.ram_start <= address < self.ram_end

    def reads_flash_table(self, ins):
        return (not self.in_ram(ins.address) and ins.base_register not in ("sp", "pc", "")
                and ins.function.startswith(self.table_functions))


def instruction_cycles(ins, previous, taken, a):
    """Issue cycles of one instruction (no memory wait states). previous: the
    instruction before it in the trace (None at a call's start); taken: the
    next executed address is not the next in memory."""
    base = ins.base
    if base == "alu":
        return (1 + a.refill) if ins.writes_pc else 1
    if base in _BRANCH:
        return 1 + a.refill if taken else 1
    if base in ("tbb", "tbh"):
        return 2 + a.refill
    if base == "it":
        return a.it_cycles
    if base in _LOAD_SINGLE:
        if ins.writes_pc:
            return 2 + a.refill
        cycles = 2
        # Neighbouring loads pipeline (N loads in N + 1 cycles) unless this one's
        # address comes from the previous load.
        if previous is not None and previous.base in _LOAD_SINGLE and previous.dest != ins.base_register:
            cycles = 1
        if ins.literal is not None:
            cycles += a.literal_contention
        return cycles
    if base in _STORE_SINGLE:
        if base == "vstr":
            return 1 if previous is not None and previous.base in _LOAD_SINGLE | _STORE_SINGLE else 2
        inner = ins.operands.split("[", 1)[-1].split("]")[0].split(",")
        register_offset = len(inner) >= 2 and not inner[1].strip().startswith("#")
        return a.store_register_offset if register_offset else 1
    if base in ("ldrd", "strd"):
        return 3
    if base in _MULTIPLE:
        cycles = 1 + ins.registers
        return cycles + a.refill if ins.writes_pc else cycles
    if base == "vmov":
        return ins.extra.get("transfers", 1)
    if base in _FP_MAC:
        return 3
    if base in ("vdiv", "vsqrt"):
        return 14
    if base in ("mla", "mls"):
        return a.multiply_accumulate
    if base in ("sdiv", "udiv"):
        return a.divide
    if base in ("dmb", "dsb"):
        return a.barrier
    if base == "isb":
        return 1 + a.refill
    return 1  # mul, smull, umull, vmrs, vmsr, vadd, vsub, vmul, vcmp, vcvt, bkpt, ...


class CallCost:
    """Accumulates one call's instructions and cycles under one set of assumptions."""

    def __init__(self, assumptions, code_map, by_function=False):
        self.a = assumptions
        self.code_map = code_map
        self.instructions = 0
        self.cycles = 0
        self.flash_lines = set()
        self.table_loads = 0
        self.previous = None
        # function -> [instructions, cycles with its wait states, flash misses charged]; only if asked
        self.functions = {} if by_function else None

    def add(self, ins, next_address):
        a = self.a
        cycles = instruction_cycles(ins, self.previous, next_address != ins.address + ins.size, a)
        lines, table_load, ram_data_access = self.code_map.memory(ins)
        misses = 0
        if self.functions is not None and a.cold_code_cache:
            misses = sum(1 for line in lines if line not in self.flash_lines)
        self.flash_lines.update(lines)
        if table_load:
            self.table_loads += 1
            if a.table_load_misses:
                misses += 1
        if ram_data_access:
            cycles += a.sram_l_contention
        self.cycles += cycles
        self.instructions += 1
        if self.functions is not None:
            entry = self.functions.setdefault(ins.function, [0, 0, 0])
            entry[0] += 1
            entry[1] += cycles + misses * a.flash_miss
            entry[2] += misses
        self.previous = ins

    def total(self):
        """Cycles including the memory system's wait states."""
        misses = len(self.flash_lines) if self.a.cold_code_cache else 0
        if self.a.table_load_misses:
            misses += self.table_loads
        return self.cycles + misses * self.a.flash_miss


def cycles_of(sequence, instructions, code_map, assumptions, end_address=None):
    """Cycles of a straight list of executed addresses (for tests and blocks)."""
    cost = CallCost(assumptions, code_map)
    for i, address in enumerate(sequence):
        ins = instructions[address]
        nxt = sequence[i + 1] if i + 1 < len(sequence) else (end_address if end_address is not None
                                                              else address + ins.size)
        cost.add(ins, nxt)
    return cost
