#!/usr/bin/env bash
# Runs ff-m4bench.elf under qemu's mps2-an386 (Cortex-M4F) with one guest
# instruction per nanosecond of virtual time (-icount shift=0), semihosting
# output into OUT. Usage: run-qemu.sh ELF OUT [smoke|accuracy] ; exit status is the harness's.
set -euo pipefail
elf=$1
out=$2
mode=${3:-full}
args=arg=$(basename "$elf" .elf)
[ "$mode" = smoke ] && args="$args,arg=smoke"
[ "$mode" = accuracy ] && args="$args,arg=accuracy"
exec qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none \
  -chardev "file,id=semihosting,path=$out" \
  -semihosting-config "enable=on,target=native,chardev=semihosting,$args" \
  -icount shift=0 -kernel "$elf"
