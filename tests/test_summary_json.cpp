// summary.json (io/run/summary_json.hpp) and the per-object state behind it
// (io/run/flight_summary.hpp): the streamed text is byte for byte what nlohmann::json writes for
// the same document (an independent writer: the tree owsim built before issue 19), for random
// summaries with ids that need escapes; the totals come before the objects; and a summary's
// checkpoint costs the objects seen, not the objects tallied.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "geometry/error.hpp"
#include "io/run/flight_summary.hpp"
#include "io/run/run_checkpoint.hpp"
#include "io/run/summary_json.hpp"
#include "synthetic_flight.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::content;

class SummaryJsonTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("owsim_summary_json_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// A scene of `wires` conductors, `trees` trees and `meshes` buildings with awkward ids, in fog
// when `fog`.
Scene scene_of(int wires, int trees, int meshes, bool fog = false) {
  Scene scene;
  const char* odd[] = {"a \"quoted\" id", "back\\slash", "tab\there",
                       "nl\nid",          "ünïcödé ✓",   "\x01"};
  for (int i = 0; i < wires; ++i) {
    Conductor& wire = scene.conductors.emplace_back();
    wire.id = i < 6 ? std::string(odd[i]) : "span-" + std::to_string(i) + "/1";
  }
  for (int i = 0; i < trees; ++i) {
    scene.cylinders.push_back(
        {"forest/" + std::to_string(i), i % 5 == 0 ? SurfaceClass::pole : SurfaceClass::tree});
  }
  for (int i = 0; i < meshes; ++i) {
    MeshObject& mesh = scene.meshes.emplace_back();
    mesh.id = "barn \"" + std::to_string(i) + "\"";
    mesh.surface = i % 4 == 3 ? SurfaceClass::pole : SurfaceClass::building;
  }
  if (fog) scene.fog.push_back(FogVolume{"haze", 300.0});
  return scene;
}

// Frames of random hits on random objects, with ranges of every magnitude.
FlightSummary random_summary(std::size_t objects, std::uint64_t seed, int frames) {
  std::mt19937_64 rng(seed);
  FlightSummary summary(objects);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int frame = 0; frame < frames; ++frame) {
    FrameTally tally;
    tally.pulses = 20352;
    tally.returns_by_class = {rng() % 100, rng() % 100, rng() % 1000, rng() % 10000,
                              rng() % 300, rng() % 200, rng() % 7};
    tally.second_returns = rng() % 50;
    for (int k = 0; k < 40; ++k) {
      const double range = std::pow(10.0, 4.0 * unit(rng) - 1.0);
      tally.object_hits.push_back({static_cast<std::uint32_t>(rng() % (objects / 3 + 1)),
                                   static_cast<std::uint32_t>(rng() % 2),
                                   frame * 0.33 + unit(rng) * 0.3, range});
    }
    summary.add_frame(frame, tally);
  }
  return summary;
}

// The document as nlohmann::json builds it: the head's keys sorted, the objects last.
std::string oracle_text(const FlightSummary& summary, const Scene& scene,
                        const nlohmann::json& facts) {
  nlohmann::json head = facts;
  head["frames"] = summary.frames();
  head["pulses"] = summary.pulses();
  head["second_returns"] = summary.second_returns();
  head["returns"] = {{"wire", summary.returns_of(SurfaceClass::wire)},
                     {"pole", summary.returns_of(SurfaceClass::pole)},
                     {"tree", summary.returns_of(SurfaceClass::tree)},
                     {"ground", summary.returns_of(SurfaceClass::ground)},
                     {"building", summary.returns_of(SurfaceClass::building)},
                     {"noise", summary.returns_of(SurfaceClass::noise)}};
  head["false_returns_per_pulse"] =
      summary.pulses() == 0 ? 0.0
                            : static_cast<double>(summary.returns_of(SurfaceClass::noise)) /
                                  static_cast<double>(summary.pulses());
  const bool weather = !scene.fog.empty();
  if (weather) head["returns"]["fog"] = summary.returns_of(SurfaceClass::fog);
  std::map<std::string, std::pair<int, int>> by_class = {
      {"wire", {}}, {"pole", {}}, {"tree", {}}, {"building", {}}};
  nlohmann::json objects = nlohmann::json::array();
  const auto optional = [](bool seen, double value) {
    return seen ? nlohmann::json(value) : nlohmann::json(nullptr);
  };
  for (std::size_t i = 0; i < summary.objects().size(); ++i) {
    const ObjectTruth& truth = summary.objects()[i];
    std::string id;
    SurfaceClass surface_class = SurfaceClass::wire;
    if (i < scene.conductors.size()) {
      id = scene.conductors[i].id;
    } else if (i < scene.conductors.size() + scene.cylinders.size()) {
      const Cylinder& cylinder = scene.cylinders[i - scene.conductors.size()];
      id = cylinder.id;
      surface_class = cylinder.surface;
    } else {
      const MeshObject& mesh = scene.meshes[i - scene.conductors.size() - scene.cylinders.size()];
      id = mesh.id;
      surface_class = mesh.surface;
    }
    const std::string surface(to_string(surface_class));
    ++by_class[surface].first;
    by_class[surface].second += truth.seen() ? 1 : 0;
    objects.push_back({{"id", id},
                       {"class", surface},
                       {"returns", truth.returns},
                       {"frames_seen", truth.frames_seen},
                       {"first_seen_s", optional(truth.seen(), truth.first_seen_s)},
                       {"first_seen_range_m", optional(truth.seen(), truth.first_seen_range_m)},
                       {"min_range_m", optional(truth.seen(), truth.min_range_m)}});
    if (weather) {
      objects.back()["seen_through_fog"] = truth.seen_through_fog;
      objects.back()["first_seen_clear_s"] = optional(truth.seen_clear(), truth.first_seen_clear_s);
      objects.back()["first_seen_clear_range_m"] =
          optional(truth.seen_clear(), truth.first_seen_clear_range_m);
    }
  }
  for (const auto& [surface, counts] : by_class) {
    head["objects_by_class"][surface] = {{"objects", counts.first}, {"seen", counts.second}};
  }
  nlohmann::ordered_json document;
  for (const auto& [key, value] : head.items()) document[key] = value;
  document["objects"] = objects;
  return document.dump(2) + "\n";
}

