#!/usr/bin/env python3
"""`adahrs campaign` as a production PC runs it: `adahrs rig` started as a separate process stands
in for the hardware (4 IMUs, 1 ADS); the campaign only gets the rig's station files (one per bench)
and a campaign file with the shipped sequences in their --quick form.

1. An uninterrupted campaign completes: every run complete, every unit downloaded once and judged,
   records and reports present, and no truth file anywhere under its directory.
2. A second campaign (a fresh rig) is stopped with SIGTERM once inside the calibration runs and
   once after the download (inside the acceptance runs), exits 143 each time saying how to
   resume, and `adahrs campaign --resume DIR` completes it. Every unit is downloaded exactly once
   (counted in the records' downloads table, which has a row per attempt), and its records equal
   the uninterrupted campaign's apart from times, checksums and measured values.
3. Refusals: a malformed campaign file names the file and JSON path; a non-empty --out is refused.

Usage: campaign_command_test.py ADAHRS_BINARY
"""
import json
import pathlib
import re
import signal
import sqlite3
import subprocess
import sys
import tempfile
import time

SOURCE = pathlib.Path(__file__).resolve().parents[2]
SEQUENCES = SOURCE / "calib" / "sequences"
# Wall time allowed for one whole quick campaign on a loaded 2-core machine (it takes about 4 min
# alone at 900x: the ADS calibration's thermal profile is 64,716 simulated seconds).
CAMPAIGN_TIMEOUT_S = 1800


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def port(path, baud, flow):
    return {"path": path, "baud": baud, "data_bits": 8, "parity": "N", "stop_bits": 1,
            "flow": flow}


def bench_station(manifest, config, kind):
    """The IMU bench (rate table, IMU chamber, IMUs) or the ADS bench (942 chamber, ADTS, ADS).
    Instruments get 3 s of wall time per reply: four builds beside the test once starved the
    ADTS past 3 x 1 s at the start of a run."""
    bench_instruments = {"imu": ("aerosmith_atl", "watlow_f4"),
                         "ads": ("watlow_942", "druck_adts_prologix")}[kind]
    instruments = {}
    for inst in manifest["instruments"]:
        role, itype = inst["role"], inst["kind"]
        if itype not in bench_instruments:
            continue
        section = config["instruments"][itype]
        address, baud, flow = 0, 9600, "none"
        if itype == "watlow_f4":
            address = section["modbus_address"]
        if itype == "druck_adts_prologix":
            address, baud = section["gpib_address"], 115200
        if itype == "watlow_942":
            flow = "xonxoff"
        instruments[role] = {"type": itype, "port": port(manifest["links"][role], baud, flow),
                             "address": address, "timeout_ms": 3000, "retries": 2}
    units = [{"role": u["role"], "kind": u["kind"], "slot": u["slot"], "timeout_ms": 500,
              "port": port(manifest["links"][u["role"]], u["baud"], "none")}
             for u in manifest["units"] if u["kind"] == kind]
    return {"name": f"{kind} bench (campaign test)", "time_scale": manifest["time_scale"],
            "clock_file": manifest["clock"]["file"],
            "site": {"latitude_deg": manifest["station"]["latitude_deg"],
                     "height_m": manifest["station"]["height_m"]},
            "instruments": instruments, "units": units,
            "operator": {"type": "virtual_fixture",
                         "port": port(manifest["links"]["control"], 115200, "none")}}


class Rig:
    """`adahrs rig` in lockstep at 900x in its own directory, with a station file per bench."""

    def __init__(self, adahrs, directory):
        self.dir = directory
        self.dir.mkdir()
        config = json.loads(subprocess.check_output([adahrs, "rig", "--print-default-config"]))
        manifest_path = directory / "manifest.json"
        self.log = open(directory / "rig.log", "w")
        self.process = subprocess.Popen(
            [adahrs, "rig", "--manifest", str(manifest_path), "--time-scale", "900",
             "--lockstep"], stdout=self.log, stderr=subprocess.STDOUT)
        deadline = time.monotonic() + 30
        while not manifest_path.exists():
            if time.monotonic() > deadline or self.process.poll() is not None:
                self.stop()
                fail("the rig did not start")
            time.sleep(0.05)
        time.sleep(0.2)
        manifest = json.loads(manifest_path.read_text())
        self.imu_station = directory / "station-imu.json"
        self.ads_station = directory / "station-ads.json"
        self.imu_station.write_text(json.dumps(bench_station(manifest, config, "imu")))
        self.ads_station.write_text(json.dumps(bench_station(manifest, config, "ads")))

    def stop(self):
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            self.process.wait(timeout=60)
        self.log.close()


