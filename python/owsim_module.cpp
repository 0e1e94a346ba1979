// The Python module `owsim` (INTERFACE.md "Embedding"): a thin shell over owsim::Simulation.
// Frames come back as numpy views into the frame's own buffers (the Frame object owns them; each
// array keeps its Frame alive), with named dtypes: returns by the points.csv columns, pulses by
// `owsim pattern`'s, words as uint64 (MilOWS) or uint32 (HELLAS). The GIL is released while owsim
// works. owsim::FileError → OSError, other owsim::Error → ValueError, a frame out of range →
// IndexError; each with owsim's one-line message.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "owsim/flight_report.hpp"
#include "owsim/frame_detector.hpp"
#include "owsim/simulation.hpp"
#include "owsim/version.hpp"

namespace py = pybind11;

namespace owsim {
namespace {

struct Field {
  const char* name;
  py::object format;  // a numpy dtype, or a format string such as "(3,)<f8"
  std::size_t offset;
};

// A record's member as a numpy field: its dtype from the member's own C++ type and its offset from
// the record's layout, so that neither can drift from the struct (a hand-written "<u4" once read a
// 2-byte member together with the two bytes after it).
template <typename Record, typename T>
std::size_t offset_in(T Record::*member) {
  static const Record record{};
  return static_cast<std::size_t>(reinterpret_cast<const char*>(&(record.*member)) -
                                  reinterpret_cast<const char*>(&record));
}

template <typename Record, typename T>
Field field(const char* name, T Record::*member) {
  return Field{name, py::dtype::of<T>(), offset_in(member)};
}

// The same for a member numpy spells with a format string (an enum: "<u1"; an Eigen vector:
// "(3,)<f8"), checked against the member's size.
template <typename Record, typename T>
Field field(const char* name, T Record::*member, const char* format) {
  Field out{name, py::str(format), offset_in(member)};
  if (py::dtype::from_args(out.format).itemsize() != static_cast<py::ssize_t>(sizeof(T))) {
    throw std::logic_error(std::string("field ") + name + ": " + format + " is not its size");
  }
  return out;
}

py::dtype record_dtype(const std::vector<Field>& fields, std::size_t itemsize) {
  py::list names, formats, offsets;
  for (const Field& field : fields) {
    names.append(field.name);
    formats.append(field.format);
    offsets.append(field.offset);
  }
  py::dict spec;
  spec["names"] = names;
  spec["formats"] = formats;
  spec["offsets"] = offsets;
  spec["itemsize"] = itemsize;
  return py::dtype::from_args(spec);
}

// points.csv's columns, in their order; `class` is the class code (owsim.CLASS_NAMES), `object`
// the index into Simulation.object_ids (owsim.NO_OBJECT for a false return, class noise).
py::dtype returns_dtype() {
  using R = ReturnRecord;
  // Made once and never freed: a static py::dtype would be released after the interpreter.
  static const py::dtype& dtype = *new py::dtype(record_dtype(
      {field("frame", &R::frame), field("pulse", &R::pulse), field("line", &R::line),
       field("fiber", &R::fiber), field("return", &R::return_number), field("time_s", &R::time_s),
       field("range_m", &R::range_m), field("counter", &R::counter), field("e_m", &R::e_m),
       field("n_m", &R::n_m), field("u_m", &R::u_m), field("lat_deg", &R::lat_deg),
       field("lon_deg", &R::lon_deg), field("h_m", &R::h_m), field("class", &R::surface),
       field("object", &R::object), field("energy_rel", &R::energy_rel),
       field("incidence_deg", &R::incidence_deg),
       field("number_of_returns", &R::number_of_returns)},
      sizeof(R)));
  return dtype;
}

// detections.csv's columns as FrameDetector.add_frame returns them: `class` is the obstacle class
// code (owsim.OBSTACLE_CLASS_NAMES), `enu_m` the track's point nearest to the aircraft.
py::dtype warnings_dtype() {
  using W = ObstacleWarning;
  // Made once and never freed: a static py::dtype would be released after the interpreter.
  static const py::dtype& dtype = *new py::dtype(record_dtype(
      {field("frame", &W::frame), field("time_s", &W::time_s), field("track", &W::track),
       field("class", &W::kind, "<u1"), field("enu_m", &W::nearest_enu_m, "(3,)<f8"),
       field("range_m", &W::range_m), field("length_m", &W::length_m),
       field("width_m", &W::width_m), field("height_m", &W::height_m),
       field("points", &W::points)},
      sizeof(W)));
  return dtype;
}

// The reference detector, keeping its Simulation alive.
struct PyFrameDetector {
  explicit PyFrameDetector(std::shared_ptr<const Simulation> s)
      : simulation(std::move(s)), detector(*simulation) {}
  std::shared_ptr<const Simulation> simulation;
  FrameDetector detector;
};

// `owsim pattern`'s columns (and the slot within the line).
py::dtype pulses_dtype() {
  // Made once and never freed: a static py::dtype would be released after the interpreter.
  static const py::dtype& dtype = *new py::dtype(record_dtype(
      {field("pulse", &Pulse::index), field("line", &Pulse::line), field("slot", &Pulse::slot),
       field("fiber", &Pulse::fiber), field("reference", &Pulse::reference),
       field("time_s", &Pulse::time_s), field("alpha_deg", &Pulse::alpha_deg),
       field("mirror_beta_deg", &Pulse::mirror_beta_deg), field("beta_deg", &Pulse::beta_deg),
       field("encoder", &Pulse::encoder), field("fg", &Pulse::frame_gate),
       field("lg", &Pulse::line_gate), field("movdir", &Pulse::mov_dir)},
      sizeof(Pulse)));
  return dtype;
}

py::dtype rays_dtype() {
  static_assert(sizeof(PulseRay) == 6 * sizeof(double));
  static const py::dtype& dtype =
      *new py::dtype(record_dtype({{"origin_enu_m", py::str("(3,)<f8"), 0},
                                   {"dir_enu", py::str("(3,)<f8"), 3 * sizeof(double)}},
                                  sizeof(PulseRay)));
  return dtype;
}

// A read-only numpy view of `count` items at `data`, kept alive by `owner`.
py::array view(const py::dtype& dtype, const void* data, std::size_t count, py::handle owner) {
  py::array array(dtype, {static_cast<py::ssize_t>(count)}, {}, data, owner);
  py::detail::array_proxy(array.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return array;
}

// Pose samples from a structured array with the PoseSample fields, or an (N, 7) float array with
// columns time_s, e_m, n_m, u_m, roll_deg, pitch_deg, heading_deg.
std::vector<PoseSample> pose_samples(const py::array& poses) {
  static const char* kNames[] = {"time_s",   "e_m",       "n_m",        "u_m",
                                 "roll_deg", "pitch_deg", "heading_deg"};
  std::vector<PoseSample> samples;
  if (poses.dtype().attr("names").is_none()) {
    const auto table =
        py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(poses);
    if (!table || table.ndim() != 2 || table.shape(1) != 7) {
      throw py::value_error(
          "poses: expected an (N, 7) array of time_s, e_m, n_m, u_m, roll_deg, pitch_deg, "
          "heading_deg, or a structured array with those fields");
    }
    samples.resize(static_cast<std::size_t>(table.shape(0)));
    const auto cells = table.unchecked<2>();
    for (py::ssize_t i = 0; i < table.shape(0); ++i) {
      double* out = &samples[static_cast<std::size_t>(i)].time_s;
      for (py::ssize_t c = 0; c < 7; ++c) out[c] = cells(i, c);
    }
    return samples;
  }
  samples.resize(static_cast<std::size_t>(poses.size()));
  for (std::size_t c = 0; c < 7; ++c) {
    py::object column;
    try {
      column = poses[py::str(kNames[c])];
    } catch (const py::error_already_set&) {
      throw py::value_error(std::string("poses: the structured array has no field '") + kNames[c] +
                            "'");
    }
    const auto values = py::array_t<double, py::array::forcecast>::ensure(column);
    const auto cells = values.unchecked<1>();
    for (py::ssize_t i = 0; i < values.shape(0); ++i) {
      (&samples[static_cast<std::size_t>(i)].time_s)[c] = cells(i);
    }
  }
  return samples;
}

SimulationOptions simulation_options(int threads, std::optional<std::int64_t> frames,
                                     std::optional<double> duration_s,
                                     std::optional<std::uint64_t> seed, bool no_noise) {
  SimulationOptions options;
  options.threads = threads;
  options.frames = frames;
  options.duration_s = duration_s;
  options.seed = seed;
  options.no_noise = no_noise;
  return options;
}

py::dict report_dict(const RunReport& report) {
  py::dict out;
  out["directory"] = report.directory.string();
  out["frames"] = report.frames;
  out["first_frame"] = report.first_frame;
  out["pulses"] = report.pulses;
  out["setup_s"] = report.setup_s;
  out["wall_s"] = report.wall_s;
  out["pulses_per_s"] = report.pulses_per_s;
  out["realtime_factor"] = report.realtime_factor;
  out["threads"] = report.threads;
  return out;
}

// Frames 0..frame_count−1 of a simulation, one new Frame each.
struct FrameIterator {
  std::shared_ptr<const Simulation> simulation;
  std::int64_t next = 0;
};

// Frames whose Python objects are gone, kept for the next sim.frame(): a new Frame's buffers
// (~9 MB on the corridor) would otherwise be fresh pages every frame. A pooled Frame has no views
// left (every array keeps its Frame alive), so refilling it changes nothing a caller holds.
class FramePool {
 public:
  std::shared_ptr<Frame> take() {
    std::unique_ptr<Frame> frame;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!free_.empty()) {
        frame = std::move(free_.back());
        free_.pop_back();
      }
    }
    if (!frame) frame = std::make_unique<Frame>();
    return {frame.release(), [this](Frame* done) { give_back(done); }};
  }

