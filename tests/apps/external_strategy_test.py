#!/usr/bin/env python3
"""adahrs fit with a strategy program (docs/strategies-external.md), on a small IMU run written here
as the executor writes one (meta.json format 2, imu.csv): a thermal_profile ramp and a 100-row
accel acquisition, with raw counts from closed forms:

1. a well-behaved program fits: its constants are written as it replied, the request and reply it
   saw are kept (gzip) beside them and their SHA-256 (computed here with hashlib) are those the
   constants file's provenance records, with the strategy file's; its log lines are printed; the
   request holds the recording's SHA-256, the acquisition's mean duty and counts as computed here
   from the rows, and every thermal row (its band sums, recomputed here from the rows); the request
   and the reply validate against docs/schemas/ (python3-jsonschema, Draft 2020-12);
2. hostile programs are refused, each with the program and the cause named, and the output
   directory left byte for byte as it was: one that hangs (killed at its timeout), exits 3, writes
   half a JSON object, writes NaN, writes a null constant, writes a constant the firmware cannot
   hold, never reads its request, is not there at all;
3. `fit --replay` runs the program again on the kept request: the same program reproduces the
   constants bit for bit; an edited program is caught at the first constant that differs (exit
   1); a kept request that is not the one recorded is refused;
4. strategy files that cannot run are refused with their JSON path before anything runs.

Usage: external_strategy_test.py ADAHRS"""
import gzip
import hashlib
import json
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time

import jsonschema

ROOT = pathlib.Path(__file__).resolve().parents[2]

HEAD = """import json, sys
request = json.load(sys.stdin)
serial = request["serial"]
def constants():
    channels = request["channels"]
    thermal = [{"temp_sensor": c["thermometer"], "k": [1e-3, -1e-7, 2e-12, 0.0],
                "temp_min_cnt": 26000.0, "temp_max_cnt": 40000.0} for c in channels]
    accel = [{"offset_duty": 0.001 * i, "scale_duty_per_g": 0.04 * c["sign"]}
             for i, c in enumerate(channels[:6])]
    gyro = [{"null_cnt": 100.0 * g, "l": [0.1, 4.7e-5, 1e-15, -1e-20]} for g in range(3)]
    eye = [[1.0 if i == j else 0.0 for j in range(3)] for i in range(3)]
    return {"thermal": thermal, "accel": accel, "gyro": gyro,
            "ca_mps2_per_g": [[9.8 * x for x in row] for row in eye], "cg": eye}
def reply(c, **extra):
    out = {"protocol": "adahrs-strategy-reply", "protocol_version": 1, "serial": serial,
           "constants": c}
    out.update(extra)
    return out
"""
PROGRAMS = {
    "good": HEAD + """
bands = request["thermal"]["bands"]
rows = sum(b["count"] for b in bands if b["thermometer"] == 0)
print("fitting", serial, file=sys.stderr)
print(json.dumps(reply(constants(), log=[f"{rows} thermal rows", "done"]), allow_nan=False))
""",
    "hangs": "import time\ntime.sleep(600)\n",
    "exits3": HEAD + "print('cannot fit: no six positions', file=sys.stderr)\nsys.exit(3)\n",
    "half": HEAD + "sys.stdout.write(json.dumps(reply(constants()))[:150])\n",
    "nan": HEAD + """c = constants()
c["cg"][1][1] = float("nan")
print(json.dumps(reply(c)))
""",
    "null": HEAD + """c = constants()
c["gyro"][2]["l"][1] = None
print(json.dumps(reply(c)))
""",
    "range": HEAD + """c = constants()
c["thermal"][3]["k"][0] = 5.0
print(json.dumps(reply(c)))
""",
    "deaf": """import json, sys
print(json.dumps({"protocol": "adahrs-strategy-reply", "protocol_version": 1,
                  "serial": "IMU-0001", "constants": {}}))
""",
}
# (program, timeout_s, what the refusal must say)
HOSTILE = [
    ("hangs", 2, "did not finish in 2 s and was killed"),
    ("exits3", 60, "exit status 3; the end of its stderr:\ncannot fit: no six positions"),
    ("half", 60, "reply refused: its standard output is not one JSON object"),
    ("nan", 60, "reply refused: its standard output is not one JSON object"),
    ("null", 60, "reply refused: the reply: $.constants.gyro[2].l[1]"),
    ("range", 60, "not representable in the firmware's constant blocks"),
    ("deaf", 60, "exited without reading its whole request from stdin"),
    ("missing", 60, "did not start: No such file or directory"),
]


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def run(*args, expect=0):
    r = subprocess.run([str(a) for a in args], capture_output=True, text=True, timeout=300)
    print(f"$ {' '.join(str(a) for a in args[1:])} -> {r.returncode}\n{r.stdout[-2000:]}"
          f"{r.stderr[-2000:]}", end="")
    if expect is not None and r.returncode != expect:
        fail(f"exit status {r.returncode}, expected {expect}")
    return r


