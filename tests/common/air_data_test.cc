#include "common/air_data.h"

#include <stdexcept>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/atmosphere.h"
#include "common/units.h"
#include "tests/support/error_text.h"

namespace adahrs::common {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

struct CasImpact {
  double cas_kt;
  double qc_pa;
};

// shared/physics.md §4.1 CAS table (qc quoted to 0.1 Pa).
constexpr CasImpact kCasTable[] = {
    {40.0, 259.6},
    {60.0, 584.8},
    {100.0, 1630.3},
    {150.0, 3694.4},
    {250.0, 10498.2},
    {350.0, 21286.3},
    {450.0, 36800.9},
};

TEST(AirData, ImpactPressureMatchesPublishedTable) {
  // Half the last quoted digit (0.05 Pa) plus 1e-6 relative for the rounding of a0 in the table.
  for (const CasImpact& row : kCasTable) {
    EXPECT_NEAR(ImpactPressurePaFromKt(row.cas_kt), row.qc_pa, 0.05 + 1e-6 * row.qc_pa)
        << row.cas_kt << " kt";
  }
}

TEST(AirData, CalibratedAirspeedMatchesPublishedTable) {
  // 0.05 Pa of qc is at most 0.05 × 0.077 kt/Pa (the 40 kt sensitivity, physics.md §4.1).
  for (const CasImpact& row : kCasTable) {
    EXPECT_NEAR(CalibratedAirspeedKt(row.qc_pa), row.cas_kt, 0.004) << row.qc_pa << " Pa";
  }
}

TEST(AirData, ProtocolCheckValues) {
  // shared/protocols.md §5, quoted in hPa to 0.001 hPa: 100 kt → 16.303, 350 kt → 212.862;
  // at Vc = a0, qc = 904.76 hPa; a0 = 661.479 kt. The 350 kt value is truncated, not rounded
  // (physics.md §4.1 gives 21 286.3 Pa), so the tolerance is one last digit (0.1 Pa).
  EXPECT_NEAR(ImpactPressurePaFromKt(100.0), common::HpaToPa(16.303), 0.1);
  EXPECT_NEAR(ImpactPressurePaFromKt(350.0), common::HpaToPa(212.862), 0.1);
  EXPECT_NEAR(common::MpsToKt(SeaLevelSpeedOfSoundMps()), 661.479, 0.0005);
  EXPECT_NEAR(ImpactPressurePa(SeaLevelSpeedOfSoundMps()), common::HpaToPa(904.76), 0.5);
}

TEST(AirData, RoundTripOverTheSpeedRange) {
  // pow and its inverse compose to a few ulp; 1e-9 kt is 1e-12 relative at 650 kt.
  for (double cas_kt = 30.0; cas_kt <= 650.0; cas_kt += 5.0) {
    EXPECT_NEAR(CalibratedAirspeedKt(ImpactPressurePaFromKt(cas_kt)), cas_kt, 1e-9) << cas_kt;
  }
}

TEST(AirData, Fl350At250KcasCheckValue) {
  // physics.md §4.1: FL350, 250 KCAS → ps = 238.4 hPa, qc = 105.0 hPa, M = 0.741,
  // TAS = 427 kt in ISA. Tolerances are half the last quoted digit.
  const double ps_pa = IsaStaticPressurePaFromFt(35000.0);
  const double qc_pa = ImpactPressurePaFromKt(250.0);
  const double mach = MachNumber(qc_pa, ps_pa);
  const double tas_kt =
      common::MpsToKt(TrueAirspeedMps(mach, IsaTemperatureK(common::FtToM(35000.0))));
  EXPECT_NEAR(ps_pa, common::HpaToPa(238.4), 5.0);
  EXPECT_NEAR(qc_pa, common::HpaToPa(105.0), 5.0);
  EXPECT_NEAR(mach, 0.741, 0.0005);
  EXPECT_NEAR(tas_kt, 427.0, 0.5);
}

TEST(AirData, MachAt30000FtCheckValue) {
  // shared/protocols.md §5: 250 kt CAS at 30 000 ft → M = 0.668.
  EXPECT_NEAR(
      MachNumber(ImpactPressurePaFromKt(250.0), IsaStaticPressurePaFromFt(30000.0)), 0.668, 0.0005);
}

TEST(AirData, MachEqualsCasRatioAtSeaLevel) {
  // At ps = p0 the Mach and CAS formulas coincide: M = Vc/a0 exactly (up to rounding).
  for (double cas_kt : {50.0, 200.0, 600.0}) {
    EXPECT_NEAR(MachNumber(ImpactPressurePaFromKt(cas_kt), kIsaSeaLevelPressure_pa),
                common::KtToMps(cas_kt) / SeaLevelSpeedOfSoundMps(),
                1e-12);
  }
}

template <typename F>
std::string DomainErrorOf(F f) {
  return test_support::ErrorText<std::domain_error>(f);
}

TEST(AirData, SupersonicAndNegativeInputsThrowNamingTheValue) {
  EXPECT_THAT(DomainErrorOf([] { ImpactPressurePaFromKt(700.0); }),
              AllOf(HasSubstr("ImpactPressurePa"), HasSubstr("cas_mps = 360.1")));
  EXPECT_THAT(DomainErrorOf([] { CalibratedAirspeedMps(-1.0); }),
              AllOf(HasSubstr("qc_pa = -1"), HasSubstr("subsonic range")));
  EXPECT_THAT(DomainErrorOf([] { CalibratedAirspeedKt(95000.0); }), HasSubstr("qc_pa = 95000"));
  EXPECT_THAT(DomainErrorOf([] { MachNumber(30000.0, 20000.0); }),
              AllOf(HasSubstr("qc_pa = 30000"), HasSubstr("ps_pa = 20000")));
  EXPECT_THAT(DomainErrorOf([] { MachNumber(100.0, 0.0); }), HasSubstr("ps_pa = 0"));
  EXPECT_THAT(DomainErrorOf([] { TrueAirspeedMps(1.2, 250.0); }), HasSubstr("mach = 1.2"));
}

}  // namespace
}  // namespace adahrs::common
