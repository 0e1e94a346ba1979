// Protects validate(ScanParams) (SENSOR-SPEC §1–3, §8): the defaults pass, and every bad field is
// rejected with an owsim::Error that names its scenario key.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "geometry/error.hpp"
#include "sensor/fiber_layout.hpp"
#include "sensor/scan_params_check.hpp"

namespace owsim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

void expect_rejected(const std::string& key, const std::function<void(ScanParams&)>& spoil) {
  ScanParams p;
  spoil(p);
  try {
    validate(p);
    ADD_FAILURE() << key << ": accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(key + ": ", 0), 0u) << e.what();
  }
}

TEST(ScanParamsCheck, DefaultsAndOverridesPass) {
  EXPECT_NO_THROW(validate(ScanParams{}));
  ScanParams p;
  p.model = SensorModel::hellas;
  p.fibers_per_line = 2;
  p.lines_per_frame = 1;
  p.sweep_deg = 59.0;
  p.frame_jitter_deg = 0.5;
  p.alpha_table_deg = {-90.0};
  p.start_s = -5.0;
  EXPECT_NO_THROW(validate(p));
  p.alpha_table_deg = default_alpha_table_deg(2);
  EXPECT_NO_THROW(validate(p));
}

TEST(ScanParamsCheck, EachBadFieldNamesItsKey) {
  expect_rejected("sensor.prf_hz", [](ScanParams& p) { p.prf_hz = 0.0; });
  expect_rejected("sensor.prf_hz", [](ScanParams& p) { p.prf_hz = -61'111.0; });
  expect_rejected("sensor.prf_hz", [](ScanParams& p) { p.prf_hz = kNaN; });
  expect_rejected("sensor.prf_hz", [](ScanParams& p) { p.prf_hz = kInf; });
  expect_rejected("sensor.fibers_per_line", [](ScanParams& p) { p.fibers_per_line = 1; });
  expect_rejected("sensor.lines_per_frame", [](ScanParams& p) { p.lines_per_frame = 0; });
  expect_rejected("sensor.lines_per_frame", [](ScanParams& p) { p.lines_per_frame = 20'000'000; });
  expect_rejected("sensor.sweep_deg", [](ScanParams& p) { p.sweep_deg = 0.0; });
  expect_rejected("sensor.sweep_deg", [](ScanParams& p) { p.sweep_deg = kNaN; });
  expect_rejected("sensor.sweep_deg", [](ScanParams& p) { p.sweep_deg = 60.0; });  // + jitter
  expect_rejected("sensor.sweep_deg", [](ScanParams& p) {
    p.sweep_deg = 59.0;
    p.frame_jitter_deg = 0.6;
  });
  expect_rejected("sensor.frame_jitter_deg", [](ScanParams& p) { p.frame_jitter_deg = -0.1; });
  expect_rejected("sensor.frame_jitter_deg", [](ScanParams& p) { p.frame_jitter_deg = kNaN; });
  expect_rejected("sensor.sawtooth_deg", [](ScanParams& p) { p.sawtooth_deg = -0.134; });
  expect_rejected("sensor.sawtooth_deg", [](ScanParams& p) { p.sawtooth_deg = kInf; });
  expect_rejected("sensor.look_into_turn_s", [](ScanParams& p) { p.look_into_turn_s = -1.0; });
  expect_rejected("sensor.look_into_turn_limit_deg",
                  [](ScanParams& p) { p.look_into_turn_limit_deg = kNaN; });
  expect_rejected("sensor.alpha_table_deg",
                  [](ScanParams& p) { p.alpha_table_deg = default_alpha_table_deg(127); });
  expect_rejected("sensor.alpha_table_deg", [](ScanParams& p) {
    p.alpha_table_deg = default_alpha_table_deg(128);
    p.alpha_table_deg[5] = 91.0;
  });
  expect_rejected("sensor.alpha_table_deg", [](ScanParams& p) {
    p.alpha_table_deg = default_alpha_table_deg(128);
    p.alpha_table_deg[126] = kNaN;
  });
  expect_rejected("sensor.hellas_mirror_angle_factor_deg",
                  [](ScanParams& p) { p.hellas_mirror_angle_factor_deg = -0.001; });
  expect_rejected("sensor.start_s", [](ScanParams& p) { p.start_s = kNaN; });
  expect_rejected("sensor.reference_counts", [](ScanParams& p) { p.reference_counts = 4'096; });
  expect_rejected("sensor.speed_of_light_mps",
                  [](ScanParams& p) { p.counter.speed_of_light_mps = 0.0; });
  expect_rejected("sensor.refractive_index_air",
                  [](ScanParams& p) { p.counter.refractive_index_air = kNaN; });
  expect_rejected("sensor.timer_period_s", [](ScanParams& p) { p.counter.timer_period_s = -4e-9; });
  expect_rejected("sensor.timeout_counts", [](ScanParams& p) { p.counter.timeout_counts = 0; });
  expect_rejected("sensor.timeout_counts", [](ScanParams& p) { p.counter.timeout_counts = 5'000; });
}

TEST(ScanParamsCheck, MessageSaysWhatIsWrong) {
  ScanParams p;
  p.prf_hz = -5.0;
  try {
    validate(p);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "sensor.prf_hz: must be a finite number > 0, got -5");
  }
}

}  // namespace
}  // namespace owsim
