#include "sensor/savitzky_golay.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "geometry/error.hpp"

namespace owsim {
namespace {

// Weights g with value(x = 0) = Σ g_j y_j for the least-squares polynomial of `degree` through
// the points (x_j, y_j): g = first row of the pseudo-inverse of the Vandermonde matrix.
Eigen::VectorXd fit_weights_at_zero(const Eigen::VectorXd& x, int degree) {
  const Eigen::Index rows = x.size();
  Eigen::MatrixXd vandermonde(rows, degree + 1);
  for (Eigen::Index j = 0; j < rows; ++j) {
    double power = 1.0;
    for (int k = 0; k <= degree; ++k) {
      vandermonde(j, k) = power;
      power *= x(j);
    }
  }
  const Eigen::MatrixXd coefficients_from_samples =
      vandermonde.householderQr().solve(Eigen::MatrixXd::Identity(rows, rows));
  return coefficients_from_samples.row(0).transpose();
}

// The window actually used for n samples: the requested one, or the largest odd count ≤ n.
SmoothingParams effective_params(const SmoothingParams& params, std::size_t n) {
  SmoothingParams effective = params;
  if (static_cast<std::size_t>(params.window) > n) {
    const int largest_odd = static_cast<int>(n % 2 == 1 ? n : n - 1);
    effective.window = std::max(largest_odd, 1);
  }
  effective.degree = std::min(effective.degree, effective.window - 1);
  return effective;
}

}  // namespace

void validate_smoothing(const SmoothingParams& params, std::string_view where) {
  if (params.window < 1 || params.window % 2 == 0) {
    throw input_error(where, "smoothing window " + std::to_string(params.window) +
                                 " must be an odd number of samples, at least 1");
  }
  if (params.degree < 0) {
    throw input_error(where,
                      "smoothing degree " + std::to_string(params.degree) + " must be at least 0");
  }
}

bool smoothing_is_identity(const SmoothingParams& params) {
  return params.window <= 1 || params.degree >= params.window - 1;
}

void savitzky_golay_in_place(std::span<const double> time_s,
                             std::span<std::vector<double>* const> channels,
                             const SmoothingParams& params) {
  validate_smoothing(params, "Savitzky-Golay");
  const std::size_t n = time_s.size();
  for (const std::vector<double>* channel : channels) {
    if (channel->size() != n)
      throw Error("Savitzky-Golay: a channel's length differs from the times'");
  }
  const SmoothingParams effective = effective_params(params, n);
  if (n == 0 || smoothing_is_identity(effective)) return;

  const auto window = static_cast<std::size_t>(effective.window);
  const std::size_t half = window / 2;
  std::vector<std::vector<double>> smoothed(channels.size(), std::vector<double>(n));
  Eigen::VectorXd x(static_cast<Eigen::Index>(window));
  // The last window's scaled abscissae and weights, reused while the abscissae agree to 1e-9 of
  // the half-window (uniform steps: one QR for all interior samples).
  Eigen::VectorXd cached_x;
  Eigen::VectorXd weights;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t first = std::clamp<std::size_t>(i < half ? 0 : i - half, 0, n - window);
    const double scale = 0.5 * (time_s[first + window - 1] - time_s[first]);
    for (std::size_t j = 0; j < window; ++j) {
      x(static_cast<Eigen::Index>(j)) = (time_s[first + j] - time_s[i]) / scale;
    }
    if (cached_x.size() != x.size() || (cached_x - x).cwiseAbs().maxCoeff() > 1e-9) {
      cached_x = x;
      weights = fit_weights_at_zero(x, effective.degree);
    }
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const std::vector<double>& values = *channels[c];
      double sum = 0.0;
      for (std::size_t j = 0; j < window; ++j) {
        sum += weights(static_cast<Eigen::Index>(j)) * values[first + j];
      }
      smoothed[c][i] = sum;
    }
  }
  for (std::size_t c = 0; c < channels.size(); ++c) *channels[c] = std::move(smoothed[c]);
}

std::vector<double> savitzky_golay(std::span<const double> time_s, std::span<const double> values,
                                   const SmoothingParams& params) {
  std::vector<double> channel(values.begin(), values.end());
  std::vector<double>* channels[] = {&channel};
  savitzky_golay_in_place(time_s, channels, params);
  return channel;
}

std::vector<double> savitzky_golay(std::span<const double> values, const SmoothingParams& params) {
  std::vector<double> time_s(values.size());
  std::iota(time_s.begin(), time_s.end(), 0.0);
  return savitzky_golay(time_s, values, params);
}

std::vector<double> savitzky_golay_centre_weights(const SmoothingParams& params) {
  validate_smoothing(params, "Savitzky-Golay");
  const int half = params.window / 2;
  Eigen::VectorXd x(params.window);
  for (int j = 0; j < params.window; ++j) x(j) = half == 0 ? 0.0 : double(j - half) / half;
  const Eigen::VectorXd weights =
      fit_weights_at_zero(x, std::min(params.degree, params.window - 1));
  return {weights.data(), weights.data() + weights.size()};
}

}  // namespace owsim
