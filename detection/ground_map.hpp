#pragma once
// The visible ground (DETECTION-SPEC §2 Decision): the lowest surface the sensor has seen there,
// estimated from the returns alone, never from the scene's terrain. The local frame is cut into
// square cells; each cell keeps the kKept lowest returns ever seen in it and takes as its ground
// the lowest pair of them that agree within kAgreeM (the higher of the two): the receiver's false
// returns (SENSOR-SPEC §11: it triggers on noise at any range, beyond the ground too, so below it)
// are scattered in range and almost never agree, while a surface seen twice does. The ground under
// a point is the lowest of the 3×3 cells around it that have a ground (so a pole's or a tree's own
// cell does not hide the ground beside it). The cells live in a fixed toroidal table that covers a
// square of at least 2 × reach metres, so memory stays flat over hours of flight; a cell farther
// than that from where the aircraft now looks is forgotten when a new one takes its slot.
#include <array>
#include <cstdint>
#include <vector>

namespace owsim {

class GroundMap {
 public:
  static constexpr std::size_t kKept = 4;  // lowest returns a cell keeps
  static constexpr double kAgreeM = 1.0;   // two of them agreeing make its ground

  // Cells of `cell_m` metres over a table reaching at least `reach_m` each way.
  GroundMap(double cell_m, double reach_m);

  // A plan position's cell: its indices and its place in the table.
  struct Place {
    std::int64_t i, j;
    std::int64_t a, b;  // the wrapped indices
  };
  [[nodiscard]] Place place_of(double e, double n) const;

  // A return at (e, n, u): lowers its cell's ground to u.
  void add(double e, double n, double u) { add(place_of(e, n), u); }
  void add(const Place& at, double u);
  // The lowest cell ground in the 3×3 cells around (e, n); NaN when none of them has one. Kept in
  // the cell until the next add(), so the many returns of one cell look it up once.
  [[nodiscard]] double ground_u(double e, double n) const { return ground_u(place_of(e, n)); }
  [[nodiscard]] double ground_u(const Place& at) const;
  [[nodiscard]] double cell_m() const { return cell_m_; }

 private:
  struct Cell {
    std::int64_t i = INT64_MIN;
    std::int64_t j = INT64_MIN;
    std::array<double, kKept> lowest{};  // ascending, +inf where fewer returns
    double ground = 0.0;                 // the lowest agreeing pair's higher; +inf: none yet
    // ground_u of this cell as of `version`.
    mutable double around = 0.0;
    mutable std::uint64_t around_version = 0;
  };
  // A cell index's place along one side of the table: i mod side_, by a multiplication.
  [[nodiscard]] std::int64_t wrapped(std::int64_t i) const;
  // Where the cell of wrapped indices (a, b) lies in the table, row by row. (Measured no faster:
  // tiles of 4 × 4 or 8 × 8 cells; what lookups read apart from what add() reads; prefetching the
  // cells of the returns ahead.)
  [[nodiscard]] std::size_t slot(std::int64_t a, std::int64_t b) const;

  double cell_m_;
  std::int64_t side_;  // cells per side of the table
  double per_side_;    // 1 / side_
  std::vector<Cell> cells_;
  std::uint64_t version_ = 1;  // advanced by every add()
};

}  // namespace owsim
