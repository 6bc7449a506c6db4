#!/usr/bin/python3
"""Temperatures of calib/sequences/imu_thermal_sensor_calibration.json, chosen by the Cramer-Rao
bound of the design.

What is computed. Each accelerometer channel's and each gyro's scale factor is taken as a
polynomial of degree 3 in the normalised temperature tau = (T - 22.5 degC) / 62.5 degC over the
rating -40...+85 degC. At a soak temperature the sequence logs one or more blocks: the six static
positions (1,000 packets each) and, about each body axis, the seven table rates -150...+150 deg/s
by 50 (1,000 packets each). For a candidate set of blocks the script builds the design of one
channel, its Fisher information A' Sigma^-1 A and the bound Cov >= (A' Sigma^-1 A)^-1, and reports
the standard error of the predicted scale factor s(T) = x(T)' c, sqrt(x(T)' Cov_c x(T)), at its
worst over -40...+85 degC (0.25 degC grid), in ppm of the scale factor.

Choice. The figure of merit (FoM) is that worst standard error times the square root of the
sequence's rig time: a variance times a time, the standard error the design would reach in one
hour if it could be repeated to fill it. The chosen set has the smallest FoM among the candidates
with at least 5 distinct temperatures (required) whose rig time is no longer than that of the
present imu_thermal_calibration_full + imu_sensor_calibration (read from their files). The bound
is needed: the ramps (25 -> -40 -> 85 -> 25 degC, 4.2 h) are a fixed cost, so without it the FoM
keeps falling as blocks are added. Candidates: equally spaced, Chebyshev-Lobatto (the extrema,
both ends included), exact G-optimal sets (searched below), the D-optimal support of a cubic, and
the same with two blocks at each end of the rating (the ends carry the largest leverage, where the
worst standard error sits).

Models (one channel; b a block, T_b its soak temperature):
  accelerometer  U = o_b + s(T_b) f_a + k2 f_a^2 + m1 f_b + m2 f_c + e
                 o_b free in each block (zero-g drift, die lag), k2 the second-order
                 nonlinearity and m1, m2 the cross-axis terms, one each for all temperatures;
                 f_a the specific force along the channel's axis (+1, -1, 0, 0, 0, 0 g in the six
                 positions). e: white, the mean of n frames.
  gyro           U = c_b + s(T_b) w + q2 (w/150)^2 + q3 (w/150)^3 + e
                 c_b free in each block's rate step (null drift, g-sensitivity and the slow
                 part of the bias wander), q2, q3 the rate nonlinearity, one set for all
                 temperatures; w the seven table rates, in ascending order in time, so wander
                 within the step maps into the scale. e: white plus the bias instability, with
                 the covariance of the window means in time (below).
  Blocks are independent of each other (each has its own free offset, which takes the slow part
  of any wander; blocks at different temperatures are 40 min and more apart). The temperature
  is the chamber's set point; the fit sees the die's TEMP counts, a few degC above the air with
  self-heating, which shifts the range and not the design.

Noise figures (../shared/physics.md; status tags as there: V verified, R recalled, D derived,
E estimate):
  ADXL210E noise density          200 ug/sqrt(Hz)           physics.md 1.1, V [L210E]
  ADXL210E filter                 32 kOhm (V) x 0.1 uF      physics.md 1.1-1.2; the capacitor is
                                                            the modelled unit's
                                                            (sensor_sim/adxl210e.h), so tau_f =
                                                            3.2 ms, 49.7 Hz, 1.78 mg rms per
                                                            frame (physics.md 1.2 table, D)
  ADXL210E low-frequency wander   not in physics.md: none assumed (white only)      E
  ADXRS150 rate noise density     0.05 deg/s/sqrt(Hz)       physics.md 2.1, V [RS150P]
  ADXRS150 bias instability       75 deg/h Allan floor      physics.md 2.1 gives 50...100 deg/h,
                                                            E (sibling ADXRS645 100 deg/h); 75 is
                                                            the calibration's own prior
                                                            (ImuDatasheetNoise), E
  bias instability form           four Gauss-Markov poles, 5, 50, 500, 5000 s, equal variance,
                                  the floor their mean Allan deviation over 10...5000 s (the
                                  simulator's and the calibration's form,
                                  sensor_sim/gyro_bias_process.h), E
  frame period                    10 ms (100 Hz packets, docs/sequences.md limits)
  logged dwell per point          1,000 packets = 10 s (the sequence; as
                                  imu_sensor_calibration.json)
Per frame: accelerometer sigma^2 = N^2 / (4 tau_f), a mean of n frames sigma^2/n (1+rho)/(1-rho)
with rho = exp(-T/tau_f); gyro N^2 / (2 T) (one-sided density), a mean of n frames N^2/(2 n T)
(as docs/calibration-strategies.md, "Cramer-Rao bound of the design").

Rig time: the duration estimate of `adahrs sequence check` (calib/sequence/execution_plan.h,
PlanTiming defaults) for the sequence this script's layout gives: a prompt (60 s), a first
accelerometer acquisition in orientation 31 (500 packets), then for each temperature in
ascending order after a first descent from 25 degC to the lowest: a logged 1 degC/min chamber
ramp (profile download 10 s) to it, a 30 min soak inside +-0.5 degC, and the block (six mounts
at 60 s, six accelerometer steps, three gyro steps) or blocks; last a logged ramp back to
25 degC. plan_duration_s() is ExpandSequence's estimate step by step; on every shipped IMU
sequence it gives the seconds `adahrs sequence check` prints (checked 2026-11-27).

Usage: /usr/bin/python3 scripts/design/scale_tempco_design.py      (numpy only; prints the table)
"""

