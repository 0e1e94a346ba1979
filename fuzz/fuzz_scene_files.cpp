// libFuzzer target: the readers of a scenario's scene files on arbitrary bytes — the ESRI ASCII
// grid (terrain.grid), GIS lines through GDAL (power_lines), meshes through assimp (meshes: OBJ
// and PLY) and a DEM through GDAL (terrain.dem, the whole raster). The first byte picks the
// reader, the rest is the file. Any input must either read or throw owsim::Error (one line naming
// the file); any other exception, a crash or a sanitizer report is a finding (issue 33).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "fuzz/fuzz_input_file.hpp"
#include "geometry/error.hpp"
#include "geometry/geodetic_frame.hpp"
#include "io/scenario/dem_terrain.hpp"
#include "io/scenario/esri_ascii_grid.hpp"
#include "io/scenario/gis_lines.hpp"
#include "io/scenario/mesh_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t reader = data[0] % 5;
  const char* const extensions[] = {".asc", ".geojson", ".obj", ".ply", ".tif"};
  const std::string path = owsim::fuzz::write_input_file(data + 1, size - 1, extensions[reader]);
  try {
    switch (reader) {
      case 0:
        (void)owsim::read_esri_ascii_grid(path);
        break;
      case 1:
        (void)owsim::read_gis_lines(path);
        break;
      case 2:
      case 3:
        (void)owsim::read_mesh_file(path);
        break;
      default: {
        static const owsim::LocalFrame frame(owsim::Geodetic{48.6881, 10.8447, 450.0});
        (void)owsim::read_dem_terrain(path, frame, std::nullopt);
      }
    }
  } catch (const owsim::Error&) {
  }
  return 0;
}
