#!/usr/bin/python3
# The reference IMU calibration (thesis Method 2-5) as an external strategy
# (docs/strategies-external.md): one JSON request on stdin, one JSON reply on stdout, log on
# stderr. It reproduces the built-in `reference` strategy (calib/imu_calibration/
# imu_reference_fit.cc) in four sequential stages:
#   1. thermal drift xi(t) = k0 + k1 t + k2 t^2 per channel (k3 = 0) over the thermal profile,
#      every temperature band weighing the same (band-weighted least squares, sandwich errors);
#   2. six-position offset and scale per accelerometer channel on thermally compensated means,
#      the acquisitions of one orientation pooled;
#   3. gyro cubic rate = l0 + l1 d + l2 d^2 + l3 d^3, d = T - T(0 deg/s), per gyro over the rate
#      steps about its axis;
#   4. cross-axis matrices CA (m/s^2 per g) and CG from fully calibrated means with CA = CG = I.
# Units: accelerometer U in duty (T1/T2 - 0.5), gyro U in counts, temperatures in counts of the
# channel's thermometer, rates in deg/s, local gravity in m/s^2.
# Left out: anything the format-2 constants cannot hold (scale vs temperature, g-sensitivity,
# accelerometer nonlinearity, lag), the up/down-ramp hysteresis diagnostics of the built-in, and
# correlation of successive samples (the standard errors are then optimistic).
import json
import sys
from math import comb

import numpy as np

STANDARD_GRAVITY_MPS2 = 9.80665   # the unit "g"
CROSS_AXIS_RATE_DPS = 150.0       # CG's reference rate (thesis Eq. 28)
NULL_STEP_TOLERANCE_DPS = 0.01    # a gyro step this close to 0 deg/s is the null step
MIN_BANDS, MIN_RATES = 4, 5
MAX_CONDITION, RANK_TOLERANCE = 1e8, 1e-12
PAIR_OF_AXIS = ((1, 4), (2, 5), (0, 3))  # body x, y, z: the two accelerometer channels


class Refused(Exception):
    """A design the reference method cannot fit; the message says why."""


def log(message):
    print(f"imu_reference: {message}", file=sys.stderr)


# ---- The double-precision compensator (firmware_model/reference_compensator.cc) ----------------

def compensate(c, mode, u, temp):
    """The nine outputs of `mode` ("thermal" or "full") for rows u (n x 9), temp (n x 3)."""
    t = np.empty_like(u)
    for ch in range(9):
        th = c["thermal"][ch]
        k, x = th["k"], temp[:, th["temp_sensor"]]
        t[:, ch] = u[:, ch] - (k[0] + x * (k[1] + x * (k[2] + x * k[3])))
    if mode == "thermal":
        return t
    cal = np.empty_like(u)
    for ch in range(6):
        a = c["accel"][ch]
        cal[:, ch] = (t[:, ch] - a["offset_duty"]) / a["scale_duty_per_g"]
    for g in range(3):
        l, d = c["gyro"][g]["l"], t[:, 6 + g] - c["gyro"][g]["null_cnt"]
        cal[:, 6 + g] = l[0] + l[1] * d + l[2] * d * d + l[3] * d * d * d
    ca_g = np.column_stack([0.5 * (cal[:, i] + cal[:, j]) for i, j in PAIR_OF_AXIS])
    out = np.empty_like(u)
    out[:, 0:3] = ca_g @ np.asarray(c["ca_mps2_per_g"]).T
    out[:, 3:6] = cal[:, 6:9] @ np.asarray(c["cg"]).T
    out[:, 6:9] = np.column_stack([0.5 * (cal[:, i] - cal[:, j]) for i, j in PAIR_OF_AXIS])
    return out


def means_of(c, mode, acquisitions):
    """Per-channel mean and standard error of the compensated rows of `acquisitions`, pooled."""
    u = np.concatenate([np.asarray(a["samples"]["u"], dtype=float) for a in acquisitions])
    temp = np.concatenate([np.asarray(a["samples"]["temp_cnt"], dtype=float)
                           for a in acquisitions])
    if len(u) < 2:
        raise Refused(f"{len(u)} sample(s), at least 2 are needed for a standard error")
    out = compensate(c, mode, u, temp)
    mean = out.mean(axis=0)
    sd = np.sqrt(((out - mean) ** 2).sum(axis=0) / (len(out) - 1))
    return mean, sd / np.sqrt(len(out))


def normalised_to_raw(centre, half_span, degree):
    """T with raw = T @ normalised for a polynomial in u = (x - centre) / half_span."""
    t = np.zeros((degree + 1, degree + 1))
    for i in range(degree + 1):
        for k in range(i + 1):
            t[k, i] = comb(i, k) * (-centre) ** (i - k) / half_span ** i
    return t


