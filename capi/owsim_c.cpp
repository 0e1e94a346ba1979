// The C ABI (capi/owsim/owsim.h): opaque handles over owsim::Simulation and owsim::Frame, one
// catch-all boundary per call (guarded) so no exception leaves, a per-thread last error.
#include <cmath>
#include <cstddef>
#include <exception>
#include <functional>
#include <limits>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "geometry/error.hpp"
#include "owsim/flight_report.hpp"
#include "owsim/owsim.h"
#include "owsim/frame_detector.hpp"
#include "owsim/simulation.hpp"
#include "owsim/version.hpp"

struct owsim_simulation {
  explicit owsim_simulation(owsim::Simulation s) : simulation(std::move(s)) {}
  owsim::Simulation simulation;
};

struct owsim_detector {
  explicit owsim_detector(const owsim::Simulation& simulation) : detector(simulation) {}
  owsim::FrameDetector detector;
  std::vector<owsim_warning> warnings;
};

struct owsim_frame {
  owsim::Frame frame;
  std::vector<owsim_pulse> pulses;  // made from frame.pulses() when first asked for
  std::vector<owsim_ray> rays;
  bool pulses_made = false;
  bool rays_made = false;
};

namespace {

// owsim_return is owsim::ReturnRecord: the frame's records are handed out as they are.
static_assert(sizeof(owsim_return) == sizeof(owsim::ReturnRecord));
static_assert(offsetof(owsim_return, frame) == offsetof(owsim::ReturnRecord, frame));
static_assert(offsetof(owsim_return, pulse) == offsetof(owsim::ReturnRecord, pulse));
static_assert(offsetof(owsim_return, return_number) ==
              offsetof(owsim::ReturnRecord, return_number));
static_assert(offsetof(owsim_return, counter) == offsetof(owsim::ReturnRecord, counter));
static_assert(offsetof(owsim_return, surface) == offsetof(owsim::ReturnRecord, surface));
static_assert(offsetof(owsim_return, number_of_returns) ==
              offsetof(owsim::ReturnRecord, number_of_returns));
static_assert(offsetof(owsim_return, object) == offsetof(owsim::ReturnRecord, object));
static_assert(offsetof(owsim_return, e_m) == offsetof(owsim::ReturnRecord, e_m));
static_assert(offsetof(owsim_return, h_m) == offsetof(owsim::ReturnRecord, h_m));
static_assert(offsetof(owsim_return, incidence_deg) ==
              offsetof(owsim::ReturnRecord, incidence_deg));
static_assert(sizeof(owsim_pose) == sizeof(owsim::PoseSample));
static_assert(offsetof(owsim_pose, heading_deg) == offsetof(owsim::PoseSample, heading_deg));
static_assert(OWSIM_CLASS_GROUND == static_cast<int>(owsim::SurfaceClass::ground));
static_assert(OWSIM_CLASS_BUILDING == static_cast<int>(owsim::SurfaceClass::building));
static_assert(OWSIM_CLASS_FOG == static_cast<int>(owsim::SurfaceClass::fog));
static_assert(OWSIM_CLASS_NOISE == static_cast<int>(owsim::SurfaceClass::noise));
static_assert(OWSIM_NO_OBJECT == owsim::kNoObject);
static_assert(OWSIM_CLASS_UNKNOWN == owsim::kUnknownSurface);

thread_local std::string last_error;

// A call's arguments were unusable: OWSIM_ERROR_ARGUMENT with `message`.
struct ArgumentError {
  std::string message;
};
// The progress callback asked to stop.
struct Cancelled {};

owsim_status fail(owsim_status status, std::string message) {
  last_error = std::move(message);
  return status;
}

// Runs `call`, turning whatever it throws into a status and this thread's last error.
template <typename Call>
owsim_status guarded(const char* function, Call&& call) noexcept {
  try {
    call();
    return OWSIM_OK;
  } catch (const ArgumentError& error) {
    return fail(OWSIM_ERROR_ARGUMENT, std::string(function) + ": " + error.message);
  } catch (const Cancelled&) {
    return fail(OWSIM_ERROR_CANCELLED,
                std::string(function) + ": stopped by the progress callback");
  } catch (const owsim::FileError& error) {
    return fail(OWSIM_ERROR_FILE, error.what());
  } catch (const owsim::Error& error) {
    return fail(OWSIM_ERROR_INPUT, error.what());
  } catch (const std::bad_alloc&) {
    return fail(OWSIM_ERROR_INTERNAL, std::string(function) + ": out of memory");
  } catch (const std::exception& error) {
    return fail(OWSIM_ERROR_INTERNAL, std::string(function) + ": internal error: " + error.what());
  } catch (...) {
    return fail(OWSIM_ERROR_INTERNAL, std::string(function) + ": internal error");
  }
}

template <typename T>
void require(const T* pointer, const char* name) {
  if (pointer == nullptr) throw ArgumentError{std::string(name) + " is NULL"};
}

// A value-returning call given a NULL handle: the "none" value, with the last error set.
template <typename T>
T none(const char* function, T value) {
  last_error = std::string(function) + ": the handle is NULL";
  return value;
}

// A caller's options struct must be at least this version's size (struct_size, set by the
// *_options_default() it came from).
template <typename Options>
void require_struct_size(const Options& options, const char* default_function) {
  if (options.struct_size < sizeof(Options)) {
    throw ArgumentError{"options->struct_size is " + std::to_string(options.struct_size) +
                        ", expected " + std::to_string(sizeof(Options)) + " (start from " +
                        default_function + "())"};
  }
}

owsim::SimulationOptions simulation_options(const owsim_simulation_options* options) {
  owsim::SimulationOptions out;
  if (options == nullptr) return out;
  // flight_area_enu_m came later: a struct that ends before it is the earlier version.
  constexpr std::size_t kWithoutArea = offsetof(owsim_simulation_options, flight_area_enu_m);
  if (options->struct_size < kWithoutArea) {
    require_struct_size(*options, "owsim_simulation_options_default");
  }
  if (options->threads < 0) throw ArgumentError{"options->threads must be ≥ 0"};
  if (options->frames < 0) throw ArgumentError{"options->frames must be ≥ 0"};
  if (!(options->duration_s >= 0)) throw ArgumentError{"options->duration_s must be ≥ 0"};
  out.threads = options->threads;
  if (options->frames > 0) out.frames = options->frames;
  if (options->duration_s > 0) out.duration_s = options->duration_s;
  if (options->override_seed != 0) out.seed = options->seed;
  out.no_noise = options->no_noise != 0;
  if (options->struct_size >= sizeof(owsim_simulation_options)) {
    const double* area = options->flight_area_enu_m;
    if (area[0] != 0 || area[1] != 0 || area[2] != 0 || area[3] != 0) {
      out.flight_area_enu_m =
          Eigen::AlignedBox2d(Eigen::Vector2d(area[0], area[1]), Eigen::Vector2d(area[2], area[3]));
    }
  }
  return out;
}

owsim_status open_into(const char* function, owsim_simulation** out,
                       const std::function<owsim::Simulation()>& open) {
  if (out != nullptr) *out = nullptr;
  return guarded(function, [&] {
    require(out, "out");
    *out = new owsim_simulation(open());
  });
}

// Fills *out (a new frame when NULL) with `simulate`'s frame.
template <typename Simulate>
owsim_status simulate_into(const char* function, owsim_simulation* simulation, owsim_frame** out,
                           Simulate&& simulate) {
  return guarded(function, [&] {
    require(simulation, "simulation");
    require(out, "out");
    owsim_frame* frame = *out != nullptr ? *out : new owsim_frame;
    try {
      simulate(frame->frame);
    } catch (...) {
      if (*out == nullptr) delete frame;
      throw;
    }
    frame->pulses_made = frame->rays_made = false;
    *out = frame;
  });
}

}  // namespace

