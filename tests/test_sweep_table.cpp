// Protects sweep.csv (io/sweep/sweep_table.hpp, INTERFACE.md "Beyond one machine"): from members'
// summary.json written by hand, the exact table — the varied values, the counts, a column per
// class with `returns_noise` (false returns, SENSOR-SPEC §11; 0 for a summary without them, as
// owsim 0.1.0 wrote) and `returns_fog` only where a member flew in weather, and the wires'
// first-seen ranges.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.hpp"
#include "io/sweep/sweep_table.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;

SweepSpec threshold_sweep() {
  SweepSpec spec;
  spec.count = 2;
  SweepVariation threshold;
  threshold.key = "sensor.threshold";
  threshold.kind = SweepVariation::Kind::values;
  threshold.items = {"0.003", "0.005"};
  spec.vary = {threshold};
  return spec;
}

nlohmann::json member_summary(std::uint64_t wire, std::uint64_t ground, double first_seen_m) {
  return {
      {"frames", 3},
      {"pulses", 61056},
      {"second_returns", 2},
      {"returns", {{"wire", wire}, {"pole", 0}, {"tree", 0}, {"ground", ground}, {"building", 0}}},
      {"objects",
       {{{"id", "span/1"},
         {"class", "wire"},
         {"first_seen_range_m",
          first_seen_m > 0 ? nlohmann::json(first_seen_m) : nlohmann::json(nullptr)}}}}};
}

TEST(SweepTable, ANoiseColumnCountsFalseReturnsAndZeroWhereASummaryHasNone) {
  const test::TempDir out("owsim_sweep_table");
  const SweepSpec spec = threshold_sweep();
  nlohmann::json noisy = member_summary(5, 900, 412.5);
  noisy["returns"]["noise"] = 12;
  const nlohmann::json old = member_summary(4, 905, 0.0);  // no returns.noise
  fs::create_directories(out / "0");
  fs::create_directories(out / "1");
  std::ofstream(out / "0/summary.json") << noisy.dump(2);
  std::ofstream(out / "1/summary.json") << old.dump(2);
  write_sweep_table(spec, out.path());
  EXPECT_EQ(test::read_whole_file(out / "sweep.csv"),
            "member,sensor.threshold,frames,pulses,returns_wire,returns_pole,returns_tree,"
            "returns_ground,returns_building,returns_noise,second_returns,"
            "first_seen_range_m[span/1]\n"
            "0,0.003,3,61056,5,0,0,900,0,12,2,412.5000\n"
            "1,0.005,3,61056,4,0,0,905,0,0,2,\n");

  // A member in weather: the fog column joins, before noise.
  noisy["returns"]["fog"] = 33;
  std::ofstream(out / "0/summary.json") << noisy.dump(2);
  write_sweep_table(spec, out.path());
  const std::string table = test::read_whole_file(out / "sweep.csv");
  EXPECT_TRUE(
      table.starts_with("member,sensor.threshold,frames,pulses,returns_wire,returns_pole,"
                        "returns_tree,returns_ground,returns_building,returns_fog,"
                        "returns_noise,second_returns,"))
      << table;
  EXPECT_NE(table.find("\n0,0.003,3,61056,5,0,0,900,0,33,12,2,412.5000\n"), std::string::npos)
      << table;
  EXPECT_NE(table.find("\n1,0.005,3,61056,4,0,0,905,0,0,0,2,\n"), std::string::npos) << table;
}

}  // namespace
}  // namespace owsim
