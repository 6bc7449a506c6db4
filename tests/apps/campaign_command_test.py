#!/usr/bin/env python3
"""`adahrs campaign` as a production PC runs it: `adahrs rig` started as a separate process stands
in for the hardware (4 IMUs, 1 ADS); the campaign only gets the rig's station files (one per bench)
and a campaign file naming short variants of the shipped sequences, run with --quick.

The short variants (`write_short_sequences`) keep every shipped step kind, orientation, table rate
and the order of the temperatures, so that every fit keeps its design, but take the chamber only a
tenth of the way from 25 degC to each shipped temperature, soak 60 s, acquire 50 packets, keep
the ADS's altitudes up to 10,000 ft and airspeeds up to 150 kt (the dense part of the shipped
sweeps) and slew at the sequence limits' safe rates. The longest run's plan (`adahrs sequence
check`) is then 2.4 h instead of the --quick ADS calibration's 16 h, and a campaign takes about
1 min: what the test proves is the chain, the journal and the resume, not the units' accuracy
(the IMUs calibrated this way fail most of their acceptance points; exit status 4, "complete,
but a unit failed acceptance" in docs/campaign.md, is accepted beside 0).

1. An uninterrupted campaign completes: every run complete, every unit downloaded once and judged,
   records and reports present, and no truth file anywhere under its directory. Every report.html
   loads in headless Chromium without a console message and holds the figures of its run's kind
   with unit-labelled axes (report_checks.py).
2. A second campaign (a fresh rig) is stopped with SIGTERM once inside the calibration runs and
   once after the download (inside the acceptance runs), exits 143 each time saying how to
   resume, and `adahrs campaign --resume DIR` completes it. Every unit is downloaded exactly once
   (counted in the records' downloads table, which has a row per attempt), and its records equal
   the uninterrupted campaign's apart from times, checksums and measured values.
3. Refusals: a malformed campaign file names the file and JSON path; a non-empty --out is refused.
4. The IMU constants downloaded are the shipped Python reference strategy's (an external program,
   docs/strategies-external.md), fitted beside the built-ins: its constants agree with the
   built-in reference fit's of the same runs to 1e-9 of each output's span
   (constants_agreement.py).

Usage: campaign_command_test.py ADAHRS_BINARY
"""
import json
import pathlib
import re
import shutil
import signal
import sqlite3
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import report_checks  # noqa: E402
from constants_agreement import worst_agreement  # noqa: E402

SOURCE = pathlib.Path(__file__).resolve().parents[2]
SEQUENCES = SOURCE / "calib" / "sequences"
# Wall time allowed for one campaign process on a loaded 2-core machine (a whole short campaign
# takes about 1 min alone, 2.5 min under the sanitizers; ctest's TIMEOUT bounds the whole test,
# tests/CMakeLists.txt).
CAMPAIGN_TIMEOUT_S = 450
# The short variants: temperatures pulled towards 25 degC by this factor, soaks and acquisitions
# cut to these, ADS aims above these left out, slews at calib/sequence/sequence_limits.h's safe
# ADS rates.
TEMPERATURE_FACTOR = 0.1
SOAK_S = 60.0
PACKETS = 50
ALT_MAX_FT = 10000.0
CAS_MAX_KT = 150.0
ALT_RATE_FT_PER_MIN = 6000.0
CAS_RATE_KT_PER_MIN = 200.0
# The IMU constants downloaded: the shipped Python reference strategy, an external program
# (docs/strategies-external.md), whose constants must equal the built-in reference fit's.
PYTHON_STRATEGY = SOURCE / "strategies" / "python" / "python-reference.json"
EXTERNAL_AGREEMENT = 1e-9
SHIPPED = {"imu_calibration": "imu_thermal_sensor_calibration", "ads_calibration": "ads_calibration",
           "imu_acceptance": "imu_acceptance", "ads_acceptance": "ads_acceptance"}


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
    """`adahrs rig` in lockstep at 900x in its own directory, with a station file per bench;
    its units drawn with `model_profile` (the built-in configuration's when None)."""

    def __init__(self, adahrs, directory, model_profile=None):
        self.dir = directory
        self.dir.mkdir()
        config = json.loads(subprocess.check_output([adahrs, "rig", "--print-default-config"]))
        manifest_path = directory / "manifest.json"
        args = [adahrs, "rig", "--manifest", str(manifest_path), "--time-scale", "900",
                "--lockstep"]
        if model_profile is not None:
            config["units"]["model_profile"] = model_profile
            (directory / "rig.json").write_text(json.dumps(config))
            args += ["--config", str(directory / "rig.json")]
        self.log = open(directory / "rig.log", "w")
        self.process = subprocess.Popen(args, stdout=self.log, stderr=subprocess.STDOUT)
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


def near_room(target_c):
    return round(25.0 + TEMPERATURE_FACTOR * (target_c - 25.0), 1)


def shorten(document):
    """The short variant of a shipped sequence document (see the module's description)."""
    steps, dropped_aim = [], False
    for step in document["steps"]:
        step = dict(step)
        kind = step["kind"]
        if kind == "log" and dropped_aim:
            continue
        dropped_aim = (kind == "altitude" and step["alt_ft"] > ALT_MAX_FT) or \
                      (kind == "airspeed" and step["cas_kt"] > CAS_MAX_KT)
        if dropped_aim:
            continue
        if kind == "target_temperature":
            step["target_c"] = near_room(step["target_c"])
            step["soak_s"] = min(step["soak_s"], SOAK_S)
        if kind == "thermal_profile":
            step["profile_steps"] = [dict(p, target_c=near_room(p["target_c"]))
                                     if "target_c" in p else p for p in step["profile_steps"]]
        if "packets" in step:
            step["packets"] = min(step["packets"], PACKETS)
        if kind == "altitude":
            step["rate_ft_per_min"] = ALT_RATE_FT_PER_MIN
        if kind == "airspeed":
            step["rate_kt_per_min"] = CAS_RATE_KT_PER_MIN
        steps.append(step)
    return dict(document, name=document["name"] + "_short", steps=steps,
                description="Short variant for the campaign test (tests/apps/"
                            "campaign_command_test.py) of: " + document["description"])