import json
import math
import os

import numpy as np

# ---- Rating and polynomial ---------------------------------------------------------------------
T_MIN_C = -40.0
T_MAX_C = 85.0
T_MID_C = 0.5 * (T_MIN_C + T_MAX_C)
T_HALF_C = 0.5 * (T_MAX_C - T_MIN_C)
DEGREE = 3
GRID_C = np.arange(T_MIN_C, T_MAX_C + 1e-9, 0.25)

# ---- Noise figures (see the module comment for sources and status) -----------------------------
ACCEL_DENSITY_G_PER_RTHZ = 200e-6
ACCEL_FILTER_TAU_S = 32e3 * 0.1e-6
GYRO_DENSITY_DPS_PER_RTHZ = 0.05
GYRO_BIAS_FLOOR_DPH = 75.0
GM_CORRELATION_TIMES_S = (5.0, 50.0, 500.0, 5000.0)
FLOOR_BAND_S = (10.0, 5000.0)
FRAME_PERIOD_S = 0.01
PACKETS_PER_POINT = 1000

# ---- Sequence layout and plan timing (calib/sequence/execution_plan.h, PlanTiming defaults) ----
OPERATOR_PROMPT_S = 60.0
TABLE_SETTLE_S = 2.0
INTERLOCK_SAMPLE_S = 1.0
CHAMBER_RAMP_C_PER_MIN = 1.0
PROFILE_DOWNLOAD_S = 10.0
INITIAL_CHAMBER_C = 25.0
INTERLOCK_JOG_DPS = 100.0
PACKET_RATE_HZ = 100.0
TABLE_ACCEL_DPS2 = 100.0
SOAK_S = 1800.0
SOAK_BAND_C = 0.5
RAMP_C_PER_MIN = 1.0
FIRST_ACCEL_PACKETS = 500
GYRO_RATES_DPS = np.arange(-150.0, 150.0 + 1e-9, 50.0)
# One block: the six positions and the rates about x, y, z, ordered so that each orientation is
# mounted once and the block ends in 31 (z up), the orientation every logged ramp runs in.
BLOCK = (("accel", 11), ("gyro", 11), ("accel", 12), ("accel", 21), ("gyro", 21), ("accel", 22),
         ("accel", 32), ("accel", 31), ("gyro", 31))
