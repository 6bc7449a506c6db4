#!/usr/bin/env python3
"""adahrs diagnose --csv: a real public recording through its JSON sidecar gives the documented
diagnosis.json (exit 0); a sidecar with a wrong version or a CSV with a bad cell is refused naming
the JSON path or the line and column (exit 1); --run and --csv together are a usage error.
Usage: diagnose_command_test.py ADAHRS"""
import hashlib
import json
import os
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT / "tests/data/pan_lsm6dsm_cold_tvac"


def run(adahrs, *args):
    return subprocess.run([adahrs, "diagnose", *args], capture_output=True, text=True, timeout=120)


def main(adahrs):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        good = run(adahrs, "--csv", str(DATA / "tvc_2020-03-07.json"), "--out", out)
        assert good.returncode == 0, good.stderr
        assert "PAN ETU LSM6DSM" in good.stdout, good.stdout
        with open(os.path.join(out, "diagnosis.json")) as f:
            d = json.load(f)
        assert d["format"] == "adahrs-diagnosis" and d["format_version"] == 1, d
        sha = hashlib.sha256((DATA / "TVCtest3_7_20.csv").read_bytes()).hexdigest()
        assert d["recording"][0]["sha256"] == sha, d["recording"]
        unit = d["units"][0]
        assert unit["rows"] == 6250 and unit["segments"] == 25, unit
        assert [c["channel"] for c in unit["channels"]] == ["gx", "gy", "gz"], unit["channels"]
        assert os.path.getsize(os.path.join(out, "report.html")) > 1000

        named = run(adahrs, "--csv", str(DATA / "tvc_2020-03-07.json"), "--profile", "nominal",
                    "--out", os.path.join(tmp, "named"))
        assert named.returncode == 0, named.stderr
        assert "compared with the nominal model" in named.stdout, named.stdout
        other = run(adahrs, "--csv", str(DATA / "tvc_2020-03-07.json"), "--profile", "truth",
                    "--out", os.path.join(tmp, "other"))
        assert other.returncode != 0 and "--profile" in other.stderr, other

        sidecar = json.loads((DATA / "tvc_2020-03-07.json").read_text())
        sidecar["format_version"] = 7
        sidecar["csv"] = str(DATA / "TVCtest3_7_20.csv")
        bad = os.path.join(tmp, "bad.json")
        with open(bad, "w") as f:
            json.dump(sidecar, f)
        result = run(adahrs, "--csv", bad, "--out", out)
        assert result.returncode == 1, result
        assert "bad.json: $.format_version: 7 is not a version" in result.stderr, result.stderr

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
        result = run(adahrs, "--csv", bad, "--out", out)
        assert result.returncode == 1, result
        assert "TVCtest3_7_20.csv line 6 column 5 ('gyrox rad/s'): 'nan?' is not a finite number" in result.stderr, \
            result.stderr

        both = run(adahrs, "--csv", bad, "--run", tmp, "--out", out)
        assert both.returncode != 0, both
        assert "excludes" in both.stderr, both.stderr
    print("ok")


if __name__ == "__main__":
    main(sys.argv[1])
