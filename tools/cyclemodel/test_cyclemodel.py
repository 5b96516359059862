"""Tests of the cycle model: straight-line blocks assembled with
arm-none-eabi-as whose cycles are counted by hand from the Cortex-M4 TRM's
timing tables (the expected numbers below are those hand counts, not the
model's output), the objdump parser, and the exec-log call finder."""
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from disassembly import classify, disassemble, parse_objdump, symbols  # noqa: E402
from exec_log import executed_addresses, measure_calls  # noqa: E402
from model import BEST, WORST, CallCost, CodeMap, cycles_of  # noqa: E402

RAM_EVERYWHERE = CodeMap(0, 1 << 32)  # zero-wait code: only the core's own timing
FLASH_EVERYWHERE = CodeMap(0, 0)


def assemble(source):
    """Address -> Instruction of a Thumb-2 snippet (Cortex-M4F), linked at 0."""
    with tempfile.TemporaryDirectory() as tmp:
        s = os.path.join(tmp, "block.s")
        o = os.path.join(tmp, "block.o")
        Path(s).write_text(".syntax unified\n.thumb\n.text\n.global block\n.thumb_func\nblock:\n" + source + "\n")
        subprocess.run(["arm-none-eabi-as", "-mcpu=cortex-m4", "-mfpu=fpv4-sp-d16", "-mthumb", s, "-o", o],
                       check=True, capture_output=True)
        dump = subprocess.run(["arm-none-eabi-objdump", "-d", o], check=True, capture_output=True, text=True).stdout
    return parse_objdump(dump)


def straight(instructions):
    return sorted(instructions)


