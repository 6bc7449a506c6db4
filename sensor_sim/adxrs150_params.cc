#include "sensor_sim/adxrs150_params.h"

#include "common/random.h"

namespace adahrs::sensor_sim {
namespace {

// Datasheet-level numbers, physics.md §2.1 (tags as there) and §6 rows 1-3, 13.
constexpr double kSensitivityTypical_mv_per_dps = 12.5;    // V [FRC]
constexpr double kSensitivityTolerance_mv_per_dps = 1.25;  // R, 11.25..13.75
constexpr double kNullTypical_v = 2.50;                    // R
constexpr double kNullTolerance_v = 0.45;                  // R, +-0.3..0.45 V: upper end
constexpr double kNullTc1Typical_dps_per_c = 0.1;          // E, 0.05..0.2 deg/s/degC
constexpr double kNullTc1Tolerance_dps_per_c = 0.2;        // E
constexpr double kNullTc2Tolerance_dps_per_c2 = 1.0e-3;    // E, <= 3.6 deg/s at +-60 degC
constexpr double kNullTc3Tolerance_dps_per_c3 = 1.0e-5;    // E, <= 2.2 deg/s at +-60 degC
constexpr double kSensTc1Typical_ppm_per_c = 300.0;        // R/E, ~ +-3 % over the range
constexpr double kSensTc1Tolerance_ppm_per_c = 500.0;      // R/E, <= 3 % at +-60 degC
constexpr double kSensTc2Tolerance_ppm_per_c2 = 5.0;       // E, <= 1.8 % at +-60 degC
constexpr double kNonlinearityTypical_pct_fs = 0.1;        // R
constexpr double kNonlinearityTolerance_pct_fs = 0.05;     // E
constexpr double kGSensitivityTypical_dps_per_g = 0.2;     // R, any axis
constexpr double kGSensitivityTolerance_dps_per_g = 0.3;   // E
constexpr double kNullSupplyTypical_dps_per_v = 1.0;       // R
constexpr double kNullSupplyTolerance_dps_per_v = 1.5;     // E
constexpr double kRateNoiseTypical_dps_per_rthz = 0.05;    // V [RS150P]
constexpr double kRateNoiseTolerance_dps_per_rthz = 0.01;  // E
constexpr double kFilterRTypical_kohm = 180.0;             // R (V for ADXRS645)
constexpr double kFilterRTolerance_kohm = 1.8;             // V for ADXRS645 (trimmed +-1 %)
constexpr double kFilterCTypical_nf = 22.0;                // 40 Hz with 180 kOhm, physics.md
constexpr double kFilterCTolerance_nf = 2.2;               // E, +-10 % capacitor
constexpr double kBiasInstabilityTypical_dph = 75.0;       // E, 50..100 deg/h
constexpr double kBiasInstabilityTolerance_dph = 25.0;     // E
constexpr double kRrwTypical_dph_per_rth = 20.0;           // E
constexpr double kRrwTolerance_dph_per_rth = 10.0;         // E
constexpr double kRateAdcNoise_lsb = 1.0;                  // E, 19-bit converter
constexpr double kTempOutTypical_v = 2.50;                 // R, at 298 K
constexpr double kTempOutTolerance_v = 0.1;                // E ("modest absolute accuracy")
constexpr double kTempSlopeTypical_mv_per_k = 8.4;         // R
constexpr double kTempSlopeTolerance_mv_per_k = 0.4;       // E
constexpr double kTempAdcNoise_lsb = 0.5;                  // E, dsPIC 12-bit ADC

double RandomSign(common::Rng& rng) { return rng.Uniform() < 0.5 ? -1.0 : 1.0; }

}  // namespace

Adxrs150Effects Adxrs150Effects::All() {
  Adxrs150Effects e;
  e.noise = e.bias_instability = e.rate_random_walk = e.null_tempco = e.sensitivity_tempco =
      e.nonlinearity = e.g_sensitivity = e.supply_sensitivity = e.adc_quantization = true;
  return e;
}

Adxrs150Params Adxrs150Params::Typical() {
  Adxrs150Params p;
  p.sensitivity_mv_per_dps = kSensitivityTypical_mv_per_dps;
  p.null_v = kNullTypical_v;
  p.output_ratiometric = false;  // ADXRS150 rate output is absolute (physics.md §2.1, V)
  p.null_tc1_dps_per_c = kNullTc1Typical_dps_per_c;
  p.null_tc2_dps_per_c2 = 0.0;
  p.null_tc3_dps_per_c3 = 0.0;
  p.sensitivity_tc1_ppm_per_c = kSensTc1Typical_ppm_per_c;
  p.sensitivity_tc2_ppm_per_c2 = 0.0;
  p.nonlinearity_quadratic_pct_fs = kNonlinearityTypical_pct_fs / 2.0;
  p.nonlinearity_cubic_pct_fs = kNonlinearityTypical_pct_fs / 2.0;
  p.g_sensitivity_dps_per_g = {kGSensitivityTypical_dps_per_g,
                               kGSensitivityTypical_dps_per_g,
                               kGSensitivityTypical_dps_per_g};
  p.null_supply_dps_per_v = kNullSupplyTypical_dps_per_v;
  p.rate_noise_dps_per_rthz = kRateNoiseTypical_dps_per_rthz;
  p.output_filter_r_kohm = kFilterRTypical_kohm;
  p.output_filter_c_nf = kFilterCTypical_nf;
  p.bias_instability_dph = kBiasInstabilityTypical_dph;
  p.rate_random_walk_dph_per_rth = kRrwTypical_dph_per_rth;
  p.rate_adc_noise_lsb = kRateAdcNoise_lsb;
  p.temp_out_v_at_298k = kTempOutTypical_v;
  p.temp_out_mv_per_k = kTempSlopeTypical_mv_per_k;
  p.temp_adc_noise_lsb = kTempAdcNoise_lsb;
  p.effects = Adxrs150Effects::Nominal();
  return p;
}

Adxrs150Params Adxrs150Params::Draw(uint64_t seed) {
  common::Rng rng(seed);
  Adxrs150Params p = Typical();
  p.sensitivity_mv_per_dps =
      rng.Tolerance(kSensitivityTypical_mv_per_dps, kSensitivityTolerance_mv_per_dps);
  p.null_v = rng.Tolerance(kNullTypical_v, kNullTolerance_v);
  // Drift signs are not known from any source: zero-mean spreads.
  p.null_tc1_dps_per_c = rng.Tolerance(0.0, kNullTc1Tolerance_dps_per_c);
  p.null_tc2_dps_per_c2 = rng.Tolerance(0.0, kNullTc2Tolerance_dps_per_c2);
  p.null_tc3_dps_per_c3 = rng.Tolerance(0.0, kNullTc3Tolerance_dps_per_c3);
  p.sensitivity_tc1_ppm_per_c = rng.Tolerance(0.0, kSensTc1Tolerance_ppm_per_c);
  p.sensitivity_tc2_ppm_per_c2 = rng.Tolerance(0.0, kSensTc2Tolerance_ppm_per_c2);
  // Total nonlinearity (max deviation from the best-fit line) split between the two shapes.
  const double total_pct_fs =
      rng.Tolerance(kNonlinearityTypical_pct_fs, kNonlinearityTolerance_pct_fs);
  const double cubic_share = rng.Uniform();
  p.nonlinearity_quadratic_pct_fs = RandomSign(rng) * (1.0 - cubic_share) * total_pct_fs;
  p.nonlinearity_cubic_pct_fs = RandomSign(rng) * cubic_share * total_pct_fs;
  for (double& g : p.g_sensitivity_dps_per_g)
    g = rng.Tolerance(0.0, kGSensitivityTolerance_dps_per_g);
  p.null_supply_dps_per_v = rng.Tolerance(0.0, kNullSupplyTolerance_dps_per_v);
  p.rate_noise_dps_per_rthz =
      rng.Tolerance(kRateNoiseTypical_dps_per_rthz, kRateNoiseTolerance_dps_per_rthz);
  p.output_filter_r_kohm = rng.Tolerance(kFilterRTypical_kohm, kFilterRTolerance_kohm);
  p.output_filter_c_nf = rng.Tolerance(kFilterCTypical_nf, kFilterCTolerance_nf);
  p.bias_instability_dph =
      rng.Tolerance(kBiasInstabilityTypical_dph, kBiasInstabilityTolerance_dph);
  p.rate_random_walk_dph_per_rth =
      rng.Tolerance(kRrwTypical_dph_per_rth, kRrwTolerance_dph_per_rth);
  p.temp_out_v_at_298k = rng.Tolerance(kTempOutTypical_v, kTempOutTolerance_v);
  p.temp_out_mv_per_k = rng.Tolerance(kTempSlopeTypical_mv_per_k, kTempSlopeTolerance_mv_per_k);
  return p;
}

nlohmann::json Adxrs150Params::ToJson() const {
  const Adxrs150Effects& e = effects;
  return nlohmann::json{
      {"effects",
       {{"noise", e.noise},
        {"bias_instability", e.bias_instability},
        {"rate_random_walk", e.rate_random_walk},
        {"null_tempco", e.null_tempco},
        {"sensitivity_tempco", e.sensitivity_tempco},
        {"nonlinearity", e.nonlinearity},
        {"g_sensitivity", e.g_sensitivity},
        {"supply_sensitivity", e.supply_sensitivity},
        {"adc_quantization", e.adc_quantization}}},
      {"sensitivity_mv_per_dps", sensitivity_mv_per_dps},
      {"null_v", null_v},
      {"output_ratiometric", output_ratiometric},
      {"null_tc1_dps_per_c", null_tc1_dps_per_c},
      {"null_tc2_dps_per_c2", null_tc2_dps_per_c2},
      {"null_tc3_dps_per_c3", null_tc3_dps_per_c3},
      {"sensitivity_tc1_ppm_per_c", sensitivity_tc1_ppm_per_c},
      {"sensitivity_tc2_ppm_per_c2", sensitivity_tc2_ppm_per_c2},
      {"nonlinearity_quadratic_pct_fs", nonlinearity_quadratic_pct_fs},
      {"nonlinearity_cubic_pct_fs", nonlinearity_cubic_pct_fs},
      {"g_sensitivity_dps_per_g", g_sensitivity_dps_per_g},
      {"null_supply_dps_per_v", null_supply_dps_per_v},
      {"rate_noise_dps_per_rthz", rate_noise_dps_per_rthz},
      {"output_filter_r_kohm", output_filter_r_kohm},
      {"output_filter_c_nf", output_filter_c_nf},
      {"bias_instability_dph", bias_instability_dph},
      {"rate_random_walk_dph_per_rth", rate_random_walk_dph_per_rth},
      {"bias_correlation_time_scale", bias_correlation_time_scale},
      {"rate_adc_noise_lsb", rate_adc_noise_lsb},
      {"temp_out_v_at_298k", temp_out_v_at_298k},
      {"temp_out_mv_per_k", temp_out_mv_per_k},
      {"temp_adc_noise_lsb", temp_adc_noise_lsb},
  };
}

Adxrs150Params Adxrs150Params::FromJson(const common::ParamReader& reader) {
  Adxrs150Params p;
  const common::ParamReader er = reader.Child("effects");
  Adxrs150Effects& e = p.effects;
  e.noise = er.Flag("noise");
  e.bias_instability = er.Flag("bias_instability");
  e.rate_random_walk = er.Flag("rate_random_walk");
  e.null_tempco = er.Flag("null_tempco");
  e.sensitivity_tempco = er.Flag("sensitivity_tempco");
  e.nonlinearity = er.Flag("nonlinearity");
  e.g_sensitivity = er.Flag("g_sensitivity");
  e.supply_sensitivity = er.Flag("supply_sensitivity");
  e.adc_quantization = er.Flag("adc_quantization");
  er.ExpectAllKeysUsed();
  // Ranges are physical plausibility bounds, several times the datasheet spreads; the external
  // scale-factor resistor can only lower the sensitivity (physics.md §2.1).
  p.sensitivity_mv_per_dps = reader.Number("sensitivity_mv_per_dps", 1.0, 20.0, "mV/(deg/s)");
  p.null_v = reader.Number("null_v", 1.0, 4.0, "V");
  p.output_ratiometric = reader.Flag("output_ratiometric");
  p.null_tc1_dps_per_c = reader.Number("null_tc1_dps_per_c", -2.0, 2.0, "deg/s/degC");
  p.null_tc2_dps_per_c2 = reader.Number("null_tc2_dps_per_c2", -0.05, 0.05, "deg/s/degC^2");
  p.null_tc3_dps_per_c3 = reader.Number("null_tc3_dps_per_c3", -1e-3, 1e-3, "deg/s/degC^3");
  p.sensitivity_tc1_ppm_per_c =
      reader.Number("sensitivity_tc1_ppm_per_c", -5000.0, 5000.0, "ppm/degC");
  p.sensitivity_tc2_ppm_per_c2 =
      reader.Number("sensitivity_tc2_ppm_per_c2", -100.0, 100.0, "ppm/degC^2");
  p.nonlinearity_quadratic_pct_fs =
      reader.Number("nonlinearity_quadratic_pct_fs", -2.0, 2.0, "% of 150 deg/s");
  p.nonlinearity_cubic_pct_fs =
      reader.Number("nonlinearity_cubic_pct_fs", -2.0, 2.0, "% of 150 deg/s");
  reader.NumberArray("g_sensitivity_dps_per_g", -2.0, 2.0, "deg/s/g", p.g_sensitivity_dps_per_g);
  p.null_supply_dps_per_v = reader.Number("null_supply_dps_per_v", -20.0, 20.0, "deg/s/V");
  p.rate_noise_dps_per_rthz = reader.Number("rate_noise_dps_per_rthz", 0.0, 1.0, "deg/s/sqrt(Hz)");
  p.output_filter_r_kohm = reader.Number("output_filter_r_kohm", 100.0, 300.0, "kOhm");
  p.output_filter_c_nf = reader.Number("output_filter_c_nf", 1.0, 1000.0, "nF");
  p.bias_instability_dph = reader.Number("bias_instability_dph", 0.0, 3600.0, "deg/h");
  p.rate_random_walk_dph_per_rth =
      reader.Number("rate_random_walk_dph_per_rth", 0.0, 3600.0, "deg/h/sqrt(h)");
  // Optional: files written before the truth variants carry no scale (the datasheet form, 1).
  if (reader.Has("bias_correlation_time_scale")) {
    p.bias_correlation_time_scale = reader.Number("bias_correlation_time_scale", 0.01, 100.0, "");
  }
  p.rate_adc_noise_lsb = reader.Number("rate_adc_noise_lsb", 0.0, 1000.0, "LSB rms");
  p.temp_out_v_at_298k = reader.Number("temp_out_v_at_298k", 1.5, 3.5, "V");
  p.temp_out_mv_per_k = reader.Number("temp_out_mv_per_k", 1.0, 20.0, "mV/K");
  p.temp_adc_noise_lsb = reader.Number("temp_adc_noise_lsb", 0.0, 100.0, "LSB rms");
  reader.ExpectAllKeysUsed();
  return p;
}

}  // namespace adahrs::sensor_sim