SEQUENCES_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "calib",
                             "sequences")


def gyro_step_windows_s():
    """Start and end of each rate's acquisition within one gyro step, by the plan's model."""
    t_s = 2.0 * INTERLOCK_JOG_DPS / TABLE_ACCEL_DPS2 + TABLE_SETTLE_S + INTERLOCK_SAMPLE_S
    table_dps = 0.0
    windows = []
    for rate_dps in GYRO_RATES_DPS:
        t_s += abs(rate_dps - table_dps) / TABLE_ACCEL_DPS2 + TABLE_SETTLE_S
        table_dps = rate_dps
        windows.append((t_s, t_s + PACKETS_PER_POINT * FRAME_PERIOD_S))
        t_s += PACKETS_PER_POINT * FRAME_PERIOD_S
    return windows


def layout(blocks_at_c):
    """The sequence's steps for {temperature: blocks}: a prompt, a first acquisition in 31, then
    from 25 degC down to the lowest temperature and up through the others, at each a logged
    1 degC/min ramp, a 30 min soak inside +-0.5 degC and its blocks; last a logged ramp to 25."""
    steps = [{"kind": "prompt",
              "text": "Mount the IMU batch fixture on the rate table inside the chamber in "
                      "orientation 31 (z up), connect the units and close the chamber"},
             {"kind": "accel", "orientation": 31, "packets": FIRST_ACCEL_PACKETS}]

    def ramp(number, target_c):
        return {"kind": "thermal_profile", "profile_name": f"ITSC RAMP{number}",
                "profile_steps": [{"type": "ramp_rate", "target_c": target_c,
                                   "rate_c_per_min": RAMP_C_PER_MIN},
                                  {"type": "end", "action": "hold"}]}

    for number, temp_c in enumerate(sorted(blocks_at_c), start=1):
        steps.append(ramp(number, temp_c))
        steps.append({"kind": "target_temperature", "target_c": temp_c, "band_c": SOAK_BAND_C,
                      "soak_s": SOAK_S})
        for _ in range(blocks_at_c[temp_c]):
            for kind, orientation in BLOCK:
                step = {"kind": kind, "orientation": orientation, "packets": PACKETS_PER_POINT}
                if kind == "gyro":
                    step.update({"rate_min_dps": float(GYRO_RATES_DPS[0]),
                                 "rate_max_dps": float(GYRO_RATES_DPS[-1]),
                                 "rate_increment_dps": float(GYRO_RATES_DPS[1] - GYRO_RATES_DPS[0]),
                                 "table_accel_dps2": TABLE_ACCEL_DPS2})
                steps.append(step)
    steps.append(ramp(len(blocks_at_c) + 1, INITIAL_CHAMBER_C))
    return steps