class HandCountedBlocks(unittest.TestCase):
    def cycles(self, source, assumptions=BEST, code_map=RAM_EVERYWHERE, sequence=None, end=None):
        ins = assemble(source)
        return cycles_of(sequence or straight(ins), ins, code_map, assumptions, end).total()

    def test_loads_pipeline_unless_the_address_depends_on_the_previous_load(self):
        # adds 1; ldr 2; ldr 1 (pipelined); str imm 1; mul 1 = 6
        self.assertEqual(self.cycles("adds r0, r1, r2\nldr r3, [r0]\nldr r4, [r0, #4]\nstr r4, [r0, #8]\n"
                                     "mul r5, r3, r4"), 6)
        # ldr r1,[r0] 2; ldr r2,[r1] 2: the second address is the first load's result
        self.assertEqual(self.cycles("ldr r1, [r0]\nldr r2, [r1]"), 4)

    def test_fpu_latencies(self):
        # vldr 2; vldr 1 (pipelined); vmla 3; vdiv 14; vsqrt 14; vstr 2; vadd 1; vmov core<-s 1 = 38
        self.assertEqual(self.cycles("vldr s0, [r0]\nvldr s1, [r0, #4]\nvmla.f32 s2, s0, s1\n"
                                     "vdiv.f32 s3, s2, s1\nvsqrt.f32 s4, s3\nvstr s4, [r0]\n"
                                     "vadd.f32 s5, s4, s4\nvmov r1, s5"), 38)

    def test_multiple_transfers_and_return(self):
        # push 1+4; vpush 1+2; vpop 1+2; pop with pc 1+4+P (best P = 1, worst 3)
        block = "push {r4, r5, r6, lr}\nvpush {s16, s17}\nvpop {s16, s17}\npop {r4, r5, r6, pc}"
        self.assertEqual(self.cycles(block, BEST, end=0x1000), 5 + 3 + 3 + 6)
        # Worst: only the refill; the stack is in SRAM_U (system bus), no SRAM_L contention.
        self.assertEqual(self.cycles(block, WORST, end=0x1000), 5 + 3 + 3 + 8)

    def test_sram_l_contention_only_for_data_off_the_stack(self):
        # RAM code, worst: ldr [r0] 2 + 1 (SRAM_L contention); ldr [sp, #4] 1 (pipelined, stack);
        # str [r1] 1 + 1; str [sp] 1; stmdb sp!, {r4, r5} 1 + 2; ldmia r0, {r2, r3} 1 + 2 + 1 = 14
        block = ("ldr r2, [r0]\nldr r3, [sp, #4]\nstr r2, [r1]\nstr r3, [sp]\nstmdb sp!, {r4, r5}\n"
                 "ldmia r0, {r2, r3}")
        self.assertEqual(self.cycles(block, WORST), 14)
        self.assertEqual(self.cycles(block, BEST), 11)  # the same without the three contention cycles
        # A function whose data is in SRAM_U (the tracker): no contention at all, except a literal load
        # (ldr r4, [pc, #0] after ldmia: 2 + 1 literal contention (worst) + 1 SRAM_L).
        tracker = CodeMap(0, 1 << 32, sram_u_functions=("block",))
        self.assertEqual(self.cycles(block, WORST, tracker), 11)
        self.assertEqual(self.cycles(block + "\nldr r4, [pc, #0]\nnop\nnop", WORST, tracker), 11 + 4 + 2)

    def test_branches_cost_a_refill_only_when_taken(self):
        source = "cmp r0, #0\nbeq 1f\nadds r0, #1\n1: adds r0, #2"
        ins = assemble(source)
        a = straight(ins)
        not_taken = cycles_of(a, ins, RAM_EVERYWHERE, BEST).total()
        taken = cycles_of([a[0], a[1], a[3]], ins, RAM_EVERYWHERE, BEST).total()
        self.assertEqual(not_taken, 4)   # cmp 1, beq 1, adds 1, adds 1
        self.assertEqual(taken, 1 + 2 + 1)  # cmp 1, beq 1 + P(1), adds 1
        self.assertEqual(cycles_of([a[0], a[1], a[3]], ins, RAM_EVERYWHERE, WORST).total(), 1 + 4 + 1)

    def test_cold_flash_costs_one_miss_per_line_touched(self):
        # Eight 16-bit instructions at 0..15: one 16-byte line; worst: 8 cycles + one 13-cycle miss.
        block = "\n".join(["adds r0, #1"] * 8)
        self.assertEqual(self.cycles(block, WORST, FLASH_EVERYWHERE), 8 + 13)
        self.assertEqual(self.cycles(block, BEST, FLASH_EVERYWHERE), 8)
        # Nine: a second line.
        self.assertEqual(self.cycles(block + "\nadds r0, #1", WORST, FLASH_EVERYWHERE), 9 + 2 * 13)

    def test_table_branches_it_and_a_load_into_pc(self):
        # tbb 2 + P: best 3, worst 5
        self.assertEqual((self.cycles("tbb [pc, r0]", BEST), self.cycles("tbb [pc, r0]", WORST)), (3, 5))
        # it 0 (folded) or 1; addeq 1
        self.assertEqual((self.cycles("it eq\naddeq r0, #1", BEST), self.cycles("it eq\naddeq r0, #1", WORST)),
                         (1, 2))
        # ldr pc, [r0]: 2 + P; worst also 1 of SRAM_L contention (a data access from RAM code)
        self.assertEqual((self.cycles("ldr pc, [r0]", BEST, end=0x100), self.cycles("ldr pc, [r0]", WORST, end=0x100)),
                         (3, 6))

    def test_doubles_multiply_accumulate_division_and_barriers(self):
        # ldrd 3 (worst + 1 SRAM_L contention); mla 1..2; sdiv, udiv 2..12; dmb, dsb 1..2; isb 1 + P
        block = "ldrd r2, r3, [r0]\nmla r0, r1, r2, r3\nsdiv r0, r1, r2\nudiv r0, r1, r2\ndmb\ndsb\nisb"
        self.assertEqual(self.cycles(block, BEST), 3 + 1 + 2 + 2 + 1 + 1 + 2)
        self.assertEqual(self.cycles(block, WORST), 4 + 2 + 12 + 12 + 2 + 2 + 4)

    def test_a_literal_in_another_flash_line_misses_too(self):
        # ldr r0, [pc, #12] at 0 reads 0x10: code in line 0, its literal in line 1. Worst: ldr 2 + 1
        # literal contention, two nops, two misses of 13.
        block = "ldr r0, [pc, #12]\nnop\nnop"
        self.assertEqual(self.cycles(block, WORST, FLASH_EVERYWHERE), 3 + 2 + 2 * 13)
        self.assertEqual(self.cycles(block, BEST, FLASH_EVERYWHERE), 2 + 2)

    def test_loads_of_a_flash_table_miss_every_time_in_the_worst_case(self):
        # two loads through r0 by a table function in flash: 2 + 1 cycles; worst: the line once, each load once
        libm = CodeMap(0, 0, table_functions=("block",))
        ins = assemble("ldr r1, [r0]\nldr r2, [r0, #4]")
        worst = cycles_of(straight(ins), ins, libm, WORST)
        self.assertEqual((worst.table_loads, worst.total()), (2, 3 + 3 * 13))
        self.assertEqual(cycles_of(straight(ins), ins, libm, BEST).total(), 3)
        self.assertEqual(cycles_of(straight(ins), ins, FLASH_EVERYWHERE, WORST).table_loads, 0)  # not a table

    def test_the_worst_case_split_by_function_adds_up(self):
        # nine 16-bit adds over two lines, worst, flash: 9 cycles and 2 misses, all in "block"
        ins = assemble("\n".join(["adds r0, #1"] * 9))
        cost = CallCost(WORST, FLASH_EVERYWHERE, by_function=True)
        sequence = straight(ins)
        for i, address in enumerate(sequence):
            cost.add(ins[address], sequence[i + 1] if i + 1 < len(sequence) else address + 2)
        self.assertEqual(cost.functions, {"block": [9, 9 + 2 * 13, 2]})
        self.assertEqual(cost.total(), 9 + 2 * 13)


