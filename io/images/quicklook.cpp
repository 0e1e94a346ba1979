#include "io/images/quicklook.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <system_error>
#include <utility>

#include "geometry/error.hpp"
#include "io/files/output_open.hpp"
#include "sensor/fiber_layout.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

// The map mask: one bit per layer. Bits 0..3 are the hit classes (1 << SurfaceClass); a hit on a
// mesh counts as a surface hit, like the ground's (map_hit_bit).
constexpr std::uint8_t kTrajectoryBit = 1 << 4;
constexpr std::uint8_t kConductorBit = 1 << 5;
constexpr std::uint8_t kPoleObjectBit = 1 << 6;
constexpr std::uint8_t kTreeObjectBit = 1 << 7;

constexpr std::uint8_t hit_bit(SurfaceClass surface) {
  return static_cast<std::uint8_t>(1u << static_cast<unsigned>(surface));
}
constexpr std::uint8_t map_hit_bit(SurfaceClass surface) {
  return hit_bit(surface == SurfaceClass::building ? SurfaceClass::ground : surface);
}

constexpr Rgb8 kGridLow{34, 52, 38};     // lowest terrain on the map
constexpr Rgb8 kGridHigh{130, 122, 98};  // highest

const QuicklookOptions& checked(const QuicklookOptions& o) {
  if (o.every_nth_frame < 0) {
    throw input_error("quicklook", "every_nth_frame " + std::to_string(o.every_nth_frame) + " < 0");
  }
  if (o.map_size_px < 16 || o.map_size_px > 16'384) {
    throw input_error("quicklook",
                      "map_size_px " + std::to_string(o.map_size_px) + " outside 16..16384");
  }
  if (o.range_image_scale < 1 || o.range_image_scale > 16) {
    throw input_error(
        "quicklook", "range_image_scale " + std::to_string(o.range_image_scale) + " outside 1..16");
  }
  if (!std::isfinite(o.range_full_scale_m) || o.range_full_scale_m < 0.0) {
    throw input_error("quicklook", "range_full_scale_m must be finite and ≥ 0");
  }
  return o;
}

const ScanParams& checked(const ScanParams& scan) {
  if (scan.fibers_per_line < 2 || scan.lines_per_frame < 1) {
    throw input_error("quicklook", "the scan needs at least 2 fibers and 1 line");
  }
  return scan;
}

const Eigen::AlignedBox2d& checked(const Eigen::AlignedBox2d& region) {
  const Eigen::Vector2d size = region.max() - region.min();
  if (!region.min().allFinite() || !region.max().allFinite() || !(size.x() > 0.0) ||
      !(size.y() > 0.0)) {
    throw input_error("quicklook", "the map region is empty or not finite");
  }
  return region;
}

// Row of each fiber (fibers_top_down); −1 for the reference fiber.
std::vector<int> rows_by_alpha(const ScanParams& scan) {
  const std::vector<int> fibers = fibers_top_down(scan);
  std::vector<int> row_of_fiber(static_cast<std::size_t>(scan.fibers_per_line) + 1, -1);
  for (std::size_t row = 0; row < fibers.size(); ++row) {
    row_of_fiber[static_cast<std::size_t>(fibers[row])] = static_cast<int>(row);
  }
  return row_of_fiber;
}

double metres_per_px_of(const Eigen::AlignedBox2d& region, int map_size_px) {
  const Eigen::Vector2d size = region.max() - region.min();
  return std::max(size.x(), size.y()) / map_size_px;
}

int pixels_along(double metres, double metres_per_px, int map_size_px) {
  const double px = std::ceil(metres / metres_per_px - 1e-9);
  return static_cast<int>(std::clamp(px, 1.0, static_cast<double>(map_size_px)));
}

// The returns' class to mark, if any: wire before pole before tree.
std::optional<SurfaceClass> marked_class(const PulseReturns& returns) {
  std::optional<SurfaceClass> best;
  for (int i = 0; i < std::min(returns.count, 2); ++i) {
    const std::uint8_t code = returns.returns[i].surface;
    if (code >= static_cast<std::uint8_t>(SurfaceClass::ground)) continue;
    const auto surface = static_cast<SurfaceClass>(code);
    if (!best || surface < *best) best = surface;
  }
  return best;
}