def campaign_file(tmp):
    path = tmp / "campaign.json"
    path.write_text(json.dumps({
        "format_version": 1, "name": "campaign test",
        "sequences": {
            "imu_calibration": [str(SEQUENCES / "imu_thermal_sensor_calibration.json")],
            "ads_calibration": str(SEQUENCES / "ads_calibration.json"),
            "imu_acceptance": str(SEQUENCES / "imu_acceptance.json"),
            "ads_acceptance": str(SEQUENCES / "ads_acceptance.json")},
        "fit": {"imu": "joint", "ads": "hysteresis_compensated"},
        "retest": {"max_attempts": 1}}))
    return path


def start(adahrs, rig, campaign, out):
    return subprocess.Popen(
        [adahrs, "campaign", "--campaign", str(campaign), "--station-imu", str(rig.imu_station),
         "--station-ads", str(rig.ads_station), "--out", str(out), "--quick"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def resume(adahrs, out):
    return subprocess.Popen([adahrs, "campaign", "--resume", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def finish(process, what):
    out, err = process.communicate(timeout=CAMPAIGN_TIMEOUT_S)
    print(f"--- {what}: exit {process.returncode}\n{out[-3000:]}\n{err[-2000:]}")
    return out, err


def stages_done(out):
    journal = out / "campaign-journal.json"
    if not journal.exists():
        return []
    return [s["stage"] for s in json.loads(journal.read_text())["stages"]]


def terminate_when(process, condition, what):
    """Sends SIGTERM once `condition()` holds; checks the exit status and the resume hint."""
    deadline = time.monotonic() + CAMPAIGN_TIMEOUT_S
    while not condition():
        if process.poll() is not None or time.monotonic() > deadline:
            process.kill()
            finish(process, what)
            fail(f"the campaign ended before {what}")
        time.sleep(0.05)
    process.send_signal(signal.SIGTERM)
    out, err = finish(process, what)
    if process.returncode != 128 + signal.SIGTERM:
        fail(f"exit status {process.returncode} after SIGTERM {what}, expected 143")
    if "adahrs campaign --resume" not in err:
        fail(f"no resume instruction after SIGTERM {what}: {err}")


def check_complete(out, status, what):
    if status not in (0, 4):
        fail(f"{what}: exit status {status}, expected 0 (all accepted) or 4 (a unit not)")
    for meta in (out / "runs").glob("*/meta.json"):
        if json.loads(meta.read_text())["status"] != "complete":
            fail(f"{what}: {meta} is not complete")
    runs = sorted(p.parent.name for p in (out / "runs").glob("*/meta.json"))
    if len(runs) != 4:
        fail(f"{what}: expected 4 runs (2 calibration, 2 acceptance), found {runs}")
    for run in runs:
        if not (out / "runs" / run / "report.html").exists():
            fail(f"{what}: no report.html in {run}")
    truth = [str(p) for p in out.rglob("*") if "truth" in p.name.lower()]
    if truth:
        fail(f"{what}: truth in the campaign's output: {truth}")
    if "records" not in stages_done(out):
        fail(f"{what}: the journal does not record the records stage: {stages_done(out)}")


def records_shape(out):
    """The records without times, checksums, run ids and measured values."""
    db = sqlite3.connect(out / "records.sqlite")
    q = lambda sql: sorted(db.execute(sql).fetchall())
    shape = {
        "units": q("SELECT serial, kind FROM units"),
        "runs": q("SELECT sequence_name, station_name, status FROM runs"),
        "run_units": q("SELECT r.sequence_name, u.serial, u.role, u.slot, u.mode "
                       "FROM run_units u JOIN runs r ON r.id = u.run"),
        "steps": q("SELECT r.sequence_name, s.step_index, s.kind, s.tag "
                   "FROM steps s JOIN runs r ON r.id = s.run"),
        "constants": q("SELECT serial, version, strategy, software_version FROM constants"),
        "downloads": q("SELECT c.serial, c.strategy, d.station_name, d.role, d.verified, "
                       "d.committed, d.detail FROM downloads d JOIN constants c "
                       "ON c.id = d.constants"),
        # A condition ends with the measured chamber temperature ("..., 25.1 degC"): a value.
        "acceptance": sorted((serial, quantity, re.sub(r", -?[0-9.]+ degC$", "", condition),
                              tolerance, unit) for serial, quantity, condition, tolerance, unit
                             in q("SELECT serial, quantity, condition, tolerance, unit "
                                  "FROM acceptance_results")),
    }
    db.close()
    return shape


def main():
    adahrs = sys.argv[1]
    with tempfile.TemporaryDirectory(prefix="adahrs-campaign-cli-") as tmp:
        tmp = pathlib.Path(tmp)
        campaign = campaign_file(tmp)

        bad = tmp / "bad.json"
        document = json.loads(campaign.read_text())
        document["fit"]["imu"] = "joint_format9"
        bad.write_text(json.dumps(document))
        refused = subprocess.run([adahrs, "campaign", "--campaign", str(bad), "--station-imu",
                                  str(tmp / "none.json"), "--out", str(tmp / "bad-out")],
                                 capture_output=True, text=True)
        if refused.returncode == 0 or str(bad) not in refused.stderr \
                or "$.fit.imu" not in refused.stderr:
            fail(f"malformed campaign file not refused with its path: {refused.stderr}")

        rig = Rig(adahrs, tmp / "rig-a")
        try:
            whole = tmp / "whole"
            t0 = time.monotonic()
            process = start(adahrs, rig, campaign, whole)
            finish(process, "uninterrupted campaign")
            print(f"uninterrupted quick campaign: {time.monotonic() - t0:.0f} s wall")
            check_complete(whole, process.returncode, "uninterrupted campaign")
        finally:
            rig.stop()
        again = subprocess.run([adahrs, "campaign", "--campaign", str(campaign), "--station-imu",
                                str(rig.imu_station), "--out", str(whole)],
                               capture_output=True, text=True)
        if again.returncode == 0 or "--resume" not in again.stderr:
            fail(f"a non-empty --out was not refused: {again.stderr}")

        rig = Rig(adahrs, tmp / "rig-b")
        try:
            interrupted = tmp / "interrupted"
            calibration_run = interrupted / "runs" / "imu_thermal_sensor_calibration_quick"
            process = start(adahrs, rig, campaign, interrupted)
            terminate_when(process,
                           lambda: (calibration_run / "journal.jsonl").exists()
                           and "step_completed" in (calibration_run / "journal.jsonl").read_text(),
                           "inside the calibration runs")
            if "calibration_runs" in stages_done(interrupted):
                fail("the calibration stage is journaled as done after SIGTERM inside it")
            process = resume(adahrs, interrupted)
            terminate_when(process, lambda: "downloads" in stages_done(interrupted),
                           "after the download")
            if "acceptance_runs" in stages_done(interrupted):
                fail("SIGTERM came too late: the acceptance runs had ended")
            process = resume(adahrs, interrupted)
            finish(process, "resumed campaign")
            check_complete(interrupted, process.returncode, "resumed campaign")
        finally:
            rig.stop()

        whole_shape, resumed_shape = records_shape(whole), records_shape(interrupted)
        downloads = [row[0] for row in resumed_shape["downloads"]]
        serials = [row[0] for row in resumed_shape["units"]]
        if len(serials) != 5 or sorted(downloads) != sorted(serials):
            fail(f"not every unit downloaded exactly once: units {serials}, downloads {downloads}")
        for table in whole_shape:
            if whole_shape[table] != resumed_shape[table]:
                fail(f"records differ in {table}:\n uninterrupted {whole_shape[table][:20]}\n"
                     f" resumed       {resumed_shape[table][:20]}")
    print("PASS")


if __name__ == "__main__":
    main()
