#pragma once
// The receiver's common case over arrays (SENSOR-SPEC §1, §7, §11): a pulse that met one surface
// and no wire, in clear air — and, with the receiver's noise on, in a group without a false
// trigger (ReceiverNoise::group_has_no_trigger) — is decided by its one echo: whether it registers,
// its range noise and its counter. A run of such pulses is evaluated a step at a time over arrays,
// so the pulses' chains of dependent arithmetic overlap instead of following one another. A pulse
// whose answer needs more than that arithmetic — an echo within kSureEchoSigmas σ_n of the
// threshold (a keyed draw decides), a range-noise normal outside the ziggurat's first rectangle,
// a count within 1e-9 of a rounding boundary — is left undecided, for select_single_return. Every
// decided pulse gets select_single_return's result, bit for bit.
#include <cstddef>
#include <cstdint>

#include "sensor/receiver.hpp"

namespace owsim {

class SingleReturnBatch {
 public:
  static constexpr std::size_t kCapacity = 256;
  enum class Outcome : std::uint8_t { no_return, one_return, undecided };

  // `noisy`: the receiver's statistics are on (ReceiverNoise::on of p's receiver_noise).
  SingleReturnBatch(const ReceiverParams& p, bool noisy);

  void clear() { size_ = 0; }
  // A pulse's one candidate (its range and energy), the background b of its noise and the
  // standard normal of its first-return range-noise key (first_block_normals: NaN when it is not
  // known; unread when the range noise is off). Returns its slot; at most kCapacity between clears.
  std::size_t add(const Candidate& candidate, double background, double range_noise_normal) {
    range_m_[size_] = candidate.range_m;
    energy_rel_[size_] = candidate.energy_rel;
    background_[size_] = background;
    normal_[size_] = range_noise_normal;
    return size_++;
  }
  // The standard normal of a slot's range-noise key, when it is drawn after the slot was added.
  void set_range_noise_normal(std::size_t slot, double range_noise_normal) {
    normal_[slot] = range_noise_normal;
  }
  // Decides every slot.
  void evaluate();
  [[nodiscard]] std::size_t size() const { return size_; }
  [[nodiscard]] Outcome outcome(std::size_t slot) const {
    return static_cast<Outcome>(static_cast<int>(outcome_[slot]));
  }
  // Writes a decided slot's returns: select_single_return's for `candidate`, the one it was
  // added with.
  void write(std::size_t slot, const Candidate& candidate, PulseReturns& out) const {
    out.count = 0;
    out.counter1 = out.counter2 = timeout_counts_;
    if (outcome(slot) != Outcome::one_return) return;
    const auto counter = static_cast<std::uint16_t>(counts_[slot]);
    out.returns[0] = return_of(candidate, noisy_range_m_[slot], counter);
    out.count = 1;
    out.counter1 = counter;
  }

 private:
  bool noisy_;
  double threshold_;
  double noise_at_1km_;
  double range_noise_sigma_m_;
  double counts_per_m_;
  std::uint16_t timeout_counts_;
  std::size_t size_ = 0;
  alignas(64) double range_m_[kCapacity];
  alignas(64) double energy_rel_[kCapacity];
  alignas(64) double background_[kCapacity];
  alignas(64) double normal_[kCapacity];
  alignas(64) double noisy_range_m_[kCapacity];  // ≥ 0
  alignas(64) double counts_[kCapacity];         // the counter, below the timeout
  alignas(64) double outcome_[kCapacity];        // an Outcome, as a double (decide's lanes)
};

}  // namespace owsim
