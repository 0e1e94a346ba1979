#pragma once
// quicklook/ of `owsim run` (INTERFACE.md "`owsim run` outputs"): a PNG range image of every Nth
// frame and a top-down PNG map of the flight, for a person to glance at. Not a data product: the
// colours are for the eye, the numbers live in the point files.
//
// Range image `frame_<NNNNNN>.png` (frame number, zero-padded to 6 digits) of every frame whose
// number is a multiple of every_nth_frame: one cell per pulse, (fibers_per_line − 1) rows ×
// lines_per_frame columns (127 × 159 by default), each cell enlarged to range_image_scale² pixels
// (4× → 636 × 508). Rows are the fibers sorted by α, highest α at the top (for MilOWS α is up,
// SENSOR-SPEC §4 pinned conventions; equal α keep fiber order: fiber 64 above 127); the reference
// fiber has no row. Columns are the lines in β order, β rising left → right: line l is column l on
// frames sweeping up (direction +1) and column lines−1−l on frames sweeping down, so successive
// frames line up. A cell's colour: the class colour if any of the pulse's returns is a wire, pole
// or tree (wire before pole before tree: a wire behind a nearer tree still shows), else yellow
// when the first return is a false return (class noise, SENSOR-SPEC §11), else the first return's
// range on the blue range ramp (io/images/png_image.hpp: light = near, dark navy = the full scale,
// the timeout range 1238 m by default), black when the pulse has no return.
//
// Map `map.png`, written by finish(): the fixed region given to the constructor (east right, north
// up, square pixels, the longer side map_size_px), drawn bottom to top: the terrain (dark; a grid
// shaded by height from dark green to tan, flat uniform, none or off the grid grey), ground hits
// (blue-grey), trees (dark green discs, their radius), conductors (light grey lines), poles (white
// discs, ≥ 2 px), the trajectory (magenta, 3 px wide), then tree, pole and wire hits as 3 px dots
// in their class colours; fog returns and false returns are no places, so not on the map.
// Everything outside the region is left out.
//
// Bounded memory whatever the flight's length: the scene objects are rasterised in the
// constructor and the Quicklook keeps no reference to the scene; hits and the trajectory go into a
// one-byte-per-pixel mask of the map as they arrive (every return of every frame, hit point = ray
// origin + range_m · direction), so the memory is 4 bytes per map pixel (4 MiB at 1024²) plus one
// range image. Each PNG is encoded in memory and written atomically (no partial file under its
// final name). checkpoint() and restore() carry the map's state across an interrupted run
// (`owsim run --resume`), so its map.png is the uninterrupted run's. Errors throw owsim::Error.
// Accuracy: a hit or an object lands in the map pixel containing it (±½ pixel, 0.5 m at the
// default 1024 px over ~1 km); a grid terrain shows its nearest sample; poles and trees smaller
// than a pixel are drawn at the minimum sizes above. Valid for any region of positive extent.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "geometry/scene.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/images/png_image.hpp"
#include "sensor/frame_view.hpp"
#include "sensor/scan_params.hpp"

