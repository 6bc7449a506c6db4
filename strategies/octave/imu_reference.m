% The reference IMU calibration (thesis Method 2-5) as an external strategy for `adahrs fit`
% (docs/strategies-external.md): one JSON request on standard input, one JSON reply on standard
% output, the log on standard error. It reproduces the built-in `reference` strategy
% (calib/imu_calibration/imu_reference_fit.cc) in four sequential stages, each on the constants
% the earlier ones fitted:
%   1. thermal drift xi(t) = k0 + k1 t + k2 t^2 per channel (k3 = 0) over the thermal profile,
%      every temperature band weighing the same (band-weighted least squares in normalised
%      temperature, sandwich standard errors), from the request's per-band sums;
%   2. six-position offset O and scale S per accelerometer channel, T(up) = O + S g_l and
%      T(down) = O - S g_l, on thermally compensated means, the acquisitions of one orientation
%      pooled;
%   3. gyro cubic rate = l0 + l1 d + l2 d^2 + l3 d^3, d = T - T(0 deg/s), per gyro over the rate
%      steps about its axis;
%   4. cross-axis CA = g_local K^-1 and CG = 150 deg/s K^-1 from the fully calibrated means (with
%      CA = CG = I) of the rest and fastest-rate acquisitions about +x, +y, +z.
% Units: accelerometer U in duty (T1/T2 - 0.5), gyro U in counts, temperatures in counts of the
% channel's thermometer, rates in deg/s, gravity in m/s^2, CA in m/s^2 per g (g = 9.80665 m/s^2).
% Left out: the format-3 terms (scale against temperature, g-sensitivity, accelerometer
% nonlinearity), a thermal lag, the built-in's up/down-ramp hysteresis diagnostics, staged fits,
% and the correlation of successive samples (the standard errors are then optimistic).
% Run: octave-cli --no-gui --quiet --no-window-system imu_reference.m < request.json > reply.json

1;  % a script file (not a function file): the functions below are local to it

% ---- The fit ------------------------------------------------------------------------------------

function [c, se, diagnostics] = fit_imu_reference(request)
  channels = request.channels;
  acquisitions = as_cell(request.acquisitions);
  if isempty(request.thermal)
    refuse("no thermal profile in the request (give the thermal-calibration run)");
  end
  for i = 1:numel(acquisitions)
    if !isfield(acquisitions{i}, "samples")
      refuse(["the acquisitions have no rows: the strategy file needs ", ...
              "\"inputs\": {\"acquisition_samples\": true}"]);
    end
  end
  % The stages fill the constants in turn; CA = CG = I until the last (its means need them so).
  c = struct("thermal", struct("temp_sensor", {}, "k", {}, "temp_min_cnt", {}, "temp_max_cnt", {}),
             "accel", struct("offset_duty", {}, "scale_duty_per_g", {}),
             "gyro", struct("null_cnt", {}, "l", {}),
             "ca_mps2_per_g", eye(3), "cg", eye(3));
  se = c;
  diagnostics = struct();

  % Stage 1: the thermal drift of each channel against its own thermometer.
  thermal = thermal_profile(request.thermal);
  for ch = 1:9
    sensor = channels(ch).thermometer;
    [k, k_se, t_min, t_max, rms, bands] = fit_thermal(thermal, ch, sensor);
    c.thermal(ch) = struct("temp_sensor", sensor, "k", [k; 0], ...
                           "temp_min_cnt", t_min, "temp_max_cnt", t_max);
    se.thermal(ch) = struct("temp_sensor", NaN, "k", [k_se; NaN], ...
                            "temp_min_cnt", NaN, "temp_max_cnt", NaN);
    diagnostics.thermal.(channels(ch).name) = struct("bands", bands, "residual_rms", rms);
  end

  % Stage 2: six-position offset and scale of the accelerometers.
  [accel, accel_se] = fit_six_position(c, acquisitions, channels, request.local_gravity_mps2);
  c.accel = accel;
  se.accel = accel_se;

  % Stage 3: each gyro's cubic over the rate steps about its axis.
  for g = 1:3
    [c.gyro(g), se.gyro(g), rms] = fit_gyro(c, acquisitions, g);
    diagnostics.gyro.(channels(6 + g).name) = struct("residual_rms_dps", rms);
  end

  % Stage 4: cross-axis, from the cross_axis step if there is one, else the accel and gyro steps.
  [accel_k, gyro_k, source] = cross_axis_means(c, acquisitions);
  [c.ca_mps2_per_g, se.ca_mps2_per_g, ca_condition] = ...
      fit_cross_axis(accel_k, request.local_gravity_mps2, "accelerometer cross-axis");
  [c.cg, se.cg, cg_condition] = fit_cross_axis(gyro_k, cross_axis_rate_dps(), "gyro cross-axis");
  diagnostics.cross_axis = struct("source", source, "ca_condition", ca_condition, ...
                                  "cg_condition", cg_condition);
