#!/usr/bin/python3
# Compares the constants of a strategy's reply (or of any constants file) with a constants file's,
# number by number: prints the worst difference per constant group (thermal.k, accel.offset_duty,
# gyro.l, cg, ...) and, where both hold them, of the standard errors; exits 1 when a constant
# differs by more than --rtol relative (|a - b| > rtol |b|, so a zero must be reproduced exactly).
# Standard errors are reported only (--se-rtol makes them count too).
# Usage: compare_constants.py REPLY.json CONSTANTS.json [--rtol 1e-9] [--se-rtol R]
import argparse
import json
import re
import sys


def numbers(tree, path=""):
    """{JSON path: value} of every number (null included as None) of a tree."""
    if isinstance(tree, dict):
        return {k: v for key, item in tree.items() for k, v in numbers(item, f"{path}.{key}").items()}
    if isinstance(tree, list):
        return {k: v for i, item in enumerate(tree) for k, v in numbers(item, f"{path}[{i}]").items()}
    if tree is None or (isinstance(tree, (int, float)) and not isinstance(tree, bool)):
        return {path: tree}
    return {}


def group_of(path):
    """".thermal[3].k[1]" -> "thermal.k"."""
    return re.sub(r"\[\d+\]", "", path).lstrip(".")


def compare(got, want, rtol, what):
    """Prints the worst difference per group; returns whether every number is within rtol."""
    a, b = numbers(got), numbers(want)
    if a.keys() != b.keys():
        print(f"{what}: the keys differ: only in the first: {sorted(a.keys() - b.keys())[:5]}, "
              f"only in the second: {sorted(b.keys() - a.keys())[:5]}")
        return False
    worst = {}  # group -> (relative, absolute, path)
    ok = True
    for path, value in b.items():
        mine = a[path]
        group = group_of(path)
        if value is None or mine is None:
            if (value is None) != (mine is None):
                print(f"{what}{path}: {mine!r} against {value!r}")
                ok = False
            continue
        diff = abs(mine - value)
        relative = diff / max(1e-300, abs(value))
        if diff > rtol * abs(value):
            ok = False
        if group not in worst or (relative, diff) > worst[group][:2]:
            worst[group] = (relative, diff, path, mine, value)
    for group, (relative, diff, path, mine, value) in worst.items():
        flag = "" if diff <= rtol * abs(value) else "   BEYOND TOLERANCE"
        print(f"{what}.{group:<26} worst relative {relative:9.3g}  absolute {diff:9.3g}  "
              f"at {path} ({mine!r} vs {value!r}){flag}")
    return ok


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("reply", help="a strategy's reply or a constants file")
    parser.add_argument("constants", help="the constants file to compare with")
    parser.add_argument("--rtol", type=float, default=1e-9)
    parser.add_argument("--se-rtol", type=float, default=None,
                        help="fail on standard errors beyond this relative difference too")
    args = parser.parse_args()
    with open(args.reply) as f:
        got = json.load(f)
    with open(args.constants) as f:
        want = json.load(f)
    ok = compare(got["constants"], want["constants"], args.rtol, "constants")
    if "standard_errors" in got and "standard_errors" in want:
        se_ok = compare(got["standard_errors"], want["standard_errors"],
                        args.se_rtol if args.se_rtol is not None else args.rtol,
                        "standard_errors")
        ok = ok and (se_ok or args.se_rtol is None)
    print("constants equal within the tolerance" if ok else "DIFFERENT beyond the tolerance")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