extern "C" {

const char* owsim_version(void) { return owsim::version_string; }
uint32_t owsim_version_number(void) { return OWSIM_VERSION_NUMBER; }
const char* owsim_last_error(void) { return last_error.c_str(); }

owsim_simulation_options owsim_simulation_options_default(void) {
  owsim_simulation_options options{};
  options.struct_size = sizeof(owsim_simulation_options);
  return options;
}

owsim_status owsim_simulation_open(const char* scenario_path, owsim_simulation** out) {
  return owsim_simulation_open_with(scenario_path, nullptr, out);
}

owsim_status owsim_simulation_open_with(const char* scenario_path,
                                        const owsim_simulation_options* options,
                                        owsim_simulation** out) {
  return open_into("owsim_simulation_open", out, [&] {
    require(scenario_path, "scenario_path");
    return owsim::Simulation::open(scenario_path, simulation_options(options));
  });
}

owsim_status owsim_simulation_open_yaml(const char* yaml, const char* name,
                                        const owsim_simulation_options* options,
                                        owsim_simulation** out) {
  return open_into("owsim_simulation_open_yaml", out, [&] {
    require(yaml, "yaml");
    return owsim::Simulation::from_yaml(yaml, name != nullptr ? name : "scenario.yaml",
                                        simulation_options(options));
  });
}

void owsim_simulation_release(owsim_simulation* simulation) { delete simulation; }

int64_t owsim_simulation_frame_count(const owsim_simulation* simulation) {
  if (simulation == nullptr) return none<int64_t>("owsim_simulation_frame_count", -1);
  return simulation->simulation.frame_count();
}

int32_t owsim_simulation_pulses_per_frame(const owsim_simulation* simulation) {
  if (simulation == nullptr) return none<int32_t>("owsim_simulation_pulses_per_frame", 0);
  return simulation->simulation.pulses_per_frame();
}

int32_t owsim_simulation_word_size(const owsim_simulation* simulation) {
  if (simulation == nullptr) return none<int32_t>("owsim_simulation_word_size", 0);
  return simulation->simulation.model() == owsim::SensorModel::hellas ? 4 : 8;
}

double owsim_simulation_frame_start_s(const owsim_simulation* simulation, int64_t frame) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (simulation == nullptr) return none("owsim_simulation_frame_start_s", kNaN);
  double time = kNaN;
  (void)guarded("owsim_simulation_frame_start_s",
                [&] { time = simulation->simulation.frame_start_s(frame); });
  return time;
}

