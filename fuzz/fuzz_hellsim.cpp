// libFuzzer target: io/trajectory/hellsim_reader.hpp read_hellsim on arbitrary text.
// Any input must either read or throw owsim::Error (one line naming the file); any other
// exception, a crash or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_input_file.hpp"
#include "geometry/error.hpp"
#include "io/trajectory/hellsim_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = owsim::fuzz::write_input_file(data, size, ".txt");
  try {
    (void)owsim::read_hellsim(path);
  } catch (const owsim::Error&) {
  }
  return 0;
}
