#include "sensor/receiver_noise.hpp"

#include <algorithm>
#include <array>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "geometry/keyed_random.hpp"

namespace owsim {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// The key's `pulse` field: the pulse in the low 32 bits, `extra` (an object, a draw number) in the
// 24 bits above (geometry/keyed_random.hpp keeps 56 bits of it).
std::int64_t pulse_with(int pulse, std::uint32_t extra) {
  return static_cast<std::int64_t>(static_cast<std::uint32_t>(pulse)) |
         (static_cast<std::int64_t>(extra & 0xFFFFFFu) << 32);
}

// The first exponential draws E_k of a pulse group (pulses 128j..128j+127 of a frame, iid
// Exp(1)) are drawn through their minimum: M = −ln(u)/128 and the index J of the minimum come from
// the group's block (seed, frame, j, false_trigger_group); E_J = M and every other E_k = M + Exp(1)
// from the pulse's own key — the same joint law (the minimum of n exponentials is Exp(n), its
// index uniform, the others' excess over it memoryless). A group whose M exceeds every pulse's
// Λ(gate) has no trigger at all, decided by one block for 128 pulses. Each thread keeps the last
// group's draw: a frame's pulses come in order.
constexpr int kTriggerGroup = ReceiverNoise::kTriggerGroup;

struct GroupMinimum {
  double minimum;
  int argmin;
};

// The group's draw itself. Not inlined: GCC otherwise computes the Philox block on every call and
// selects it after the cache test (corridor, one thread: 8.6 % of all samples).
[[gnu::noinline]] GroupMinimum group_minimum(std::uint64_t seed, std::int64_t frame,
                                             std::int64_t group) {
  const PhiloxBlock block = random_block({seed, frame, group, RandomPurpose::false_trigger_group});
  const double u =
      static_cast<double>((static_cast<std::uint64_t>(block[0]) << 21) ^ (block[1] >> 11)) *
      0x1p-53;  // 53 bits, [0, 1)
  return GroupMinimum{-std::log1p(-u) / kTriggerGroup, static_cast<int>(block[2] % kTriggerGroup)};
}

GroupMinimum first_exponentials_minimum(std::uint64_t seed, std::int64_t frame, int pulse) {
  struct Cached {
    std::uint64_t seed;
    std::int64_t frame;
    std::int64_t group;
    GroupMinimum draw;
  };
  thread_local Cached cached{0, -1, -1, {0.0, 0}};
  const std::int64_t group = pulse / kTriggerGroup;
  if (cached.group != group || cached.frame != frame || cached.seed != seed) {
    cached = {seed, frame, group, group_minimum(seed, frame, group)};
  }
  return cached.draw;
}

}  // namespace

Eigen::Vector3d sun_direction_enu(const SunPosition& sun) {
  const double elevation = sun.elevation_deg * kDegree;
  const double azimuth = sun.azimuth_deg * kDegree;  // clockwise from north
  return {std::cos(elevation) * std::sin(azimuth), std::cos(elevation) * std::cos(azimuth),
          std::sin(elevation)};
}

double noise_sigma(double range_m, double background, double noise_at_1km) {
  const double r = range_m / 1000.0;
  return noise_at_1km * r * r * std::sqrt(1.0 + background);
}