double owsim_simulation_frame_end_s(const owsim_simulation* simulation, int64_t frame) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (simulation == nullptr) return none("owsim_simulation_frame_end_s", kNaN);
  double time = kNaN;
  (void)guarded("owsim_simulation_frame_end_s",
                [&] { time = simulation->simulation.frame_end_s(frame); });
  return time;
}

uint32_t owsim_simulation_object_count(const owsim_simulation* simulation) {
  if (simulation == nullptr) return none<uint32_t>("owsim_simulation_object_count", 0);
  return static_cast<uint32_t>(simulation->simulation.object_ids().size());
}

const char* owsim_simulation_object_id(const owsim_simulation* simulation, uint32_t object) {
  if (simulation == nullptr) return none<const char*>("owsim_simulation_object_id", nullptr);
  const auto& ids = simulation->simulation.object_ids();
  if (object >= ids.size()) {
    last_error = "owsim_simulation_object_id: object " + std::to_string(object) +
                 " is out of range (" + std::to_string(ids.size()) + " objects)";
    return nullptr;
  }
  return ids[object].c_str();
}

owsim_status owsim_simulate_frame(owsim_simulation* simulation, int64_t frame, owsim_frame** out) {
  return simulate_into("owsim_simulate_frame", simulation, out, [&](owsim::Frame& into) {
    const int64_t count = simulation->simulation.frame_count();
    if (frame < 0 || frame >= count) {
      throw ArgumentError{"frame " + std::to_string(frame) +
                          " is out of range: the flight has frames 0.." +
                          std::to_string(count - 1)};
    }
    simulation->simulation.simulate_frame(frame, into);
  });
}

