#pragma once
// One frame's outputs encoded ahead of FlightOutputs::add_frame (io/run/flight_outputs.hpp): the
// bytes every requested output file gets from the frame, and what the serial part needs besides
// (the frame's points for the writers' counts, the pose at its first pulse). Filled by
// FlightOutputs::encode_frame on any thread, so the serial sink of the flight pipeline only
// appends ready bytes. Reused frame after frame: it allocates only while its buffers grow.
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "io/points/las_writer.hpp"
#include "io/points/point_record.hpp"
#include "io/run/flight_mcap.hpp"
#include "io/run/flight_summary.hpp"
#include "io/run/frame_truth.hpp"
#include "sensor/mounting.hpp"

namespace owsim {

struct FrameEncoding {
  std::int64_t frame = -1;  // the frame encoded; −1 before the first
  Pose frame_start;         // the aircraft's pose at the frame's first pulse
  FrameTally tally;         // the frame's part of summary.json
  std::vector<PointRecord> points;
  std::vector<std::uint64_t> milows_words;  // flight.d64 of a MilOWS scenario
  std::vector<std::uint32_t> hellas_words;  // flight.hellas of a HELLAS scenario
  std::uint32_t hellas_header_word = 0;     // written before the file's first frame only
  std::string csv_rows;                     // points.csv
  LasEncodedPoints las;                     // points.las
  std::vector<unsigned char> ply_vertices;  // points.ply
  FrameTruth truth;                         // the frame's ground truth
  std::string truth_rows;                   // truth.csv
  McapFrameEncoding mcap;                   // flight.mcap: the frame's chunk
  // What encoding threw: add_frame rethrows it, so errors surface in frame order.
  std::exception_ptr error;
  // The per-pulse part as FlightOutputs::encode_pulses leaves it, one entry per scan line: a
  // block's tally and error in the entry of its first line, the block's other lines empty.
  // finish_encoding merges them, in line order, into `tally` and `error`.
  struct LineBlock {
    FrameTally tally;
    std::exception_ptr error;
  };
  std::vector<LineBlock> line_blocks;
};

// What a frame adds to the outputs besides its bytes, for FlightOutputs::add_placed_frame when
// another process wrote those bytes into the files at their places (a distributed run,
// distributed/). The bytes follow from it: the words of every pulse (and the HELLAS header word
// before frame 0), csv_bytes of points.csv, 30 bytes a point of points.las, 29 of points.ply;
// truth.csv's and flight.mcap's it holds.
struct PlacedFrame {
  std::int64_t frame = -1;
  Pose frame_start;
  FrameTally tally;
  std::uint64_t points = 0;
  std::uint64_t csv_bytes = 0;
  LasEncodedPoints las;  // its statistics; `records` stays empty
  // truth.csv's rows of the frame, whole: process 0 appends them (a frame's are kilobytes).
  std::uint64_t truth_row_count = 0;
  std::string truth_rows;
  // flight.mcap's chunk of the frame as McapChunk::append_finished lays it out: process 0 appends
  // it (a frame's chunk is tens of kilobytes). Empty without flight.mcap.
  std::string mcap_chunk;
};

}  // namespace owsim
