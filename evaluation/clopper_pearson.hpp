#pragma once
// The Clopper–Pearson ("exact") confidence interval of a binomial proportion, and how many
// trials without a miss a lower bound needs to reach a probability (docs/evidence.md). The beta
// quantiles are Boost.Math's (ibeta_inv), accurate to a few ulp; tests/python/ checks them against
// scipy.stats.beta.ppf to 1e-9.
//   lower = B⁻¹(α/2; k, n − k + 1)      (0 when k = 0)
//   upper = B⁻¹(1 − α/2; k + 1, n − k)  (1 when k = n),   α = 1 − confidence
#include <cstdint>

namespace owsim {

inline constexpr const char* kIntervalMethod = "clopper-pearson";

struct ProportionInterval {
  double lower = 0.0;
  double upper = 1.0;
};

// The two-sided interval of k successes in n trials at `confidence` (0 < confidence < 1);
// n = 0 gives NaN bounds (no evidence). Throws owsim::Error for k > n or a confidence outside
// (0, 1).
[[nodiscard]] ProportionInterval clopper_pearson(std::uint64_t successes, std::uint64_t trials,
                                                 double confidence);

// The fewest trials whose interval's lower bound reaches `probability` when none of them misses:
// the smallest n with (α/2)^(1/n) ≥ p, i.e. ⌈ln(α/2) / ln p⌉ (736 for p = 0.995 at 95 %).
[[nodiscard]] std::uint64_t trials_needed_without_misses(double probability, double confidence);

}  // namespace owsim
