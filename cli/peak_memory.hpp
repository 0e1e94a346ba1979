#pragma once
// Peak memory of this process, as the kernel counts it (getrusage ru_maxrss: the largest resident
// set so far, in KiB on Linux), for `owsim bench`.

namespace owsim::cli {

// The peak resident set size of this process so far, in MiB.
[[nodiscard]] double peak_rss_mb();

}  // namespace owsim::cli