Rgb8 class_colour(SurfaceClass surface) {
  switch (surface) {
    case SurfaceClass::wire:
      return kQuicklookWire;
    case SurfaceClass::pole:
      return kQuicklookPole;
    case SurfaceClass::tree:
      return kQuicklookTree;
    case SurfaceClass::noise:
      return kQuicklookNoise;
    case SurfaceClass::ground:
    case SurfaceClass::building:
    case SurfaceClass::fog:
      return kQuicklookGroundHit;
  }
  return kQuicklookGroundHit;
}

// A range-image cell's colour: its marked class, a false first return's, else the first return's
// range on the ramp.
Rgb8 range_cell_colour(const PulseReturns& returns, double range_full_scale_m) {
  if (const std::optional<SurfaceClass> marked = marked_class(returns)) {
    return class_colour(*marked);
  }
  const Return& first = returns.returns[0];
  if (first.surface == static_cast<std::uint8_t>(SurfaceClass::noise)) {
    return class_colour(SurfaceClass::noise);
  }
  return range_ramp_colour(first.range_m / range_full_scale_m);
}

}  // namespace

Eigen::AlignedBox2d quicklook_map_region(const Scene& scene,
                                         std::span<const Eigen::Vector3d> points_enu_m,
                                         double margin_m) {
  if (!std::isfinite(margin_m) || margin_m < 0.0) {
    throw input_error("quicklook", "map margin must be finite and ≥ 0");
  }
  Eigen::AlignedBox2d box;
  for (const Conductor& conductor : scene.conductors) {
    for (const Eigen::Vector3d& p : conductor.points_enu_m) box.extend(p.head<2>());
  }
  for (const Cylinder& cylinder : scene.cylinders) {
    box.extend(cylinder.base_enu_m.head<2>() - Eigen::Vector2d::Constant(cylinder.radius_m));
    box.extend(cylinder.base_enu_m.head<2>() + Eigen::Vector2d::Constant(cylinder.radius_m));
  }
  for (const MeshObject& object : scene.meshes) {
    for (const Eigen::Vector3d& p : object.mesh.vertices) box.extend(p.head<2>());
  }
  for (const Eigen::Vector3d& p : points_enu_m) {
    if (p.allFinite()) box.extend(p.head<2>());
  }
  if (box.isEmpty()) box.extend(Eigen::Vector2d::Zero());
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(margin_m);
  return {box.min() - margin, box.max() + margin};
}

std::string quicklook_frame_file_name(std::int64_t frame) {
  char name[48];
  std::snprintf(name, sizeof name, "frame_%06lld.png", static_cast<long long>(frame));
  return name;
}

Quicklook::Quicklook(std::filesystem::path directory, const Scene& scene, const ScanParams& scan,
                     const Eigen::AlignedBox2d& map_region, QuicklookOptions options)
    : directory_(std::move(directory)),
      options_(checked(options)),
      lines_per_frame_(checked(scan).lines_per_frame),
      range_full_scale_m_(options_.range_full_scale_m > 0.0 ? options_.range_full_scale_m
                                                            : timeout_range_m(scan.counter)),
      row_of_fiber_(rows_by_alpha(scan)),
      rows_(scan.fibers_per_line - 1),
      frame_cells_(scan.lines_per_frame, rows_),
      region_(checked(map_region)),
      metres_per_px_(metres_per_px_of(region_, options_.map_size_px)),
      base_(pixels_along(region_.sizes().x(), metres_per_px_, options_.map_size_px),
            pixels_along(region_.sizes().y(), metres_per_px_, options_.map_size_px)) {
  // The run folder may be the user's link; quicklook/, owsim's name, is never followed.
  std::error_code error;
  if (directory_.has_parent_path()) {
    std::filesystem::create_directories(directory_.parent_path(), error);
  }
  if (error) {
    throw file_error(directory_.parent_path().string(),
                     "cannot create the output folder: " + error.message());
  }
  make_output_subfolder(directory_);
  mask_.assign(static_cast<std::size_t>(base_.width()) * static_cast<std::size_t>(base_.height()),
               0);
  draw_terrain(scene.terrain);
  draw_objects(scene);
}

