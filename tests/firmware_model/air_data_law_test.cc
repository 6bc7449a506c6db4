// The ADS firmware's air-data laws (target/air_data_law.h) against independent truth: the
// published ISA pressures (US Standard Atmosphere 1976 / ICAO) and sensor_sim's own atmosphere and
// airspeed formulas, over the whole envelope; the compiled ROM tables against their generator.
#include "adahrs_build_paths.h"
#include "firmware_model/unit_firmware.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "common/air_data.h"
#include "common/atmosphere.h"
#include "firmware_model/air_data_law.h"

namespace adahrs::firmware_model {
namespace {

int32_t PressureQ31(double pa) {
  return static_cast<int32_t>(std::llround(std::ldexp(pa, 31 - kPressureExponent)));
}

double AltitudeFt(double ps_pa, uint16_t* flags) {
  DspEngine engine(CompensatorDspConfig());
  return std::ldexp(static_cast<double>(IsaAltitudeQ31(&engine, PressureQ31(ps_pa), flags)),
                    kAltitudeExponent - 31);
}

double AirspeedKt(double qc_pa, uint16_t* flags) {
  DspEngine engine(CompensatorDspConfig());
  return std::ldexp(static_cast<double>(CasQ31(&engine, PressureQ31(qc_pa), flags)),
                    kAirspeedExponent - 31);
}

TEST(AirDataTables, CompiledTablesAreTheGeneratorsOutput) {
  if (std::getenv("ADAHRS_WRITE_AIR_DATA_TABLES") != nullptr) {
    std::ofstream(std::string(ADAHRS_SOURCE_DIR) + "/firmware_model/target/air_data_tables.c")
        << AirDataTablesSource();
  }
  const std::vector<int32_t> isa = IsaAltitudeTable(), cas = CasSquaredTable();
  for (size_t k = 0; k < isa.size(); ++k)
    ASSERT_EQ(kIsaAltitudeTableQ31[k], isa[k]) << "ISA entry " << k;
  for (size_t k = 0; k < cas.size(); ++k)
    ASSERT_EQ(kCasSquaredTableQ31[k], cas[k]) << "CAS entry " << k;
  std::ifstream file(std::string(ADAHRS_SOURCE_DIR) + "/firmware_model/target/air_data_tables.c");
  std::stringstream text;
  text << file.rdbuf();
  EXPECT_EQ(text.str(), AirDataTablesSource()) << "air_data_tables.c differs from its generator";
}

// Published ISA static pressure (hPa, to 0.01 hPa) at pressure altitudes; the tolerance is the
// rounding of the published figure (0.005 hPa) through the local slope, plus 0.5 ft.
TEST(AirDataLaw, IsaAltitudeMatchesThePublishedTable) {
  const std::pair<double, double> kTable[] = {{0.0, 1013.25},
                                              {5000.0, 843.07},
                                              {10000.0, 696.82},
                                              {20000.0, 465.63},
                                              {30000.0, 300.90},
                                              {36089.0, 226.32},
                                              {40000.0, 187.54},
                                              {50000.0, 115.97}};
  for (const auto& [alt_ft, hpa] : kTable) {
    uint16_t flags = 0;
    const double slope_ft_per_pa =
        AltitudeFt(hpa * 100.0 - 1.0, &flags) - AltitudeFt(hpa * 100.0, &flags);
    EXPECT_NEAR(AltitudeFt(hpa * 100.0, &flags), alt_ft, 0.5 + 0.5 * std::abs(slope_ft_per_pa))
        << hpa << " hPa";
    EXPECT_EQ(flags, 0) << hpa << " hPa";
  }
}

// Largest |error(x)| for x = from, from + step, ... <= to, and where; every output unflagged.
struct Worst {
  double error = 0.0;
  double at = 0.0;
};
template <typename ErrorOf>
Worst WorstOver(double from, double to, double step, ErrorOf error_of) {
  Worst w;
  for (double x = from; x <= to; x += step) {
    uint16_t flags = 0;
    const double e = std::abs(error_of(x, &flags));
    EXPECT_EQ(flags, 0) << x;
    if (e > w.error) w = {e, x};
  }
  return w;
}

// Every 10 Pa from 11 kPa (above 51,000 ft) to 125 kPa (below -5,000 ft): within 0.5 ft of
// sensor_sim's ISA (its own implementation); the interpolation error alone is <= 0.36 ft there.
// Up to 63,000 ft (6.2 kPa) within 1.2 ft (the table's curvature error grows as 1/p^2).
TEST(AirDataLaw, IsaAltitudeWithinHalfAFootOfTheAtmosphereModelOverTheEnvelope) {
  auto error_of = [](double pa, uint16_t* flags) {
    return AltitudeFt(pa, flags) - common::IsaPressureAltitudeFt(pa);
  };
  EXPECT_LT(WorstOver(6200.0, 10990.0, 10.0, error_of).error, 1.2);
  const Worst w = WorstOver(11000.0, 125000.0, 10.0, error_of);
  std::printf("worst ISA altitude error %.3f ft at %.0f Pa\n", w.error, w.at);
  EXPECT_LT(w.error, 0.5);
}

// 5...510 kt every 0.25 kt: within 0.02 kt of sensor_sim's calibrated airspeed (1/128 kt from the
// square root, the rest from the CAS^2 table's interpolation, largest at low speed).
TEST(AirDataLaw, CasWithinAFiftiethOfAKnotOfTheAirspeedLaw) {
  const Worst w = WorstOver(5.0, 510.0, 0.25, [](double kt, uint16_t* flags) {
    return AirspeedKt(common::ImpactPressurePaFromKt(kt), flags) - kt;
  });
  std::printf("worst CAS error %.4f kt at %.2f kt\n", w.error, w.at);
  EXPECT_LT(w.error, 0.02);
}

TEST(AirDataLaw, OutsideTheTablesTheOutputIsHeldAndFlagged) {
  uint16_t flags = 0;
  EXPECT_EQ(AirspeedKt(0.0, &flags), 0.0);
  EXPECT_EQ(AirspeedKt(-200.0, &flags), 0.0);
  EXPECT_EQ(flags, 0);
  const double top_kt = AirspeedKt(common::ImpactPressurePaFromKt(540.0), &flags);
  EXPECT_EQ(flags, kFlagOutputSaturated);
  EXPECT_NEAR(top_kt, CasKtFromImpactPa(kCasLastValidEntry * 256.0), 0.01);
  EXPECT_LT(top_kt, 512.0);
  flags = 0;
  const double high_ft = AltitudeFt(3000.0, &flags);
  EXPECT_EQ(flags, kFlagOutputSaturated);
  EXPECT_NEAR(high_ft, IsaAltitudeFtFromStaticPa(kIsaFirstValidEntry * 128.0), 0.01);
  flags = 0;
  EXPECT_EQ(AltitudeFt(-10.0, &flags), high_ft);
  EXPECT_EQ(flags, kFlagOutputSaturated);
}

TEST(AirDataLaw, CyclesPerLaw) {
  uint16_t flags = 0;
  DspEngine engine(CompensatorDspConfig());
  IsaAltitudeQ31(&engine, PressureQ31(50000.0), &flags);
  const uint32_t isa_cycles = engine.cycles();
  CasQ31(&engine, PressureQ31(20000.0), &flags);
  std::printf(
      "ISA altitude law %u cycles, CAS law %u cycles\n", isa_cycles, engine.cycles() - isa_cycles);
  EXPECT_LT(engine.cycles(), 600u);  // a few percent of the surface's cost budget per frame
}

}  // namespace
}  // namespace adahrs::firmware_model
