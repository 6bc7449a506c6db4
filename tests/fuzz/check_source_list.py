#!/usr/bin/env python3
"""The fuzz targets link one library built from an explicit source list (tests/fuzz/CMakeLists.txt)
rather than the folder libraries. A parser that gains a dependency would show only in the clang
fuzz build, at link time, at the end of CI. This check follows the quoted includes from the listed
sources and the fuzz targets and fails when a header that has a .cc beside it is reached but that
.cc is not listed, naming the header and who includes it.

Usage: check_source_list.py <repository root>
"""
import pathlib
import re
import sys

# Headers reached for their types or constexpr tables only: the linker needs none of their .cc.
HEADER_ONLY_USES = {
    "hil/transport/serial_port": "hil/station.h uses the SerialSettings types, not the port",
    "common/imu_layout": "the constants readers use the constexpr channel table",
    "tests/fuzz/fuzz_support": "added to the library beside the list",
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def listed_sources(cmake_text):
    match = re.search(r"set\(parser_sources[^\n]*\n(.*?)\)", cmake_text, re.S)
    if not match:
        raise SystemExit("tests/fuzz/CMakeLists.txt: no set(parser_sources ...) list")
    return set(match.group(1).split())


def main(root):
    root = pathlib.Path(root)
    listed = listed_sources((root / "tests/fuzz/CMakeLists.txt").read_text())
    errors = [f"tests/fuzz/CMakeLists.txt lists '{s}' but {s}.cc does not exist"
              for s in sorted(listed) if not (root / f"{s}.cc").exists()]
    todo = [f"{s}.cc" for s in listed]
    todo += [str(p.relative_to(root)) for p in (root / "tests/fuzz").glob("*.cc")]
    seen, missing = set(), {}
    while todo:
        path = todo.pop()
        if path in seen or not (root / path).exists():
            continue
        seen.add(path)
        for header in INCLUDE.findall((root / path).read_text()):
            if not (root / header).exists():
                continue
            todo.append(header)
            stem = header[:-2] if header.endswith(".h") else None
            if stem is None or not (root / f"{stem}.cc").exists():
                continue
            if stem in listed:
                todo.append(f"{stem}.cc")
            elif stem not in HEADER_ONLY_USES:
                missing.setdefault(stem, set()).add(path)
    for stem, users in sorted(missing.items()):
        errors.append(f"{stem}.cc is not in tests/fuzz/CMakeLists.txt parser_sources but "
                      f"{stem}.h is included by {', '.join(sorted(users))}")
    for error in errors:
        print(error, file=sys.stderr)
    return 1 if errors else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    sys.exit(main(sys.argv[1]))
