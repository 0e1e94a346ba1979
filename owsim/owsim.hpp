#pragma once
// owsim — the MilOWS / HELLAS obstacle-warning LiDAR simulator as a library. The one include an
// embedding program needs (after find_package(owsim), target owsim::owsim):
//
//   owsim::Simulation sim = owsim::Simulation::open("corridor.yaml");
//   owsim::Frame frame;
//   for (std::int64_t k = 0; k < sim.frame_count(); ++k) {
//     sim.simulate_frame(k, frame);  // frame.word_bytes(), frame.returns(), frame.pulses(), …
//   }
//
// The reference obstacle detector fed frame by frame: owsim/frame_detector.hpp.
// owsim/simulation.hpp says what each call does, its errors and its threading contract;
// docs/embedding.md shows the same in C and Python.
#include "geometry/error.hpp"
#include "io/scenario/scenario.hpp"
#include "owsim/flight_report.hpp"
#include "owsim/frame.hpp"
#include "owsim/frame_detector.hpp"
#include "owsim/simulation.hpp"
#include "owsim/version.hpp"
