#pragma once
// Fast exact-enough geodesy for many points near each other: where every return of a flight is
// placed on WGS-84 (lat, lon, h) and in a UTM/UPS grid (points.csv, points.las), at a small
// fraction of GeographicLib's cost per point (Geocentric reverse + transverse Mercator forward,
// ~0.4 µs) — SENSOR-SPEC is silent on it; the bound is docs/model.md's "Geodesy of the points".
//
// Space is cut into cubes of kGeodesyCellM on a side, fixed in the local ENU frame (cube
// (i, j, k) spans [i·S, (i+1)·S) × …), so a point's expansion depends on where it is, never on
// which other points come with it: a run, a decode, the embedding API and every process of a
// distributed run place a point identically. In each cube the five functions of ENU — lat, lon,
// h and the grid's easting, northing — are their exact values at the cube's centre (GeographicLib)
// plus a polynomial of total degree 3 in the offset from the centre (19 terms, no constant term:
// exact at the centre), fitted by least squares to GeographicLib's values at 5³ Chebyshev nodes of
// the cube. A cube is accepted when the fit agrees with GeographicLib within kGeodesyCellToleranceM
// at its nodes and at its 8 corners and 6 face centres; otherwise (or where GeographicLib throws
// at a node: a grid's edge, the poles) its points take the exact path, so no point is ever
// placed worse than the tolerance. Truncation error of degree 3 over a cube of half-width a is
// ~a⁴/R³: ~2·10⁻¹⁰ m at a = 500 m, below double rounding of the degrees themselves (~1 nm).
//
// Cubes are built on first use (125 + 15 exact evaluations, ~60 µs) and kept in a table shared by
// all threads (a mutex guards only the table); each caller keeps the cube it used last in its
// own Cursor, so a stream of nearby points takes no lock. The table is bounded: when it holds
// kGeodesyCellsKept cubes it is emptied (cubes in use live on through the cursors).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include "geometry/geodetic_frame.hpp"
#include "geometry/utm.hpp"

namespace owsim {

inline constexpr double kGeodesyCellM = 1000.0;
inline constexpr double kGeodesyCellToleranceM = 1e-8;  // 10 nm
inline constexpr std::size_t kGeodesyCellsKept = 4096;

// A point placed: on WGS-84 and, if the cells have a grid, in it (else NaN).
struct PlacedPoint {
  Geodetic geodetic;
  Eigen::Vector2d grid_m;
};

class GeodesyCells {
 public:
  struct Cell;
  // What a caller keeps between points: the cubes it used last (a frame's returns fall in a
  // few cubes and alternate between them line by line).
  struct Cursor {
    static constexpr std::size_t kCells = 8;
    std::array<std::shared_ptr<const Cell>, kCells> cells;
    std::size_t next = 0;  // the entry replaced on the next miss
  };

  // Points in `frame`; with a grid, also its easting/northing (utm.hpp grid_from_geodetic).
  explicit GeodesyCells(const LocalFrame& frame, std::optional<UtmGrid> grid = std::nullopt);

  // lat, lon, h of enu_m as LocalFrame::geodetic_from_enu within the tolerance; the grid position
  // as grid_from_geodetic within it, or NaN where that throws. Thread-safe.
  [[nodiscard]] PlacedPoint place(const Eigen::Vector3d& enu_m, Cursor& cursor) const;
  // The exact path (GeographicLib), for the tests and the cubes that failed their check.
  [[nodiscard]] PlacedPoint place_exactly(const Eigen::Vector3d& enu_m) const;

  [[nodiscard]] const LocalFrame& frame() const { return frame_; }
  [[nodiscard]] const std::optional<UtmGrid>& grid() const { return grid_; }
  // How far the cube holding enu_m may be off GeographicLib, in metres: its largest check error
  // (lat/lon converted at 1° = 111.32 km), or 0 for a cube on the exact path.
  [[nodiscard]] double cell_error_m(const Eigen::Vector3d& enu_m) const;

 private:
  [[nodiscard]] std::shared_ptr<const Cell> cell_at(const std::array<std::int64_t, 3>& index) const;
  [[nodiscard]] std::shared_ptr<const Cell> build(const std::array<std::int64_t, 3>& index) const;

  LocalFrame frame_;
  std::optional<UtmGrid> grid_;
  mutable std::mutex mutex_;
  mutable std::map<std::array<std::int64_t, 3>, std::shared_ptr<const Cell>> cells_;
};

}  // namespace owsim
