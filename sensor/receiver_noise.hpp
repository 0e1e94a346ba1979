#pragma once
// The receiver's statistics (SENSOR-SPEC §11): Gaussian noise in §7's normalised energy unit,
// growing as R² under the range-compensated gain and raised by scattered sunlight; whether an echo
// near the threshold registers; and the false triggers noise alone makes, an inhomogeneous Poisson
// process in range. Pure functions of their arguments and of keyed draws (DESIGN.md
// "Determinism"); nothing here knows of Embree, files or threads.
//
// The false triggers' cumulative intensity has a closed form. With σ_n(r) = s·r² (s = σ_1km·√(1+b)
// / 10⁶ m²) the intensity is λ(r) = P · exp(−K / r⁴), P = (2/c) / (2√3 τ_p), K = T² / (2 s²), so
//   Λ(R) = ∫₀ᴿ λ dr = P · (R · e^(−x) − K^¼ · Γ(¾, x)),  x = K / R⁴
// (substitute u = K/r⁴, then Γ(−¼, x) = 4 (x^(−¼) e^(−x) − Γ(¾, x))), with Boost.Math's upper
// incomplete gamma. Λ is inverted by a bracketed Newton iteration on its exact derivative λ, so a
// trigger's range is exact to double rounding: no range cells, no table to interpolate.
#include <Eigen/Core>
#include <cstdint>
#include <span>

namespace owsim {

// Keys sensor.receiver.* and the scenario's `sun` (INTERFACE.md "Receiver noise and sunlight").
// Defaults calibrated in docs/model.md "Receiver statistics".
struct ReceiverNoiseParams {
  bool on = true;  // sensor.receiver.noise: on | off (off: §7's deterministic receiver)
  // σ_1km, the dark receiver's noise at 1,000 m in energy_rel units: the default threshold / 7.5,
  // 5.9e-5 false returns per pulse at night (SENSOR-SPEC §11 target ≤ 1e-4)
  double noise_at_1km = 0.000387;
  double pulse_width_ns = 5.0;  // τ_p of Rice's rate
  double sun_noise = 1.3;       // k_sun: sunlit ground (A 0.2, sun at the zenith) 8.6e-4 (≤ 1e-3)
  double sky_noise = 0.09;      // k_sky: clear sky at noon 1.7e-4 per pulse (≤ 2e-4)
};

// The sun as the scenario gives it (`sun`; a UTC time is turned into these at the origin when the
// scenario is read). Absent: night.
struct SunPosition {
  bool given = false;
  double elevation_deg = 0.0;  // above the horizon, −90..90
  double azimuth_deg = 0.0;    // clockwise from north, 0..360
};

// Unit vector toward the sun in local ENU  (SENSOR-SPEC §11 sunlight)
[[nodiscard]] Eigen::Vector3d sun_direction_enu(const SunPosition& sun);

// σ_n(R) = σ_1km · (R / 1000 m)² · √(1 + b)  (SENSOR-SPEC §11 units)
[[nodiscard]] double noise_sigma(double range_m, double background, double noise_at_1km);
// Φ(x), the standard normal distribution function
[[nodiscard]] double standard_normal_cdf(double x);
// Whether u ≤ standard_normal_cdf(x): the same answer, from a table of Φ where u lies clear of
// it (no erfc), from standard_normal_cdf itself where u lies within the table's error bound of it
// or |x| > kSureEchoSigmas: an echo's registration, u ≤ Pd  (SENSOR-SPEC §11 echo detection)
[[nodiscard]] bool uniform_within_standard_normal_cdf(double u, double x);
// Pd = Φ((e − T) / σ_n)  (SENSOR-SPEC §11 echo detection); a step at T when σ_n = 0
[[nodiscard]] double echo_detection_probability(double energy_rel, double threshold, double sigma);
// ν = exp(−T² / 2σ_n²) / (2√3 τ_p), upward crossings per second  (SENSOR-SPEC §11, Rice)
[[nodiscard]] double threshold_crossing_rate_hz(double threshold, double sigma,
                                                double pulse_width_s);
// b = k_sun · A · max(0, cos θ_s), θ_s between the surface normal (either orientation: the side
// the ray meets is used) and the sun  (SENSOR-SPEC §11 sunlight)
[[nodiscard]] double sunlit_background(const Eigen::Vector3d& normal,
                                       const Eigen::Vector3d& ray_dir, double reflectivity,
                                       const Eigen::Vector3d& to_sun, double sun_noise);
// b = k_sky · max(0, sin ε_sun)  (SENSOR-SPEC §11 sunlight)
[[nodiscard]] double sky_background(const SunPosition& sun, double sky_noise);

// |e − T| / σ_n beyond which Φ is 0 or 1 to below a 53-bit uniform's resolution (Φ(−8.5) ≈ 1e-17):
// an echo that far from the threshold registers, or not, without a draw.
inline constexpr double kSureEchoSigmas = 8.5;

// A fog volume's busy interval [begin_m, end_m): no echo and no false trigger registers in it
// (SENSOR-SPEC §10, §11 returns).
struct BusyInterval {
  double begin_m;
  double end_m;
};

// One receiver's false-trigger process and echo statistics, set up once (it validates nothing:
// validate(ReceiverParams) has). Thread-safe, allocation-free.
class ReceiverNoise {
 public:
  // No statistics: off (§7's deterministic receiver).
  ReceiverNoise() = default;
  // threshold T; gate_m the counter's timeout range; speed_of_light_mps c (in air: c / n)
  ReceiverNoise(const ReceiverNoiseParams& params, const SunPosition& sun, double threshold,
                double gate_m, double speed_of_light_mps);

