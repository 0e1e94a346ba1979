// Protects the embedding API's detector (owsim/frame_detector.hpp, issue 69): fed the frames of a
// Simulation one by one, owsim::FrameDetector's warnings are the rows `owsim run --outputs
// detections` writes, byte for byte, MilOWS and HELLAS (whose frame 0 is placed by the word file's
// header word); frames out of order are refused.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "cli_runner.hpp"
#include "owsim/owsim.hpp"

namespace owsim {
namespace {

using test::read_whole_file;
using test::run_cli;
using test::TempDir;

const std::string kDetectorApproach = OWSIM_SOURCE_DIR "/tests/data/detector/approach.yaml";

std::string detections_of(const Simulation& simulation) {
  FrameDetector detector(simulation);
  std::string csv(FrameDetector::csv_header());
  Frame frame;
  for (std::int64_t k = 0; k < simulation.frame_count(); ++k) {
    simulation.simulate_frame(k, frame);
    const std::span<const ObstacleWarning> warnings = detector.add_frame(frame);
    const std::string rows = detector.csv_rows();
    EXPECT_EQ(static_cast<std::size_t>(std::count(rows.begin(), rows.end(), '\n')),
              warnings.size());
    csv += rows;
  }
  return csv;
}

TEST(FrameDetector, WarnsAsTheRunsDetectionsCsvForMilowsAndHellas) {
  const TempDir dir;
  std::filesystem::copy_file(OWSIM_SOURCE_DIR "/tests/data/detector/building.obj",
                             dir / "building.obj");
  std::ifstream in(kDetectorApproach);
  std::ofstream hellas(dir / "hellas.yaml");
  std::string line;
  while (std::getline(in, line)) {
    hellas << (line == "  model: milows" ? "  model: hellas" : line) << '\n';
  }
  hellas.close();
  for (const std::filesystem::path scenario :
       {std::filesystem::path(kDetectorApproach), dir / "hellas.yaml"}) {
    SCOPED_TRACE(scenario.string());
    const test::CliResult run =
        run_cli({"run", scenario.string(), "--frames", "45", "--out",
                 "run_" + scenario.stem().string(), "--outputs", "detections", "--quiet"},
                dir.path());
    ASSERT_EQ(run.exit_status, 0) << run.err;
    const std::string written =
        read_whole_file(dir / ("run_" + scenario.stem().string()) / "detections.csv");
    ASSERT_GT(written.size(), 2000u);
    SimulationOptions options;
    options.frames = 45;
    EXPECT_EQ(detections_of(Simulation::open(scenario, options)), written);
  }
}

TEST(FrameDetector, RefusesFramesOutOfOrder) {
  SimulationOptions options;
  options.frames = 3;
  const Simulation simulation = Simulation::open(kDetectorApproach, options);
  FrameDetector detector(simulation);
  Frame frame;
  simulation.simulate_frame(1, frame);
  detector.add_frame(frame);  // any first frame
  EXPECT_THROW(detector.add_frame(frame), Error);
  simulation.simulate_frame(0, frame);
  EXPECT_THROW(detector.add_frame(frame), Error);
  simulation.simulate_frame(2, frame);
  EXPECT_NO_THROW(detector.add_frame(frame));
}

}  // namespace
}  // namespace owsim