owsim_status owsim_simulate_frame_poses(owsim_simulation* simulation, int64_t frame,
                                        const owsim_pose* poses, size_t pose_count,
                                        owsim_frame** out) {
  return simulate_into("owsim_simulate_frame_poses", simulation, out, [&](owsim::Frame& into) {
    if (pose_count > 0) require(poses, "poses");
    if (frame < 0) throw ArgumentError{"frame " + std::to_string(frame) + " is negative"};
    const auto* samples = reinterpret_cast<const owsim::PoseSample*>(poses);
    simulation->simulation.simulate_frame(frame, std::span(samples, pose_count), into);
  });
}

void owsim_frame_release(owsim_frame* frame) { delete frame; }

owsim_status owsim_detector_create(const owsim_simulation* simulation, owsim_detector** out) {
  if (out != nullptr) *out = nullptr;
  return guarded("owsim_detector_create", [&] {
    require(simulation, "simulation");
    require(out, "out");
    *out = new owsim_detector(simulation->simulation);
  });
}

void owsim_detector_release(owsim_detector* detector) { delete detector; }

owsim_status owsim_detector_add_frame(owsim_detector* detector, const owsim_frame* frame,
                                      const owsim_warning** warnings, size_t* count) {
  if (warnings != nullptr) *warnings = nullptr;
  if (count != nullptr) *count = 0;
  return guarded("owsim_detector_add_frame", [&] {
    require(detector, "detector");
    require(frame, "frame");
    require(warnings, "warnings");
    require(count, "count");
    detector->warnings.clear();
    for (const owsim::ObstacleWarning& w : detector->detector.add_frame(frame->frame)) {
      owsim_warning out{};
      out.frame = w.frame;
      out.time_s = w.time_s;
      out.track = w.track;
      out.obstacle_class = static_cast<int32_t>(w.kind);
      out.points = w.points;
      out.e_m = w.nearest_enu_m.x();
      out.n_m = w.nearest_enu_m.y();
      out.u_m = w.nearest_enu_m.z();
      out.range_m = w.range_m;
      out.length_m = w.length_m;
      out.width_m = w.width_m;
      out.height_m = w.height_m;
      detector->warnings.push_back(out);
    }
    *warnings = detector->warnings.data();
    *count = detector->warnings.size();
  });
}

int64_t owsim_frame_index(const owsim_frame* frame) {
  if (frame == nullptr) return none<int64_t>("owsim_frame_index", -1);
  return frame->frame.index();
}

const void* owsim_frame_words(const owsim_frame* frame, size_t* byte_count) {
  if (byte_count != nullptr) *byte_count = 0;
  if (frame == nullptr) return none<const void*>("owsim_frame_words", nullptr);
  const std::span<const std::byte> bytes = frame->frame.word_bytes();
  if (byte_count != nullptr) *byte_count = bytes.size();
  return bytes.data();
}

const owsim_return* owsim_frame_returns(const owsim_frame* frame, size_t* count) {
  if (count != nullptr) *count = 0;
  if (frame == nullptr) return none<const owsim_return*>("owsim_frame_returns", nullptr);
  const auto records = frame->frame.returns();
  if (count != nullptr) *count = records.size();
  return reinterpret_cast<const owsim_return*>(records.data());
}

