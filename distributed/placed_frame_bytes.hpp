#pragma once
// PlacedFrame (io/run/frame_encoding.hpp) as bytes, to gather every process's frames at the one
// that keeps the files' state (distributed/distributed_run.hpp). Both ends are the same owsim
// build: the bytes are the fields in a fixed order, native byte order, not a file format.
#include <string>
#include <string_view>
#include <vector>

#include "io/run/frame_encoding.hpp"

namespace owsim {

// Appends `frame` to `out`.
void append_placed_frame(const PlacedFrame& frame, std::string& out);
// Every frame append_placed_frame wrote into `bytes`, in order. Throws owsim::Error if the bytes
// end inside a frame.
[[nodiscard]] std::vector<PlacedFrame> read_placed_frames(std::string_view bytes);

}  // namespace owsim