Eigen::Vector2d Quicklook::map_px(double e_m, double n_m) const {
  return {(e_m - region_.min().x()) / metres_per_px_ - 0.5,
          (region_.max().y() - n_m) / metres_per_px_ - 0.5};
}

void Quicklook::mark(const Eigen::Vector2d& px, std::uint8_t bits) {
  if (!px.allFinite()) return;
  const double x = std::round(px.x()), y = std::round(px.y());
  if (x < 0.0 || y < 0.0 || x >= base_.width() || y >= base_.height()) return;
  mask_[static_cast<std::size_t>(y) * static_cast<std::size_t>(base_.width()) +
        static_cast<std::size_t>(x)] |= bits;
}

void Quicklook::mark_line(const Eigen::Vector2d& from_px, const Eigen::Vector2d& to_px,
                          std::uint8_t bits) {
  const auto width = static_cast<std::size_t>(base_.width());
  for_each_line_pixel(from_px, to_px, base_.width(), base_.height(), [&](int x, int y) {
    mask_[static_cast<std::size_t>(y) * width + static_cast<std::size_t>(x)] |= bits;
  });
}

void Quicklook::mark_disc(const Eigen::Vector2d& centre_px, int radius_px, std::uint8_t bits) {
  if (!centre_px.allFinite()) return;
  const double cx = std::round(centre_px.x()), cy = std::round(centre_px.y());
  const double r = radius_px;
  const double y_first = std::max(cy - r, 0.0), y_last = std::min(cy + r, base_.height() - 1.0);
  const double x_first = std::max(cx - r, 0.0), x_last = std::min(cx + r, base_.width() - 1.0);
  for (double y = y_first; y <= y_last; ++y) {
    for (double x = x_first; x <= x_last; ++x) {
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r) mark({x, y}, bits);
    }
  }
}

void Quicklook::draw_terrain(const Terrain& terrain) {
  if (terrain.kind == TerrainKind::none) {
    base_.fill(kQuicklookNoTerrain);
    return;
  }
  if (terrain.kind == TerrainKind::flat) {
    base_.fill(kQuicklookFlatTerrain);
    return;
  }
  base_.fill(kQuicklookNoTerrain);
  // The height under each pixel centre: the nearest sample of a grid, the surface of a DEM.
  std::function<std::optional<double>(double, double)> height_under;
  double low = std::numeric_limits<double>::infinity(), high = -low;
  const auto extend = [&](double h) {
    low = std::min(low, h);
    high = std::max(high, h);
  };
  if (terrain.kind == TerrainKind::dem) {
    const PostLattice& dem = *terrain.dem;
    for (std::size_t i = 0; i < dem.posts.size() && i < dem.valid.size(); ++i) {
      if (dem.valid[i] != 0) extend(dem.posts[i].z());
    }
    if (dem.ncols < 2 || dem.nrows < 2 || dem.posts.size() != dem.valid.size()) return;
    height_under = [&dem](double e_m, double n_m) { return dem.height_if_any(e_m, n_m); };
  } else {
    const HeightGrid& grid = terrain.grid;
    if (grid.ncols < 2 || grid.nrows < 2 || !(grid.cellsize_m > 0.0) ||
        grid.heights.size() !=
            static_cast<std::size_t>(grid.ncols) * static_cast<std::size_t>(grid.nrows)) {
      return;
    }
    for (const double h : grid.heights) {
      if (!grid.is_nodata(h) && std::isfinite(h)) extend(h);
    }
    height_under = [&grid](double e_m, double n_m) -> std::optional<double> {
      const double row = std::round((grid.y_north_m() - n_m) / grid.cellsize_m);
      const double col = std::round((e_m - grid.x_west_m) / grid.cellsize_m);
      if (row < 0.0 || row > grid.nrows - 1 || col < 0.0 || col > grid.ncols - 1) {
        return std::nullopt;
      }
      const double h = grid.sample(static_cast<int>(row), static_cast<int>(col));
      if (grid.is_nodata(h) || !std::isfinite(h)) return std::nullopt;
      return h;
    };
  }
  if (!(high >= low)) return;
  const double span = std::max(high - low, 1e-9);
  for (int y = 0; y < base_.height(); ++y) {
    const double n_m = region_.max().y() - (y + 0.5) * metres_per_px_;
    for (int x = 0; x < base_.width(); ++x) {
      const double e_m = region_.min().x() + (x + 0.5) * metres_per_px_;
      const std::optional<double> h = height_under(e_m, n_m);
      if (!h) continue;
      const double w = (*h - low) / span;
      const auto mix = [w](std::uint8_t a, std::uint8_t b) {
        return static_cast<std::uint8_t>(std::lround(a + (static_cast<double>(b) - a) * w));
      };
      base_.set(x, y,
                {mix(kGridLow.r, kGridHigh.r), mix(kGridLow.g, kGridHigh.g),
                 mix(kGridLow.b, kGridHigh.b)});
    }
  }
}