namespace owsim {

struct QuicklookOptions {
  int every_nth_frame = 10;         // range image of frames f with f mod N = 0; 0 = none
  int map_size_px = 1024;           // the map's longer side, 16..16384
  int range_image_scale = 4;        // each pulse becomes a scale × scale block, 1..16
  double range_full_scale_m = 0.0;  // range at the dark end of the ramp; 0 = the timeout range
  AtomicOutputOptions file_options;
};

// Class colours, the same in the range image and on the map.
inline constexpr Rgb8 kQuicklookWire{255, 0, 0};
inline constexpr Rgb8 kQuicklookPole{255, 150, 0};
inline constexpr Rgb8 kQuicklookTree{60, 220, 80};
inline constexpr Rgb8 kQuicklookNoReturn{0, 0, 0};
// Range images only: a false first return.
inline constexpr Rgb8 kQuicklookNoise{255, 230, 0};
// Map-only colours.
inline constexpr Rgb8 kQuicklookGroundHit{96, 112, 150};
inline constexpr Rgb8 kQuicklookConductor{225, 225, 225};
inline constexpr Rgb8 kQuicklookPoleObject{255, 255, 255};
inline constexpr Rgb8 kQuicklookTreeObject{30, 110, 45};
inline constexpr Rgb8 kQuicklookTrajectory{255, 0, 255};
inline constexpr Rgb8 kQuicklookNoTerrain{40, 40, 40};
inline constexpr Rgb8 kQuicklookFlatTerrain{46, 58, 46};

// A map region for a flight: the east/north extent of the scene's conductors and cylinders and of
// `points_enu_m` (e.g. the trajectory), grown by margin_m on every side; margin_m around the
// origin when there is nothing. Throws owsim::Error for a negative or non-finite margin.
[[nodiscard]] Eigen::AlignedBox2d quicklook_map_region(
    const Scene& scene, std::span<const Eigen::Vector3d> points_enu_m, double margin_m = 50.0);

// "frame_000010.png"
[[nodiscard]] std::string quicklook_frame_file_name(std::int64_t frame);

// The state a Quicklook builds up from the frames: the map mask (a byte per map pixel, row-major)
// and the last trajectory point, in map pixels.
struct QuicklookCheckpoint {
  std::vector<std::uint8_t> map_mask;
  std::optional<Eigen::Vector2d> last_trajectory_px;
  friend bool operator==(const QuicklookCheckpoint&, const QuicklookCheckpoint&) = default;
};

class Quicklook {
 public:
  // Creates `directory` if missing (its parent as create_directories does, `directory` itself
  // never through a link planted at its name: io/files/output_open.hpp) and rasterises the scene's
  // terrain and objects into the map of `map_region` (east = x, north = y, local ENU metres).
  // Throws owsim::Error for an empty or non-finite region, options outside their ranges, a scan
  // with fewer than 2 fibers or no line, or a directory that cannot be created.
  Quicklook(std::filesystem::path directory, const Scene& scene, const ScanParams& scan,
            const Eigen::AlignedBox2d& map_region, QuicklookOptions options = {});

  // One frame, in frame order: writes its range image if it is an Nth frame and adds its returns
  // to the map. Throws if pulses, rays and returns differ in length, a pulse's line or fiber lies
  // outside the scan, or after finish().
  void add_frame(const FrameView& frame);
  // The sensor position at a frame start; consecutive points are joined by a line.
  void add_trajectory_point(const Eigen::Vector3d& enu_m);
  // Writes map.png. Call once; nothing may be added afterwards.
  void finish();

  [[nodiscard]] QuicklookCheckpoint checkpoint() const;
  // ORs the map mask of another Quicklook of the same scene, scan, region and options (its
  // checkpoint's map_mask) into this one's: the hits of frames another process added (a
  // distributed run). The trajectory bits are ORed too; the last trajectory point stays. Throws
  // owsim::Error if the mask's size is not this map's.
  void add_map_hits(std::span<const std::uint8_t> map_mask);
  // Continues from the state of a Quicklook built with the same scene, scan, region and options.
  // Throws owsim::Error if the mask's size is not this map's.
  void restore(QuicklookCheckpoint from);

  [[nodiscard]] int map_width_px() const { return base_.width(); }
  [[nodiscard]] int map_height_px() const { return base_.height(); }
  [[nodiscard]] double map_metres_per_px() const { return metres_per_px_; }

 private:
  [[nodiscard]] Eigen::Vector2d map_px(double e_m, double n_m) const;
  void mark(const Eigen::Vector2d& px, std::uint8_t bits);
  void mark_line(const Eigen::Vector2d& from_px, const Eigen::Vector2d& to_px, std::uint8_t bits);
  void mark_disc(const Eigen::Vector2d& centre_px, int radius_px, std::uint8_t bits);
  void draw_terrain(const Terrain& terrain);
  void draw_objects(const Scene& scene);
  void write_range_image(const FrameView& frame);
  void require_open(const char* operation) const;

  std::filesystem::path directory_;
  QuicklookOptions options_;
  int lines_per_frame_;
  double range_full_scale_m_;
  std::vector<int> row_of_fiber_;  // index fiber 0..fibers_per_line; −1 for no row
  int rows_;
  RgbImage frame_cells_;  // one cell per pulse, reused

  Eigen::AlignedBox2d region_;
  double metres_per_px_;
  RgbImage base_;                   // the terrain
  std::vector<std::uint8_t> mask_;  // per map pixel: the bits of quicklook.cpp
  std::optional<Eigen::Vector2d> last_trajectory_px_;
  bool finished_ = false;
};

}  // namespace owsim