 private:
  static constexpr std::size_t kKept = 4;
  void give_back(Frame* frame) {
    std::unique_ptr<Frame> owned(frame);
    const std::lock_guard<std::mutex> lock(mutex_);
    if (free_.size() < kKept) free_.push_back(std::move(owned));
  }
  std::mutex mutex_;
  std::vector<std::unique_ptr<Frame>> free_;
};

// Never destroyed: frames may come back after the interpreter (and static destructors) are done.
FramePool& frame_pool() {
  static FramePool& pool = *new FramePool;
  return pool;
}

std::shared_ptr<Frame> simulate(const Simulation& simulation, std::int64_t k) {
  if (k < 0 || k >= simulation.frame_count()) {
    throw py::index_error("frame " + std::to_string(k) +
                          " is out of range: the flight has frames 0.." +
                          std::to_string(simulation.frame_count() - 1));
  }
  std::shared_ptr<Frame> frame = frame_pool().take();
  py::gil_scoped_release unlocked;
  simulation.simulate_frame(k, *frame);
  return frame;
}

}  // namespace
}  // namespace owsim

PYBIND11_MODULE(owsim, m) {
  using namespace owsim;
  m.doc() = "owsim: the MilOWS / HELLAS obstacle-warning LiDAR simulator (docs/embedding.md)";
  m.attr("__version__") = version_string;
  py::tuple class_names(kSurfaceClassCount);
  for (std::size_t c = 0; c < kSurfaceClassCount; ++c) {
    class_names[c] = std::string(to_string(kSurfaceClasses[c]));
  }
  m.attr("CLASS_NAMES") = class_names;
  m.attr("UNKNOWN_CLASS") = kUnknownSurface;
  m.attr("NO_OBJECT") = kNoObject;
  m.attr("OBSTACLE_CLASS_NAMES") = py::make_tuple("none", "wire", "pole", "tree");

  m.def(
      "view",
      [](const std::filesystem::path& folder, std::optional<std::filesystem::path> out,
         std::optional<std::filesystem::path> scenario, std::uint64_t max_points, int max_frames) {
        FlightReportOptions options;
        if (out) options.out = *out;
        options.scenario = std::move(scenario);
        options.max_points = max_points;
        options.max_frames = max_frames;
        FlightReport report;
        {
          py::gil_scoped_release unlocked;
          report = write_flight_report(folder, options);
        }
        py::dict done;
        done["file"] = report.file.string();
        done["bytes"] = report.bytes;
        done["points_total"] = report.points_total;
        done["points_shown"] = report.points_shown;
        done["frames_total"] = report.frames_total;
        done["frames_shown"] = report.frames_shown;
        done["notes"] = report.notes;
        return done;
      },
      py::arg("folder"), py::arg("out") = py::none(), py::kw_only(),
      py::arg("scenario") = py::none(), py::arg("max_points") = FlightReportOptions{}.max_points,
      py::arg("max_frames") = FlightReportOptions{}.max_frames,
      "What `owsim view` does: the folder as one self-contained page; returns what it holds");

  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const FileError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const Error& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });

  py::class_<Frame, std::shared_ptr<Frame>>(m, "Frame",
                                            "One simulated frame; its arrays are read-only views "
                                            "into buffers the Frame owns.")
      .def_property_readonly("index", &Frame::index)
      .def_property_readonly("model",
                             [](const Frame& f) { return std::string(to_string(f.model())); })
      .def_property_readonly(
          "words",
          [](py::object self) {
            const Frame& f = self.cast<const Frame&>();
            if (f.model() == SensorModel::hellas) {
              return view(py::dtype::of<std::uint32_t>(), f.hellas_words().data(),
                          f.hellas_words().size(), self);
            }
            return view(py::dtype::of<std::uint64_t>(), f.milows_words().data(),
                        f.milows_words().size(), self);
          },
          "The sensor's words, one a pulse, as in flight.d64 (uint64) or flight.hellas (uint32)")
      .def_property_readonly(
          "returns",
          [](py::object self) {
            const Frame& f = self.cast<const Frame&>();
            return view(returns_dtype(), f.returns().data(), f.returns().size(), self);
          },
          "Every detected return: a structured array named by the points.csv columns")
      .def_property_readonly(
          "pulses",
          [](py::object self) {
            const Frame& f = self.cast<const Frame&>();
            return view(pulses_dtype(), f.pulses().data(), f.pulses().size(), self);
          },
          "Every pulse of the frame, firing order (`owsim pattern`'s columns)")
      .def_property_readonly(
          "rays",
          [](py::object self) {
            const Frame& f = self.cast<const Frame&>();
            return view(rays_dtype(), f.rays().data(), f.rays().size(), self);
          },
          "The central ray of every pulse: origin_enu_m (m) and dir_enu (unit)")
      .def("__repr__", [](const Frame& f) {
        return "<owsim.Frame " + std::to_string(f.index()) + ": " +
               std::to_string(f.pulses().size()) + " pulses, " +
               std::to_string(f.returns().size()) + " returns>";
      });

  py::class_<FrameIterator>(m, "FrameIterator")
      .def("__iter__", [](FrameIterator& it) -> FrameIterator& { return it; })
      .def("__next__", [](FrameIterator& it) {
        if (it.next >= it.simulation->frame_count()) throw py::stop_iteration();
        return simulate(*it.simulation, it.next++);
      });

  py::class_<Simulation, std::shared_ptr<Simulation>>(
      m, "Simulation", "A scenario set up once, simulated frame by frame or run whole")
      .def(py::init([](const std::filesystem::path& scenario, int threads,
                       std::optional<std::int64_t> frames, std::optional<double> duration_s,
                       std::optional<std::uint64_t> seed, bool no_noise) {
             const SimulationOptions options =
                 simulation_options(threads, frames, duration_s, seed, no_noise);
             py::gil_scoped_release unlocked;
             return std::make_shared<Simulation>(Simulation::open(scenario, options));
           }),
           py::arg("scenario"), py::kw_only(), py::arg("threads") = 0,
           py::arg("frames") = py::none(), py::arg("duration_s") = py::none(),
           py::arg("seed") = py::none(), py::arg("no_noise") = false)
      .def_static(
          "from_yaml",
          [](const std::string& yaml, const std::filesystem::path& name, int threads,
             std::optional<std::int64_t> frames, std::optional<double> duration_s,
             std::optional<std::uint64_t> seed, bool no_noise) {
            const SimulationOptions options =
                simulation_options(threads, frames, duration_s, seed, no_noise);
            py::gil_scoped_release unlocked;
            return std::make_shared<Simulation>(Simulation::from_yaml(yaml, name, options));
          },
          py::arg("yaml"), py::arg("name") = "scenario.yaml", py::kw_only(), py::arg("threads") = 0,
          py::arg("frames") = py::none(), py::arg("duration_s") = py::none(),
          py::arg("seed") = py::none(), py::arg("no_noise") = false)
      .def_property_readonly("frame_count", &Simulation::frame_count)
      .def_property_readonly("pulses_per_frame", &Simulation::pulses_per_frame)
      .def_property_readonly("model",
                             [](const Simulation& s) { return std::string(to_string(s.model())); })
      .def_property_readonly("name", [](const Simulation& s) { return s.scenario().name; })
      .def_property_readonly("seed", [](const Simulation& s) { return s.scenario().seed; })
      .def_property_readonly("object_ids", &Simulation::object_ids)
      .def_property_readonly("threads", &Simulation::threads)
      .def("frame_start_s", &Simulation::frame_start_s, py::arg("frame"))
      .def("frame_end_s", &Simulation::frame_end_s, py::arg("frame"))
      .def(
          "frame",
          [](const Simulation& s, std::int64_t k, std::optional<py::array> poses) {
            if (!poses) return simulate(s, k);
            const std::vector<PoseSample> samples = pose_samples(*poses);
            std::shared_ptr<Frame> frame = frame_pool().take();
            py::gil_scoped_release unlocked;
            s.simulate_frame(k, samples, *frame);
            return frame;
          },
          py::arg("k"), py::arg("poses") = py::none(),
          "Frame k along the scenario's trajectory, or (co-simulation) flown through `poses`")
      .def("__len__", [](const Simulation& s) { return s.frame_count(); })
      .def("__iter__",
           [](std::shared_ptr<const Simulation> s) {
             return FrameIterator{std::move(s), 0};
           })
      .def(
          "run",
          [](const Simulation& s, std::optional<std::filesystem::path> out,
             std::optional<std::string> outputs, bool resume,
             std::function<void(std::int64_t, std::int64_t)> progress) {
            RunOptions run;
            run.out = std::move(out);
            if (outputs) run.outputs = parse_output_list(*outputs);
            run.resume = resume;
            if (progress) {
              run.progress = [progress](const RunProgress& at) {
                py::gil_scoped_acquire locked;
                progress(at.frames_done, at.frames_total);
              };
            }
            RunReport report;
            {
              py::gil_scoped_release unlocked;
              report = s.run(run);
            }
            return report_dict(report);
          },
          py::arg("out") = py::none(), py::kw_only(), py::arg("outputs") = py::none(),
          py::arg("resume") = false, py::arg("progress") = py::none(),
          "What `owsim run` does; returns the run's report as a dict");

  py::class_<PyFrameDetector>(
      m, "FrameDetector",
      "The reference obstacle detector fed frame by frame (docs/detection.md): it reads the "
      "frames' words and the scenario's navigation, never their returns' truth")
      .def(py::init([](std::shared_ptr<const Simulation> s) {
             return std::make_unique<PyFrameDetector>(std::move(s));
           }),
           py::arg("simulation"))
      .def(
          "add_frame",
          [](PyFrameDetector& d, const Frame& frame) {
            std::span<const ObstacleWarning> warnings;
            {
              py::gil_scoped_release unlocked;
              warnings = d.detector.add_frame(frame);
            }
            py::array out(warnings_dtype(),
                          py::array::ShapeContainer{static_cast<py::ssize_t>(warnings.size())});
            if (!warnings.empty()) {
              std::memcpy(out.mutable_data(), warnings.data(), warnings.size_bytes());
            }
            return out;
          },
          py::arg("frame"),
          "The warnings after `frame` (frames in order, each once): a structured array of "
          "detections.csv's columns")
      .def("csv_rows", [](const PyFrameDetector& d) { return d.detector.csv_rows(); },
           "The last frame's warnings as detections.csv rows")
      .def_property_readonly_static(
          "csv_header", [](py::object) { return std::string(FrameDetector::csv_header()); });
}