void Quicklook::draw_objects(const Scene& scene) {
  for (const Cylinder& cylinder : scene.cylinders) {
    const bool pole = cylinder.surface == SurfaceClass::pole;
    const double radius =
        std::fmin(std::fmax(cylinder.radius_m / metres_per_px_, 0.0), options_.map_size_px);
    const int radius_px = std::max(pole ? 2 : 1, static_cast<int>(std::lround(radius)));
    mark_disc(map_px(cylinder.base_enu_m.x(), cylinder.base_enu_m.y()), radius_px,
              pole ? kPoleObjectBit : kTreeObjectBit);
  }
  for (const Conductor& conductor : scene.conductors) {
    const auto& points = conductor.points_enu_m;
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
      mark_line(map_px(points[i].x(), points[i].y()), map_px(points[i + 1].x(), points[i + 1].y()),
                kConductorBit);
    }
    if (points.size() == 1) mark(map_px(points.front().x(), points.front().y()), kConductorBit);
  }
  // Meshes as the outlines of their triangles seen from above, in the poles' colour.
  for (const MeshObject& object : scene.meshes) {
    const TriangleMesh& mesh = object.mesh;
    for (const auto& triangle : mesh.triangles) {
      for (std::size_t corner = 0; corner < 3; ++corner) {
        const Eigen::Vector3d& a = mesh.vertices[triangle[corner]];
        const Eigen::Vector3d& b = mesh.vertices[triangle[(corner + 1) % 3]];
        mark_line(map_px(a.x(), a.y()), map_px(b.x(), b.y()), kPoleObjectBit);
      }
    }
  }
}

void Quicklook::require_open(const char* operation) const {
  if (finished_) throw input_error("quicklook", std::string(operation) + " after finish()");
}

void Quicklook::add_trajectory_point(const Eigen::Vector3d& enu_m) {
  require_open("add_trajectory_point");
  if (!enu_m.allFinite()) return;
  const Eigen::Vector2d px = map_px(enu_m.x(), enu_m.y());
  if (last_trajectory_px_) {
    mark_line(*last_trajectory_px_, px, kTrajectoryBit);
  } else {
    mark(px, kTrajectoryBit);
  }
  last_trajectory_px_ = px;
}

void Quicklook::add_frame(const FrameView& frame) {
  require_open("add_frame");
  if (frame.rays.size() != frame.pulses.size() || frame.returns.size() != frame.pulses.size()) {
    throw input_error("quicklook", "frame " + std::to_string(frame.frame) + ": " +
                                       std::to_string(frame.pulses.size()) + " pulses, " +
                                       std::to_string(frame.rays.size()) + " rays, " +
                                       std::to_string(frame.returns.size()) + " returns");
  }
  for (std::size_t k = 0; k < frame.pulses.size(); ++k) {
    const PulseReturns& pulse_returns = frame.returns[k];
    for (int i = 0; i < std::min(pulse_returns.count, 2); ++i) {
      const Return& r = pulse_returns.returns[i];
      // Fog echoes and false returns (class noise) are not places on the map.
      if (r.surface >= static_cast<std::uint8_t>(SurfaceClass::fog)) continue;
      const Eigen::Vector3d point = frame.rays[k].origin_enu_m + r.range_m * frame.rays[k].dir_enu;
      mark(map_px(point.x(), point.y()), map_hit_bit(static_cast<SurfaceClass>(r.surface)));
    }
  }
  const std::int64_t n = options_.every_nth_frame;
  if (n > 0 && frame.frame % n == 0) write_range_image(frame);
}

