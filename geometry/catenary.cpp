#include "geometry/catenary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "geometry/error.hpp"
#include "geometry/number_text.hpp"

namespace owsim {
namespace {

constexpr double kResidualTolerance = 1e-12;  // |f(a)| ≤ 1e-12·D
constexpr double kStepTolerance = 1e-15;      // or |Δa| ≤ 1e-15·a
constexpr double kMinParameterRatio = 1e-12;  // a ≥ 1e-12·max(h1, h2)
constexpr double kMaxParameterRatio = 1e12;   // a ≤ 1e12·D
constexpr double kSampleSafety = 0.9;         // Δx = 0.9·√(8·a·e)
constexpr double kMaxSamples = 1e7;

// acosh(1 + u) for u ≥ 0, accurate for small u.
double acosh_one_plus(double u) { return std::log1p(u + std::sqrt(u * (2.0 + u))); }

// Horizontal distance from the vertex to a support h above it: a·acosh(1 + h/a).
double vertex_to_support_m(double a, double h) { return a * acosh_one_plus(h / a); }

// d/da of a·acosh(1 + h/a) = acosh(1 + u) − u/√(u(2 + u)), u = h/a; 0 for h = 0.
double vertex_to_support_slope(double a, double h) {
  const double u = h / a;
  if (u == 0.0) return 0.0;
  return acosh_one_plus(u) - u / std::sqrt(u * (2.0 + u));
}

void check_profile(const CatenaryProfile& p) {
  if (!(std::isfinite(p.span_m) && std::isfinite(p.support_1_m) && std::isfinite(p.support_2_m) &&
        std::isfinite(p.lowest_m))) {
    throw input_error(
        "catenary", "D, H1, H2 and S must be finite (got D = " + number_text(p.span_m) + ", H1 = " +
                        number_text(p.support_1_m) + ", H2 = " + number_text(p.support_2_m) +
                        ", S = " + number_text(p.lowest_m) + ")");
  }
  if (!(p.span_m > 0.0)) {
    throw input_error("catenary",
                      "the support distance D must be > 0, got " + number_text(p.span_m));
  }
  if (p.lowest_m > p.support_1_m || p.lowest_m > p.support_2_m) {
    throw input_error("catenary", "the lowest point S = " + number_text(p.lowest_m) +
                                      " m is above a support (H1 = " + number_text(p.support_1_m) +
                                      " m, H2 = " + number_text(p.support_2_m) + " m)");
  }
  if (p.lowest_m == p.support_1_m && p.lowest_m == p.support_2_m) {
    throw input_error("catenary", "the lowest point S equals both supports (" +
                                      number_text(p.lowest_m) +
                                      " m): a wire without sag cannot be reached");
  }
}

}  // namespace

Catenary Catenary::solve(const CatenaryProfile& profile) {
  check_profile(profile);
  const double span = profile.span_m;
  const double h1 = profile.support_1_m - profile.lowest_m;
  const double h2 = profile.support_2_m - profile.lowest_m;
  const auto residual = [&](double a) {  // f(a), SENSOR-SPEC §6 eq 6.13 generalised
    return vertex_to_support_m(a, h1) + vertex_to_support_m(a, h2) - span;
  };

  double lo = kMinParameterRatio * std::max(h1, h2);
  if (!(residual(lo) < 0.0)) {
    throw input_error("catenary", "the supports are too close (D = " + number_text(span) +
                                      " m) for a sag of " + number_text(std::max(h1, h2)) +
                                      " m: the wire would hang vertically");
  }
  double hi = std::max(span, std::max(h1, h2));
  while (!(residual(hi) > 0.0)) {
    lo = hi;
    hi *= 2.0;
    if (hi > kMaxParameterRatio * span) {
      throw input_error("catenary", "the sag " + number_text(std::max(h1, h2)) +
                                        " m is too small for D = " + number_text(span) +
                                        " m: the wire would have to lie flat");
    }
  }

  double a = std::sqrt(lo * hi);
  for (int iteration = 0; iteration < 400; ++iteration) {
    const double f = residual(a);
    if (std::abs(f) <= kResidualTolerance * span) break;
    if (f < 0.0)
      lo = a;
    else
      hi = a;
    const double slope = vertex_to_support_slope(a, h1) + vertex_to_support_slope(a, h2);
    double next = a - f / slope;
    if (!(next > lo && next < hi)) next = std::sqrt(lo * hi);  // Newton left the bracket
    const bool converged = std::abs(next - a) <= kStepTolerance * a;
    a = next;
    if (converged) break;
  }
  // Split the remaining residual evenly between the two supports.
  const double x0 = 0.5 * (vertex_to_support_m(a, h1) + span - vertex_to_support_m(a, h2));
  return Catenary(profile, a, std::clamp(x0, 0.0, span));
}

double Catenary::height_at(double x_m) const {
  const double half = std::sinh(0.5 * (x_m - x0_) / a_);
  return profile_.lowest_m + 2.0 * a_ * half * half;  // a·(cosh z − 1) = 2a·sinh²(z/2)
}

double Catenary::slope_at(double x_m) const { return std::sinh((x_m - x0_) / a_); }

double Catenary::length_m() const {
  return a_ * (std::sinh((profile_.span_m - x0_) / a_) + std::sinh(x0_ / a_));
}

std::vector<double> Catenary::sample_x(double max_chord_error_m) const {
  if (!(std::isfinite(max_chord_error_m) && max_chord_error_m > 0.0)) {
    throw input_error("catenary", "the chord error bound must be a finite number > 0, got " +
                                      number_text(max_chord_error_m));
  }
  const double step = kSampleSafety * std::sqrt(8.0 * a_ * max_chord_error_m);
  const double segments = std::max(1.0, std::ceil(profile_.span_m / step));
  if (segments > kMaxSamples) {
    throw input_error("catenary", "sampling to " + number_text(max_chord_error_m) +
                                      " m would need " + number_text(segments) + " points");
  }
  const auto n = static_cast<std::size_t>(segments);
  std::vector<double> xs(n + 1);
  for (std::size_t i = 0; i < n; ++i) {
    xs[i] = profile_.span_m * static_cast<double>(i) / static_cast<double>(n);
  }
  xs[n] = profile_.span_m;
  return xs;
}

}  // namespace owsim
