// Co-simulation with a host flight simulator: each frame, the host pushes the poses it flew
// (here a toy flight model: straight and level at 40 m/s, 60 m up, heading east, sampled at
// 50 Hz) and owsim returns what the sensor saw. Reports the first wire detection.
#include <cstdio>
#include <exception>
#include <owsim/owsim.hpp>
#include <vector>

// The host's state at time t: single_span's route, flown by the host instead of the scenario.
owsim::PoseSample host_pose(double t) {
  owsim::PoseSample pose;
  pose.time_s = t;
  pose.e_m = -600.0 + 40.0 * t;
  pose.u_m = 60.0;
  pose.heading_deg = 90.0;
  return pose;
}

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: cosim SCENARIO.yaml\n");
    return 2;
  }
  try {
    owsim::SimulationOptions options;
    options.flight_area_enu_m = Eigen::AlignedBox2d(Eigen::Vector2d(-2000, -2000),
                                                    Eigen::Vector2d(2000, 2000));  // the host's
    const owsim::Simulation sim = owsim::Simulation::open(argv[1], options);
    owsim::Frame frame;  // refilled every frame
    std::vector<owsim::PoseSample> poses;
    for (std::int64_t k = 0; k < sim.frame_count(); ++k) {
      poses.clear();  // what the host flew around this frame
      for (double t = sim.frame_start_s(k) - 0.04; t < sim.frame_end_s(k) + 0.04; t += 0.02) {
        poses.push_back(host_pose(t));
      }
      sim.simulate_frame(k, poses, frame);
      for (const owsim::ReturnRecord& hit : frame.returns()) {
        if (hit.surface != static_cast<std::uint8_t>(owsim::SurfaceClass::wire)) continue;
        std::printf("first wire detection: frame %lld, t = %.3f s, %s at %.1f m\n",
                    static_cast<long long>(k), hit.time_s, sim.object_ids()[hit.object].c_str(),
                    hit.range_m);
        return 0;
      }
    }
    std::printf("no wire detected in %lld frames\n", static_cast<long long>(sim.frame_count()));
    return 1;
  } catch (const owsim::Error& error) {
    std::fprintf(stderr, "cosim: %s\n", error.what());
    return 1;
  }
}