void Quicklook::write_range_image(const FrameView& frame) {
  frame_cells_.fill(kQuicklookNoReturn);
  for (std::size_t k = 0; k < frame.pulses.size(); ++k) {
    const Pulse& pulse = frame.pulses[k];
    if (pulse.reference) continue;
    if (pulse.line < 0 || pulse.line >= lines_per_frame_ || pulse.fiber < 1 ||
        pulse.fiber >= static_cast<int>(row_of_fiber_.size())) {
      throw input_error("quicklook", "frame " + std::to_string(frame.frame) + " pulse " +
                                         std::to_string(pulse.index) + ": line " +
                                         std::to_string(pulse.line) + " or fiber " +
                                         std::to_string(pulse.fiber) + " outside the scan");
    }
    const int row = row_of_fiber_[static_cast<std::size_t>(pulse.fiber)];
    if (row < 0) continue;
    const int column = frame.sweep.direction < 0 ? lines_per_frame_ - 1 - pulse.line : pulse.line;
    const PulseReturns& returns = frame.returns[k];
    if (returns.count < 1) continue;
    frame_cells_.set(column, row, range_cell_colour(returns, range_full_scale_m_));
  }
  write_png(directory_ / quicklook_frame_file_name(frame.frame),
            enlarged(frame_cells_, options_.range_image_scale), options_.file_options);
}

QuicklookCheckpoint Quicklook::checkpoint() const { return {mask_, last_trajectory_px_}; }

void Quicklook::add_map_hits(std::span<const std::uint8_t> map_mask) {
  require_open("add_map_hits");
  if (map_mask.size() != mask_.size()) {
    throw input_error("quicklook", "a map mask of " + std::to_string(map_mask.size()) +
                                       " bytes for " + std::to_string(base_.width()) + " × " +
                                       std::to_string(base_.height()) + " pixels");
  }
  for (std::size_t i = 0; i < mask_.size(); ++i) mask_[i] |= map_mask[i];
}

void Quicklook::restore(QuicklookCheckpoint from) {
  require_open("restore");
  if (from.map_mask.size() != mask_.size()) {
    throw input_error("quicklook", "cannot resume: a map mask of " +
                                       std::to_string(from.map_mask.size()) + " bytes for " +
                                       std::to_string(base_.width()) + " × " +
                                       std::to_string(base_.height()) + " pixels");
  }
  mask_ = std::move(from.map_mask);
  last_trajectory_px_ = from.last_trajectory_px;
}

void Quicklook::finish() {
  require_open("finish");
  finished_ = true;
  RgbImage map = base_;
  const int width = map.width();
  // Paints every pixel carrying `bit`, as a disc of radius_px, in the order of the header.
  const auto paint = [&](std::uint8_t bit, Rgb8 colour, int radius_px) {
    for (int y = 0; y < map.height(); ++y) {
      for (int x = 0; x < width; ++x) {
        if ((mask_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                   static_cast<std::size_t>(x)] &
             bit) == 0) {
          continue;
        }
        if (radius_px == 0) {
          map.set(x, y, colour);
        } else {
          fill_circle(map, x, y, radius_px, colour);
        }
      }
    }
  };
  paint(hit_bit(SurfaceClass::ground), kQuicklookGroundHit, 0);
  paint(kTreeObjectBit, kQuicklookTreeObject, 0);
  paint(kConductorBit, kQuicklookConductor, 0);
  paint(kPoleObjectBit, kQuicklookPoleObject, 0);
  paint(kTrajectoryBit, kQuicklookTrajectory, 1);
  paint(hit_bit(SurfaceClass::tree), kQuicklookTree, 1);
  paint(hit_bit(SurfaceClass::pole), kQuicklookPole, 1);
  paint(hit_bit(SurfaceClass::wire), kQuicklookWire, 1);
  write_png(directory_ / "map.png", map, options_.file_options);
}

}  // namespace owsim
