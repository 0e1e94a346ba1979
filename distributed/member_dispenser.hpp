#pragma once
// Sweep members handed out one at a time, to whichever process asks first (their costs differ, so
// a fixed split would leave processes idle). Process 0 keeps the count: a thread of its own
// answers the others' requests (polling every millisecond, so it takes no core from the members
// being run) while process 0 takes members from the same count itself. Without MPI the count is
// a local one. With an MPI that does not allow threads, process 0 only hands out. Which process runs which member varies from run to run; nothing else depends on it.
#include <atomic>
#include <cstdint>
#include <optional>
#include <thread>

#include "distributed/communicator.hpp"

namespace owsim {

class MemberDispenser {
 public:
  // Collective: every process of `comm` makes one, for members 0..count−1.
  MemberDispenser(Communicator& comm, std::int64_t count);
  // Waits for process 0's answering thread (after every process was told there is no more).
  ~MemberDispenser();
  MemberDispenser(const MemberDispenser&) = delete;
  MemberDispenser& operator=(const MemberDispenser&) = delete;

  // The next member this process should run; std::nullopt once all are handed out. After that,
  // the process may not call it again.
  [[nodiscard]] std::optional<std::int64_t> next();

 private:
  void answer_requests();

  Communicator& comm_;
  std::int64_t count_;
  std::atomic<std::int64_t> next_{0};  // process 0's count
  std::thread answering_;
};

}  // namespace owsim
