#!/usr/bin/env python3
"""`adahrs campaign` refuses a unit by its serial before anything moves: on `adahrs rig` (a
separate process), an IMU-bench-only campaign whose file expects imu1's serial on imu2 and imu2's on
imu1 (two units swapped between ports) and the right serials on imu3 and imu4, on the short
sequences of campaign_command_test. The serials expected are the labels the rig's manifest gives
its units, not what the pipeline reads.
Checks: both swapped slots are refused naming role, serial read and serial expected; no run holds
them (meta.json units) and the records have no run, download or acceptance of theirs; imu3 and
imu4 complete (downloaded once, judged); exit status 4 (complete, a unit refused).

Usage: campaign_identity_test.py ADAHRS_BINARY
"""
import json
import pathlib
import sqlite3
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from campaign_command_test import CAMPAIGN_TIMEOUT_S, Rig, campaign_file, fail  # noqa: E402


def main():
    adahrs = sys.argv[1]
    with tempfile.TemporaryDirectory(prefix="adahrs-campaign-id-") as tmp:
        tmp = pathlib.Path(tmp)
        rig = Rig(adahrs, tmp / "rig")
        try:
            manifest = json.loads((rig.dir / "manifest.json").read_text())
            label = {u["role"]: u["serial"] for u in manifest["units"]}
            campaign = campaign_file(tmp)
            document = json.loads(campaign.read_text())
            document["expected_serials"] = {"imu1": label["imu2"], "imu2": label["imu1"],
                                            "imu3": label["imu3"], "imu4": label["imu4"]}
            campaign.write_text(json.dumps(document))
            out = tmp / "out"
            result = subprocess.run(
                [adahrs, "campaign", "--campaign", str(campaign), "--station-imu",
                 str(rig.imu_station), "--out", str(out), "--quick"],
                capture_output=True, text=True, timeout=CAMPAIGN_TIMEOUT_S)
            print(result.stdout[-4000:], result.stderr[-2000:])
        finally:
            rig.stop()
        if result.returncode != 4:
            fail(f"exit status {result.returncode}, expected 4 (complete, units refused)")
        for role, other in (("imu1", "imu2"), ("imu2", "imu1")):
            line = [x for x in result.stdout.splitlines() if x.startswith(f"refused: {role} ")]
            if not line or label[role] not in line[0] or label[other] not in line[0]:
                fail(f"no refusal of {role} naming {label[role]} and {label[other]}: {line}")
        for meta in (out / "runs").glob("*/meta.json"):
            roles = sorted(u["role"] for u in json.loads(meta.read_text())["units"])
            if roles != ["imu3", "imu4"]:
                fail(f"{meta} holds units {roles}, expected imu3 and imu4 only")
        db = sqlite3.connect(out / "records.sqlite")
        downloads = sorted(r[0] for r in db.execute(
            "SELECT c.serial FROM downloads d JOIN constants c ON c.id = d.constants"))
        judged = sorted(r[0] for r in db.execute("SELECT DISTINCT serial FROM acceptance_results"))
        in_runs = sorted(r[0] for r in db.execute("SELECT DISTINCT serial FROM run_units"))
        kept = sorted([label["imu3"], label["imu4"]])
        if downloads != kept or judged != kept or in_runs != kept:
            fail(f"records: downloads {downloads}, judged {judged}, in runs {in_runs}; "
                 f"expected {kept} each")
    print("PASS")


if __name__ == "__main__":
    main()