# ---- Stage 1: thermal drift (calib/solvers/thermal_drift_fit.cc) ------------------------------

def fit_thermal(thermal, ch, thermometer):
    """k (3), their standard errors and the fitted temperature span of channel `ch`."""
    rows = [b for b in thermal["bands"] if b["thermometer"] == thermometer]
    t_min = min(b["temp_min_cnt"] for b in rows)
    t_max = max(b["temp_max_cnt"] for b in rows)
    centre, half = 0.5 * (t_min + t_max), 0.5 * (t_max - t_min)
    half = half if half > 0.0 else 1.0
    band_count = {}  # the segments of one band pool: every band weighs the same
    for b in rows:
        band_count[b["band"]] = band_count.get(b["band"], 0) + b["count"]
    if len(band_count) < MIN_BANDS:
        raise Refused(f"thermal fit of channel {ch}: {len(band_count)} temperature band(s), "
                      f"at least {MIN_BANDS} are needed")
    m, g, rhs = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros(3)
    for b in rows:
        # u = alpha + beta d: the sums of u^k and u^k U from those of d^k and d^k U.
        alpha, beta = (b["pivot_cnt"] - centre) / half, 1.0 / half
        s_d = [float(b["count"])] + b["d_sums"]
        y = next(c for c in b["channels"] if c["channel"] == ch)["u_sums"]
        s_u = [sum(comb(k, j) * alpha ** (k - j) * beta ** j * s_d[j] for j in range(k + 1))
               for k in range(5)]
        s_uy = [sum(comb(k, j) * alpha ** (k - j) * beta ** j * y[j] for j in range(k + 1))
                for k in range(3)]
        w = 1.0 / band_count[b["band"]]
        for i in range(3):
            rhs[i] += w * s_uy[i]
            for j in range(3):
                m[i, j] += w * s_u[i + j]
                g[i, j] += w * w * s_u[i + j]
    coef, m_inv = solve_normal(m, rhs, f"thermal fit of channel {ch}")
    n = sum(b["count"] for b in rows)
    sigma2 = thermal_residual_sum(rows, ch, coef, centre, half) / (n - 3)
    t = normalised_to_raw(centre, half, 2)
    cov = t @ (sigma2 * m_inv @ g @ m_inv) @ t.T
    return t @ coef, np.sqrt(np.diag(cov)), t_min, t_max


def solve_normal(m, rhs, context):
    """The equilibrated normal equations' solution and inverse, with the driver's refusals."""
    d = 1.0 / np.sqrt(np.diag(m))
    ms = m * np.outer(d, d)
    s = np.sqrt(np.maximum(np.linalg.eigvalsh(ms), 0.0))  # ascending
    condition = s[2] / s[0] if s[0] > 0.0 else np.inf
    if np.sum(s > RANK_TOLERANCE * s[2]) < 3 or not condition <= MAX_CONDITION:
        raise Refused(f"{context}: condition number {condition:.3g} (limit {MAX_CONDITION:.3g})")
    ms_inv = np.linalg.inv(ms)
    return d * (ms_inv @ (d * rhs)), ms_inv * np.outer(d, d)


def thermal_residual_sum(rows, ch, coef, centre, half):
    """Sum of squared residuals of U, from each row's sums about its own mean (no cancellation
    against the large gyro counts)."""
    total = 0.0
    for b in rows:
        alpha, beta = (b["pivot_cnt"] - centre) / half, 1.0 / half
        q1 = (coef[1] + 2.0 * coef[2] * alpha) * beta  # the fit as q0 + q1 d + q2 d^2
        q2 = coef[2] * beta * beta
        c = next(c for c in b["channels"] if c["channel"] == ch)
        n, (s1, s2, s3, s4), y, mean = b["count"], b["d_sums"], c["u_sums"], c["u_mean"]
        a = coef[0] + coef[1] * alpha + coef[2] * alpha * alpha - mean  # q0 - mean
        sum_e2 = c["u_m2"] + (y[0] - n * mean) ** 2 / n
        sum_er = a * (y[0] - n * mean) + q1 * (y[1] - mean * s1) + q2 * (y[2] - mean * s2)
        sum_r2 = (a * a * n + q1 * q1 * s2 + q2 * q2 * s4 + 2.0 * a * q1 * s1
                  + 2.0 * a * q2 * s2 + 2.0 * q1 * q2 * s3)
        total += sum_e2 - 2.0 * sum_er + sum_r2
    return total


# ---- Stage 2: six-position offset and scale (calib/solvers/six_position_fit.cc) ---------------

