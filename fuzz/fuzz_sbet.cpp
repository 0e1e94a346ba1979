// libFuzzer target: io/trajectory/sbet_reader.hpp read_sbet on arbitrary bytes.
// Any input must either read or throw owsim::Error (one line naming the file); any other
// exception, a crash or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_input_file.hpp"
#include "geometry/error.hpp"
#include "io/trajectory/sbet_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = owsim::fuzz::write_input_file(data, size, ".sbet");
  try {
    (void)owsim::read_sbet(path);
  } catch (const owsim::Error&) {
  }
  return 0;
}