def plan_duration_s(steps):
    """ExpandSequence's duration estimate (execution_plan.cc) for a list of sequence steps."""
    total_s = 0.0
    mounted = 0
    table_dps = 0.0
    chamber_c = INITIAL_CHAMBER_C

    def mount(orientation):
        nonlocal mounted
        if orientation == mounted:
            return 0.0
        mounted = orientation
        return OPERATOR_PROMPT_S

    def table(rate_dps, accel_dps2):
        nonlocal table_dps
        t_s = abs(rate_dps - table_dps) / accel_dps2 + TABLE_SETTLE_S
        table_dps = rate_dps
        return t_s

    def stop(accel_dps2):
        nonlocal table_dps
        t_s = abs(table_dps) / accel_dps2
        table_dps = 0.0
        return t_s

    def check_gyro(accel_dps2):
        return 2.0 * INTERLOCK_JOG_DPS / accel_dps2 + TABLE_SETTLE_S + INTERLOCK_SAMPLE_S

    for step in steps:
        kind = step["kind"]
        if kind == "prompt":
            total_s += OPERATOR_PROMPT_S
        elif kind == "accel":
            total_s += mount(step["orientation"]) + INTERLOCK_SAMPLE_S + step["packets"] / PACKET_RATE_HZ
        elif kind == "gyro":
            a = step["table_accel_dps2"]
            total_s += mount(step["orientation"]) + check_gyro(a)
            n = int(round((step["rate_max_dps"] - step["rate_min_dps"]) / step["rate_increment_dps"]))
            for k in range(n + 1):
                total_s += table(step["rate_min_dps"] + k * step["rate_increment_dps"], a)
                total_s += step["packets"] / PACKET_RATE_HZ
            total_s += stop(a)
        elif kind == "cross_axis":
            a = step["table_accel_dps2"]
            for orientation in (11, 21, 31):
                total_s += mount(orientation) + INTERLOCK_SAMPLE_S + step["packets"] / PACKET_RATE_HZ
                total_s += check_gyro(a) + table(step["rate_dps"], a) + step["packets"] / PACKET_RATE_HZ
                total_s += stop(a)
        elif kind == "target_temperature":
            total_s += abs(step["target_c"] - chamber_c) / CHAMBER_RAMP_C_PER_MIN * 60.0 + step["soak_s"]
            chamber_c = step["target_c"]
        elif kind == "thermal_profile":
            total_s += PROFILE_DOWNLOAD_S
            profile = step["profile_steps"]
            done = [0] * len(profile)
            i = 0
            while i < len(profile):
                p = profile[i]
                if p["type"] == "ramp_time":
                    total_s += p["duration_s"]
                    chamber_c = p["target_c"]
                elif p["type"] == "ramp_rate":
                    total_s += abs(p["target_c"] - chamber_c) / p["rate_c_per_min"] * 60.0
                    chamber_c = p["target_c"]
                elif p["type"] == "soak":
                    total_s += p["duration_s"]
                elif p["type"] == "jump":
                    if done[i] < p["count"]:
                        done[i] += 1
                        i = p["to_step"] - 1
                        continue
                    done[i] = 0
                else:
                    if p.get("action") == "idle":
                        chamber_c = p["idle_c"]
                    break
                i += 1
        else:
            raise ValueError(f"step kind {kind} is not an IMU step this script knows")
    return total_s


def rig_time_h(temps_c):
    """Plan estimate of the sequence laid out for these temperatures (a repeat = one more block)."""
    blocks_at_c = {}
    for temp_c in temps_c:
        blocks_at_c[temp_c] = blocks_at_c.get(temp_c, 0) + 1
    return plan_duration_s(layout(blocks_at_c)) / 3600.0


def shipped_rig_time_h(name):
    with open(os.path.join(SEQUENCES_DIR, name + ".json"), encoding="utf-8") as f:
        return plan_duration_s(json.load(f)["steps"]) / 3600.0


# ---- Noise of the window means ------------------------------------------------------------------
def accel_mean_variance_g2(packets):
    sigma2_frame = ACCEL_DENSITY_G_PER_RTHZ ** 2 / (4.0 * ACCEL_FILTER_TAU_S)
    rho = math.exp(-FRAME_PERIOD_S / ACCEL_FILTER_TAU_S)
    return sigma2_frame / packets * (1.0 + rho) / (1.0 - rho)


def unit_gm_adev(tau_s):
    """Allan deviation of the four unit-variance Gauss-Markov poles (IEEE 952 Annex C)."""
    avar = 0.0
    for tc_s in GM_CORRELATION_TIMES_S:
        x = tau_s / tc_s
        avar += (2.0 * tc_s / tau_s) * (1.0 - (3.0 - 4.0 * math.exp(-x) + math.exp(-2.0 * x)) / (2.0 * x))
    return math.sqrt(avar)


def gm_pole_sigma_dps():
    log_taus = np.linspace(math.log(FLOOR_BAND_S[0]), math.log(FLOOR_BAND_S[1]), 201)
    floor_unit = np.mean([unit_gm_adev(math.exp(v)) for v in log_taus])
    return GYRO_BIAS_FLOOR_DPH / 3600.0 / floor_unit


