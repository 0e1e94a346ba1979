// libFuzzer target: a MilOWS recording of arbitrary bytes through io/recording/recording_check.hpp
// (what `owsim info` runs: the structure check, the text and JSON reports) and every whole word
// through io/recording/milows_word.hpp, whose unpack must be total and whose pack must give the
// word back bit for bit. Any input must be checked or throw owsim::Error; anything else is a
// finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "fuzz/fuzz_input_file.hpp"
#include "geometry/error.hpp"
#include "io/recording/milows_word.hpp"
#include "io/recording/recording_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  for (std::size_t at = 0; at + sizeof(std::uint64_t) <= size; at += sizeof(std::uint64_t)) {
    std::uint64_t bits = 0;
    for (std::size_t byte = 0; byte < sizeof(std::uint64_t); ++byte) {
      bits |= std::uint64_t{data[at + byte]} << (8 * byte);  // little-endian
    }
    if (owsim::pack(owsim::unpack_milows(bits)) != bits) std::abort();
  }
  const std::string path = owsim::fuzz::write_input_file(data, size, ".d64");
  try {
    owsim::ScanParams scan;
    scan.model = owsim::SensorModel::milows;
    const owsim::RecordingReport report = owsim::check_recording(path, scan);
    (void)owsim::render_text(report);
    (void)owsim::to_json(report).dump();
  } catch (const owsim::Error&) {
  }
  return 0;
}
