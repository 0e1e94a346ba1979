// libFuzzer target: io/scenario/scenario_loader.hpp load_scenario_text on arbitrary YAML text.
// Any input must either load or throw owsim::Error (one line naming the file); any other
// exception, a crash or a sanitizer report is a finding. Relative paths in the scenario resolve
// against an empty temporary folder, so a fuzzed scenario reads no file of ours.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "geometry/error.hpp"
#include "io/scenario/scenario_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "owsim_fuzz_scenario" / "fuzz.yaml";
  const std::string_view yaml(reinterpret_cast<const char*>(data), size);
  try {
    (void)owsim::load_scenario_text(yaml, path);
  } catch (const owsim::Error&) {
  }
  return 0;
}
