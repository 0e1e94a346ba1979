#include "geometry/forest.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "geometry/error.hpp"
#include "geometry/keyed_random.hpp"
#include "geometry/number_text.hpp"

namespace owsim {
namespace {

std::string key(std::string_view where, std::string_view name) {
  if (where.empty()) return std::string(name);
  return std::string(where) + "." + std::string(name);
}

void check_range(std::string_view where, std::string_view name, double lo, double hi,
                 bool positive) {
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo <= hi)) {
    throw input_error(key(where, name), "must be a finite range [min, max] with min ≤ max, got [" +
                                            number_text(lo) + ", " + number_text(hi) + "]");
  }
  if (positive && !(lo > 0.0)) {
    throw input_error(key(where, name), "must be > 0, got a minimum of " + number_text(lo));
  }
}

// A 32-bit word as a uniform fraction in [0, 1).
double unit_fraction(std::uint32_t word) { return static_cast<double>(word) * 0x1.0p-32; }

double lerp(double lo, double hi, double fraction) { return lo + fraction * (hi - lo); }

}  // namespace

std::vector<Cylinder> generate_forest(const ForestSpec& spec, std::uint64_t seed,
                                      const Terrain& terrain, std::string_view where) {
  if (spec.count < 0) {
    throw input_error(key(where, "count"), "must be ≥ 0, got " + std::to_string(spec.count));
  }
  check_range(where, "area.e", spec.e_range[0], spec.e_range[1], false);
  check_range(where, "area.n", spec.n_range[0], spec.n_range[1], false);
  check_range(where, "height_m", spec.height_min_m, spec.height_max_m, true);
  check_range(where, "diameter_m", spec.diameter_min_m, spec.diameter_max_m, true);
  if (!(std::isfinite(spec.reflectivity) && spec.reflectivity >= 0.0 && spec.reflectivity <= 1.0)) {
    throw input_error(key(where, "reflectivity"),
                      "must be between 0 and 1, got " + number_text(spec.reflectivity));
  }

  std::vector<Cylinder> trees;
  trees.reserve(static_cast<std::size_t>(spec.count));
  for (int i = 0; i < spec.count; ++i) {
    const PhiloxBlock block = random_block({seed, 0, i, RandomPurpose::forest_layout});
    const double e = lerp(spec.e_range[0], spec.e_range[1], unit_fraction(block[0]));
    const double n = lerp(spec.n_range[0], spec.n_range[1], unit_fraction(block[1]));
    double ground = 0.0;
    try {
      ground = terrain.height_at(e, n);
    } catch (const Error& error) {
      throw input_error(key(where, "area"), "tree " + std::to_string(i) + ": " + error.what());
    }
    trees.push_back(Cylinder{
        "forest/" + std::to_string(i), SurfaceClass::tree, Eigen::Vector3d(e, n, ground),
        0.5 * lerp(spec.diameter_min_m, spec.diameter_max_m, unit_fraction(block[3])),
        lerp(spec.height_min_m, spec.height_max_m, unit_fraction(block[2])), spec.reflectivity});
  }
  return trees;
}

}  // namespace owsim
