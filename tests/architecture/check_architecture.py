#!/usr/bin/env python3
"""Our own check of the layering rules (the same rules as shared/tools/check-architecture).

1. One-way folder dependencies: apps -> calib -> hil -> firmware_model / sensor_sim, and
   rig_sim -> hil + sensor_sim + firmware_model. calib never includes rig_sim. common/ (units,
   random numbers, the parameter reader, the Allan estimator) is below them all and includes
   nothing of ours; firmware_model/target/ includes nothing of it (rule 3).
2. No inverse crime: calib/ code that turns recordings into constants, verdicts or diagnoses
   includes none of the simulator's sensor models (only evaluation/, campaign/ and study/, which
   judge against truth or draw units, may); calib/diagnosis/ includes nothing of sensor_sim/.
3. firmware_model/target/ is target-clean for the 16-bit dsPIC, whose compiler (MPLAB XC16) is a
   C compiler: only C99 sources (.c, .h), no C++ (namespaces, classes, templates, constexpr, casts
   of C++, nullptr, #pragma once), no floating point, heap or exceptions; it includes only its own
   headers (by bare name, so the folder drops into an MPLAB project as it is) and the C standard
   library's freestanding headers <stdint.h>, <stdbool.h>, <stddef.h> (and avr-libc's, in the
   AVR branch of rom.h).
4. Inside calib/, a subfolder includes only the calib subfolders its CMakeLists.txt declares
   (adahrs_calib_<folder> among its DEPS, followed transitively), so the order between them is
   the one the build states, and the declared graph has no cycle.
Prints every violation as file:line and exits 1 if there is any.
"""
import pathlib
import re
import sys

FORBID = {
    "common": ["sensor_sim", "firmware_model", "rig_sim", "hil", "calib", "apps"],
    "sensor_sim": ["firmware_model", "rig_sim", "hil", "calib", "apps"],
    "firmware_model": ["sensor_sim", "rig_sim", "hil", "calib", "apps"],
    "hil": ["rig_sim", "calib", "apps"],
    "calib": ["rig_sim", "apps"],
    "rig_sim": ["calib", "apps"],
}
# Folders below a top-level folder with a stricter rule of their own.
FORBID_SUBFOLDER = {
    "calib/diagnosis": ["sensor_sim", "rig_sim"],
}
SENSOR_MODELS = re.compile(
    r'^\s*#\s*include\s*[<"]sensor_sim/(adxl210e|adxrs150|adxrs150_params|pressure_bridge|'
    r'preisach_hysteresis|gyro_bias_process|imu_unit|ads_unit|ads1254|die_thermal|summed_adc|'
    r'duty_cycle_modulator|oat_probe)\.h')
MAY_USE_SENSOR_MODELS = ("evaluation", "campaign", "study", "studies")
SOURCE_SUFFIXES = {".h", ".hpp", ".cc", ".cpp", ".c"}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([./]*)([A-Za-z_]+)/')
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


def target_violations(root):
    """Rule 3: firmware_model/target/ holds only C99 that the dsPIC's C compiler takes."""
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


def main(root):
    root = pathlib.Path(root)
    violations = []
    for folder, forbidden in FORBID.items():
        for path in sources(root / folder):
            for number, line in enumerate(path.read_text().splitlines(), 1):
                match = INCLUDE.match(line)
                if match and match.group(2) in forbidden:
                    violations.append(f"{path.relative_to(root)}:{number}: {folder}/ must not "
                                      f"include {match.group(2)}/")
    for path in sources(root / "calib"):
        if path.relative_to(root / "calib").parts[0] in MAY_USE_SENSOR_MODELS:
            continue
        for number, line in enumerate(path.read_text().splitlines(), 1):
            if SENSOR_MODELS.match(line):
                violations.append(f"{path.relative_to(root)}:{number}: calib/ outside "
                                  f"{', '.join(MAY_USE_SENSOR_MODELS[:3])} must not include a "
                                  f"sensor model (no inverse crime)")
    for folder, forbidden in FORBID_SUBFOLDER.items():
        for path in sources(root / folder):
            for number, line in enumerate(path.read_text().splitlines(), 1):
                match = INCLUDE.match(line)
                if match and match.group(2) in forbidden:
                    violations.append(f"{path.relative_to(root)}:{number}: {folder}/ must not "
                                      f"include {match.group(2)}/ (no inverse crime)")
    violations += target_violations(root)
    violations += calib_order_violations(root)
    for v in violations:
        print(v)
    if violations:
        print(f"architecture: {len(violations)} violation(s)")
        return 1
    print("architecture: one-way dependencies hold; firmware_model/target is C99 and target-clean")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
