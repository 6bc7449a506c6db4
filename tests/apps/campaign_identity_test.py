#!/usr/bin/env python3
"""`adahrs campaign` refuses a unit by its serial before anything moves: on `adahrs rig` (a
separate process), an IMU-bench-only campaign whose file expects imu1's serial on imu2 and imu2's on
imu1 (two units swapped between ports) and the right serials on imu3 and imu4, on the short
sequences of campaign_command_test. The serials expected are the labels the rig's manifest gives
its units, not what the pipeline reads.
Checks: both swapped slots are refused naming role, serial read and serial expected; no run holds
them (meta.json units) and the records have no run, download or acceptance of theirs; imu3 and
imu4 complete (downloaded once, judged); exit status 4 (complete, a unit refused).

The campaign file also allows two acceptance attempts (docs/campaign.md "Retests"). The IMUs
calibrated by the short sequences fail their first acceptance (campaign_command_test's docstring),
which forces a retest. Checks: the units whose first acceptance.json says FAIL, and only those,
are run again in runs/imu_acceptance-attempt2 (its meta.json names them alone); the records hold
one attempt per judged unit and run, with the outcome its acceptance.json states; first-pass and
final yield, counted here from those acceptance.json files, are what `adahrs records yield --json`
and the campaign's summary line say. The campaign's certificates are checked in their PDF form
(check_certificates).

Usage: campaign_identity_test.py ADAHRS_BINARY
"""
import hashlib
import json
import pathlib
import sqlite3
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from campaign_command_test import CAMPAIGN_TIMEOUT_S, Rig, campaign_file, fail  # noqa: E402


def outcome_of(run_dir, serial):
    return json.loads((run_dir / "acceptance" / serial / "acceptance.json").read_text())["outcome"]


def check_report_page_one(run_dir, judged):
    """The acceptance run's report.html opens on the verdict: one row per unit with the outcome its
    acceptance.json states; the units recorded in mode 3 get no "missing from step" complaint."""
    root = ET.parse(run_dir / "report.html").getroot()
    sections = [e for e in root.iter() if e.tag.split("}")[-1] == "section"]
    if not sections or sections[0].get("id") != "verdict":
        fail(f"{run_dir}/report.html does not open on the verdict section")
    rows = {}
    for tr in sections[0].iter():
        cells = ["".join(td.itertext()) for td in tr if td.tag.split("}")[-1] == "td"]
        if len(cells) == 7:
            rows[cells[0]] = cells[2]
    expected = {s: outcome_of(run_dir, s) for s in judged}
    if rows != expected:
        fail(f"page one says {rows}, the acceptance files {expected}")
    text = "".join(root.itertext())
    if "is missing from step" in text:
        fail(f"{run_dir}/report.html still says a unit is missing from a step")
    # A real browser loads the page: Chromium's DOM after load holds the verdict and every figure.
    dom = subprocess.run(
        ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         f"--user-data-dir={run_dir.parent.parent / 'chromium-profile'}", "--dump-dom",
         (run_dir / "report.html").as_uri()], capture_output=True, text=True, timeout=120).stdout
    svgs = sum(1 for e in root.iter() if e.tag.split("}")[-1] == "svg")
    has_verdict = 'id="verdict"' in dom
    if not has_verdict or dom.count("<svg") != svgs or svgs < 3:
        fail(f"Chromium's DOM of {run_dir}/report.html: verdict section {has_verdict}, "
             f"{dom.count('<svg')} svg of {svgs} in the file")


def pdf_text(pdf):
    result = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True,
                            text=True, timeout=60)
    if result.returncode != 0:
        fail(f"pdftotext {pdf}: {result.stderr}")
    return " ".join(result.stdout.split())