def strategy(tmp, name, timeout_s=60, **extra):
    path = tmp / f"{name}.json"
    program = ["python3", f"{name}.py"] if name != "missing" else ["adahrs-no-such-fitter"]
    doc = {"format": "adahrs-imu-strategy", "format_version": 1, "strategy": f"test-{name}",
           "program": program, "timeout_s": timeout_s}
    doc.update(extra)
    path.write_text(json.dumps(doc))
    if name in PROGRAMS:
        (tmp / f"{name}.py").write_text(PROGRAMS[name])
    return path


def snapshot(directory):
    return {p.relative_to(directory): p.read_bytes() for p in sorted(directory.rglob("*"))
            if p.is_file()}


IMU_COLUMNS = ("t_s,unit,seq,step,tag,orientation,chamber_c,table_rate_dps,az1_t1,az1_t2,ax1_t1,"
               "ax1_t2,ay1_t1,ay1_t2,az2_t1,az2_t2,ax2_t1,ax2_t2,ay2_t1,ay2_t2,gx,gy,gz,tx,ty,tz,"
               "mode,comp0,comp1,comp2,comp3,comp4,comp5,comp6,comp7,comp8,comp_flags")
ADS_COLUMNS = ("t_s,unit,seq,step,tag,chamber_c,ps_ref_pa,qc_ref_pa,ps_counts,pt_counts,"
               "ps_temp_counts,pt_temp_counts,oat_counts,mode,alt_ft,cas_kt,comp_flags")
SEQUENCE = {"format_version": 1, "name": "external_strategy_test", "unit_kind": "imu",
            "description": "a thermal ramp and one accel acquisition", "steps": [
    {"kind": "thermal_profile", "profile_name": "DOWN",
     "profile_steps": [{"type": "ramp_rate", "target_c": 5.0, "rate_c_per_min": 1.0},
                       {"type": "end", "action": "hold"}]},
    {"kind": "accel", "orientation": 31, "packets": 100}]}
THERMAL_ROWS = 3000


def raw_row(i, temp_c):
    """One packet's raw counts at die temperature temp_c: duties drifting with temperature, TEMP
    counts 110 per degC."""
    t2 = 29727
    t1 = [round(t2 * (0.5 + 0.04 * k - 0.001 * (temp_c - 25.0)) + (i * 7 + k) % 5)
          for k in range(6)]
    gyro = [4000000 + 1500 * round(temp_c) + 37 * ((i + g) % 11) for g in range(3)]
    temp = [30000 + round(110 * temp_c) + j + (i % 3) for j in range(3)]
    return [v for k in range(6) for v in (t1[k], t2)] + gyro + temp