def fit_six_position(c, acquisitions, channels, g_mps2):
    """Offset and scale (and their standard errors) of the six accelerometer channels."""
    g = g_mps2 / STANDARD_GRAVITY_MPS2
    by_orientation = {}
    for a in acquisitions:
        if a["kind"] == "accel":
            by_orientation.setdefault(a["orientation"], []).append(a)
    means = {o: means_of(c, "thermal", acqs) for o, acqs in by_orientation.items()}
    out = []
    for ch in range(6):
        up, down = (10 * (channels[ch]["axis"] + 1) + face for face in (1, 2))
        for o in (up, down):
            if o not in means:
                raise Refused(f"six-position fit: orientation {o} is missing (channel {ch})")
        (yu, su), (yd, sd) = ((means[o][0][ch], means[o][1][ch]) for o in (up, down))
        # Two observations, two unknowns: the weighted solution is the exact one.
        var = 0.25 * (su * su + sd * sd)
        out.append(((0.5 * (yu + yd), 0.5 * (yu - yd) / g), (np.sqrt(var), np.sqrt(var) / g)))
    return out


# ---- Stage 3: gyro cubic (calib/solvers/gyro_scale_fit.cc) ------------------------------------

def fit_gyro(c, acquisitions, axis):
    """null_cnt, l (4) and their standard errors of the gyro about body axis `axis`."""
    steps = []
    for a in acquisitions:
        if a["kind"] == "gyro" and a["orientation"] // 10 - 1 == axis:
            mean, se = means_of(c, "thermal", [a])
            sign = 1.0 if a["orientation"] % 10 == 1 else -1.0
            steps.append((a["rate_dps"] * sign, mean[6 + axis], se[6 + axis]))
    zero = None
    for s in steps:  # the first step nearest 0 deg/s
        if abs(s[0]) <= NULL_STEP_TOLERANCE_DPS and (zero is None or abs(s[0]) < abs(zero[0])):
            zero = s
    if zero is None:
        raise Refused(f"gyro scale fit of axis {axis}: no 0 deg/s step")
    if len({s[0] for s in steps}) < MIN_RATES:
        raise Refused(f"gyro scale fit of axis {axis}: too few distinct rates")
    x = np.array([s[1] - zero[1] for s in steps])
    rate = np.array([s[0] for s in steps])
    centre, half = 0.5 * (x.min() + x.max()), 0.5 * (x.max() - x.min())
    half = half if half > 0.0 else 1.0
    u = (x - centre) / half
    coef, cov = least_squares(np.column_stack([u ** p for p in range(4)]), rate,
                              f"gyro scale fit of axis {axis}")
    t = normalised_to_raw(centre, half, 3)
    return zero[1], t @ coef, zero[2], np.sqrt(np.diag(t @ cov @ t.T))


def least_squares(design, y, context):
    """Equal-weight least squares by QR on equilibrated columns, residual variance
    (calib/solvers/linear_least_squares.cc)."""
    n, p = design.shape
    if n <= p:
        raise Refused(f"{context}: {n} observations for {p} terms")
    d = 1.0 / np.linalg.norm(design, axis=0)
    q, r = np.linalg.qr(design * d)
    s = np.linalg.svd(r, compute_uv=False)
    condition = s[0] / s[-1] if s[-1] > 0.0 else np.inf
    if np.sum(s > RANK_TOLERANCE * s[0]) < p or not condition <= MAX_CONDITION:
        raise Refused(f"{context}: condition number {condition:.3g} (limit {MAX_CONDITION:.3g})")
    coef = d * np.linalg.solve(r, q.T @ y)
    residuals = y - design @ coef
    r_inv = np.linalg.inv(r)
    sigma2 = residuals @ residuals / (n - p)
    return coef, sigma2 * (r_inv @ r_inv.T) * np.outer(d, d)


# ---- Stage 4: cross-axis (calib/solvers/cross_axis_fit.cc) ------------------------------------

def cross_axis_steps(c, acquisitions):
    """The fully calibrated means (and errors) of the rest and fastest-rate acquisitions about
    +x, +y, +z: accelerometers in g, gyros scaled to CROSS_AXIS_RATE_DPS."""
    have_step = any(a["kind"] == "cross_axis" for a in acquisitions)
    rest_kind, rate_kind = ("cross_axis",) * 2 if have_step else ("accel", "gyro")
    accel, gyro = {}, {}
    for o in (11, 21, 31):
        rest = fast = None
        for a in acquisitions:
            if a["kind"] == rest_kind and a["orientation"] == o and abs(a["rate_dps"]) < 1.0:
                rest = a  # the last one
        for a in acquisitions:
            if a["kind"] == rate_kind and a["orientation"] == o and a["rate_dps"] > 1.0 and \
                    (fast is None or a["rate_dps"] > fast["rate_dps"]):
                fast = a  # the first of the fastest
        if rest is not None:
            mean, se = means_of(c, "full", [rest])
            accel[o] = (mean[0:3], se[0:3])
        if fast is not None:
            mean, se = means_of(c, "full", [fast])
            k = CROSS_AXIS_RATE_DPS / fast["rate_dps"]
            gyro[o] = (k * mean[3:6], k * se[3:6])
    return accel, gyro, "cross_axis step" if have_step else "accel and gyro steps"


