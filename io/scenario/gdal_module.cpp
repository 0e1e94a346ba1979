#include "io/scenario/gdal_module.hpp"

#include <array>
#include <system_error>

#include "geometry/error.hpp"
#include "io/scenario/gdal_module_abi.hpp"

namespace owsim {
namespace {

void receive_file(void* context, const char* path) {
  static_cast<std::vector<std::filesystem::path>*>(context)->emplace_back(path);
}

}  // namespace

const OptionalModule& gdal_module(std::string_view purpose) {
  return OptionalModule::get("gdal", purpose, OWSIM_GDAL_MODULE_ABI);
}

std::vector<std::filesystem::path> dataset_companions(const std::filesystem::path& file,
                                                      bool vector) {
  const auto list = reinterpret_cast<owsim_dataset_files_fn>(
      gdal_module(vector ? "power lines from GIS files (power_lines)" : "DEM terrain (terrain.dem)")
          .symbol("owsim_dataset_files"));
  std::vector<std::filesystem::path> files;
  std::array<char, 1024> error{};
  if (list(file.c_str(), vector ? 1 : 0, receive_file, &files, error.data(), error.size()) != 0) {
    throw Error(file.string() + ": " + error.data());
  }
  std::vector<std::filesystem::path> companions;
  for (const std::filesystem::path& listed : files) {
    std::error_code failed;
    const std::filesystem::path real = std::filesystem::canonical(listed, failed);
    if (!failed && real != file) companions.push_back(real);
  }
  return companions;
}

}  // namespace owsim