def write_run(run_dir):
    """The run's directory; returns the rows of each step as lists of raw counts."""
    run_dir.mkdir()
    unit = {"role": "imu1", "kind": "imu", "serial": "IMU-0001", "serial_number": 1,
            "firmware": "1.0.0", "slot": 1, "constants_version": 0, "mode": 0}
    meta = {"format_version": 2, "run_id": "r-ext", "started_utc": "2026-12-08T08:00:00Z",
            "status": "complete", "station": {"name": "virtual lab"}, "sequence": SEQUENCE,
            "sequence_file": "external_strategy_test.json", "time_base": "s",
            "sample_rate_hz": 100, "local_gravity_mps2": 9.79, "units": [unit],
            "instruments": [], "rejected_intervals": []}
    (run_dir / "meta.json").write_text(json.dumps(meta))
    lines, steps, t_s = [IMU_COLUMNS], {0: [], 1: []}, 0.0
    for step, count in ((0, THERMAL_ROWS), (1, 100)):
        for i in range(count):
            t_s += 0.01
            temp_c = 25.0 - 20.0 * i / THERMAL_ROWS if step == 0 else 5.0
            raw = raw_row(i, temp_c)
            steps[step].append(raw)
            lines.append(f"{t_s:.4f},IMU-0001,{i % 256},{step},{step % 250 + 1},31,{temp_c:.3f},"
                         f"0.0000,{','.join(map(str, raw))},0,,,,,,,,,,")
    (run_dir / "imu.csv").write_text("\n".join(lines) + "\n")
    (run_dir / "ads.csv").write_text(ADS_COLUMNS + "\n")
    return steps


def check_request(req, steps):
    """The request's acquisition means and thermal band sums against the rows written."""
    acquisition = req["acquisitions"][0]
    rows = steps[1]
    duty = [sum(r[2 * k] / r[2 * k + 1] - 0.5 for r in rows) / len(rows) for k in range(6)]
    gyro = [sum(r[12 + g] for r in rows) / len(rows) for g in range(3)]
    for got, want in zip(acquisition["u_mean"], duty + gyro):
        if abs(got - want) > 1e-12 * max(1.0, abs(want)):
            fail(f"acquisition u_mean {acquisition['u_mean']}, computed {duty + gyro}")
    if acquisition["count"] != 100 or acquisition["orientation"] != 31 or len(req["acquisitions"]) != 1:
        fail(f"acquisitions {[(a['count'], a['orientation']) for a in req['acquisitions']]}")
    width = req["thermal"]["band_width_cnt"]
    for j in range(3):
        bands = {}
        for r in steps[0]:
            t = r[15 + j]
            band = t // width
            d = t - band * width
            sums = bands.setdefault(band, [0, 0, 0, 0, 0])
            sums[0] += 1
            for k in range(1, 5):
                sums[k] += d ** k
        got = {}
        for b in req["thermal"]["bands"]:
            if b["thermometer"] == j:
                sums = got.setdefault(b["band"], [0, 0, 0, 0, 0])
                sums[0] += b["count"]
                for k in range(4):
                    sums[k + 1] += b["d_sums"][k]
        if got != bands:
            fail(f"thermometer {j}: band sums {got}, computed from the rows {bands}")


def check_good(adahrs, tmp, run_dir, steps):
    out = tmp / "good-fit"
    r = run(adahrs, "fit", "--run", run_dir, "--strategy", strategy(tmp, "good"), "--out", out)
    constants = json.loads((out / "IMU-0001.json").read_text())
    request = gzip.decompress((out / "IMU-0001.request.json.gz").read_bytes())
    reply = gzip.decompress((out / "IMU-0001.reply.json.gz").read_bytes())
    external = constants["provenance"]["external"]
    expected = {"program": ["python3", "good.py"], "strategy_file": str(tmp / "good.json"),
                "strategy_sha256": hashlib.sha256((tmp / "good.json").read_bytes()).hexdigest(),
                "request_sha256": hashlib.sha256(request).hexdigest(),
                "reply_sha256": hashlib.sha256(reply).hexdigest()}
    if external != expected:
        fail(f"provenance.external {external}, expected {expected}")
    if constants["strategy"] != "test-good" or \
            constants["constants"] != json.loads(reply)["constants"]:
        fail("the constants file does not hold the reply's constants under the strategy's name")
    req = json.loads(request)
    for document, schema in ((req, "strategy-request"), (json.loads(reply), "strategy-reply")):
        schema_doc = json.loads((ROOT / "docs" / "schemas" / f"{schema}.schema.json").read_text())
        try:
            jsonschema.validate(document, schema_doc, cls=jsonschema.Draft202012Validator)
        except jsonschema.ValidationError as e:
            fail(f"the {schema} does not validate: {e.message} at {list(e.absolute_path)}")
    sha = constants["provenance"]["recordings"][0]["sha256"]
    if req["recordings"][0]["sha256"] != sha or req["serial"] != "IMU-0001":
        fail(f"the request's recordings {req['recordings']}")
    check_request(req, steps)
    rows = THERMAL_ROWS
    if f"IMU-0001: test-good: {rows} thermal rows" not in r.stdout or "test-good: done" not in r.stdout:
        fail(f"the program's log with {rows} thermal rows is not printed")
    return out