def write_short_sequences(tmp):
    """The short variants of the shipped sequences in tmp/sequences; their paths by stage."""
    directory = tmp / "sequences"
    directory.mkdir(exist_ok=True)
    paths = {}
    for stage, name in SHIPPED.items():
        path = directory / f"{name}_short.json"
        path.write_text(json.dumps(shorten(json.loads((SEQUENCES / f"{name}.json").read_text())),
                                   indent=1))
        paths[stage] = str(path)
    return paths


def campaign_file(tmp):
    path = tmp / "campaign.json"
    sequences = write_short_sequences(tmp)
    path.write_text(json.dumps({
        "format_version": 1, "name": "campaign test",
        "sequences": {
            "imu_calibration": [sequences["imu_calibration"]],
            "ads_calibration": sequences["ads_calibration"],
            "imu_acceptance": sequences["imu_acceptance"],
            "ads_acceptance": sequences["ads_acceptance"]},
        "fit": {"imu": str(PYTHON_STRATEGY), "ads": "hysteresis_compensated"},
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
    db = sqlite3.connect(out / "records.sqlite")
    serials = sorted(r[0] for r in db.execute("SELECT serial FROM units"))
    downloads = sorted(r[0] for r in db.execute(
        "SELECT c.serial FROM downloads d JOIN constants c ON c.id = d.constants"))
    judged = sorted(r[0] for r in db.execute("SELECT DISTINCT serial FROM acceptance_results"))
    db.close()
    if len(serials) != 5 or downloads != serials:
        fail(f"{what}: not every unit downloaded exactly once: units {serials}, "
             f"downloads {downloads}")
    if judged != serials:
        fail(f"{what}: units {serials}, judged {judged}")
    for run in runs:
        if "acceptance" in run:
            judgements = list((out / "runs" / run / "acceptance").glob("*/acceptance.json"))
            if len(judgements) != (4 if run.startswith("imu") else 1):
                fail(f"{what}: {run} holds {len(judgements)} acceptance.json")


def check_external_fits(out, what):
    """The Python strategy's constants (downloaded) against the built-in reference fit of the same
    runs (constants_agreement.py: each difference's effect on the output over the fitted range,
    relative to its span); its request and reply kept beside them."""
    external, builtin = out / "fits" / "imu-python-reference", out / "fits" / "imu-reference"
    files = sorted(builtin.glob("IMU-*.json"))
    if len(files) != 4:
        fail(f"{what}: {len(files)} built-in reference fits")
    worst = (0.0, "")
    for path in files:
        mine = json.loads((external / path.name).read_text())
        if mine["strategy"] != "python-reference" or "external" not in mine["provenance"] or \
                not (external / f"{path.stem}.request.json.gz").exists():
            fail(f"{what}: {external / path.name} is not the Python strategy's fit")
        value, where = worst_agreement(mine["constants"], json.loads(path.read_text())["constants"])
        worst = max(worst, (value, f"{path.stem} {where}"))
    print(f"{what}: the Python reference strategy agrees with the built-in to {worst[0]:.2g} "
          f"(worst: {worst[1]})")
    if worst[0] > EXTERNAL_AGREEMENT:
        fail(f"{what}: the Python reference strategy differs from the built-in: {worst}")


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
        # One attempt per unit (no retest allowed), recorded once however often resumed.
        "attempts": q("SELECT serial, role, attempt FROM acceptance_attempts"),
    }
    db.close()
    return shape


def main():
    # The campaigns' directories and the rigs' logs are kept when the test fails (under the
    # suite's scratch directory, which scripts/test keeps after a failure), removed when it passes.
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="adahrs-campaign-cli-"))
    try:
        campaigns(sys.argv[1], tmp)
    except BaseException:
        print(f"campaign test files kept in {tmp}")
        raise
    shutil.rmtree(tmp)
    print("PASS")


def campaigns(adahrs, tmp):
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
        check_external_fits(whole, "uninterrupted campaign")
    finally:
        rig.stop()
    report_checks.check_reports(sorted(p.parent for p in (whole / "runs").glob("*/meta.json")),
                                tmp / "chromium-profile")
    again = subprocess.run([adahrs, "campaign", "--campaign", str(campaign), "--station-imu",
                            str(rig.imu_station), "--out", str(whole)],
                           capture_output=True, text=True)
    if again.returncode == 0 or "--resume" not in again.stderr:
        fail(f"a non-empty --out was not refused: {again.stderr}")

    rig = Rig(adahrs, tmp / "rig-b")
    try:
        interrupted = tmp / "interrupted"
        calibration_run = interrupted / "runs" / "imu_thermal_sensor_calibration_short_quick"
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
        check_external_fits(interrupted, "resumed campaign")
    finally:
        rig.stop()

    whole_shape, resumed_shape = records_shape(whole), records_shape(interrupted)
    for table in whole_shape:
        if whole_shape[table] != resumed_shape[table]:
            fail(f"records differ in {table}:\n uninterrupted {whole_shape[table][:20]}\n"
                 f" resumed       {resumed_shape[table][:20]}")


if __name__ == "__main__":
    main()
