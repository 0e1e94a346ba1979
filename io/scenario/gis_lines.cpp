#include "io/scenario/gis_lines.hpp"

#include <array>
#include <string>

#include "geometry/error.hpp"
#include "io/scenario/gdal_module.hpp"
#include "io/scenario/gdal_module_abi.hpp"

namespace owsim {
namespace {

void receive_line(void* context, const char* line_json) {
  auto* lines = static_cast<std::vector<GisLine>*>(context);
  const nlohmann::json line = nlohmann::json::parse(line_json);
  GisLine out;
  out.feature = line.at("feature").get<int>();
  out.properties = line.at("properties");
  for (const auto& vertex : line.at("coordinates")) {
    out.lon_lat.emplace_back(vertex.at(0).get<double>(), vertex.at(1).get<double>());
  }
  lines->push_back(std::move(out));
}

}  // namespace

std::vector<GisLine> read_gis_lines(const std::filesystem::path& file) {
  const auto read = reinterpret_cast<owsim_lines_read_fn>(
      gdal_module("power lines from GIS files (power_lines)").symbol("owsim_lines_read"));
  std::vector<GisLine> lines;
  std::array<char, 1024> error{};
  if (read(file.c_str(), receive_line, &lines, error.data(), error.size()) != 0) {
    throw Error(file.string() + ": " + error.data());
  }
  return lines;
}

}  // namespace owsim
