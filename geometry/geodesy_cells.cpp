#include "geometry/geodesy_cells.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <numbers>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/exact_round.hpp"

namespace owsim {
namespace {

constexpr int kTerms = 19;   // monomials of total degree 1..3 in three variables
constexpr int kOutputs = 5;  // lat, lon, h, easting, northing
constexpr int kNodesPerAxis = 5;
constexpr double kMetresPerDegree = 111'320.0;  // the largest, at the equator: errors err high
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using Terms = Eigen::Matrix<double, 1, kTerms>;
using Coefficients = Eigen::Matrix<double, kTerms, kOutputs>;
using Values = Eigen::Matrix<double, 1, kOutputs>;

// t1, t2, t3, then the degree-2 and degree-3 products in lexicographic order.
Terms terms_of(const Eigen::Vector3d& t) {
  const double x = t.x(), y = t.y(), z = t.z();
  const double xx = x * x, yy = y * y, zz = z * z;
  Terms m;
  m << x, y, z, xx, x * y, x * z, yy, y * z, zz, xx * x, xx * y, xx * z, x * yy, x * y * z, x * zz,
      yy * y, yy * z, y * zz, zz * z;
  return m;
}

// The fitting nodes in the unit cube: Chebyshev points of the first kind on each axis.
const std::vector<Eigen::Vector3d>& fit_nodes() {
  static const std::vector<Eigen::Vector3d> nodes = [] {
    std::array<double, kNodesPerAxis> c{};
    for (int k = 0; k < kNodesPerAxis; ++k) {
      c[static_cast<std::size_t>(k)] =
          std::cos((2 * k + 1) * std::numbers::pi / (2 * kNodesPerAxis));
    }
    std::vector<Eigen::Vector3d> all;
    for (const double x : c) {
      for (const double y : c) {
        for (const double z : c) all.emplace_back(x, y, z);
      }
    }
    return all;
  }();
  return nodes;
}

// The 8 corners and 6 face centres: where a fit over the cube is least certain.
const std::vector<Eigen::Vector3d>& check_nodes() {
  static const std::vector<Eigen::Vector3d> nodes = [] {
    std::vector<Eigen::Vector3d> all;
    for (const double x : {-1.0, 1.0}) {
      for (const double y : {-1.0, 1.0}) {
        for (const double z : {-1.0, 1.0}) all.emplace_back(x, y, z);
      }
    }
    for (int axis = 0; axis < 3; ++axis) {
      for (const double side : {-1.0, 1.0}) {
        Eigen::Vector3d face = Eigen::Vector3d::Zero();
        face[axis] = side;
        all.push_back(face);
      }
    }
    return all;
  }();
  return nodes;
}

const Eigen::ColPivHouseholderQR<Eigen::MatrixXd>& fit_solver() {
  static const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> solver = [] {
    const std::vector<Eigen::Vector3d>& nodes = fit_nodes();
    Eigen::MatrixXd design(static_cast<Eigen::Index>(nodes.size()), kTerms);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      design.row(static_cast<Eigen::Index>(i)) = terms_of(nodes[i]);
    }
    return Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(design);
  }();
  return solver;
}

}  // namespace

struct GeodesyCells::Cell {
  std::array<std::int64_t, 3> index{};
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  bool exact = true;      // the fit failed its check: the exact path
  bool has_grid = false;  // the grid's easting/northing are fitted too
  Values at_centre = Values::Zero();
  Coefficients coefficients = Coefficients::Zero();
  double error_m = 0.0;
};

GeodesyCells::GeodesyCells(const LocalFrame& frame, std::optional<UtmGrid> grid)
    : frame_(frame), grid_(grid) {}

PlacedPoint GeodesyCells::place_exactly(const Eigen::Vector3d& enu_m) const {
  PlacedPoint placed{frame_.geodetic_from_enu(enu_m), Eigen::Vector2d::Constant(kNaN)};
  if (grid_ && enu_m.allFinite()) {
    try {
      placed.grid_m = grid_from_geodetic(*grid_, placed.geodetic.lat_deg, placed.geodetic.lon_deg);
    } catch (const std::exception&) {
      // Outside the grid's range: left NaN, the LAS writer names the point.
    }
  }
  return placed;
}

