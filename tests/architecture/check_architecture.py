#!/usr/bin/env python3
"""Our own check of the layering rules (the same rules as shared/tools/check-architecture).

1. The wings, one row each: a folder may include only its own files and the folders its row
   names. The production pipeline (calib/), the diagnosis and hil/ never include sensor_sim/ or
   rig_sim/: only proving/ and rig_sim/ may know the truth (no inverse crime), and calib/ never
   includes the diagnosis or proving/ above it.
2. firmware_model/target/ is target-clean for the 16-bit dsPIC, whose compiler (MPLAB XC16) is a
   C compiler: only C99 sources (.c, .h), no C++ (namespaces, classes, templates, constexpr, casts
   of C++, nullptr, #pragma once), no floating point, heap or exceptions; it includes only its own
   headers (by bare name, so the folder drops into an MPLAB project as it is) and the C standard
   library's freestanding headers <stdint.h>, <stdbool.h>, <stddef.h> (and avr-libc's, in the
   AVR branch of rom.h).
3. Inside calib/, a subfolder includes only the calib subfolders its CMakeLists.txt declares
   (adahrs_calib_<folder> among its DEPS, followed transitively), so the order between them is
   the one the build states, and the declared graph has no cycle.
Prints every violation as file:line and exits 1 if there is any.
"""
import pathlib
import re
import sys

