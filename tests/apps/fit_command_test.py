#!/usr/bin/env python3
"""adahrs fit --ads-strategy end to end: an ADS calibration run written here (meta.json format 2
and ads.csv as the executor writes them) from a closed-form bridge, fitted with pressure_minimax;
the constants file's static-pressure surface, evaluated here in exact rational arithmetic from its
raw-code coefficients (coeff_x_y), must give back the test set's pressure at every point. An
unknown strategy, two runs, and a run without an ADS unit are refused with their reason.
Usage: fit_command_test.py ADAHRS"""
import json
import pathlib
import subprocess
import sys
import tempfile
from fractions import Fraction

ROOT = pathlib.Path(__file__).resolve().parents[2]
SERIAL = "ADS-0007"
COLUMNS = ("t_s,unit,seq,step,tag,chamber_c,ps_ref_pa,qc_ref_pa,ps_counts,pt_counts,"
           "ps_temp_counts,pt_temp_counts,oat_counts,mode,alt_ft,cas_kt,comp_flags")
IMU_COLUMNS = ("t_s,unit,seq,step,tag,orientation,chamber_c,table_rate_dps,az1_t1,az1_t2,ax1_t1,"
               "ax1_t2,ay1_t1,ay1_t2,az2_t1,az2_t2,ax2_t1,ax2_t2,ay2_t1,ay2_t2,gx,gy,gz,tx,ty,tz,"
               "mode,comp0,comp1,comp2,comp3,comp4,comp5,comp6,comp7,comp8,comp_flags")


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, timeout=120)


def isa_static_pa(alt_ft):
    h_m = alt_ft * 0.3048
    if h_m <= 11000.0:
        return 101325.0 * (1.0 - 2.25577e-5 * h_m) ** 5.25588
    return 22632.06 * 2.718281828459045 ** (-(h_m - 11000.0) / 6341.62)


def impact_pa(cas_kt):
    m = cas_kt / 661.4788
    return 101325.0 * ((1.0 + 0.2 * m * m) ** 3.5 - 1.0)


# A bridge in closed form: 1.6 codes per Pa with a -500 ppm/degC span, an offset drifting 40 codes
# per degC, and a bridge voltage rising 0.26 %/degC (the temperature signal).
def pressure_code(p_pa, temp_c):
    return round(30000 + 1.62222 * p_pa * (1.0 - 5e-4 * (temp_c - 25.0)) + 40.0 * (temp_c - 25.0))


def bridge_code(temp_c):
    return round(6710886 * (1.0 + 0.0026 * (temp_c - 25.0)))


def write_run(run_dir, with_ads=True, ads_rows=True):
    run_dir.mkdir()
    sequence = json.loads((ROOT / "calib/sequences/ads_calibration.json").read_text())
    unit = {"role": "ads1", "kind": "ads", "serial": SERIAL, "serial_number": 7,
            "firmware": "1.0.0", "slot": 1, "constants_version": 0, "mode": 0}
    if not with_ads:
        unit.update(role="imu1", kind="imu", serial="IMU-0007")
    meta = {"format_version": 2, "run_id": "r-ads", "started_utc": "2026-11-23T08:00:00Z",
            "status": "complete", "station": {"name": "virtual lab"}, "sequence": sequence,
            "sequence_file": "ads_calibration.json", "time_base": "s", "sample_rate_hz": 100,
            "local_gravity_mps2": 9.79, "units": [unit], "instruments": [],
            "rejected_intervals": []}
    (run_dir / "meta.json").write_text(json.dumps(meta))
    (run_dir / "imu.csv").write_text(IMU_COLUMNS + "\n")
    lines = [COLUMNS]
    points = []
    step, t_s = 0, 0.0
    alts = [-1000, 0, 2000, 5000, 10000, 20000, 30000, 40000, 50000]
    speeds = [30, 60, 100, 200, 300, 450]
    for temp_c in (-40.0, -15.0, 25.0, 65.0, 85.0, 75.0, 45.0, 0.0, -30.0):
        stimuli = [(isa_static_pa(a), 0.0) for a in alts]
        stimuli += [(101325.0, impact_pa(v)) for v in speeds]
        for ps_pa, qc_pa in stimuli:
            step += 1
            points.append((pressure_code(ps_pa, temp_c), bridge_code(temp_c), ps_pa))
            for k in range(5):
                t_s += 0.01
                lines.append(f"{t_s:.4f},{SERIAL},{k},{step},{step % 250 + 1},{temp_c:.3f},"
                             f"{ps_pa:.2f},{qc_pa:.2f},{pressure_code(ps_pa, temp_c)},"
                             f"{pressure_code(qc_pa, temp_c)},{bridge_code(temp_c)},"
                             f"{bridge_code(temp_c)},800000,0,,,")
    (run_dir / "ads.csv").write_text("\n".join(lines if ads_rows else lines[:1]) + "\n")
    return points


