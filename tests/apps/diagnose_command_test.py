#!/usr/bin/env python3
"""adahrs diagnose --csv: a real public recording through its JSON sidecar gives the documented
diagnosis.json (exit 0), the generic model named and each output's bias slope printed; a sidecar
with a wrong version is refused naming the JSON path (exit 1); a CSV row with a bad cell is skipped
with a note naming its line and column; --run and --csv together are a usage error.
Usage: diagnose_command_test.py ADAHRS"""
import hashlib
import json
import os
import pathlib
import subprocess
import sys
import tempfile

from app_checks import expect

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT / "tests/data/pan_lsm6dsm_cold_tvac"


def run(adahrs, *args):
    return subprocess.run([adahrs, "diagnose", *args], capture_output=True, text=True, timeout=120)


def main(adahrs):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        good = run(adahrs, "--csv", str(DATA / "tvc_2020-03-07.json"), "--out", out)
        expect(good.returncode == 0, good.stderr)
        expect("PAN ETU LSM6DSM" in good.stdout, good.stdout)
        with open(os.path.join(out, "diagnosis.json")) as f:
            d = json.load(f)
        expect(d["format"] == "adahrs-diagnosis" and d["format_version"] == 1, d)
        sha = hashlib.sha256((DATA / "TVCtest3_7_20.csv").read_bytes()).hexdigest()
        expect(d["recording"][0]["sha256"] == sha, d["recording"])
        unit = d["units"][0]
        expect(unit["rows"] == 6250 and unit["segments"] == 25, unit)
        expect([c["channel"] for c in unit["channels"]] == ["gx", "gy", "gz"], unit["channels"])
        expect(os.path.getsize(os.path.join(out, "report.html")) > 1000)

        # The summary names the model a --csv recording is compared with: the generic thermal
        # model, not the pipeline's; and it prints each output's bias slope against temperature.
        expect("compared with: generic thermal model" in good.stdout, good.stdout)
        expect("pipeline" not in good.stdout.splitlines()[0], good.stdout)
        for ch in ("gx", "gy", "gz"):
            expect(f"  {ch}: bias slope against temperature " in good.stdout, good.stdout)
            slope = unit["channels"][[c["channel"] for c in unit["channels"]].index(ch)]
            expect(slope["bias_slope_per_degc"]["unit"] == "dps/degC", slope)
            expect(slope["bias_slope_per_degc"]["standard_error"] > 0, slope)
        expect("verdict: " in good.stdout, good.stdout)
        expect(unit["verdict"] in good.stdout, (unit["verdict"], good.stdout))
        other = run(adahrs, "--csv", str(DATA / "tvc_2020-03-07.json"), "--profile", "truth",
                    "--out", os.path.join(tmp, "other"))
        expect(other.returncode != 0 and "--profile" in other.stderr, other)

        sidecar = json.loads((DATA / "tvc_2020-03-07.json").read_text())
        sidecar["format_version"] = 7
        sidecar["csv"] = str(DATA / "TVCtest3_7_20.csv")
        bad = os.path.join(tmp, "bad.json")
        with open(bad, "w") as f:
            json.dump(sidecar, f)
        result = run(adahrs, "--csv", bad, "--out", out)
        expect(result.returncode == 1, result)
        expect("bad.json: $.format_version: 7 is not a version" in result.stderr, result.stderr)

        lines = (DATA / "TVCtest3_7_20.csv").read_text().splitlines()
        cells = lines[5].split(",")
        cells[4] = "nan?"  # gyrox, a column the sidecar maps
        lines[5] = ",".join(cells)
        with open(os.path.join(tmp, "TVCtest3_7_20.csv"), "w") as f:
            f.write("\n".join(lines) + "\n")
        sidecar["format_version"] = 1
        sidecar["csv"] = "TVCtest3_7_20.csv"
        with open(bad, "w") as f:
            json.dump(sidecar, f)
        # A row that does not parse is counted and skipped with a note naming it, not a refusal.
        result = run(adahrs, "--csv", bad, "--out", out)
        expect(result.returncode == 0, result)
        expect("TVCtest3_7_20.csv: 1 of 6250 rows do not parse and were skipped" in result.stdout, result.stdout)
        expect("TVCtest3_7_20.csv line 6 column 5 ('gyrox rad/s'): 'nan?' is not a finite number" in result.stdout, result.stdout)
        with open(os.path.join(out, "diagnosis.json")) as f:
            expect(json.load(f)["units"][0]["rows"] == 6249)

        both = run(adahrs, "--csv", bad, "--run", tmp, "--out", out)
        expect(both.returncode != 0, both)
        expect("excludes" in both.stderr, both.stderr)
    print("ok")


if __name__ == "__main__":
    main(sys.argv[1])
