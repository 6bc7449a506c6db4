#!/usr/bin/env python3
"""The architecture check refuses an include across a wall: a copy of the real source tree, with
one include planted into a real file per wall, must fail at that file and line; the unplanted copy
must pass. Run: planted_include_test.py <project root>."""
import pathlib
import shutil
import sys
import tempfile
import unittest

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import check_architecture  # noqa: E402

ROOT = pathlib.Path(sys.argv.pop(1) if len(sys.argv) > 1 else HERE.parent.parent).resolve()
WINGS = ("common", "sensor_sim", "firmware_model", "hil", "rig_sim", "calib", "diagnosis",
         "proving", "apps")

# (file in the wing, planted include): one wall each.
PLANTS = [
    ("calib/acceptance/acceptance_judge.cc", '#include "sensor_sim/adxl210e.h"'),
    ("calib/campaign/campaign.cc", '#include "diagnosis/imu_diagnosis.h"'),
    ("calib/campaign/campaign.cc", '#include "proving/demo/truth_evaluation.h"'),
    ("calib/executor/executor.cc", '#include "rig_sim/rig.h"'),
    ("diagnosis/imu_diagnosis.cc", '#include "sensor_sim/imu_unit.h"'),
    ("diagnosis/imu_diagnosis.cc", '#include "proving/evaluation/truth_file.h"'),
    ("hil/station.cc", '#include "sensor_sim/atmosphere.h"'),
    ("hil/station.cc", '#include "calib/sequence/sequence.h"'),
    ("common/units.h", '#include "hil/station.h"'),
    ("rig_sim/rig.cc", '#include "calib/sequence/sequence.h"'),
    ("firmware_model/target/crc16.h", '#include "common/units.h"'),
    ("proving/studies/study_runner.cc", '#include "apps/commands.h"'),
]


class PlantedInclude(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.copy = pathlib.Path(cls.tmp.name)
        for wing in WINGS:
            shutil.copytree(ROOT / wing, cls.copy / wing)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_the_tree_as_it_is_passes(self):
        self.assertEqual(check_architecture.violations_of(self.copy), [])

    def test_each_planted_include_is_refused_at_its_line(self):
        for relative, include in PLANTS:
            with self.subTest(file=relative, include=include):
                path = self.copy / relative
                self.assertTrue(path.is_file(), f"{relative} is gone: update PLANTS")
                original = path.read_text()
                lines = original.splitlines()
                at = next(i for i, l in enumerate(lines) if l.startswith(("#include", "#pragma"))) + 1
                lines.insert(at, include)
                path.write_text("\n".join(lines) + "\n")
                try:
                    found = check_architecture.violations_of(self.copy)
                finally:
                    path.write_text(original)
                self.assertTrue(any(v.startswith(f"{relative}:{at + 1}:") for v in found),
                                f"planted {include} in {relative}:{at + 1}, check said {found}")


if __name__ == "__main__":
    unittest.main()
