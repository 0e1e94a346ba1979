#include "distributed/member_dispenser.hpp"

#include <chrono>
#include <cstdio>
#include <exception>

namespace owsim {
namespace {

constexpr int kRequestTag = 7001;
constexpr int kAnswerTag = 7002;

}  // namespace

MemberDispenser::MemberDispenser(Communicator& comm, std::int64_t count)
    : comm_(comm), count_(count) {
  if (comm_.rank() == 0 && comm_.size() > 1 && comm_.any_thread_may_call()) {
    answering_ = std::thread([this] { answer_requests(); });
  }
}

MemberDispenser::~MemberDispenser() {
  if (!answering_.joinable()) return;
  // Unwinding from an error: the other processes may never ask again, and this process is about
  // to end the job (cli/mpi_job.hpp); waiting would hang it.
  if (std::uncaught_exceptions() > 0) {
    answering_.detach();
  } else {
    answering_.join();
  }
}

std::optional<std::int64_t> MemberDispenser::next() {
  std::int64_t member = 0;
  if (comm_.rank() == 0 && comm_.size() > 1 && !comm_.any_thread_may_call()) {
    answer_requests();  // an MPI without threads: process 0 only hands out
    return std::nullopt;
  }
  if (comm_.rank() == 0) {
    member = next_.fetch_add(1);
  } else {
    comm_.send(0, kRequestTag, 0);
    member = static_cast<std::int64_t>(comm_.receive(0, kAnswerTag));
  }
  if (member >= count_) return std::nullopt;
  return member;
}

void MemberDispenser::answer_requests() try {
  // Every other process asks until it is told "no more" (a member ≥ count) once.
  int finished = 0;
  while (finished < comm_.size() - 1) {
    const auto request = comm_.try_receive(kRequestTag);
    if (!request) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    const std::int64_t member = next_.fetch_add(1);
    comm_.send(request->first, kAnswerTag, static_cast<std::uint64_t>(member));
    if (member >= count_) ++finished;
  }
} catch (const std::exception& e) {
  std::fprintf(stderr, "owsim: process 0: handing out sweep members: %s\n", e.what());
  comm_.abort(1);
}

}  // namespace owsim
