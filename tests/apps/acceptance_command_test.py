#!/usr/bin/env python3
"""adahrs acceptance end to end on a hand-written ADS recording (format 2): the test set's static
pressure from ISA computed here (independently of sensor_sim), the unit reading the reference
altitude + 14 ft (passes +-15 ft at 5,000 ft: exit 0, MARGINAL: inside the shipped -A file's band
of 0.1 x 15 ft) or + 16 ft (fails: exit 1); raw-mode rows are bad input (exit 2, naming run, unit
and step). With --db the points land in the records' acceptance_results, read back with Python's
sqlite3. The specification's SHA-256 in acceptance.json and in the records is the one hashlib
computes over the shipped file's bytes, for the default (-A) and for --specification (-B); a
malformed --specification is bad input naming the file and JSON path.
Usage: acceptance_command_test.py ADAHRS"""
import hashlib
import json
import pathlib
import sqlite3
import subprocess
import sys
import tempfile

from app_checks import expect

IMU_HEADER = ("t_s,unit,seq,step,tag,orientation,chamber_c,table_rate_dps,"
              "az1_t1,az1_t2,ax1_t1,ax1_t2,ay1_t1,ay1_t2,az2_t1,az2_t2,ax2_t1,ax2_t2,ay2_t1,ay2_t2,"
              "gx,gy,gz,tx,ty,tz,mode,comp0,comp1,comp2,comp3,comp4,comp5,comp6,comp7,comp8,comp_flags")
ADS_HEADER = ("t_s,unit,seq,step,tag,chamber_c,ps_ref_pa,qc_ref_pa,ps_counts,pt_counts,"
              "ps_temp_counts,pt_temp_counts,oat_counts,mode,alt_ft,cas_kt,comp_flags")


def isa_static_pa(alt_ft):
    # ISA troposphere: p0 (1 - L h / T0)^(g0 / (R L)), ICAO Doc 7488.
    h_m = alt_ft * 0.3048
    return 101325.0 * (1.0 - 0.0065 * h_m / 288.15) ** (9.80665 / (287.05287 * 0.0065))


SPEC_DIR = pathlib.Path(__file__).resolve().parents[2] / "calib" / "specifications"


def sha256_of(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, timeout=60)


def write_run(run_dir, error_ft, mode=1):
    run_dir.mkdir(parents=True)
    sequence = {"format_version": 1, "name": "ads_acceptance_small", "description": "5,000 ft",
                "unit_kind": "ads",
                "steps": [{"kind": "altitude", "alt_ft": 5000.0, "rate_ft_per_min": 3000.0},
                          {"kind": "log", "packets": 50}]}
    meta = {"format_version": 2, "run_id": f"acc-{error_ft}-{mode}", "started_utc": "2026-11-22T08:00:00Z",
            "status": "complete", "station": {"name": "virtual lab"}, "sequence": sequence,
            "sequence_file": "ads_acceptance_small.json", "time_base": "s", "sample_rate_hz": 100,
            "units": [{"role": "ads1", "kind": "ads", "serial": "ADS-0009", "serial_number": 9,
                       "firmware": "1.0.0", "slot": 1, "constants_version": 1, "mode": mode}],
            "instruments": [], "rejected_intervals": []}
    (run_dir / "meta.json").write_text(json.dumps(meta))
    (run_dir / "imu.csv").write_text(IMU_HEADER + "\n")
    rows = [ADS_HEADER]
    ps_pa = isa_static_pa(5000.0)
    for i in range(50):
        comp = f"{5000.0 + error_ft + (0.5 if i % 2 else -0.5)},0,0" if mode else ",,"
        rows.append(f"{i * 0.01},ADS-0009,{i},1,2,25,{ps_pa!r},0,1000,1000,10,10,10,{mode},{comp}")
    (run_dir / "ads.csv").write_text("\n".join(rows) + "\n")


