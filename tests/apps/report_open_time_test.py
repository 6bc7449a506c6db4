#!/usr/bin/env python3
"""scripts/report-open-time, the measure behind docs/report.md's open-time figure, against pages
made here: a page that takes a known time to lay out (a script in it spins for 300 ms before its
body ends) measures at least that and less than the process's wall time; a missing report is
refused naming it, and nothing is measured.

Usage: report_open_time_test.py /path/to/adahrs (unused: the script needs only Chromium)
"""
import os
import pathlib
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from app_checks import expect  # noqa: E402

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "report-open-time"
SPIN_MS = 300
LOAD = re.compile(r"^load 1: open (\d+) ms; process ([0-9.]+) s, empty page ([0-9.]+) s$", re.M)


def main():
    with tempfile.TemporaryDirectory() as scratch:
        page = pathlib.Path(scratch) / "report.html"
        page.write_text(
            "<!DOCTYPE html><html><body><p>before</p><script>var t = performance.now(); "
            f"while (performance.now() - t < {SPIN_MS}) {{}}</script><p>after</p></body></html>",
            encoding="utf-8")
        result = subprocess.run([sys.executable, str(SCRIPT), str(page), "--loads", "1"],
                                capture_output=True, text=True, timeout=300)
        expect(result.returncode == 0, result.stdout, result.stderr)
        found = LOAD.search(result.stdout)
        expect(found is not None, "no load line", result.stdout)
        open_ms, process_s = int(found.group(1)), float(found.group(2))
        expect(open_ms >= SPIN_MS, f"open {open_ms} ms < the page's {SPIN_MS} ms of script")
        expect(open_ms < process_s * 1000, f"open {open_ms} ms beyond the process's {process_s} s")
        expect("over 1 loads" in result.stdout, result.stdout)

        missing = pathlib.Path(scratch) / "absent.html"
        result = subprocess.run([sys.executable, str(SCRIPT), str(missing)],
                                capture_output=True, text=True, timeout=60)
        expect(result.returncode != 0, "a missing report was measured", result.stdout)
        expect(str(missing) in result.stderr, result.stderr)
        expect("load 1" not in result.stdout, result.stdout)
    print("PASS")


if __name__ == "__main__":
    main()