double standard_normal_cdf(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

namespace {

// Φ at kCdfNodes + 1 evenly spaced nodes over [−kSureEchoSigmas, kSureEchoSigmas], each node's
// value standard_normal_cdf's own. Between nodes the chord differs from Φ by at most
// h²/8 · max|Φ''| = h²/8 · φ(1) = 2.1e-6 for h = 17/2048, plus the nodes' and the chord's
// rounding (below 1e-15); kCdfBand is twice that.
constexpr int kCdfNodes = 2048;
constexpr double kCdfStep = 2.0 * kSureEchoSigmas / kCdfNodes;
constexpr double kCdfBand = 4.2e-6;

const std::array<double, kCdfNodes + 1>& cdf_nodes() {
  static const std::array<double, kCdfNodes + 1> nodes = [] {
    std::array<double, kCdfNodes + 1> values{};
    for (int i = 0; i <= kCdfNodes; ++i) {
      values[static_cast<std::size_t>(i)] = standard_normal_cdf(-kSureEchoSigmas + i * kCdfStep);
    }
    return values;
  }();
  return nodes;
}

}  // namespace

bool uniform_within_standard_normal_cdf(double u, double x) {
  if (!(std::abs(x) < kSureEchoSigmas)) return u <= standard_normal_cdf(x);
  const double at = (x + kSureEchoSigmas) / kCdfStep;
  const int node = std::min(kCdfNodes - 1, static_cast<int>(at));
  const std::array<double, kCdfNodes + 1>& nodes = cdf_nodes();
  const double low = nodes[static_cast<std::size_t>(node)];
  const double chord = low + (at - node) * (nodes[static_cast<std::size_t>(node) + 1] - low);
  if (u <= chord - kCdfBand) return true;
  if (u > chord + kCdfBand) return false;
  return u <= standard_normal_cdf(x);
}

double echo_detection_probability(double energy_rel, double threshold, double sigma) {
  if (!(sigma > 0.0)) return energy_rel >= threshold ? 1.0 : 0.0;
  return standard_normal_cdf((energy_rel - threshold) / sigma);
}

double threshold_crossing_rate_hz(double threshold, double sigma, double pulse_width_s) {
  const double ratio = threshold / sigma;
  return std::exp(-0.5 * ratio * ratio) / (2.0 * std::sqrt(3.0) * pulse_width_s);
}

double sunlit_background(const Eigen::Vector3d& normal, const Eigen::Vector3d& ray_dir,
                         double reflectivity, const Eigen::Vector3d& to_sun, double sun_noise) {
  // The side of the surface the ray meets faces against the ray.
  const double facing = normal.dot(ray_dir) > 0.0 ? -1.0 : 1.0;
  const double cos_sun = facing * normal.dot(to_sun) / normal.norm();
  return sun_noise * reflectivity * std::max(0.0, cos_sun);
}

double sky_background(const SunPosition& sun, double sky_noise) {
  if (!sun.given) return 0.0;
  return sky_noise * std::max(0.0, std::sin(sun.elevation_deg * kDegree));
}

ReceiverNoise::ReceiverNoise(const ReceiverNoiseParams& params, const SunPosition& sun,
                             double threshold, double gate_m, double speed_of_light_mps)
    : on_(params.on),
      sunlit_(params.on && sun.given && sun.elevation_deg > 0.0),
      threshold_(threshold),
      gate_m_(gate_m),
      noise_at_1km_(params.noise_at_1km),
      sun_noise_(params.sun_noise),
      prefactor_per_m_((2.0 / speed_of_light_mps) /
                       (2.0 * std::sqrt(3.0) * params.pulse_width_ns * 1e-9)),
      to_sun_(sun_direction_enu(sun)) {
  if (!on_) return;
  sky_b_ = sunlit_ ? owsim::sky_background(sun, params.sky_noise) : 0.0;
  max_b_ = sunlit_ ? std::max(sun_noise_, sky_b_) : 0.0;
  night_gate_ = cumulative(gate_m_, 0.0);
  sky_gate_ = cumulative(gate_m_, sky_b_);
  max_gate_ = cumulative(gate_m_, max_b_);
}

double ReceiverNoise::solid_background(const Eigen::Vector3d& normal,
                                       const Eigen::Vector3d& ray_dir, double reflectivity) const {
  if (!sunlit_) return 0.0;
  return sunlit_background(normal, ray_dir, reflectivity, to_sun_, sun_noise_);
}

double ReceiverNoise::sigma(double range_m, double background) const {
  return noise_sigma(range_m, background, noise_at_1km_);
}

double ReceiverNoise::intensity_per_m(double range_m, double background) const {
  // (2/c) · ν: ν per second of round trip, dR = c dt / 2.
  const double s = sigma(range_m, background);
  if (!(s > 0.0)) return threshold_ > 0.0 ? 0.0 : prefactor_per_m_;
  const double ratio = threshold_ / s;
  return prefactor_per_m_ * std::exp(-0.5 * ratio * ratio);
}

double ReceiverNoise::cumulative(double range_m, double background) const {
  if (!(range_m > 0.0)) return 0.0;
  if (threshold_ <= 0.0) return prefactor_per_m_ * range_m;
  // σ_n(r) = s·r², K = T² / (2 s²), x = K / R⁴ = (T / σ_n(R))² / 2.
  const double s = noise_at_1km_ * 1e-6 * std::sqrt(1.0 + background);
  if (!(s > 0.0)) return 0.0;
  const double ratio = threshold_ / sigma(range_m, background);
  const double x = 0.5 * ratio * ratio;
  if (x > 700.0) return 0.0;  // e^(−x) below every double's resolution of Λ's scale
  const double k_quarter = std::sqrt(threshold_ / s) / std::pow(2.0, 0.25);
  const double value = range_m * std::exp(-x) - k_quarter * boost::math::tgamma(0.75, x);
  return prefactor_per_m_ * std::max(0.0, value);
}

double ReceiverNoise::gate_cumulative(double background) const {
  if (background == 0.0) return night_gate_;
  if (background == sky_b_) return sky_gate_;
  return cumulative(gate_m_, background);
}

double ReceiverNoise::range_of_cumulative(double target, double background) const {
  if (!(target > 0.0)) return 0.0;
  if (threshold_ <= 0.0) return std::min(gate_m_, target / prefactor_per_m_);
  // Newton on ln Λ(R) − ln target (concave in R: steps from either side converge), kept inside
  // the bracket [low, high] that always holds the root; bisection when a step leaves it.
  double low = 0.0;
  double high = gate_m_;
  double r = gate_m_;
  const double log_target = std::log(target);
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double value = cumulative(r, background);
    if (value <= 0.0) {
      low = r;
      r = 0.5 * (low + high);
      continue;
    }
    const double g = std::log(value) - log_target;
    if (g > 0.0) {
      high = r;
    } else {
      low = r;
    }
    const double step = g * value / intensity_per_m(r, background);
    double next = r - step;
    if (!(next > low && next < high)) next = 0.5 * (low + high);
    if (std::abs(next - r) <= 1e-13 * r || high - low <= 1e-13 * high) return next;
    r = next;
  }
  return r;
}