std::shared_ptr<const GeodesyCells::Cell> GeodesyCells::build(
    const std::array<std::int64_t, 3>& index) const {
  auto cell = std::make_shared<Cell>();
  cell->index = index;
  const double half = kGeodesyCellM / 2;
  for (int a = 0; a < 3; ++a) {
    cell->centre[a] =
        (static_cast<double>(index[static_cast<std::size_t>(a)]) + 0.5) * kGeodesyCellM;
  }
  // Exact values at the centre, the fitting nodes and the check nodes; any throw: exact path.
  bool grid_ok = grid_.has_value();
  const auto exact = [&](const Eigen::Vector3d& t) {
    const Geodetic g = frame_.geodetic_from_enu(cell->centre + half * t);
    Values v;
    v << g.lat_deg, g.lon_deg, g.h_m, kNaN, kNaN;
    if (grid_ok) {
      try {
        const Eigen::Vector2d en = grid_from_geodetic(*grid_, g.lat_deg, g.lon_deg);
        v(3) = en.x();
        v(4) = en.y();
      } catch (const std::exception&) {
        grid_ok = false;
      }
    }
    return v;
  };
  cell->at_centre = exact(Eigen::Vector3d::Zero());
  const std::vector<Eigen::Vector3d>& nodes = fit_nodes();
  Eigen::MatrixXd differences(static_cast<Eigen::Index>(nodes.size()), kOutputs);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    differences.row(static_cast<Eigen::Index>(i)) = exact(nodes[i]) - cell->at_centre;
  }
  std::vector<Values> checks;
  for (const Eigen::Vector3d& t : check_nodes()) checks.push_back(exact(t));
  cell->has_grid = grid_ok;
  if (!grid_ok) {  // easting/northing not fitted: zero terms, compared as equal below
    differences.rightCols(2).setZero();
    cell->at_centre.tail<2>().setZero();
  }
  if (!differences.allFinite()) return cell;  // exact path
  // Solved apart too, the same arithmetic for lat/lon/h with or without a grid.
  cell->coefficients.leftCols<3>() = fit_solver().solve(differences.leftCols(3));
  cell->coefficients.rightCols<2>() = fit_solver().solve(differences.rightCols(2));
  // Checked apart: lat/lon/h decide the exact path, easting/northing only whether the grid is
  // fitted, so a point's lat/lon/h never depend on whether a grid is asked for.
  double worst_geodetic = 0.0, worst_grid = 0.0;
  const auto compare = [&](const Eigen::Vector3d& t, const Values& truth) {
    const Values fit = cell->at_centre + terms_of(t) * cell->coefficients;
    const Values d = (fit - truth).cwiseAbs();
    const double geodetic = d.head<3>().allFinite()
                                ? std::max({d(0) * kMetresPerDegree, d(1) * kMetresPerDegree, d(2)})
                                : std::numeric_limits<double>::infinity();
    const double grid =
        d.tail<2>().allFinite() ? d.tail<2>().maxCoeff() : std::numeric_limits<double>::infinity();
    worst_geodetic = std::max(worst_geodetic, geodetic);
    worst_grid = std::max(worst_grid, grid);
  };
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    compare(nodes[i], cell->at_centre + differences.row(static_cast<Eigen::Index>(i)));
  }
  for (std::size_t i = 0; i < checks.size(); ++i) {
    Values truth = checks[i];
    if (!grid_ok) truth.tail<2>().setZero();
    compare(check_nodes()[i], truth);
  }
  if (!(worst_geodetic <= kGeodesyCellToleranceM)) return cell;  // exact path
  if (!(worst_grid <= kGeodesyCellToleranceM)) cell->has_grid = false;
  cell->error_m = cell->has_grid ? std::max(worst_geodetic, worst_grid) : worst_geodetic;
  cell->exact = false;
  return cell;
}

std::shared_ptr<const GeodesyCells::Cell> GeodesyCells::cell_at(
    const std::array<std::int64_t, 3>& index) const {
  {
    const std::lock_guard lock(mutex_);
    const auto found = cells_.find(index);
    if (found != cells_.end()) return found->second;
  }
  std::shared_ptr<const Cell> cell = build(index);  // outside the lock: ~60 µs
  const std::lock_guard lock(mutex_);
  if (cells_.size() >= kGeodesyCellsKept) cells_.clear();
  return cells_.emplace(index, std::move(cell)).first->second;  // another thread's if it won
}

PlacedPoint GeodesyCells::place(const Eigen::Vector3d& enu_m, Cursor& cursor) const {
  constexpr double kReach = 1e12;  // cube indices stay far inside int64
  if (!enu_m.allFinite() || enu_m.cwiseAbs().maxCoeff() > kReach) return place_exactly(enu_m);
  const std::array<std::int64_t, 3> index = {
      static_cast<std::int64_t>(round_down(enu_m.x() / kGeodesyCellM)),
      static_cast<std::int64_t>(round_down(enu_m.y() / kGeodesyCellM)),
      static_cast<std::int64_t>(round_down(enu_m.z() / kGeodesyCellM))};
  const Cell* found = nullptr;
  for (const std::shared_ptr<const Cell>& kept : cursor.cells) {
    if (kept && kept->index[0] == index[0] && kept->index[1] == index[1] &&
        kept->index[2] == index[2]) {
      found = kept.get();
      break;
    }
  }
  if (found == nullptr) {
    std::shared_ptr<const Cell>& slot = cursor.cells[cursor.next];
    cursor.next = (cursor.next + 1) % Cursor::kCells;
    slot = cell_at(index);
    found = slot.get();
  }
  const Cell& cell = *found;
  if (cell.exact) return place_exactly(enu_m);
  const Values v =
      cell.at_centre + terms_of((enu_m - cell.centre) / (kGeodesyCellM / 2)) * cell.coefficients;
  PlacedPoint placed{{v(0), v(1), v(2)}, {v(3), v(4)}};
  if (grid_ && !cell.has_grid) {
    placed.grid_m = place_exactly(enu_m).grid_m;
  } else if (!grid_) {
    placed.grid_m = Eigen::Vector2d::Constant(kNaN);
  }
  return placed;
}

double GeodesyCells::cell_error_m(const Eigen::Vector3d& enu_m) const {
  Cursor cursor;
  if (!enu_m.allFinite()) return 0.0;
  (void)place(enu_m, cursor);
  return cursor.cells[0] ? cursor.cells[0]->error_m : 0.0;
}

}  // namespace owsim