const owsim_pulse* owsim_frame_pulses(owsim_frame* frame, size_t* count) {
  if (count != nullptr) *count = 0;
  if (frame == nullptr) return none<const owsim_pulse*>("owsim_frame_pulses", nullptr);
  if (!frame->pulses_made) {
    const auto pulses = frame->frame.pulses();
    frame->pulses.resize(pulses.size());
    for (std::size_t k = 0; k < pulses.size(); ++k) {
      const owsim::Pulse& p = pulses[k];
      frame->pulses[k] = owsim_pulse{p.index,
                                     p.line,
                                     p.fiber,
                                     p.reference ? 1 : 0,
                                     p.time_s,
                                     p.alpha_deg,
                                     p.beta_deg,
                                     p.mirror_beta_deg,
                                     static_cast<int32_t>(p.encoder),
                                     static_cast<uint8_t>(p.frame_gate),
                                     static_cast<uint8_t>(p.line_gate),
                                     static_cast<uint8_t>(p.mov_dir),
                                     0};
    }
    frame->pulses_made = true;
  }
  if (count != nullptr) *count = frame->pulses.size();
  return frame->pulses.data();
}

const owsim_ray* owsim_frame_rays(owsim_frame* frame, size_t* count) {
  if (count != nullptr) *count = 0;
  if (frame == nullptr) return none<const owsim_ray*>("owsim_frame_rays", nullptr);
  if (!frame->rays_made) {
    const auto rays = frame->frame.rays();
    frame->rays.resize(rays.size());
    for (std::size_t k = 0; k < rays.size(); ++k) {
      const owsim::PulseRay& r = rays[k];
      frame->rays[k] = owsim_ray{r.origin_enu_m.x(), r.origin_enu_m.y(), r.origin_enu_m.z(),
                                 r.dir_enu.x(),      r.dir_enu.y(),      r.dir_enu.z()};
    }
    frame->rays_made = true;
  }
  if (count != nullptr) *count = frame->rays.size();
  return frame->rays.data();
}

owsim_run_options owsim_run_options_default(void) {
  owsim_run_options options{};
  options.struct_size = sizeof(owsim_run_options);
  return options;
}

owsim_status owsim_simulation_run(const owsim_simulation* simulation,
                                  const owsim_run_options* options, owsim_run_report* report) {
  return guarded("owsim_simulation_run", [&] {
    require(simulation, "simulation");
    owsim::RunOptions run;
    if (options != nullptr) {
      require_struct_size(*options, "owsim_run_options_default");
      if (options->out_dir != nullptr) run.out = options->out_dir;
      if (options->outputs != nullptr) run.outputs = owsim::parse_output_list(options->outputs);
      run.resume = options->resume != 0;
      if (options->progress != nullptr) {
        run.progress = [callback = options->progress,
                        user_data = options->user_data](const owsim::RunProgress& at) {
          if (callback(at.frames_done, at.frames_total, user_data) != 0) throw Cancelled{};
        };
      }
    }
    const owsim::RunReport done = simulation->simulation.run(run);
    if (report != nullptr) {
      *report = owsim_run_report{done.frames,       done.first_frame,     done.pulses, done.wall_s,
                                 done.pulses_per_s, done.realtime_factor, done.threads};
    }
  });
}

owsim_view_options owsim_view_options_default(void) {
  const owsim::FlightReportOptions defaults;
  return owsim_view_options{sizeof(owsim_view_options), nullptr, nullptr, defaults.max_points,
                            defaults.max_frames};
}

owsim_status owsim_view(const char* folder, const owsim_view_options* options,
                        owsim_view_report* report) {
  return guarded("owsim_view", [&] {
    require(folder, "folder");
    owsim::FlightReportOptions view;
    if (options != nullptr) {
      require_struct_size(*options, "owsim_view_options_default");
      if (options->out_file != nullptr) view.out = options->out_file;
      if (options->scenario_path != nullptr) view.scenario = options->scenario_path;
      view.max_points = options->max_points;
      view.max_frames = options->max_frames;
    }
    const owsim::FlightReport done = owsim::write_flight_report(folder, view);
    if (report != nullptr) {
      *report = owsim_view_report{done.bytes, done.points_total, done.points_shown,
                                  done.frames_total, done.frames_shown};
    }
  });
}

}  // extern "C"
