#include "evaluation/clopper_pearson.hpp"

#include <boost/math/special_functions/beta.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "geometry/error.hpp"

namespace owsim {
namespace {

void require_confidence(double confidence) {
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw Error("confidence must lie between 0 and 1, got " + std::to_string(confidence));
  }
}

}  // namespace

ProportionInterval clopper_pearson(std::uint64_t successes, std::uint64_t trials,
                                   double confidence) {
  require_confidence(confidence);
  if (successes > trials) {
    throw Error(std::to_string(successes) + " successes in " + std::to_string(trials) + " trials");
  }
  if (trials == 0) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan};
  }
  const double alpha = 1.0 - confidence;
  const auto k = static_cast<double>(successes);
  const auto n = static_cast<double>(trials);
  ProportionInterval interval;
  interval.lower = successes == 0 ? 0.0 : boost::math::ibeta_inv(k, n - k + 1.0, alpha / 2.0);
  interval.upper =
      successes == trials ? 1.0 : boost::math::ibeta_inv(k + 1.0, n - k, 1.0 - alpha / 2.0);
  return interval;
}

std::uint64_t trials_needed_without_misses(double probability, double confidence) {
  require_confidence(confidence);
  if (!(probability > 0.0 && probability < 1.0)) {
    throw Error("probability must lie between 0 and 1, got " + std::to_string(probability));
  }
  // With n trials and no miss the lower bound is (α/2)^(1/n); the smallest n reaching p.
  const double tail = (1.0 - confidence) / 2.0;
  auto n = static_cast<std::uint64_t>(std::ceil(std::log(tail) / std::log(probability)));
  // Rounding: step to the exact boundary.
  while (n > 1 && std::pow(tail, 1.0 / static_cast<double>(n - 1)) >= probability) --n;
  while (std::pow(tail, 1.0 / static_cast<double>(n)) < probability) ++n;
  return n;
}

}  // namespace owsim