def gm_window_covariance(w1, w2, tc_s):
    """Covariance of the means over two windows of a unit-variance Gauss-Markov process."""
    (a1, b1), (a2, b2) = w1, w2
    l1, l2 = b1 - a1, b2 - a2
    if w1 == w2:
        return 2.0 * tc_s ** 2 / l1 ** 2 * (l1 / tc_s - 1.0 + math.exp(-l1 / tc_s))
    if a2 < a1:
        (a1, b1), (a2, b2), l1, l2 = (a2, b2), (a1, b1), l2, l1
    return (tc_s ** 2 / (l1 * l2) * (1.0 - math.exp(-l1 / tc_s)) * (1.0 - math.exp(-l2 / tc_s))
            * math.exp(-(a2 - b1) / tc_s))


def gyro_step_covariance_dps2():
    """Covariance of the seven rate means of one gyro step: white noise and bias wander."""
    windows = gyro_step_windows_s()
    white = GYRO_DENSITY_DPS_PER_RTHZ ** 2 / (2.0 * PACKETS_PER_POINT * FRAME_PERIOD_S)
    q2 = gm_pole_sigma_dps() ** 2
    n = len(windows)
    cov = np.eye(n) * white
    for i in range(n):
        for k in range(n):
            cov[i, k] += q2 * sum(gm_window_covariance(windows[i], windows[k], tc)
                                  for tc in GM_CORRELATION_TIMES_S)
    return cov


# ---- Cramer-Rao bound of the scale polynomial ---------------------------------------------------
def powers(temp_c):
    tau = (np.asarray(temp_c, dtype=float) - T_MID_C) / T_HALF_C
    return np.vander(np.atleast_1d(tau), DEGREE + 1, increasing=True)


def scale_coefficient_covariance(temps_c, stimuli, step_cov, n_shared):
    """Cov of the DEGREE+1 scale coefficients for one channel.

    stimuli: (points, 1 + n_shared) rows [stimulus along the axis, shared regressors...] of one
    temperature's step; step_cov: their covariance. Parameters: one offset per temperature, the
    scale coefficients, the shared terms."""
    n_t = len(temps_c)
    n_p = stimuli.shape[0]
    n_par = n_t + DEGREE + 1 + n_shared
    info = np.zeros((n_par, n_par))
    step_inv = np.linalg.inv(step_cov)
    for j, temp_c in enumerate(temps_c):
        a = np.zeros((n_p, n_par))
        a[:, j] = 1.0
        a[:, n_t:n_t + DEGREE + 1] = np.outer(stimuli[:, 0], powers(temp_c)[0])
        a[:, n_t + DEGREE + 1:] = stimuli[:, 1:]
        info += a.T @ step_inv @ a
    cov = np.linalg.inv(info)
    return cov[n_t:n_t + DEGREE + 1, n_t:n_t + DEGREE + 1]


def worst_se_ppm(temps_c, stimuli, step_cov, n_shared):
    cov = scale_coefficient_covariance(temps_c, stimuli, step_cov, n_shared)
    x = powers(GRID_C)
    se = np.sqrt(np.einsum("ij,jk,ik->i", x, cov, x))
    return 1e6 * se.max(), GRID_C[int(np.argmax(se))]


def accel_design():
    # Six positions for the channel along +x: f = +x, -x, +y, -y, +z, -z (g);
    # columns [f_a, f_a^2, f_b, f_c].
    f = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)
    stimuli = np.column_stack([f[:, 0], f[:, 0] ** 2, f[:, 1], f[:, 2]])
    cov = np.eye(6) * accel_mean_variance_g2(PACKETS_PER_POINT)
    return stimuli, cov, 3


def gyro_design():
    # Scale in (deg/s out)/(deg/s in): stimulus w in deg/s, so s ~ 1 and its error is relative.
    w = GYRO_RATES_DPS
    stimuli = np.column_stack([w, (w / 150.0) ** 2, (w / 150.0) ** 3])
    return stimuli, gyro_step_covariance_dps2(), 2


