#pragma once
// The processes of a distributed run or sweep (DESIGN.md "distributed driver") and the few things
// they do together: MPI's model, behind an interface so the driver is the same code with one
// process (single_process_communicator, no MPI needed) as under mpirun (mpi_communicator, through
// the optional module libowsim_mpi.so). Collective operations must be called by every process, in
// the same order; point-to-point ones only by the two processes concerned. Every failure throws
// owsim::Error naming the operation.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "geometry/error.hpp"

namespace owsim {

// A file every process writes into at explicit offsets (MPI-IO), opened and closed by all together.
class SharedFile {
 public:
  virtual ~SharedFile() = default;
  // This process's bytes at `offset` (not collective: each process writes its own range).
  virtual void write_at(std::uint64_t offset, std::span<const unsigned char> bytes) = 0;
  // Every process's bytes so far handed to the file system (collective).
  virtual void sync() = 0;
  // Collective; after it the bytes are visible to every process that opens the file.
  virtual void close() = 0;
};

class Communicator {
 public:
  virtual ~Communicator() = default;
  [[nodiscard]] virtual int rank() const = 0;
  [[nodiscard]] virtual int size() const = 0;
  // The processes of the job on this process's machine, which share its cores.
  [[nodiscard]] virtual int local_size() const = 0;
  // Whether a thread other than the one that made the communicator may make calls (one thread at
  // a time): MPI_THREAD_MULTIPLE granted.
  [[nodiscard]] virtual bool any_thread_may_call() const = 0;

  virtual void barrier() = 0;
  // A barrier whose waiting sleeps (polling every fraction of a millisecond) instead of spinning:
  // a process that is early leaves its core to the work of others (its own threads, or the other
  // processes on its machine).
  virtual void sleeping_barrier() = 0;
  // For each value: the sum of that value over the processes ranked before this one.
  [[nodiscard]] virtual std::vector<std::uint64_t> exclusive_sum(
      std::span<const std::uint64_t> values) = 0;
  // In place: each value summed / the maximum over every process.
  virtual void sum(std::span<std::uint64_t> values) = 0;
  virtual void max(std::span<std::uint64_t> values) = 0;
  // `bytes` of `root` to every process (whatever their size elsewhere).
  virtual void broadcast(std::string& bytes, int root) = 0;
  // Every process's bytes, in rank order, at `root`; empty elsewhere.
  [[nodiscard]] virtual std::vector<std::string> gather(std::string_view mine, int root) = 0;
  // In place at `root`: the bitwise OR of every process's bytes (the same size everywhere).
  virtual void or_at_root(std::span<std::uint8_t> bytes, int root) = 0;
  // Collective: the file at `path`, which exists, opened for writing by every process.
  [[nodiscard]] virtual std::unique_ptr<SharedFile> open_shared(
      const std::filesystem::path& path) = 0;

  // One value with a tag, to or from one process.
  virtual void send(int destination, int tag, std::uint64_t value) = 0;
  [[nodiscard]] virtual std::uint64_t receive(int source, int tag) = 0;
  // A value with `tag` from any process, if one is waiting: (its sender, the value).
  [[nodiscard]] virtual std::optional<std::pair<int, std::uint64_t>> try_receive(int tag) = 0;

  // Ends every process of the job with `exit_code`: what a process does when it fails alone,
  // since the others would wait for it forever.
  [[noreturn]] virtual void abort(int exit_code) = 0;
};

// A job of one process: every collective is the identity, files are written with pwrite.
[[nodiscard]] std::unique_ptr<Communicator> single_process_communicator();

// True when this process was started by mpirun/mpiexec (or srun): the launcher's environment.
[[nodiscard]] bool started_by_mpi_launcher();

// The job this process belongs to, through libowsim_mpi.so (MPI initialised here, finalised when
// the communicator is destroyed). Throws owsim::Error with one line if the module is missing
// (owsim built without MPI) or MPI cannot start.
[[nodiscard]] std::unique_ptr<Communicator> mpi_communicator();

// An error every process of the job met at the same step (process 0 found it and told the
// others): process 0 throws JobError with the message, to be said once; the others throw
// ReportedElsewhere and say nothing. No process has to end the job for it.
class JobError : public Error {
 public:
  using Error::Error;
};
class ReportedElsewhere : public std::exception {
 public:
  [[nodiscard]] const char* what() const noexcept override { return "reported by process 0"; }
};

// A step every process takes on its own (reading the scenario): `error` is this process's failure
// (empty: none). Collective. If any process failed, the lowest-ranked one that did throws
// JobError with its message and every other throws ReportedElsewhere, so the job says one line
// whether one process or all of them met it.
void throw_if_any_failed(Communicator& comm, const std::string& error);

// The worker threads for each process of `comm` when none are asked for: the cores this process
// may run on, shared with the job's other processes on this machine.
[[nodiscard]] int default_threads_per_process(const Communicator& comm);

}  // namespace owsim
