"""How closely two IMU constants sets agree, each difference measured by its effect on the
compensated output over the range the constants were fitted for, relative to that output's span
(a normwise relative error): two exact implementations of one least-squares fit agree to the
fit's condition number times the rounding unit in these terms, while a raw polynomial
coefficient of a narrow temperature span (an ill-conditioned monomial basis) may differ far more.

- thermal drift xi(t) = sum k_i t^i of each channel: the coefficients re-expanded in the
  normalised temperature u = (t - centre) / half_span of its fitted span (the firmware's own
  basis), differences relative to the largest normalised coefficient;
- gyro cubic in d = T - null: re-expanded in d / d_150 (d_150 = 150 deg/s / |l1|, the counts of the
  calibrated rate range), relative to the largest; the null's difference relative to d_150;
- accelerometer offset relative to the channel's scale (a difference in g), the scale relative to
  itself; CA and CG: the largest element difference relative to the largest element.

Usage: worst_agreement(a_constants, b_constants) -> (worst relative difference, where)."""
from math import comb

RATE_RANGE_DPS = 150.0


def _normalised(k, centre, half_span):
    """Coefficients of sum k_i t^i in u = (t - centre) / half_span."""
    return [sum(k[i] * comb(i, j) * centre ** (i - j) for i in range(j, len(k))) * half_span ** j
            for j in range(len(k))]


def _relative(a, b, scale):
    return max(abs(x - y) for x, y in zip(a, b)) / scale if scale > 0 else \
        max(abs(x - y) for x, y in zip(a, b))


def worst_agreement(a, b):
    """The largest relative difference between IMU constants `a` and `b` (the `constants`
    objects of two constants files) and where it is."""
    worst = (0.0, "")

    def note(value, where):
        nonlocal worst
        if value > worst[0]:
            worst = (value, where)

    for ch, (ta, tb) in enumerate(zip(a["thermal"], b["thermal"])):
        if (ta["temp_min_cnt"], ta["temp_max_cnt"], ta["temp_sensor"]) != \
                (tb["temp_min_cnt"], tb["temp_max_cnt"], tb["temp_sensor"]):
            return float("inf"), f"thermal[{ch}] span or sensor"
        centre = 0.5 * (ta["temp_min_cnt"] + ta["temp_max_cnt"])
        half = max(0.5 * (ta["temp_max_cnt"] - ta["temp_min_cnt"]), 1.0)
        na, nb = _normalised(ta["k"], centre, half), _normalised(tb["k"], centre, half)
        note(_relative(na, nb, max(abs(x) for x in nb)), f"thermal[{ch}].k")
    for g, (ga, gb) in enumerate(zip(a["gyro"], b["gyro"])):
        d150 = RATE_RANGE_DPS / abs(gb["l"][1])
        na = [c * d150 ** j for j, c in enumerate(ga["l"])]
        nb = [c * d150 ** j for j, c in enumerate(gb["l"])]
        note(_relative(na, nb, max(abs(x) for x in nb)), f"gyro[{g}].l")
        note(abs(ga["null_cnt"] - gb["null_cnt"]) / d150, f"gyro[{g}].null_cnt")
    for ch, (aa, ab) in enumerate(zip(a["accel"], b["accel"])):
        scale = abs(ab["scale_duty_per_g"])
        note(abs(aa["offset_duty"] - ab["offset_duty"]) / scale, f"accel[{ch}].offset_duty")
        note(abs(aa["scale_duty_per_g"] - ab["scale_duty_per_g"]) / scale,
             f"accel[{ch}].scale_duty_per_g")
    for key in ("ca_mps2_per_g", "cg"):
        ma = [x for row in a[key] for x in row]
        mb = [x for row in b[key] for x in row]
        note(_relative(ma, mb, max(abs(x) for x in mb)), key)
    if ("scale_temperature" in a) != ("scale_temperature" in b):
        return float("inf"), "scale_temperature present in one set only"
    return worst
