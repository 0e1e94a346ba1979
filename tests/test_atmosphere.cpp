// Protects the two-way atmospheric transmission (SENSOR-SPEC §7 T_atm): the source's constant and
// the Kruse/Kim visibility law, against hand-computed values and Koschmieder's definition.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geometry/error.hpp"
#include "sensor/atmosphere.hpp"

namespace owsim {
namespace {

TEST(Atmosphere, ConstantWithoutVisibility) {
  const Atmosphere air;
  EXPECT_EQ(two_way_transmission(air, 0.0), 0.95);
  EXPECT_EQ(two_way_transmission(air, 1200.0), 0.95);
  EXPECT_EQ(extinction_per_m(air), 0.0);
}

TEST(Atmosphere, KimExponent) {
  EXPECT_EQ(kim_size_exponent(100.0), 1.6);
  EXPECT_EQ(kim_size_exponent(50.0), 1.3);
  EXPECT_EQ(kim_size_exponent(10.0), 1.3);
  EXPECT_NEAR(kim_size_exponent(6.0), 1.3, 1e-15);  // the 0.16·V + 0.34 branch meets 1.3
  EXPECT_NEAR(kim_size_exponent(5.0), 1.14, 1e-15);
  EXPECT_NEAR(kim_size_exponent(1.0), 0.5, 1e-15);
  EXPECT_NEAR(kim_size_exponent(0.8), 0.3, 1e-15);
  EXPECT_EQ(kim_size_exponent(0.5), 0.0);
  EXPECT_EQ(kim_size_exponent(0.2), 0.0);
}

TEST(Atmosphere, FiveKilometreVisibilityAtOnePointFiveMicrons) {
  Atmosphere haze;
  haze.visibility_km = 5.0;
  // By hand: q = 0.16·5 + 0.34 = 1.14; σ = 3.912/5 · (1.5/0.55)^−1.14 = 0.249286 /km;
  // T(1 km) = exp(−2 · 0.249286) = 0.607397.
  EXPECT_NEAR(extinction_per_m(haze), 0.24928622e-3, 1e-11);
  EXPECT_NEAR(two_way_transmission(haze, 1000.0), 0.60739714, 1e-8);
  EXPECT_EQ(two_way_transmission(haze, 0.0), 1.0);
  EXPECT_EQ(two_way_transmission(haze, -5.0), 1.0);
  // Beer–Lambert: out and back over R is one way over 2R.
  EXPECT_NEAR(two_way_transmission(haze, 600.0),
              two_way_transmission(haze, 300.0) * two_way_transmission(haze, 300.0), 1e-15);
}

TEST(Atmosphere, VisibilityIsTwoPercentContrastAtFiveHundredFiftyNanometres) {
  // Koschmieder: at 0.55 µm one-way transmission over V is 2 % (3.912 ≈ ln 50), i.e. two-way
  // over V/2.
  for (const double v : {0.3, 0.9, 3.0, 20.0, 80.0}) {
    Atmosphere air;
    air.visibility_km = v;
    air.wavelength_um = 0.55;
    EXPECT_NEAR(two_way_transmission(air, 500.0 * v), 0.02, 1e-6) << "V = " << v;
  }
}

TEST(Atmosphere, LongerWavelengthsSeeFurtherInHaze) {
  Atmosphere clear;
  clear.visibility_km = 23.0;
  const double infrared = extinction_per_m(clear);
  clear.wavelength_um = 0.905;
  EXPECT_LT(infrared, extinction_per_m(clear));
  // q = 0 below 0.5 km: fog attenuates every wavelength alike.
  Atmosphere fog;
  fog.visibility_km = 0.2;
  EXPECT_NEAR(extinction_per_m(fog), 3.912 / 0.2 * 1e-3, 1e-15);
}

void expect_rejected(const Atmosphere& atmosphere, const std::string& key) {
  try {
    validate(atmosphere);
    ADD_FAILURE() << "accepted a bad " << key;
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(key), std::string::npos) << error.what();
  }
}

TEST(Atmosphere, ValidationNamesTheKey) {
  EXPECT_NO_THROW(validate(Atmosphere{}));
  Atmosphere a;
  a.transmission = 0.0;
  expect_rejected(a, "atmosphere.transmission");
  a.transmission = 1.2;
  expect_rejected(a, "atmosphere.transmission");
  a.transmission = NAN;
  expect_rejected(a, "atmosphere.transmission");
  a = {};
  a.visibility_km = 0.0;
  expect_rejected(a, "atmosphere.visibility_km");
  a.visibility_km = INFINITY;
  expect_rejected(a, "atmosphere.visibility_km");
  a = {};
  a.wavelength_um = -1.5;
  expect_rejected(a, "atmosphere.wavelength_um");
  a = {};
  a.visibility_km = 12.0;
  EXPECT_NO_THROW(validate(a));
}

}  // namespace
}  // namespace owsim