bool ReceiverNoise::echo_registers(double energy_rel, double range_m, double background,
                                   std::uint64_t seed, std::int64_t frame, int pulse,
                                   std::uint32_t object) const {
  if (!(std::isfinite(energy_rel) && std::isfinite(range_m))) return false;
  const double s = sigma(range_m, background);
  const double margin = energy_rel - threshold_;
  if (!(s > 0.0)) return margin >= 0.0;
  if (margin > kSureEchoSigmas * s) return true;
  if (margin < -kSureEchoSigmas * s) return false;
  // u on (0, 1]: 1 − a [0, 1) uniform.
  const double u =
      1.0 - uniform01({seed, frame, pulse_with(pulse, object), RandomPurpose::echo_detection});
  return uniform_within_standard_normal_cdf(u, margin / s);
}

bool ReceiverNoise::group_is_quiet(std::uint64_t seed, std::int64_t frame,
                                   std::int64_t group) const {
  return first_exponentials_minimum(seed, frame, static_cast<int>(group * kTriggerGroup)).minimum >
         max_gate_;
}

bool ReceiverNoise::group_has_no_trigger(double background, std::uint64_t seed, std::int64_t frame,
                                         int pulse) const {
  return group_is_quiet(seed, frame, pulse / kTriggerGroup) && background <= max_b_;
}

double ReceiverNoise::next_false_trigger_m(double from_m, double background,
                                           std::span<const BusyInterval> busy, std::uint64_t seed,
                                           std::int64_t frame, int pulse,
                                           std::uint32_t& draw) const {
  double from = from_m;
  while (from < gate_m_) {
    // E exponential: the pulse's first through its group's minimum (above), later ones
    // −ln(1 − u) from the pulse's key with u uniform on [0, 1).
    double exponential = 0.0;
    if (draw == 0) {
      const GroupMinimum group = first_exponentials_minimum(seed, frame, pulse);
      // Every pulse's bound first: most groups stop here without a Λ or a draw of their own.
      if (group.minimum > max_gate_ && background <= max_b_) return -1.0;
      exponential = group.minimum;
      if (pulse % kTriggerGroup != group.argmin) {
        exponential -= std::log1p(
            -uniform01({seed, frame, pulse_with(pulse, draw), RandomPurpose::false_trigger}));
      }
      ++draw;
    } else {
      exponential = -std::log1p(
          -uniform01({seed, frame, pulse_with(pulse, draw++), RandomPurpose::false_trigger}));
    }
    if (exponential > max_gate_ && background <= max_b_) return -1.0;
    const double start = from > 0.0 ? cumulative(from, background) : 0.0;
    const double target = start + exponential;
    if (target > gate_cumulative(background)) return -1.0;
    const double range = std::max(from, range_of_cumulative(target, background));
    const auto hiding = std::find_if(busy.begin(), busy.end(), [&](const BusyInterval& b) {
      return range >= b.begin_m && range < b.end_m;
    });
    if (hiding == busy.end()) return range;
    from = hiding->end_m;  // swallowed: the process beyond the interval is independent of it
  }
  return -1.0;
}

}  // namespace owsim