TEST_F(SummaryJsonTest, TextIsNlohmannsForTheSameDocument) {
  const nlohmann::json facts = {{"scenario", "corridor"}, {"seed", 2024}, {"wall_s", 0.1 + 0.2},
                                {"setup_s", 1e-7},        {"threads", 2}, {"version", "0.1.0"}};
  for (const auto& [wires, trees, meshes, fog] : {std::tuple{0, 0, 0, false},
                                                  {3, 0, 0, false},
                                                  {0, 7, 0, false},
                                                  {59, 417, 5, false},
                                                  {6, 3000, 0, false},
                                                  {0, 0, 9, false},
                                                  {59, 417, 5, true},
                                                  {0, 0, 0, true}}) {
    SCOPED_TRACE(std::to_string(wires) + " wires, " + std::to_string(trees) + " trees, " +
                 std::to_string(meshes) + " meshes" + (fog ? ", fog" : ""));
    const Scene scene = scene_of(wires, trees, meshes, fog);
    const std::size_t objects =
        scene.conductors.size() + scene.cylinders.size() + scene.meshes.size();
    const FlightSummary summary = random_summary(objects, objects + 1, objects == 0 ? 0 : 25);
    const fs::path path = dir_ / "summary.json";
    write_summary_json(path, summary, scene, facts);
    EXPECT_EQ(content(path), oracle_text(summary, scene, facts));
    // Totals first: the objects array is the last key.
    const std::string text = content(path);
    EXPECT_LT(text.find("\"returns\""), text.find("\"objects\": ["));
  }
}

TEST_F(SummaryJsonTest, FalseReturnsAreCountedAndNoObjectsReturns) {
  // Two frames of 4 pulses: a false return alone, a false return before a wire, a wire before a
  // false return, ground; the false returns (object kNoObject) are counted under returns.noise
  // and reach no object. Without any, returns.noise is 0 and so is the rate.
  const Scene scene = scene_of(2, 0, 0);
  const auto ret = [](SurfaceClass surface, std::uint32_t object, double range_m) {
    Return r;
    r.surface = static_cast<std::uint8_t>(surface);
    r.object_index = object;
    r.range_m = range_m;
    r.true_range_m = range_m;
    r.energy_rel = 0.0029;
    r.incidence_deg = std::numeric_limits<double>::quiet_NaN();
    return r;
  };
  std::vector<Pulse> pulses(4);
  std::vector<PulseReturns> returns(4);
  returns[0].count = 1;
  returns[0].returns[0] = ret(SurfaceClass::noise, kNoObject, 412.5);
  returns[1].count = 2;
  returns[1].returns[0] = ret(SurfaceClass::noise, kNoObject, 97.0);
  returns[1].returns[1] = ret(SurfaceClass::wire, 1, 240.0);
  returns[2].count = 2;
  returns[2].returns[0] = ret(SurfaceClass::wire, 1, 239.0);
  returns[2].returns[1] = ret(SurfaceClass::noise, kNoObject, 1100.0);
  returns[3].count = 1;
  returns[3].returns[0] = ret(SurfaceClass::ground, 2, 300.0);
  FlightSummary summary(2);
  for (std::int64_t frame = 0; frame < 2; ++frame) {
    FrameTally tally;
    FlightSummary::tally(2, pulses, returns, tally);
    summary.add_frame(frame, tally);
  }
  write_summary_json(dir_ / "summary.json", summary, scene, nlohmann::json::object());
  const nlohmann::json written = nlohmann::json::parse(content(dir_ / "summary.json"));
  EXPECT_EQ(written["pulses"], 8);
  EXPECT_EQ(written["returns"]["noise"], 6);
  EXPECT_EQ(written["returns"]["wire"], 4);
  EXPECT_EQ(written["returns"]["ground"], 2);
  EXPECT_EQ(written["second_returns"], 4);
  EXPECT_EQ(written["false_returns_per_pulse"], 0.75);
  EXPECT_EQ(written["objects"][0]["returns"], 0);
  EXPECT_EQ(written["objects"][1]["returns"], 4);
  EXPECT_EQ(written["objects_by_class"]["wire"]["seen"], 1);

  FlightSummary quiet(2);
  FrameTally tally;
  tally.pulses = 20352;
  tally.returns_by_class[static_cast<std::size_t>(SurfaceClass::ground)] = 19000;
  quiet.add_frame(0, tally);
  write_summary_json(dir_ / "quiet.json", quiet, scene, nlohmann::json::object());
  const nlohmann::json none = nlohmann::json::parse(content(dir_ / "quiet.json"));
  EXPECT_EQ(none["returns"]["noise"], 0);
  EXPECT_EQ(none["false_returns_per_pulse"], 0.0);
}