end

% ---- Constants of the method --------------------------------------------------------------------

function g = standard_gravity_mps2()  % the unit "g"
  g = 9.80665;
end

function r = cross_axis_rate_dps()  % CG's reference rate (thesis Eq. 28)
  r = 150.0;
end

% The least-squares driver's limits (calib/solvers/linear_least_squares.h).
function c = max_condition()
  c = 1e8;
end

function t = rank_tolerance()
  t = 1e-12;
end

function refuse(message)
  error("imu_reference:refused", "design refused: %s", message);
end

function c = as_cell(x)  % jsondecode gives a struct array for alike objects, else a cell array
  if isstruct(x)
    c = num2cell(x);
  else
    c = x;
  end
end

% ---- The double-precision compensator (firmware_model/reference_compensator.cc) ----------------

% The nine outputs for the rows u (n x 9, raw U) and temp (n x 3, counts): "thermal" gives
% T = U - xi(t); "full" gives A (m/s^2, 3), W (deg/s, 3) and the accelerometer pairs'
% half-differences (g, 3) as the firmware does.
function out = compensate(c, mode, u, temp)
  t = zeros(size(u));
  for ch = 1:9
    k = c.thermal(ch).k;
    x = temp(:, c.thermal(ch).temp_sensor + 1);
    t(:, ch) = u(:, ch) - (k(1) + x .* (k(2) + x .* (k(3) + x .* k(4))));
  end
  if strcmp(mode, "thermal")
    out = t;
    return;
  end
  cal = zeros(size(u));
  for ch = 1:6
    cal(:, ch) = (t(:, ch) - c.accel(ch).offset_duty) / c.accel(ch).scale_duty_per_g;
  end
  for g = 1:3
    l = c.gyro(g).l;
    d = t(:, 6 + g) - c.gyro(g).null_cnt;
    cal(:, 6 + g) = l(1) + l(2) * d + l(3) * d .* d + l(4) * d .* d .* d;
  end
  pair = [2 5; 3 6; 1 4];  % body x, y, z: the two accelerometer channels (ax1 ax2, ...)
  ca_g = 0.5 * (cal(:, pair(:, 1)) + cal(:, pair(:, 2)));
  out = [ca_g * c.ca_mps2_per_g', cal(:, 7:9) * c.cg', ...
         0.5 * (cal(:, pair(:, 1)) - cal(:, pair(:, 2)))];
end

% The rows of an acquisition: u (n x 9) and temp (n x 3), whatever shape jsondecode gave an
% acquisition of one row or none.
function [u, temp] = rows_of(a)
  u = reshape(double(a.samples.u), [], 9);
  temp = reshape(double(a.samples.temp_cnt), [], 3);
end

% Per channel mean and standard error of the compensated rows of the acquisitions, pooled
% (calib/solvers/sample_statistics.cc: two passes, the deviations from the mean).
function [m, m_se] = means_of(c, mode, acquisitions)
  u = zeros(0, 9);
  temp = zeros(0, 3);
  for i = 1:numel(acquisitions)
    [ui, ti] = rows_of(acquisitions{i});
    u = [u; ui];
    temp = [temp; ti];
  end
  n = rows(u);
  if n < 2
    refuse(sprintf("%d sample(s), at least 2 are needed for a standard error", n));
  end
  out = compensate(c, mode, u, temp);
  if !all(isfinite(out(:)))
    refuse("a compensated sample is not finite");
  end
  m = sum(out, 1) / n;
  m_se = sqrt(sum((out - m) .^ 2, 1) / (n - 1)) / sqrt(n);
end

% ---- Polynomials in a normalised input (calib/solvers/polynomial_basis.cc) ----------------------

