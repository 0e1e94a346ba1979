#include "io/detections/detections_csv.hpp"

#include "io/files/csv_cells.hpp"

namespace owsim {

void append_detection_rows(std::span<const ObstacleWarning> warnings, std::string& out) {
  for (const ObstacleWarning& w : warnings) {
    append_csv_integer(out, w.frame);
    out += ',';
    append_csv_fixed(out, w.time_s, 9);
    out += ',';
    append_csv_integer(out, w.track);
    out += ',';
    out += to_string(w.kind);
    for (const double value : {w.nearest_enu_m.x(), w.nearest_enu_m.y(), w.nearest_enu_m.z(),
                               w.range_m, w.length_m, w.width_m, w.height_m}) {
      out += ',';
      append_csv_fixed(out, value, 3);
    }
    out += ',';
    append_csv_integer(out, w.points);
    out += '\n';
  }
}

}  // namespace owsim