TEST_F(SummaryJsonTest, ASummaryOfAnotherSceneIsRefused) {
  const Scene scene = scene_of(2, 2, 0);
  const FlightSummary summary(3);
  EXPECT_THROW(write_summary_json(dir_ / "summary.json", summary, scene, nlohmann::json::object()),
               Error);
  EXPECT_FALSE(fs::exists(dir_ / "summary.json"));
}

TEST_F(SummaryJsonTest, ACheckpointCostsTheObjectsSeenNotTheObjectsTallied) {
  // A million objects, three seen: the checkpoint holds three, and restores to the same summary.
  FlightSummary summary(1'000'000);
  FrameTally tally;
  tally.object_hits = {
      {999'999, 0, 0.5, 812.25}, {3, 1, 0.6, 95.0}, {999'999, 0, 0.7, 811.0}, {42, 0, 0.8, 1}};
  summary.add_frame(0, tally);
  const FlightSummaryCheckpoint checkpoint = summary.checkpoint();
  ASSERT_EQ(checkpoint.seen.size(), 3u);
  EXPECT_EQ(checkpoint.seen[0].index, 999'999u);  // in the order first seen
  EXPECT_EQ(checkpoint.seen[0].truth.returns, 2u);
  EXPECT_EQ(checkpoint.seen[0].truth.first_seen_range_m, 812.25);
  EXPECT_EQ(checkpoint.seen[0].truth.min_range_m, 811.0);
  // Object 3 was seen only through fog: never clear.
  EXPECT_EQ(checkpoint.seen[1].index, 3u);
  EXPECT_EQ(checkpoint.seen[1].truth.seen_through_fog, 1u);
  EXPECT_FALSE(checkpoint.seen[1].truth.seen_clear());
  EXPECT_EQ(checkpoint.seen[0].truth.first_seen_clear_range_m, 812.25);
  RunCheckpoint run;
  run.summary = checkpoint;
  const fs::path path = dir_ / ".owsim-resume";
  write_run_checkpoint(path, run);
  EXPECT_LT(fs::file_size(path), 400u);
  FlightSummary restored(1'000'000);
  restored.restore(read_run_checkpoint(path)->summary);
  EXPECT_EQ(restored.checkpoint(), checkpoint);
  for (const std::uint32_t i : {0u, 3u, 42u, 500'000u, 999'999u}) {
    EXPECT_EQ(restored.objects()[i], summary.objects()[i]) << i;
  }
  // Another object count, an index past it, an object given twice, an unseen one: refused.
  EXPECT_THROW(FlightSummary(999'999).restore(checkpoint), Error);
  FlightSummaryCheckpoint bad = checkpoint;
  bad.seen[1].index = 1'000'000;
  EXPECT_THROW(FlightSummary(1'000'000).restore(bad), Error);
  bad = checkpoint;
  bad.seen[1].index = bad.seen[0].index;
  EXPECT_THROW(FlightSummary(1'000'000).restore(bad), Error);
  bad = checkpoint;
  bad.seen[2].truth.returns = 0;
  EXPECT_THROW(FlightSummary(1'000'000).restore(bad), Error);
  // A hit on an object the summary does not tally.
  FrameTally outside;
  outside.object_hits = {{1'000'000, 0, 0.1, 5.0}};
  EXPECT_THROW(summary.add_frame(1, outside), Error);
}

}  // namespace
}  // namespace owsim