# ---- Candidate temperature sets -----------------------------------------------------------------
MIN_SPACING_C = 10.0  # distinct temperatures of a searched set at least this far apart


def to_c(tau):
    """Normalised temperatures to set points, rounded to 0.5 degC (the F4 takes 0.1 degC)."""
    return [float(np.round(2.0 * (T_MID_C + T_HALF_C * t)) / 2.0) for t in tau]


def equally_spaced(n):
    return to_c(np.linspace(-1.0, 1.0, n))


def chebyshev_lobatto(n):
    return to_c(sorted(np.cos(np.pi * np.arange(n) / (n - 1))))


def ends_twice(temps_c):
    return sorted(temps_c + [T_MIN_C, T_MAX_C])


def g_optimal(n, design, end_blocks=1):
    """Exact minimax (G-optimal) set of n distinct temperatures: both ends of the rating (each
    logged end_blocks times), the interior symmetric about 22.5 degC on a 1 degC grid, at least
    MIN_SPACING_C apart, chosen to minimise the worst predicted standard error of `design`. (By
    the Kiefer-Wolfowitz theorem the continuous G-optimal design is the D-optimal one: for a cubic
    the ends and +-1/sqrt(5) with equal weights.)"""
    inner = n - 2
    half = inner // 2
    middle = [T_MID_C] if inner % 2 else []
    # A low interior point stays MIN_SPACING_C from -40 degC and from its mirror or the centre.
    upper_c = T_MID_C - (MIN_SPACING_C if middle else MIN_SPACING_C / 2.0)
    lows = np.arange(T_MIN_C + MIN_SPACING_C, upper_c + 1e-9, 1.0)
    best = None

    def sets(k, start):
        if k == 0:
            yield []
            return
        for i in range(start, len(lows)):
            for rest in sets(k - 1, i + 1):
                yield [float(lows[i])] + rest

    for chosen in sets(half, 0):
        temps = sorted([T_MIN_C, T_MAX_C] + chosen + middle + [2.0 * T_MID_C - c for c in chosen])
        if min(np.diff(temps)) < MIN_SPACING_C:
            continue
        blocks = sorted(temps + [T_MIN_C, T_MAX_C] * (end_blocks - 1))
        se, _ = worst_se_ppm(blocks, *design)
        if best is None or se < best[0]:
            best = (se, blocks)
    return best[1]


def describe(blocks_c):
    counts = {}
    for c in blocks_c:
        counts[c] = counts.get(c, 0) + 1
    return ", ".join(f"{c:g}" + (f" x{k}" if k > 1 else "") for c, k in sorted(counts.items()))