% The input's range [lo, hi] mapped onto [-1, 1]: u = (x - centre) / half_span.
function [centre, half_span] = scaling_from_range(lo, hi)
  centre = 0.5 * (lo + hi);
  half_span = 0.5 * (hi - lo);
  if !(half_span > 0)
    half_span = 1.0;
  end
end

% T with raw = T * normalised for a polynomial of `degree` in u = (x - centre) / half_span.
function t = normalised_to_raw(centre, half_span, degree)
  t = zeros(degree + 1);
  for i = 0:degree
    for k = 0:i
      t(k + 1, i + 1) = nchoosek(i, k) * (-centre) ^ (i - k) / half_span ^ i;
    end
  end
end

% ---- The least-squares driver (calib/solvers/linear_least_squares.cc) --------------------------

% Minimises sum w (y - A beta)^2 by Householder QR on the equilibrated columns of sqrt(W) A;
% cov is (A'WA)^-1 scaled by the residual variance ("residual") or not ("known").
function [beta, cov, rms] = weighted_least_squares(a, y, w, error_scale, context)
  [n, p] = size(a);
  if n < p || (n == p && strcmp(error_scale, "residual"))
    refuse(sprintf("%s: %d observations for %d terms", context, n, p));
  end
  if !all(isfinite([a(:); y(:); w(:)])) || any(w <= 0)
    refuse(sprintf("%s: an observation is not finite or has a weight <= 0", context));
  end
  sqrt_w = sqrt(w);
  scaled = sqrt_w .* a;
  norms = sqrt(sum(scaled .^ 2, 1));
  d = ones(1, p);
  d(norms > 0) = 1 ./ norms(norms > 0);
  scaled = scaled .* d;
  [q, r] = qr(scaled, 0);
  s = svd(r);  % descending
  condition = Inf;
  if s(p) > 0
    condition = s(1) / s(p);
  end
  if sum(s > rank_tolerance() * s(1)) < p || !(condition <= max_condition())
    refuse(sprintf("%s: rank %d of %d terms, condition number %.3g (limit %.3g)", context, ...
                   sum(s > rank_tolerance() * s(1)), p, condition, max_condition()));
  end
  beta = d' .* (r \ (q' * (sqrt_w .* y)));
  residuals = y - a * beta;
  r_inv = r \ eye(p);
  sigma2 = 1.0;
  if strcmp(error_scale, "residual")
    sigma2 = (w' * residuals .^ 2) / (n - p);
  end
  cov = d' .* (sigma2 * (r_inv * r_inv')) .* d;
  rms = sqrt(sum(residuals .^ 2) / n);
end

% ---- Stage 1: thermal drift (calib/solvers/thermal_drift_fit.cc) --------------------------------

% The request's thermal profile as arrays, one column per (thermometer, band, segment) row:
% y(:, ch, row) the sums of d^k U (k = 0..2) of channel ch (NaN when another thermometer drives
% it), mean and m2 its mean and sum of squared deviations.
function p = thermal_profile(thermal)
  bands = as_cell(thermal.bands);
  nb = numel(bands);
  p.thermometer = zeros(1, nb);
  p.band = zeros(1, nb);
  p.pivot = zeros(1, nb);
  p.count = zeros(1, nb);
  p.temp_min = zeros(1, nb);
  p.temp_max = zeros(1, nb);
  p.d_sums = zeros(4, nb);
  p.y = NaN(3, 9, nb);
  p.mean = NaN(9, nb);
  p.m2 = NaN(9, nb);
  for b = 1:nb
    r = bands{b};
    p.thermometer(b) = r.thermometer;
    p.band(b) = r.band;
    p.pivot(b) = r.pivot_cnt;
    p.count(b) = r.count;
    p.temp_min(b) = r.temp_min_cnt;
    p.temp_max(b) = r.temp_max_cnt;
    p.d_sums(:, b) = r.d_sums(:);
    chs = as_cell(r.channels);
    for i = 1:numel(chs)
      ch = chs{i}.channel + 1;
      p.y(:, ch, b) = chs{i}.u_sums(:);
      p.mean(ch, b) = chs{i}.u_mean;
      p.m2(ch, b) = chs{i}.u_m2;
    end
  end
end

