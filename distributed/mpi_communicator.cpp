// The job mpirun started, through the table of libowsim_mpi.so
// (distributed/mpi/mpi_module_abi.hpp).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>

#include "distributed/communicator.hpp"
#include "distributed/mpi/mpi_module_abi.hpp"
#include "geometry/error.hpp"
#include "io/files/optional_module.hpp"
#include "io/files/output_open.hpp"

namespace owsim {
namespace {

const owsim_mpi_table& mpi_table() {
  const OptionalModule& module =
      OptionalModule::get("mpi", "runs under mpirun (owsim built with MPI)");
  const auto entry = reinterpret_cast<owsim_mpi_module_fn>(module.symbol("owsim_mpi_module"));
  const owsim_mpi_table* table = entry();
  if (table == nullptr || table->abi != OWSIM_MPI_MODULE_ABI) {
    throw Error(module.path() + ": an MPI module of another owsim build (ABI " +
                std::to_string(table == nullptr ? -1 : table->abi) + ", expected " +
                std::to_string(OWSIM_MPI_MODULE_ABI) + ")");
  }
  return *table;
}

// Throws owsim::Error "MPI <operation>: <MPI's text>" unless rc is 0.
void check(const owsim_mpi_table& mpi, int rc, const char* operation) {
  if (rc == 0) return;
  char text[512];
  mpi.error_text(rc, text, sizeof text);
  throw Error(std::string("MPI ") + operation + ": " + text);
}

// A file opened as open_output_file() allows (never through a link), held open while MPI opens it
// by name, so that no other file can take its inode number meanwhile.
class CheckedOutputFile {
 public:
  explicit CheckedOutputFile(const std::filesystem::path& path)
      : path_(path), fd_(open_output_file(path, O_WRONLY, path.string(), "cannot open")) {}
  ~CheckedOutputFile() { ::close(fd_); }
  CheckedOutputFile(const CheckedOutputFile&) = delete;
  CheckedOutputFile& operator=(const CheckedOutputFile&) = delete;

  // Device and inode.
  [[nodiscard]] std::pair<dev_t, ino_t> identity() const {
    struct stat status {};
    if (::fstat(fd_, &status) != 0) {
      throw file_error(path_.string(), std::string("cannot open: ") + std::strerror(errno));
    }
    return {status.st_dev, status.st_ino};
  }

 private:
  std::filesystem::path path_;
  int fd_;
};

class MpiFile final : public SharedFile {
 public:
  // MPI-IO opens by name and may follow a link: the name must give one and the same file that
  // open_output_file() accepts before and after MPI opens it.
  MpiFile(const owsim_mpi_table& mpi, const std::filesystem::path& path) : mpi_(mpi) {
    const CheckedOutputFile before(path);
    const int rc = mpi_.file_open(path.c_str(), &file_);
    if (rc != 0) {
      char text[512];
      mpi_.error_text(rc, text, sizeof text);
      throw file_error(path.string(), std::string("MPI cannot open: ") + text);
    }
    if (CheckedOutputFile(path).identity() != before.identity()) {
      throw file_error(path.string(), "cannot open: another file was put in its place");
    }
  }
  // Not closed (an error on the way): the process is about to end the job (Communicator::abort).
  ~MpiFile() override = default;
  MpiFile(const MpiFile&) = delete;
  MpiFile& operator=(const MpiFile&) = delete;

  void write_at(std::uint64_t offset, std::span<const unsigned char> bytes) override {
    check(mpi_, mpi_.file_write_at(file_, offset, bytes.data(), bytes.size()), "write_at");
  }
  void sync() override { check(mpi_, mpi_.file_sync(file_), "file sync"); }
  void close() override {
    void* file = file_;
    file_ = nullptr;
    check(mpi_, mpi_.file_close(file), "file close");
  }

 private:
  const owsim_mpi_table& mpi_;
  void* file_ = nullptr;
};

class MpiJob final : public Communicator {
 public:
  explicit MpiJob(const owsim_mpi_table& mpi) : mpi_(mpi) {
    int threads_ok = 0;
    check(mpi_, mpi_.init(&rank_, &size_, &local_size_, &threads_ok), "init");
    any_thread_may_call_ = threads_ok != 0;
  }
  ~MpiJob() override { mpi_.finalize(); }
  MpiJob(const MpiJob&) = delete;
  MpiJob& operator=(const MpiJob&) = delete;