class Disassembly(unittest.TestCase):
    def test_conditions_are_not_mistaken_for_other_mnemonics(self):
        self.assertEqual(classify(0, 2, "bls.n", "4", "f").base, "b")
        self.assertTrue(classify(0, 2, "bls.n", "4", "f").conditional)
        self.assertEqual(classify(0, 4, "bl", "100 <x>", "f").base, "bl")
        self.assertEqual(classify(0, 4, "vmlage.f32", "s0, s1, s2", "f").base, "vmla")
        self.assertEqual(classify(0, 2, "itte", "eq", "f").base, "it")
        self.assertEqual(classify(0, 2, "bics", "r0, r1", "f").base, "alu")

    def test_literal_address_and_register_lists(self):
        ldr = classify(0x102, 2, "ldr", "r3, [pc, #8]\t@ (10c <f+0xc>)", "f")
        self.assertEqual(ldr.literal, 0x104 + 8)
        pop = classify(0, 2, "pop", "{r4, r5, r6, pc}", "f")
        self.assertEqual((pop.registers, pop.writes_pc), (4, True))
        vpush = classify(0, 4, "vpush", "{d8-d9}", "f")
        self.assertEqual(vpush.registers, 4)

    def test_flag_setting_conditional_and_pc_writing_forms(self):
        self.assertEqual(_split(classify(0, 4, "muls", "r0, r1, r0", "f")), ("mul", False))
        self.assertEqual(_split(classify(0, 4, "mulseq", "r0, r1, r0", "f")), ("mul", True))
        self.assertEqual(_split(classify(0, 2, "addeq", "r0, #1", "f")), ("alu", True))
        self.assertTrue(classify(0, 2, "mov", "pc, lr", "f").writes_pc)
        self.assertFalse(classify(0, 2, "mov", "r0, lr", "f").writes_pc)
        self.assertTrue(classify(0, 4, "ldr.w", "pc, [sp], #4", "f").writes_pc)
        self.assertEqual(classify(0, 2, "pop", "", "f").registers, 0)  # no list: nothing counted, no error

    def test_an_object_file_and_its_symbols(self):
        source = (".syntax unified\n.thumb\n.text\n.global sized\n.thumb_func\nsized:\nldr r0, =0x12345678\n"
                  "bx lr\n.ltorg\n.size sized, .-sized\n.global bare\n.thumb_func\nbare:\nnop\nbx lr\n.short 0xabcd\n"
                  "nop\n")
        with tempfile.TemporaryDirectory() as tmp:
            s, o = os.path.join(tmp, "f.s"), os.path.join(tmp, "f.o")
            Path(s).write_text(source)
            subprocess.run(["arm-none-eabi-as", "-mcpu=cortex-m4", "-mthumb", s, "-o", o], check=True)
            ins, table = disassemble(o), symbols(o)
        # ldr (0), bx (2), the literal .word (4) skipped; bare: nop (8), bx (10), .short (12) skipped, nop (14)
        self.assertEqual(sorted(ins), [0, 2, 8, 10, 14])
        self.assertEqual((ins[0].function, ins[8].function), ("sized", "bare"))
        self.assertEqual(table["sized"], (0, 8))   # nm -S: address and size
        self.assertEqual(table["bare"], (8, 0))    # no .size: its address only


def _split(ins):
    return ins.base, ins.conditional


class ExecLog(unittest.TestCase):
    def test_a_call_runs_from_entry_to_the_return_address_even_through_a_tail_call(self):
        # main: bl wrapper; wrapper: b.w target; target: adds; bx lr -> back to main.
        ins = assemble("bl wrapper\nnop\nwrapper: b.w target\ntarget: adds r0, #1\nbx lr")
        a = straight(ins)  # bl(0), nop(4), b.w(6), adds(10), bx(12)
        log = [f"Trace 0: 0x7f0000000000 [00000000/{x:08x}/00000110/ff020201] f\n" for x in
               (a[0], a[2], a[3], a[4], a[1])]
        calls = list(measure_calls(executed_addresses(log), ins, {a[3]: "target"}, RAM_EVERYWHERE))
        self.assertEqual(len(calls), 1)
        self.assertEqual(calls[0].instructions, 2)      # adds, bx lr
        self.assertEqual(calls[0].best, 1 + 1 + 1)      # adds 1, bx 1 + P

    def test_other_lines_are_skipped_and_a_foreign_address_is_an_error(self):
        log = ["qemu: some warning\n", "Trace 0: no bracket here\n",
               "Trace 0: 0x7f0000000000 [00000000/00000004/00000110/ff020201] f\n"]
        self.assertEqual(list(executed_addresses(log)), [4])
        ins = assemble("nop\nnop\nadds r0, #1\nbx lr")
        with self.assertRaisesRegex(ValueError, "executed address 0x40 is not an instruction"):
            list(measure_calls([0, 0x40], ins, {}, RAM_EVERYWHERE))
        with self.assertRaisesRegex(ValueError, "target entered without a call"):
            list(measure_calls([4], ins, {4: "target"}, RAM_EVERYWHERE))


if __name__ == "__main__":
    unittest.main()
