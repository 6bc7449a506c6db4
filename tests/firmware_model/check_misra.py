#!/usr/bin/env python3
"""cppcheck's MISRA C:2012 addon over the firmware (firmware_model/target/), against the deviation
record in docs/firmware-compensator.md ("MISRA C:2012 deviations").

Usage: check_misra.py --cppcheck CPPCHECK --target DIR --record DOC.md

Runs cppcheck (Debian's 2.10: --addon=misra, --enable=style, C99) on a copy of the sources, so no
dump file lands in the tree. Without the licensed rule texts the addon names rules by number only,
which is all this check needs. It fails on
  - any finding of cppcheck's own checks (style, warning, portability, performance): none is
    accepted;
  - a MISRA finding that no row of the record covers: a row names the rule, the file (or *) and the
    symbol (the function defined, the macro or the type declared on the flagged line; or *);
  - a row of the record that covers no finding (the record must say what the code does now).
Prints the findings per rule and the rows that cover them.
"""
import argparse
import collections
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

SECTION = "## MISRA C:2012 deviations"
FINDING = re.compile(r"^(?P<file>[^:]+):(?P<line>\d+):(?P<severity>\w+):(?P<id>[\w.-]+):(?P<msg>.*)$")


def symbol_at(path, line_number):
    """The function defined, macro defined or type declared on a source line ('' if none)."""
    lines = path.read_text().splitlines()
    line = lines[line_number - 1]
    match = re.match(r"\s*#\s*define\s+(\w+)", line)
    if match:
        return match.group(1)
    if re.match(r"\s*typedef\s+(enum|struct)\b", line):
        for following in lines[line_number - 1:]:
            match = re.match(r"\s*}\s*(\w+)\s*;", following)
            if match:
                return match.group(1)
    match = re.search(r"\b([A-Za-z_]\w*)\s*\(", line)
    return match.group(1) if match else ""


def record_rows(doc):
    """(rule, file, symbol) of every row of the deviation table."""
    text = pathlib.Path(doc).read_text()
    if SECTION not in text:
        sys.exit(f"check_misra: {doc} has no section '{SECTION}'")
    rows = []
    for line in text.split(SECTION, 1)[1].splitlines():
        if line.startswith("## "):
            break
        cells = [c.strip().strip("`") for c in line.strip().strip("|").split("|")]
        if len(cells) >= 5 and re.fullmatch(r"\d+\.\d+", cells[0]):
            for symbol in cells[3].replace("`", "").split(","):
                rows.append((cells[0], cells[2], symbol.strip()))
    return rows


def covers(row, rule, file, symbol):
    return row[0] == rule and row[1] in ("*", file) and row[2] in ("*", symbol)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cppcheck", required=True)
    parser.add_argument("--target", required=True)
    parser.add_argument("--record", required=True)
    args = parser.parse_args()
    rows = record_rows(args.record)
    with tempfile.TemporaryDirectory() as work:
        for source in pathlib.Path(args.target).glob("*.[ch]"):
            shutil.copy(source, work)
        sources = sorted(str(p.name) for p in pathlib.Path(work).glob("*.c"))
        run = subprocess.run(
            [args.cppcheck, "--addon=misra", "--std=c99", "--language=c", "--enable=style",
             "--quiet", "--template={file}:{line}:{severity}:{id}:{message}", "-I.", *sources],
            cwd=work, capture_output=True, text=True, timeout=280)
        output = run.stdout + run.stderr
        findings = []
        problems = []
        for line in output.splitlines():
            match = FINDING.match(line)
            if not match:
                if line.strip():
                    problems.append(f"cppcheck: {line}")
                continue
            file, number, finding = match.group("file"), int(match.group("line")), match.group("id")
            if not finding.startswith("misra-c2012-"):
                problems.append(f"{file}:{number}: cppcheck {finding}: {match.group('msg')}")
                continue
            rule = finding[len("misra-c2012-"):]
            findings.append((rule, file, number, symbol_at(pathlib.Path(work, file), number)))
    if run.returncode != 0:
        problems.append(f"cppcheck exited {run.returncode}")
    used = set()
    for rule, file, number, symbol in findings:
        row = next((r for r in rows if covers(r, rule, file, symbol)), None)
        if row is None:
            problems.append(f"{file}:{number}: MISRA C:2012 rule {rule} ({symbol or 'no symbol'}) "
                            f"is not in the deviation record of {args.record}")
        else:
            used.add(row)
    for row in rows:
        if row not in used:
            problems.append(f"{args.record}: deviation row {row} covers no finding (remove it)")
    per_rule = collections.Counter(rule for rule, _, _, _ in findings)
    print(f"check_misra: {len(sources)} files, {len(findings)} MISRA findings: " +
          ", ".join(f"rule {r} x{n}" for r, n in sorted(per_rule.items())) +
          f"; {len(used)} record rows cover them")
    for p in problems:
        print(f"check_misra: FAIL: {p}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