  [[nodiscard]] int rank() const override { return rank_; }
  [[nodiscard]] int size() const override { return size_; }
  [[nodiscard]] int local_size() const override { return local_size_; }
  [[nodiscard]] bool any_thread_may_call() const override { return any_thread_may_call_; }
  void barrier() override { check(mpi_, mpi_.barrier(), "barrier"); }
  void sleeping_barrier() override {
    constexpr int kPollMicroseconds = 200;
    check(mpi_, mpi_.sleeping_barrier(kPollMicroseconds), "barrier");
  }
  std::vector<std::uint64_t> exclusive_sum(std::span<const std::uint64_t> values) override {
    std::vector<std::uint64_t> out(values.size());
    check(mpi_, mpi_.exclusive_sum(values.data(), out.data(), static_cast<int>(values.size())),
          "exscan");
    return out;
  }
  void sum(std::span<std::uint64_t> values) override {
    check(mpi_, mpi_.sum(values.data(), static_cast<int>(values.size())), "allreduce");
  }
  void max(std::span<std::uint64_t> values) override {
    check(mpi_, mpi_.max(values.data(), static_cast<int>(values.size())), "allreduce");
  }
  void broadcast(std::string& bytes, int root) override {
    std::uint64_t size = bytes.size();
    check(mpi_, mpi_.broadcast(&size, sizeof size, root), "broadcast");
    bytes.resize(size);
    check(mpi_, mpi_.broadcast(bytes.data(), bytes.size(), root), "broadcast");
  }
  std::vector<std::string> gather(std::string_view mine, int root) override {
    std::vector<std::uint64_t> counts(rank_ == root ? static_cast<std::size_t>(size_) : 0);
    check(mpi_, mpi_.gather_sizes(mine.size(), counts.data(), root), "gather");
    std::string all;
    std::uint64_t total = 0;
    for (const std::uint64_t count : counts) total += count;
    all.resize(total);
    check(mpi_, mpi_.gather_bytes(mine.data(), mine.size(), all.data(), counts.data(), root),
          "gatherv");
    std::vector<std::string> parts;
    std::size_t at = 0;
    for (const std::uint64_t count : counts) {
      parts.push_back(all.substr(at, count));
      at += count;
    }
    return parts;
  }
  void or_at_root(std::span<std::uint8_t> bytes, int root) override {
    check(mpi_, mpi_.reduce_or(bytes.data(), bytes.size(), root), "reduce");
  }
  std::unique_ptr<SharedFile> open_shared(const std::filesystem::path& path) override {
    return std::make_unique<MpiFile>(mpi_, path);
  }
  void send(int destination, int tag, std::uint64_t value) override {
    check(mpi_, mpi_.send(destination, tag, value), "send");
  }
  std::uint64_t receive(int source, int tag) override {
    std::uint64_t value = 0;
    check(mpi_, mpi_.receive(source, tag, &value), "receive");
    return value;
  }
  std::optional<std::pair<int, std::uint64_t>> try_receive(int tag) override {
    int source = 0;
    int received = 0;
    std::uint64_t value = 0;
    check(mpi_, mpi_.try_receive(tag, &source, &value, &received), "probe");
    if (received == 0) return std::nullopt;
    return std::pair{source, value};
  }
  [[noreturn]] void abort(int exit_code) override { mpi_.abort(exit_code); }

 private:
  const owsim_mpi_table& mpi_;
  int rank_ = 0;
  int size_ = 1;
  int local_size_ = 1;
  bool any_thread_may_call_ = false;
};

}  // namespace

bool started_by_mpi_launcher() {
  // Open MPI's mpirun, PMIx launchers (srun --mpi=pmix), MPICH's Hydra and Slurm's PMI-2.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

std::unique_ptr<Communicator> mpi_communicator() { return std::make_unique<MpiJob>(mpi_table()); }

}  // namespace owsim