def fit_cross_axis(steps, reference, context):
    """reference * K^-1, K's columns the means about +x, +y, +z, with first-order errors."""
    for axis, o in enumerate((11, 21, 31)):
        if o not in steps:
            raise Refused(f"{context}: orientation {o} is missing")
        if not steps[o][0][axis] > 0.0:
            raise Refused(f"{context}: in orientation {o} the up axis reads {steps[o][0][axis]}")
    k = np.column_stack([steps[o][0] for o in (11, 21, 31)])
    k_se = np.column_stack([steps[o][1] for o in (11, 21, 31)])
    s = np.linalg.svd(k, compute_uv=False)
    if not (s[2] > 0.0 and s[0] / s[2] <= MAX_CONDITION):
        raise Refused(f"{context}: the three means do not span three axes")
    k_inv = np.linalg.inv(k)
    # d(K^-1)_rc / dK_ij = -(K^-1)_ri (K^-1)_jc, the means' errors independent.
    var = np.einsum("ri,jc,ij->rc", k_inv ** 2, k_inv ** 2, k_se ** 2)
    return reference * k_inv, reference * np.sqrt(var), s[0] / s[2]


# ---- The request and the reply -----------------------------------------------------------------

def fit(request):
    channels, acquisitions = request["channels"], request["acquisitions"]
    g_mps2 = request["local_gravity_mps2"]
    if request["thermal"] is None:
        raise Refused("no thermal_profile rows (give the thermal-calibration run)")
    if any("samples" not in a for a in acquisitions):
        raise Refused("the acquisitions have no rows: the strategy file needs "
                      "\"inputs\": {\"acquisition_samples\": true}")
    # The stages fill the constants in turn; CA = CG = I until the last (its means need them so).
    c = {"thermal": [], "accel": [], "gyro": [], "ca_mps2_per_g": np.eye(3).tolist(),
         "cg": np.eye(3).tolist()}
    se = {"thermal": [], "accel": [], "gyro": []}
    for ch, table in enumerate(channels):
        k, k_se, t_min, t_max = fit_thermal(request["thermal"], ch, table["thermometer"])
        c["thermal"].append({"k": [*k.tolist(), 0.0], "temp_min_cnt": t_min,
                             "temp_max_cnt": t_max, "temp_sensor": table["thermometer"]})
        se["thermal"].append({"k": [*k_se.tolist(), None], "temp_min_cnt": None,
                              "temp_max_cnt": None, "temp_sensor": None})
    for (offset, scale), (offset_se, scale_se) in fit_six_position(c, acquisitions, channels,
                                                                   g_mps2):
        c["accel"].append({"offset_duty": offset, "scale_duty_per_g": scale})
        se["accel"].append({"offset_duty": offset_se, "scale_duty_per_g": scale_se})
    for axis in range(3):
        null, l, null_se, l_se = fit_gyro(c, acquisitions, axis)
        c["gyro"].append({"null_cnt": null, "l": l.tolist()})
        se["gyro"].append({"null_cnt": null_se, "l": l_se.tolist()})
    accel_steps, gyro_steps, source = cross_axis_steps(c, acquisitions)
    ca, ca_se, ca_cond = fit_cross_axis(accel_steps, g_mps2, "accelerometer cross-axis")
    cg, cg_se, cg_cond = fit_cross_axis(gyro_steps, CROSS_AXIS_RATE_DPS, "gyro cross-axis")
    c["ca_mps2_per_g"], c["cg"] = ca.tolist(), cg.tolist()
    se["ca_mps2_per_g"], se["cg"] = ca_se.tolist(), cg_se.tolist()
    diagnostics = {"cross_axis": {"source": source, "ca_condition": ca_cond,
                                  "cg_condition": cg_cond}}
    return c, se, diagnostics


def main():
    request = json.load(sys.stdin)
    log(f"{request['serial']}: {len(request['acquisitions'])} acquisitions")
    try:
        constants, standard_errors, diagnostics = fit(request)
    except Refused as e:
        log(f"unit {request['serial']}: design refused: {e}")
        return 1
    reply = {"protocol": "adahrs-strategy-reply", "protocol_version": 1,
             "serial": request["serial"], "constants": constants,
             "standard_errors": standard_errors, "diagnostics": diagnostics,
             "log": [f"reference fit, cross-axis from the {diagnostics['cross_axis']['source']}"]}
    sys.stdout.write(json.dumps(reply, allow_nan=False) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
