"""ff-bench's `fits_teensy` is what the device accepts: a table that fits the 96 KiB slot but whose
preparation the cost model prices past the watchdog's budget is refused on the Teensy
(ff-m4bench's HapticPipeline::set_condition under qemu says TooCostlyToPrepare for general-3's
4 px int16 tables) and must not read as fitting; its 8 px float table is accepted."""
import csv
import subprocess
import sys
import tempfile


def fits(bench, case_filter):
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([bench, "--filter", case_filter, "--grid-step", "50", "--no-timing", "--threads", "1",
                        "--out", out], check=True, capture_output=True)
        with open(out + "/host_cases.csv") as f:
            rows = csv.DictReader(line for line in f if not line.startswith("#"))
            return {r["id"]: (int(r["table_bytes"]), r["fits_teensy"]) for r in rows}


def main(bench):
    refused = fits(bench, "general-3/table-4px-int16")
    assert set(refused) == {"general-3/table-4px-int16-gradient", "general-3/table-4px-int16-height-cd"}, refused
    for case, (table_bytes, fit) in refused.items():
        assert table_bytes <= 96 * 1024, (case, table_bytes)  # it would fit the slot ...
        assert fit == "0", (case, fit)  # ... but the device refuses it for its cost
    accepted = fits(bench, "general-3/table-8px-float-gradient")
    assert [fit for _, fit in accepted.values()] == ["1"], accepted

if __name__ == "__main__":
    main(sys.argv[1])