% Channel ch's drift k (3) in raw counts with its standard errors, the fitted temperature span, the
% residual rms and the number of bands. Every band weighs the same: w = 1 / (rows in the band,
% every segment pooled). The normal equations are in u = (t - centre) / half_span; a row's sums of
% u^k and u^k U follow from its sums of d^k and d^k U with u = alpha + beta d (t = pivot + d).
function [k, k_se, t_min, t_max, rms, bands] = fit_thermal(p, ch, sensor)
  rows = find(p.thermometer == sensor);
  if isempty(rows) || any(isnan(p.y(1, ch, rows)))
    refuse(sprintf("thermal fit of channel %d: no thermal sums for thermometer %d", ch - 1, sensor));
  end
  [band_numbers, ~, band_of_row] = unique(p.band(rows));
  band_count = accumarray(band_of_row(:), p.count(rows)(:));
  bands = numel(band_numbers);
  if bands < 4
    refuse(sprintf("thermal fit of channel %d: %d temperature band(s), at least 4 are needed", ...
                   ch - 1, bands));
  end
  t_min = min(p.temp_min(rows));
  t_max = max(p.temp_max(rows));
  [centre, half_span] = scaling_from_range(t_min, t_max);

  m = zeros(3);    % sum w a a', a = (1, u, u^2)
  g = zeros(3);    % sum w^2 a a' (the sandwich's middle)
  rhs = zeros(3, 1);
  for i = 1:numel(rows)
    b = rows(i);
    alpha = (p.pivot(b) - centre) / half_span;
    beta = 1.0 / half_span;
    s_d = [p.count(b); p.d_sums(:, b)];   % sum d^j, j = 0..4
    s_dy = p.y(:, ch, b);                 % sum d^j U, j = 0..2
    s_u = zeros(5, 1);                    % sum u^k, k = 0..4
    s_uy = zeros(3, 1);                   % sum u^k U, k = 0..2
    for kk = 0:4
      for j = 0:kk
        term = nchoosek(kk, j) * alpha ^ (kk - j) * beta ^ j;
        s_u(kk + 1) += term * s_d(j + 1);
        if kk <= 2
          s_uy(kk + 1) += term * s_dy(j + 1);
        end
      end
    end
    w = 1.0 / band_count(band_of_row(i));
    m += w * hankel(s_u(1:3), s_u(3:5));
    g += w * w * hankel(s_u(1:3), s_u(3:5));
    rhs += w * s_uy;
  end

  % The equilibrated normal equations, with the driver's rank and condition tests.
  d = 1 ./ sqrt(diag(m));
  ms = d .* m .* d';
  s = sqrt(max(eig((ms + ms') / 2), 0));  % ascending
  condition = Inf;
  if s(1) > 0
    condition = s(3) / s(1);
  end
  if sum(s > rank_tolerance() * s(3)) < 3 || !(condition <= max_condition())
    refuse(sprintf("thermal fit of channel %d: condition number %.3g (limit %.3g)", ...
                   ch - 1, condition, max_condition()));
  end
  r = chol(ms);
  ms_inv = r \ (r' \ eye(3));
  m_inv = d .* ms_inv .* d';
  coef = d .* (ms_inv * (d .* rhs));

  n = sum(p.count(rows));
  sum_sq = thermal_residual_sum(p, ch, rows, coef, centre, half_span);
  covariance = (sum_sq / (n - 3)) * m_inv * g * m_inv;
  t = normalised_to_raw(centre, half_span, 2);
  k = t * coef;
  k_se = sqrt(diag(t * covariance * t'));
  rms = sqrt(sum_sq / n);
end

% Sum of the squared residuals of U about the fit, from each row's sums about its own mean (no
% cancellation against the large gyro counts): in a row the fit is q0 + q1 d + q2 d^2 and
% sum (U - q)^2 = M2 - 2 sum (U - mean)(q - mean) + sum (q - mean)^2.
function total = thermal_residual_sum(p, ch, rows, coef, centre, half_span)
  total = 0.0;
  for b = rows
    alpha = (p.pivot(b) - centre) / half_span;
    beta = 1.0 / half_span;
    n = p.count(b);
    s = p.d_sums(:, b);
    y = p.y(:, ch, b);
    mean = p.mean(ch, b);
    a = coef(1) + coef(2) * alpha + coef(3) * alpha * alpha - mean;  % q0 - mean
    q1 = (coef(2) + 2.0 * coef(3) * alpha) * beta;
    q2 = coef(3) * beta * beta;
    cross = a * (y(1) - n * mean) + q1 * (y(2) - mean * s(1)) + q2 * (y(3) - mean * s(2));
    fit_sq = a * a * n + 2 * a * q1 * s(1) + (q1 * q1 + 2 * a * q2) * s(2) ...
             + 2 * q1 * q2 * s(3) + q2 * q2 * s(4);
    total += p.m2(ch, b) - 2 * cross + fit_sq;
  end
end

% ---- Stage 2: six-position offset and scale (calib/solvers/six_position_fit.cc) ----------------

function [accel, accel_se] = fit_six_position(c, acquisitions, channels, g_local_mps2)
  g = g_local_mps2 / standard_gravity_mps2();  % the station's gravity in g
  % The thermally compensated means of each orientation, its accel acquisitions pooled.
  orientation = cellfun(@(a) a.orientation, acquisitions);
  is_accel = cellfun(@(a) strcmp(a.kind, "accel"), acquisitions);
  means = containers.Map("KeyType", "double", "ValueType", "any");
  for o = unique(orientation(is_accel))(:)'
    [m, m_se] = means_of(c, "thermal", acquisitions(is_accel & orientation == o));
    means(o) = [m; m_se];
  end
  accel = struct("offset_duty", {}, "scale_duty_per_g", {});
  accel_se = accel;
  for ch = 1:6
    up = 10 * (channels(ch).axis + 1) + 1;
    down = up + 1;
    if !isKey(means, up) || !isKey(means, down)
      refuse(sprintf("six-position fit: channel %s needs orientations %d and %d", ...
                     channels(ch).name, up, down));
    end
    y = [means(up)(1, ch); means(down)(1, ch)];
    y_se = [means(up)(2, ch); means(down)(2, ch)];
    % T = O + S g up, O - S g down: two observations, two unknowns, known variances.
    [beta, cov] = weighted_least_squares([1, g; 1, -g], y, 1 ./ y_se .^ 2, "known", ...
                                         ["six-position fit of ", channels(ch).name]);
    accel(ch) = struct("offset_duty", beta(1), "scale_duty_per_g", beta(2));
    accel_se(ch) = struct("offset_duty", sqrt(cov(1, 1)), "scale_duty_per_g", sqrt(cov(2, 2)));
  end
end

% ---- Stage 3: gyro cubic (calib/solvers/gyro_scale_fit.cc) -------------------------------------

% Gyro g (1..3, about body axis g) from the gyro acquisitions whose up axis is g.
function [fit, fit_se, rms] = fit_gyro(c, acquisitions, g)
  rate = [];
  t = [];
  t_se = [];
  for i = 1:numel(acquisitions)
    a = acquisitions{i};
    if !strcmp(a.kind, "gyro") || floor(a.orientation / 10) != g
      continue;
    end
    [m, m_se] = means_of(c, "thermal", {a});
    up_sign = 1 - 2 * (mod(a.orientation, 10) != 1);  % face 1: the axis up, 2: down
    rate(end + 1, 1) = a.rate_dps * up_sign;
    t(end + 1, 1) = m(6 + g);
    t_se(end + 1, 1) = m_se(6 + g);
  end
  context = sprintf("gyro scale fit of gyro %d", g - 1);
  % The null step: the first of those nearest 0 deg/s, within 0.01 deg/s.
  zero = 0;
  for i = 1:numel(rate)
    if abs(rate(i)) <= 0.01 && (zero == 0 || abs(rate(i)) < abs(rate(zero)))
      zero = i;
    end
  end
  if zero == 0
    refuse([context, ": no 0 deg/s step to normalise the means by"]);
  end
  if numel(unique(rate)) < 5
    refuse(sprintf("%s: %d distinct rates, at least 5 are needed", context, numel(unique(rate))));
  end
  x = t - t(zero);
  [centre, half_span] = scaling_from_range(min(x), max(x));
  u = (x - centre) / half_span;
  [beta, cov, rms] = weighted_least_squares([ones(size(u)), u, u .^ 2, u .^ 3], rate, ...
                                            ones(size(u)), "residual", context);
  tr = normalised_to_raw(centre, half_span, 3);
  fit = struct("null_cnt", t(zero), "l", tr * beta);
  fit_se = struct("null_cnt", t_se(zero), "l", sqrt(diag(tr * cov * tr')));
end

% ---- Stage 4: cross-axis (calib/solvers/cross_axis_fit.cc) -------------------------------------

% K's columns (means) and their standard errors for CA (accelerometers, g) and CG (gyros, scaled
% to 150 deg/s) from the fully calibrated means about +x, +y, +z: the last acquisition at rest
% (|rate| < 1 deg/s) and the first of the fastest (rate > 1 deg/s) in each orientation.
function [accel_k, gyro_k, source] = cross_axis_means(c, acquisitions)
  kinds = cellfun(@(a) a.kind, acquisitions, "UniformOutput", false);
  if any(strcmp(kinds, "cross_axis"))
    rest_kind = "cross_axis";
    rate_kind = "cross_axis";
    source = "cross_axis step";
  else
    rest_kind = "accel";
    rate_kind = "gyro";
    source = "accel and gyro steps";
  end
  accel_k = struct("mean", NaN(3), "se", NaN(3), "found", [0 0 0]);
  gyro_k = accel_k;
  for axis = 1:3
    o = 10 * axis + 1;
    rest = [];
    fast = [];
    for i = 1:numel(acquisitions)
      a = acquisitions{i};
      if a.orientation != o
        continue;
      end
      if strcmp(a.kind, rest_kind) && abs(a.rate_dps) < 1.0
        rest = a;
      end
      if strcmp(a.kind, rate_kind) && a.rate_dps > 1.0 && ...
         (isempty(fast) || a.rate_dps > fast.rate_dps)
        fast = a;
      end
    end
    if !isempty(rest)
      [m, m_se] = means_of(c, "full", {rest});
      accel_k.mean(:, axis) = m(1:3);
      accel_k.se(:, axis) = m_se(1:3);
      accel_k.found(axis) = 1;
    end
    if !isempty(fast)
      [m, m_se] = means_of(c, "full", {fast});
      scale = cross_axis_rate_dps() / fast.rate_dps;
      gyro_k.mean(:, axis) = scale * m(4:6);
      gyro_k.se(:, axis) = scale * m_se(4:6);
      gyro_k.found(axis) = 1;
    end
  end
end

% C = reference * K^-1 with first-order standard errors, the means independent:
% dC_rc / dK_ij = -reference (K^-1)_ri (K^-1)_jc.
function [matrix, matrix_se, condition] = fit_cross_axis(k, reference, context)
  for axis = 1:3
    if !k.found(axis)
      refuse(sprintf("%s: orientation %d is missing (11, 21 and 31 are needed)", ...
                     context, 10 * axis + 1));
    end
    if !(k.mean(axis, axis) > 0)
      refuse(sprintf("%s: in orientation %d the up axis reads %.6g, not a positive reference", ...
                     context, 10 * axis + 1, k.mean(axis, axis)));
    end
  end
  s = svd(k.mean);
  condition = Inf;
  if s(3) > 0
    condition = s(1) / s(3);
  end
  if !(condition <= 2.0)
    refuse(sprintf("%s: the three means do not span three axes (condition number %.3g)", ...
                   context, condition));
  end
  k_inv = inv(k.mean);
  matrix = reference * k_inv;
  matrix_se = zeros(3);
  for r = 1:3
    for col = 1:3
      partial = reference * k_inv(r, :)' * k_inv(:, col)';  % (i, j)
      matrix_se(r, col) = sqrt(sum(sum((partial .* k.se) .^ 2)));
    end
  end
end

% ---- JSON out -----------------------------------------------------------------------------------
% Written by hand: Octave 7's jsonencode writes some small numbers as 0 (1.2345678901234567e-18,
% 1e-20/3: a gyro's l3 is ~1e-20) and a 1-element array as a scalar.

function s = json_number(x)
  if !isfinite(x)
    s = "null";
    return;
  end
  for digits = 15:17  % the shortest form that reads back as the same double
    s = sprintf("%.*g", digits, x);
    if str2double(s) == x
      break;
    end
  end
end

function s = json_array(v)  % always an array, whatever the length
  parts = arrayfun(@json_number, v(:)', "UniformOutput", false);
  s = ["[", strjoin(parts, ", "), "]"];
end

function s = json_matrix(m)  % rows as arrays
  parts = arrayfun(@(r) json_array(m(r, :)), 1:rows(m), "UniformOutput", false);
  s = ["[", strjoin(parts, ", "), "]"];
end

function s = json_string(text)
  s = strrep(text, "\\", "\\\\");
  s = strrep(s, "\"", "\\\"");
  s = regexprep(s, "[\\x00-\\x1f]", " ");
  s = ["\"", s, "\""];
end

function s = json_object(varargin)  % json_object(key, json text, key, json text, ...)
  parts = cell(1, nargin / 2);
  for i = 1:2:nargin
    parts{(i + 1) / 2} = [json_string(varargin{i}), ": ", varargin{i + 1}];
  end
  s = ["{", strjoin(parts, ", "), "}"];
end

function s = json_list(items)  % a cell of JSON texts
  s = ["[", strjoin(items, ",\n  "), "]"];
end

% The IMU constants object (docs/constants-file.md); the standard errors have the same shape.
function s = constants_json(c)
  thermal = arrayfun(@(t) json_object("temp_sensor", json_number(t.temp_sensor),
                                      "k", json_array(t.k),
                                      "temp_min_cnt", json_number(t.temp_min_cnt),
                                      "temp_max_cnt", json_number(t.temp_max_cnt)),
                     c.thermal, "UniformOutput", false);
  accel = arrayfun(@(a) json_object("offset_duty", json_number(a.offset_duty),
                                    "scale_duty_per_g", json_number(a.scale_duty_per_g)),
                   c.accel, "UniformOutput", false);
  gyro = arrayfun(@(g) json_object("null_cnt", json_number(g.null_cnt), "l", json_array(g.l)),
                  c.gyro, "UniformOutput", false);
  s = json_object("thermal", json_list(thermal), "accel", json_list(accel),
                  "gyro", json_list(gyro), "ca_mps2_per_g", json_matrix(c.ca_mps2_per_g),
                  "cg", json_matrix(c.cg));
end

function s = diagnostics_json(d, channels)
  thermal = cell(1, 9);
  for ch = 1:9
    t = d.thermal.(channels(ch).name);
    thermal{ch} = json_object("channel", json_string(channels(ch).name),
                              "bands", json_number(t.bands),
                              "residual_rms", json_number(t.residual_rms));
  end
  gyro = cell(1, 3);
  for g = 1:3
    gyro{g} = json_object("channel", json_string(channels(6 + g).name), "residual_rms_dps",
                          json_number(d.gyro.(channels(6 + g).name).residual_rms_dps));
  end
  x = d.cross_axis;
  s = json_object("thermal", json_list(thermal), "gyro", json_list(gyro),
                  "cross_axis", json_object("source", json_string(x.source),
                                            "ca_condition", json_number(x.ca_condition),
                                            "cg_condition", json_number(x.cg_condition)));
end

% ---- The program --------------------------------------------------------------------------------

% Octave 7 saves the command history at exit and, once standard input has reached its end, prints
% "error: ignoring const execution_exception& while preparing to exit" there: save none.
history_save(false);
try
  text = fread(stdin, Inf, "*char")';  % the whole request, to its end
  % jsondecode (RapidJSON's fast parse) reads a few percent of 17-digit numbers one unit in
  % the last place off; the constants move by ~1e-15 of their size, far inside any tolerance.
  request = jsondecode(text);
  if !strcmp(request.protocol, "adahrs-strategy-request") || request.protocol_version != 1 ...
     || !strcmp(request.kind, "imu")
    error("imu_reference:request", "not an IMU strategy request of protocol version 1");
  end
  if request.firmware_format != 2
    error("imu_reference:request", ...
          "firmware format %d asked: this strategy fits format-2 constants only", ...
          request.firmware_format);
  end
  fprintf(stderr, "imu_reference: %s: %d acquisitions\n", request.serial, ...
          numel(request.acquisitions));
  [c, se, diagnostics] = fit_imu_reference(request);
  reply = json_object("protocol", json_string("adahrs-strategy-reply"),
                      "protocol_version", "1",
                      "serial", json_string(request.serial),
                      "constants", constants_json(c),
                      "standard_errors", constants_json(se),
                      "diagnostics", diagnostics_json(diagnostics, request.channels),
                      "log", json_list({json_string(["reference fit, cross-axis from the ", ...
                                                     diagnostics.cross_axis.source])}));
  fputs(stdout, [reply, "\n"]);
  fflush(stdout);
catch err
  serial = "?";
  if exist("request", "var") && isstruct(request) && isfield(request, "serial")
    serial = request.serial;
  end
  fprintf(stderr, "imu_reference: unit %s: %s\n", serial, err.message);
  exit(1);
end