def main():
    accel = accel_design()
    gyro = gyro_design()
    d_support = to_c([-1.0, -1.0 / math.sqrt(5.0), 1.0 / math.sqrt(5.0), 1.0])
    candidates = [
        ("D-optimal support (4: below the minimum)", d_support),
        ("equally spaced 5", equally_spaced(5)),
        ("Chebyshev-Lobatto 5", chebyshev_lobatto(5)),
        ("G-optimal 5", g_optimal(5, gyro)),
        ("equally spaced 6", equally_spaced(6)),
        ("Chebyshev-Lobatto 6", chebyshev_lobatto(6)),
        ("G-optimal 6", g_optimal(6, gyro)),
        ("equally spaced 7", equally_spaced(7)),
        ("Chebyshev-Lobatto 7", chebyshev_lobatto(7)),
        ("G-optimal 7", g_optimal(7, gyro)),
        ("D-optimal support, all twice (4: below min.)", sorted(d_support * 2)),
        ("equally spaced 5, ends twice", ends_twice(equally_spaced(5))),
        ("Chebyshev-Lobatto 5, ends twice", ends_twice(chebyshev_lobatto(5))),
        ("G-optimal 5, ends twice", g_optimal(5, gyro, end_blocks=2)),
        ("G-optimal 6, ends twice", g_optimal(6, gyro, end_blocks=2)),
        ("G-optimal 7, ends twice", g_optimal(7, gyro, end_blocks=2)),
    ]
    present_h = (shipped_rig_time_h("imu_thermal_calibration_full")
                 + shipped_rig_time_h("imu_sensor_calibration"))
    sigma_a_ug = 1e6 * math.sqrt(accel_mean_variance_g2(PACKETS_PER_POINT))
    gyro_cov = gyro[1]
    white_mdps = 1e3 * GYRO_DENSITY_DPS_PER_RTHZ / math.sqrt(2 * PACKETS_PER_POINT * FRAME_PERIOD_S)
    block_h = (rig_time_h([T_MIN_C, T_MIN_C, T_MAX_C]) - rig_time_h([T_MIN_C, T_MAX_C]))
    print("Scale factor vs temperature, cubic in (T - 22.5)/62.5 over -40...+85 degC: worst standard")
    print("error (Cramer-Rao bound) of the predicted scale over the range (0.25 degC grid), ppm.")
    print(f"Per point ({PACKETS_PER_POINT} packets): accelerometer mean {sigma_a_ug:.1f} ug (white); gyro "
          f"rate mean {white_mdps:.1f} mdps white, {1e3 * math.sqrt(gyro_cov[0, 0]):.1f} mdps with the "
          f"{GYRO_BIAS_FLOOR_DPH:g} deg/h bias instability")
    print("(each block's own offset is free, so only the wander within a rate step counts).")
    print(f"Rig time (plan estimate): a block (six positions, rates about x, y, z) {60 * block_h:.1f} min;")
    print("each temperature a 30 min soak; ramps 25 -> lowest -> ... -> highest -> 25 degC at 1 degC/min.")
    print(f"Present imu_thermal_calibration_full + imu_sensor_calibration: {present_h:.2f} h (the budget).")
    print("FoM = worst SE x sqrt(rig h) (ppm sqrt(h)): smaller is better. 'x2': two blocks in one soak.")
    print()
    cols = [("set", 45), ("temperatures, degC", 40), ("blocks", 6), ("rig h", 5),
            ("accel SE", 8), ("gyro SE", 7), ("accel FoM", 9), ("gyro FoM", 8), ("budget", 6)]
    print("| " + " | ".join(f"{name:<{w}}" if i < 2 else f"{name:>{w}}"
                            for i, (name, w) in enumerate(cols)) + " |")
    print("|" + "|".join("-" * (w + 2) for _, w in cols) + "|")
    rows = []
    for name, blocks in candidates:
        hours = rig_time_h(blocks)
        se_a, _ = worst_se_ppm(blocks, *accel)
        se_g, _ = worst_se_ppm(blocks, *gyro)
        fom_a, fom_g = se_a * math.sqrt(hours), se_g * math.sqrt(hours)
        within = hours <= present_h and len(set(blocks)) >= 5
        rows.append((name, blocks, hours, se_a, se_g, fom_a, fom_g, within))
        print(f"| {name:<45} | {describe(blocks):<40} | {len(blocks):>6} | {hours:5.2f} | "
              f"{se_a:8.1f} | {se_g:7.1f} | {fom_a:9.1f} | {fom_g:8.1f} | "
              f"{'yes' if within else 'no':>6} |")
    eligible = [r for r in rows if r[7]]
    best_a = min(eligible, key=lambda r: r[5])
    best_g = min(eligible, key=lambda r: r[6])
    print()
    print("Within the budget (at least 5 distinct temperatures, rig time <= the present pair's):")
    print(f"  smallest accelerometer FoM: {best_a[0]} ({describe(best_a[1])} degC)")
    print(f"  smallest gyro FoM:          {best_g[0]} ({describe(best_g[1])} degC)")
    try:
        shipped_h = shipped_rig_time_h("imu_thermal_sensor_calibration")
        print(f"Shipped imu_thermal_sensor_calibration.json, plan estimate: {shipped_h:.2f} h")
    except FileNotFoundError:
        pass


if __name__ == "__main__":
    main()