  [[nodiscard]] bool on() const { return on_; }
  [[nodiscard]] double threshold() const { return threshold_; }
  [[nodiscard]] double gate_m() const { return gate_m_; }
  // Whether sunlight reaches the receiver (the sun given and above the horizon).
  [[nodiscard]] bool sunlit() const { return sunlit_; }
  // The background of a pulse whose central ray meets nothing within the gate.
  [[nodiscard]] double sky_background() const { return sky_b_; }
  // The background of a pulse whose central ray meets a solid of `reflectivity` with `normal`.
  [[nodiscard]] double solid_background(const Eigen::Vector3d& normal,
                                        const Eigen::Vector3d& ray_dir, double reflectivity) const;
  // The largest background a pulse can have (k_sun·1 or the sky's, whichever is larger).
  [[nodiscard]] double max_background() const { return max_b_; }

  // σ_n(R) for a pulse of background b  (SENSOR-SPEC §11)
  [[nodiscard]] double sigma(double range_m, double background) const;
  // λ(R), false triggers per metre of range  (SENSOR-SPEC §11: (2/c) · ν)
  [[nodiscard]] double intensity_per_m(double range_m, double background) const;
  // Λ(R) = ∫₀ᴿ λ dr, the expected false triggers up to R  (SENSOR-SPEC §11, closed form above)
  [[nodiscard]] double cumulative(double range_m, double background) const;
  // Λ over the whole gate: the expected false triggers of one pulse.
  [[nodiscard]] double gate_cumulative(double background) const;
  // The R in [0, gate] with Λ(R) = target (target ≤ gate_cumulative(b)).
  [[nodiscard]] double range_of_cumulative(double target, double background) const;

  // Whether an echo of energy e at range R registers on this pulse: u ≤ Φ((e − T)/σ_n(R)) with u
  // uniform on (0, 1] keyed (seed, frame, pulse | object << 32, echo_detection) — the event
  // e + σ_n z ≥ T for z = Φ⁻¹(u). Far from the threshold (|e − T| > 8.5 σ_n, where Φ is 0 or 1 to
  // below a 53-bit uniform's resolution) no draw is made; the answer is the same.
  [[nodiscard]] bool echo_registers(double energy_rel, double range_m, double background,
                                    std::uint64_t seed, std::int64_t frame, int pulse,
                                    std::uint32_t object) const;

  // The nearest false trigger at or beyond `from_m` outside every busy interval (sorted, disjoint),
  // or a negative number when none falls in the gate. `draw` numbers the pulse's exponential draws
  // (keyed pulse | draw << 32, false_trigger); it is advanced by each one made. The process on
  // [from, gate) is independent of what lies before `from`, so successive calls with growing
  // `from` draw exactly from one Poisson process.
  [[nodiscard]] double next_false_trigger_m(double from_m, double background,
                                            std::span<const BusyInterval> busy, std::uint64_t seed,
                                            std::int64_t frame, int pulse,
                                            std::uint32_t& draw) const;
  // The pulses that share the draw of their first exponentials' minimum: 128j..128j+127.
  static constexpr int kTriggerGroup = 128;
  // Whether group j (pulses kTriggerGroup·j ..) draws no false trigger for any pulse of
  // background at most max_background(): next_false_trigger_m from 0 then returns a negative
  // number at its first test, with no draw of the pulse's own.
  [[nodiscard]] bool group_is_quiet(std::uint64_t seed, std::int64_t frame,
                                    std::int64_t group) const;
  // The same for the pulse's group and a background of its own: group_is_quiet and b at most
  // max_background(). One cached block per group.
  [[nodiscard]] bool group_has_no_trigger(double background, std::uint64_t seed, std::int64_t frame,
                                          int pulse) const;

 private:
  bool on_ = false;
  bool sunlit_ = false;
  double threshold_ = 0.0;
  double gate_m_ = 0.0;
  double noise_at_1km_ = 0.0;
  double sun_noise_ = 0.0;
  double prefactor_per_m_ = 0.0;  // P = (2/c) / (2√3 τ_p)
  double sky_b_ = 0.0;
  double max_b_ = 0.0;
  Eigen::Vector3d to_sun_ = Eigen::Vector3d::UnitZ();
  double night_gate_ = 0.0;  // Λ(gate) at b = 0
  double sky_gate_ = 0.0;    // Λ(gate) at the sky's b
  double max_gate_ = 0.0;    // Λ(gate) at max_background(): every pulse's bound
};

}  // namespace owsim