def check_certificates(adahrs, out, judged):
    """A certificate per judged unit, as HTML and PDF: the PDF's text (Poppler's pdftotext, not our
    code) holds the serial, the outcome of the unit's last acceptance.json, the specification's
    SHA-256 that file names and the SHA-256 of the constants file the unit was given (hashlib).
    `adahrs report --certificate` writes the same from the run and the fit directory."""
    db = sqlite3.connect(out / "records.sqlite")
    last_run = dict(db.execute("SELECT serial, run_id FROM acceptance_attempts a WHERE attempt = "
                               "(SELECT max(attempt) FROM acceptance_attempts b WHERE "
                               "b.serial = a.serial)"))
    runs = {json.loads(m.read_text())["run_id"]: m.parent for m in (out / "runs").glob("*/meta.json")}
    fits = out / "fits" / "imu-joint"
    for serial in judged:
        acceptance = json.loads((runs[last_run[serial]] / "acceptance" / serial /
                                 "acceptance.json").read_text())
        constants_sha = hashlib.sha256((fits / f"{serial}.json").read_bytes()).hexdigest()
        wanted = [serial, f"Acceptance: {acceptance['outcome']}", acceptance["specification"]["sha256"],
                  constants_sha]
        pdf = out / "certificates" / f"{serial}.pdf"
        text = pdf_text(pdf)
        missing = [w for w in wanted if w not in text]
        if missing:
            fail(f"{pdf} lacks {missing}: {text[:1500]}")
        certs = out / "report-certificates" / last_run[serial]
        if not certs.exists():  # one report per run certifies every unit judged in it
            result = subprocess.run(
                [adahrs, "report", "--run", str(runs[last_run[serial]]), "--fit", str(fits),
                 "--out", str(out / "again.html"), "--certificate", str(certs), "--operator",
                 "T. Tester"], capture_output=True, text=True, timeout=300)
            if result.returncode != 0:
                fail(f"adahrs report --certificate: {result.stdout} {result.stderr}")
        text = pdf_text(certs / f"{serial}.pdf")
        missing = [w for w in wanted + ["T. Tester"] if w not in text]
        if missing:
            fail(f"report --certificate {serial}.pdf lacks {missing}")
    print(f"certificates: {len(judged)} units, PDF text checked")


def check_retests(adahrs, out, stdout, judged):
    first_run = next(d for d in (out / "runs").iterdir()
                     if d.name.startswith("imu_acceptance") and "-attempt" not in d.name)
    retest_run = first_run.with_name(first_run.name + "-attempt2")
    check_report_page_one(first_run, judged)
    first = {s: outcome_of(first_run, s) for s in judged}
    failed = sorted(s for s, o in first.items() if o == "FAIL")
    if not failed:
        fail(f"no unit failed its first acceptance ({first}): no retest to check; force one "
             "with a tighter specification file")
    retested = sorted(u["serial"] for u in json.loads((retest_run / "meta.json").read_text())["units"])
    if retested != failed:
        fail(f"retest run holds {retested}, the units that failed are {failed}")
    second = {s: outcome_of(retest_run, s) for s in failed}
    db = sqlite3.connect(out / "records.sqlite")
    rows = sorted(db.execute("SELECT serial, attempt, outcome, run_id FROM acceptance_attempts"))
    run_id = {1: json.loads((first_run / "meta.json").read_text())["run_id"],
              2: json.loads((retest_run / "meta.json").read_text())["run_id"]}
    expected = sorted([(s, 1, o, run_id[1]) for s, o in first.items()] +
                      [(s, 2, o, run_id[2]) for s, o in second.items()])
    if rows != expected:
        fail(f"acceptance_attempts rows {rows}, expected {expected}")
    passed = ("PASS", "MARGINAL")
    first_pass = sum(first[s] in passed for s in judged)
    final_pass = sum(second.get(s, first[s]) in passed for s in judged)
    report = json.loads(subprocess.run(
        [adahrs, "records", "yield", "--json", "--db", str(out / "records.sqlite")],
        capture_output=True, text=True, check=True).stdout)
    if len(report) != 1 or (report[0]["units_judged"], report[0]["first_pass"],
                            report[0]["final_pass"], report[0]["retested"]) != (
                                len(judged), first_pass, final_pass, len(failed)):
        fail(f"records yield {report}: expected {len(judged)} judged, first pass {first_pass}, "
             f"final {final_pass}, {len(failed)} retested")
    line = (f"first-pass yield {first_pass} of {len(judged)}", f"final yield {final_pass} of "
            f"{len(judged)}")
    if not all(part in stdout for part in line):
        fail(f"the campaign's summary does not say {line}")
    print(f"retests: first {first}, second {second}; yield first-pass {first_pass}, "
          f"final {final_pass} of {len(judged)}")


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
            document["retest"] = {"max_attempts": 2}
            document["fit"]["imu"] = "joint"  # the built-in downloaded: fits/imu-joint
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
        check_retests(adahrs, out, result.stdout, sorted([label["imu3"], label["imu4"]]))
        check_certificates(adahrs, out, sorted([label["imu3"], label["imu4"]]))
        for meta in (out / "runs").glob("*/meta.json"):
            roles = sorted(u["role"] for u in json.loads(meta.read_text())["units"])
            if "-attempt" in meta.parent.name:  # a retest: the failed units (check_retests)
                roles = sorted(set(roles) | {"imu3", "imu4"})
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