def check_replay(adahrs, tmp, fit_dir):
    r = run(adahrs, "fit", "--replay", fit_dir)
    if "IMU-0001: constants reproduced bit for bit" not in r.stdout or \
            "reply byte-identical" not in r.stdout:
        fail("the replay of an unchanged program did not reproduce the constants")
    program = tmp / "good.py"
    program.write_text(program.read_text().replace("0.001 * i", "0.002 * i"))
    r = run(adahrs, "fit", "--replay", fit_dir, expect=1)
    if "constants differ: $.constants.accel[1].offset_duty: kept 0.001, now 0.002" not in r.stdout:
        fail("an edited program's different constants are not named")
    request = fit_dir / "IMU-0001.request.json.gz"
    text = gzip.decompress(request.read_bytes()).replace(b'"IMU-0001"', b'"IMU-0009"', 1)
    request.write_bytes(gzip.compress(text))
    r = run(adahrs, "fit", "--replay", fit_dir, expect=1)
    if "not the request the constants of IMU-0001 were fitted from" not in r.stderr:
        fail("a changed kept request is not refused")


def main():
    adahrs = sys.argv[1]
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="adahrs-external-"))
    ok = False
    try:
        run_dir = tmp / "run"
        steps = write_run(run_dir)
        check_replay(adahrs, tmp, check_good(adahrs, tmp, run_dir, steps))
        out = tmp / "out"
        out.mkdir()
        (out / "IMU-0001.json").write_text('{"kept": "as it was"}\n')
        before = snapshot(out)
        for name, timeout_s, cause in HOSTILE:
            start = time.monotonic()
            r = run(adahrs, "fit", "--run", run_dir, "--strategy", strategy(tmp, name, timeout_s),
                    "--out", out, expect=1)
            head = f"strategy \"test-{name}\" ("
            if head not in r.stderr or "for IMU-0001" not in r.stderr or cause not in r.stderr:
                fail(f"{name}: the refusal does not name the program and '{cause}'")
            if snapshot(out) != before:
                fail(f"{name}: the output directory changed")
            if name == "hangs" and time.monotonic() - start > 60:
                fail("the hanging program was not killed near its 2 s timeout")
        for doc, path_and_cause in [
                ({"program": ["python3", "x.py"], "strategy": "reference"}, "$.strategy"),
                ({"program": []}, "$.program"),
                ({"program": ["python3", ""]}, "$.program[1]"),
                ({"program": ["python3"], "timeout_s": 0}, "$.timeout_s"),
                ({"program": ["python3"], "inputs": {"samples": True}}, "$.inputs.samples"),
                ({"program": ["python3"], "firmware_format": 4}, "$.firmware_format")]:
            path = tmp / "bad.json"
            full = {"format": "adahrs-imu-strategy", "format_version": 1, "strategy": "bad"}
            full.update(doc)
            path.write_text(json.dumps(full))
            r = run(adahrs, "fit", "--run", run_dir, "--strategy", path, "--out", out, expect=None)
            if r.returncode == 0 or path_and_cause not in r.stderr or "bad.json" not in r.stderr:
                fail(f"strategy file {doc} not refused naming {path_and_cause}")
        ok = True
    finally:
        if ok:
            shutil.rmtree(tmp)
        else:
            print(f"kept {tmp}")
    print("PASS")


if __name__ == "__main__":
    main()
