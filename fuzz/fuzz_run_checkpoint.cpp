// libFuzzer target: io/run/run_checkpoint.hpp read_run_checkpoint on damaged checkpoints (issue
// 17, binary since issue 19). The first byte chooses how the rest becomes the file: as it is (so
// the magic, version and checksum are what refuse it), or behind a correct header (so the record
// reader and every field's checks see arbitrary bytes). Any input must either read or throw owsim::Error; anything else is a
// finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz/fuzz_input_file.hpp"
#include "geometry/error.hpp"
#include "io/run/run_checkpoint.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
  const std::string text =
      (data[0] & 1) != 0 ? owsim::checkpoint_file_bytes(rest) : std::string(rest);
  const std::string path = owsim::fuzz::write_input_file(
      reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), ".bin");
  try {
    (void)owsim::read_run_checkpoint(path);
  } catch (const owsim::Error&) {
  }
  return 0;
}