def main(adahrs):
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        db = tmp / "records.sqlite"

        write_run(tmp / "pass", 14.0)
        ok = run(adahrs, "acceptance", "--run", tmp / "pass", "--db", db)
        expect(ok.returncode == 0, (ok.returncode, ok.stdout, ok.stderr))
        expect("ADS-0009: MARGINAL" in ok.stdout, ok.stdout)
        expect("acceptance: PASS" in ok.stdout, ok.stdout)
        doc = json.loads((tmp / "pass" / "acceptance" / "ADS-0009" / "acceptance.json").read_text())
        expect(doc["format"] == "adahrs-acceptance" and doc["verdict"] == "pass", doc)
        expect(doc["outcome"] == "MARGINAL" and doc["points"][0]["outcome"] == "MARGINAL", doc)
        a_sha = sha256_of(SPEC_DIR / "ahr150a-a.json")
        expect(doc["specification"]["sha256"] == a_sha, (doc["specification"], a_sha))
        expect(doc["specification"]["name"] == "AHR150A-A", doc["specification"])
        (point,) = doc["points"]
        expect(point["quantity"] == "altitude" and point["tolerance"] == 15.0, point)
        expect(abs(point["reference"] - 5000.0) < 0.01, point)  # our ISA and the judge's agree
        expect(abs(point["error"] - 14.0) < 0.01, point)

        write_run(tmp / "fail", 16.0)
        bad = run(adahrs, "acceptance", "--run", tmp / "fail", "--out", tmp / "out", "--db", db)
        expect(bad.returncode == 1, (bad.returncode, bad.stdout, bad.stderr))
        expect("FAIL" in bad.stdout and (tmp / "out" / "ADS-0009" / "acceptance.json").exists())

        b_sha = sha256_of(SPEC_DIR / "ahr150a-b.json")
        b_run = run(adahrs, "acceptance", "--run", tmp / "pass", "--out", tmp / "b",
                    "--specification", SPEC_DIR / "ahr150a-b.json", "--db", db)
        expect(b_run.returncode == 0, (b_run.returncode, b_run.stdout, b_run.stderr))
        b_doc = json.loads((tmp / "b" / "ADS-0009" / "acceptance.json").read_text())
        expect(b_doc["specification"]["sha256"] == b_sha != a_sha, b_doc["specification"])
        expect(b_doc["specification"]["rated_rate_dps"] == 300.0, b_doc["specification"])

        broken = json.loads((SPEC_DIR / "ahr150a-a.json").read_text())
        del broken["quantities"]["altitude"]["input_max_ft"]
        (tmp / "broken.json").write_text(json.dumps(broken))
        refused = run(adahrs, "acceptance", "--run", tmp / "pass", "--out", tmp / "c",
                      "--specification", tmp / "broken.json")
        expect(refused.returncode == 2, (refused.returncode, refused.stdout, refused.stderr))
        for text in (str(tmp / "broken.json"), "$.quantities.altitude.input_max_ft", "missing"):
            expect(text in refused.stderr, refused.stderr)
        expect(not (tmp / "c").exists())

        write_run(tmp / "raw", 0.0, mode=0)
        raw = run(adahrs, "acceptance", "--run", tmp / "raw")
        expect(raw.returncode == 2, (raw.returncode, raw.stdout, raw.stderr))
        for text in (str(tmp / "raw"), "unit ADS-0009", "step 1 (log", "raw mode"):
            expect(text in raw.stderr, raw.stderr)

        again = run(adahrs, "acceptance", "--run", tmp / "fail", "--out", tmp / "out2", "--db", db)
        expect(again.returncode == 1 and "already recorded" in again.stdout, again.stdout)
        expect((tmp / "out2" / "ADS-0009" / "acceptance.json").read_bytes() == \
            (tmp / "out" / "ADS-0009" / "acceptance.json").read_bytes())

        with sqlite3.connect(db) as connection:
            rows = connection.execute(
                "SELECT serial, run_id, quantity, condition, error, tolerance, unit, pass, "
                "outcome, specification_sha256 FROM acceptance_results ORDER BY id").fetchall()
        # The pass run, the fail run, the pass run judged against -B; the fail run's second
        # judgement recorded once.
        expect([r[1] for r in rows] == ["acc-14.0-1", "acc-16.0-1", "acc-14.0-1"], rows)
        expect([r[8] for r in rows] == ["MARGINAL", "FAIL", "MARGINAL"], rows)
        expect([r[9] for r in rows] == [a_sha, a_sha, b_sha], rows)
        expect(rows[0][0] == "ADS-0009" and rows[0][2] == "altitude" and rows[0][7] == 1, rows)
        expect(rows[0][3] == "step 1, 5000 ft, 25.0 degC", rows)
        expect(abs(rows[1][4] - 16.0) < 0.01 and rows[1][5] == 15.0 and rows[1][6] == "ft", rows)
        expect(rows[1][7] == 0, rows)
    print("ok")


if __name__ == "__main__":
    main(sys.argv[1])