# Each wing and the wings it may include (besides itself). Folders of ours not named here may be
# included by nobody; tests/ and bench/ are not wings and may use everything.
MAY_INCLUDE = {
    "common": [],
    "sensor_sim": ["common"],
    "firmware_model": ["common"],
    "hil": ["common", "firmware_model"],
    "rig_sim": ["common", "sensor_sim", "firmware_model", "hil"],
    "calib": ["common", "firmware_model", "hil"],
    "diagnosis": ["common", "firmware_model", "hil", "calib"],
    "proving": ["common", "sensor_sim", "firmware_model", "hil", "rig_sim", "calib", "diagnosis"],
    "apps": ["common", "sensor_sim", "firmware_model", "hil", "rig_sim", "calib", "diagnosis",
             "proving"],
}
# Sub-wings with a stricter row of their own.
MAY_INCLUDE_SUBFOLDER = {
    "firmware_model/target": ["firmware_model/target"],
}
OURS = set(MAY_INCLUDE) | {"tests", "bench"}
SOURCE_SUFFIXES = {".h", ".hpp", ".c", ".cc", ".cpp"}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([./]*)([A-Za-z_]+)/([^">]*)[">]')
TARGET_BANNED = re.compile(
    r"\b(float|double|new|delete|malloc|calloc|realloc|free|throw|try|catch|namespace|class|"
    r"template|typename|constexpr|nullptr|static_cast|reinterpret_cast|const_cast|"
    r"dynamic_cast|using)\b"
    r"|std::|#\s*pragma\s+once")
TARGET_SUFFIXES = {".c", ".h"}
TARGET_SYSTEM_HEADERS = {"stdint.h", "stdbool.h", "stddef.h", "avr/pgmspace.h"}
TARGET_INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def sources(folder):
    return sorted(p for p in folder.rglob("*") if p.suffix in SOURCE_SUFFIXES and p.is_file())


def strip_comment(line):
    return line.split("//", 1)[0]


def includes(path):
    """(line number, top folder, rest of the path) of every include of one of our folders."""
    for number, line in enumerate(path.read_text().splitlines(), 1):
        match = INCLUDE.match(line)
        if match and match.group(2) in OURS:
            yield number, match.group(2), match.group(3)


def wing_violations(root):
    violations = []
    for wing, allowed in MAY_INCLUDE.items():
        for path in sources(root / wing):
            for number, folder, _ in includes(path):
                if folder != wing and folder not in allowed:
                    violations.append(f"{path.relative_to(root)}:{number}: {wing}/ may include "
                                      f"{', '.join(a + '/' for a in allowed) or 'nothing of ours'}"
                                      f", not {folder}/")
    for sub, allowed in MAY_INCLUDE_SUBFOLDER.items():
        for path in sources(root / sub):
            for number, folder, rest in includes(path):
                target = f"{folder}/{rest}"
                if not any(target.startswith(a + "/") for a in allowed):
                    violations.append(f"{path.relative_to(root)}:{number}: {sub}/ may include "
                                      f"only {', '.join(allowed)}/, not {target}")
    return violations


def target_violations(root):
    """Rule 2: firmware_model/target/ holds only C99 that the dsPIC's C compiler takes."""
    violations = []
    target = root / "firmware_model" / "target"
    files = sorted(p for p in target.rglob("*") if p.is_file())
    own_headers = {p.name for p in files if p.suffix == ".h"}
    for path in files:
        where = path.relative_to(root)
        if path.suffix not in TARGET_SUFFIXES:
            violations.append(f"{where}: firmware_model/target/ holds only C99 sources (.c, .h)")
            continue
        in_block_comment = False
        for number, line in enumerate(path.read_text().splitlines(), 1):
            stripped = line.strip()
            if in_block_comment:
                if "*/" in stripped:
                    in_block_comment = False
                continue
            if stripped.startswith("/*"):
                in_block_comment = "*/" not in stripped
                continue
            if stripped.startswith("*"):
                continue
            code = strip_comment(line)
            if TARGET_BANNED.search(code):
                violations.append(f"{where}:{number}: firmware_model/target/ must stay C99 and "
                                  f"target-clean: {stripped}")
            include = TARGET_INCLUDE.match(code)
            if include:
                system, header = include.group(1) == "<", include.group(2)
                if (system and header not in TARGET_SYSTEM_HEADERS) or (
                        not system and header not in own_headers):
                    violations.append(f"{where}:{number}: firmware_model/target/ includes only its "
                                      f"own headers by name and <stdint.h>, <stdbool.h>, "
                                      f"<stddef.h>: {stripped}")
    return violations


CALIB_DEP = re.compile(r"adahrs_calib_([a-z_]+)")
CALIB_INCLUDE = re.compile(r'^\s*#\s*include\s*"calib/([a-z_]+)/')


def calib_declared(root):
    """Each calib subfolder's declared calib dependencies, followed transitively."""
    direct = {}
    for cmake in sorted((root / "calib").glob("*/CMakeLists.txt")):
        direct[cmake.parent.name] = set(CALIB_DEP.findall(cmake.read_text()))
    closure = {}

    def visit(folder, path):
        if folder in path:
            raise ValueError("calib subfolders declare a cycle: " + " -> ".join(path + [folder]))
        if folder not in closure:
            reach = set()
            for dep in direct.get(folder, ()):
                reach |= {dep} | visit(dep, path + [folder])
            closure[folder] = reach
        return closure[folder]

    for folder in direct:
        visit(folder, [])
    return closure


def calib_order_violations(root):
    violations = []
    try:
        declared = calib_declared(root)
    except ValueError as e:
        return [f"calib/*/CMakeLists.txt: {e}"]
    for path in sources(root / "calib"):
        folder = path.relative_to(root / "calib").parts[0]
        for number, line in enumerate(path.read_text().splitlines(), 1):
            match = CALIB_INCLUDE.match(line)
            if match and match.group(1) != folder and match.group(1) not in declared.get(folder, set()):
                violations.append(f"{path.relative_to(root)}:{number}: calib/{folder}/ includes "
                                  f"calib/{match.group(1)}/, which calib/{folder}/CMakeLists.txt "
                                  f"does not declare (adahrs_calib_{match.group(1)})")
    return violations


def violations_of(root):
    root = pathlib.Path(root)
    return wing_violations(root) + target_violations(root) + calib_order_violations(root)


def main(root):
    violations = violations_of(root)
    for v in violations:
        print(v)
    if violations:
        print(f"architecture: {len(violations)} violation(s)")
        return 1
    print("architecture: every wing includes only what its row allows; firmware_model/target is "
          "C99 and target-clean")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