def surface_at(coeff_x_y, x, y):
    x, y = Fraction(x), Fraction(y)
    return sum(Fraction(c) * x ** p * y ** q
               for p, row in enumerate(coeff_x_y) for q, c in enumerate(row))


def main(adahrs):
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        points = write_run(tmp / "run")
        out = tmp / "fit"
        r = run(adahrs, "fit", "--run", tmp / "run", "--ads-strategy", "pressure_minimax",
                "--out", out)
        if r.returncode != 0:
            failures.append(f"fit failed ({r.returncode}): {r.stderr}")
        else:
            expected_line = f"{SERIAL}: strategy pressure_minimax -> {out / (SERIAL + '.json')}"
            if expected_line not in r.stdout:
                failures.append(f"stdout lacks '{expected_line}': {r.stdout}")
            constants = json.loads((out / (SERIAL + ".json")).read_text())
            surface = constants["constants"]["altitude_ft"]
            if constants["strategy"] != "pressure_minimax" or surface["law"] != "isa_altitude":
                failures.append(f"strategy/law: {constants['strategy']}, {surface['law']}")
            coeff = surface["coeff_x_y"]
            if len(coeff) != 4 or any(len(row) != 6 for row in coeff):
                failures.append(f"coeff_x_y is not 4 x 6: {coeff}")
            else:
                worst = max(abs(float(surface_at(coeff, x, y)) - p) for x, y, p in points)
                print(f"static pressure surface: worst |error| at the {len(points)} points "
                      f"{worst:.3f} Pa")
                if worst > 2.0:  # code rounding is 0.3 Pa; a 2 Pa miss is a wrong surface
                    failures.append(f"surface misses the reference by {worst:.3f} Pa")
        r = run(adahrs, "fit", "--run", tmp / "run", "--ads-strategy", "minimax", "--out", out)
        if r.returncode == 0 or "unknown ADS strategy 'minimax' (known: reference, " \
                "tolerance_minimax, pressure_minimax, hysteresis_compensated)" not in r.stderr:
            failures.append(f"unknown strategy: {r.returncode} {r.stderr}")
        r = run(adahrs, "fit", "--run", tmp / "run", "--run", tmp / "run", "--ads-strategy",
                "reference", "--out", out)
        if r.returncode == 0 or "takes exactly one --run" not in r.stderr:
            failures.append(f"two runs: {r.returncode} {r.stderr}")
        write_run(tmp / "imu_run", with_ads=False, ads_rows=False)
        r = run(adahrs, "fit", "--run", tmp / "imu_run", "--ads-strategy", "reference",
                "--out", out)
        if r.returncode == 0 or "meta.json: the run has no ADS unit" not in r.stderr:
            failures.append(f"no ADS unit: {r.returncode} {r.stderr}")
        # Rows of a unit meta.json does not list are refused by file and line.
        write_run(tmp / "stray_run", with_ads=False)
        r = run(adahrs, "fit", "--run", tmp / "stray_run", "--ads-strategy", "reference",
                "--out", out)
        stray = f"stray_run/ads.csv:2: unit '{SERIAL}' is not listed in meta.json $.units"
        if r.returncode == 0 or stray not in r.stderr:
            failures.append(f"unlisted unit: {r.returncode} {r.stderr}")
        # A duplicated row (a copy, not a new packet) would count twice in the fit.
        lines = (tmp / "run" / "ads.csv").read_text().splitlines()
        (tmp / "run" / "ads.csv").write_text("\n".join(lines[:40] + [lines[39]] + lines[40:]) + "\n")
        r = run(adahrs, "fit", "--run", tmp / "run", "--ads-strategy", "reference", "--out", out)
        if r.returncode == 0 or "ads.csv:41: unit ADS-0007 repeats its previous row" not in r.stderr:
            failures.append(f"repeated row: {r.returncode} {r.stderr}")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
