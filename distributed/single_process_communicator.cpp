// The one-process job of distributed/communicator.hpp.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "distributed/communicator.hpp"
#include "geometry/error.hpp"
#include "io/files/output_open.hpp"

namespace owsim {
namespace {

class LocalFile final : public SharedFile {
 public:
  explicit LocalFile(const std::filesystem::path& path)
      : path_(path), fd_(open_output_file(path, O_WRONLY, path.string(), "cannot open")) {}
  ~LocalFile() override {
    if (fd_ >= 0) ::close(fd_);
  }
  LocalFile(const LocalFile&) = delete;
  LocalFile& operator=(const LocalFile&) = delete;

  void write_at(std::uint64_t offset, std::span<const unsigned char> bytes) override {
    while (!bytes.empty()) {
      const ssize_t n = ::pwrite(fd_, bytes.data(), bytes.size(), static_cast<off_t>(offset));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) fail("cannot write");
      bytes = bytes.subspan(static_cast<std::size_t>(n));
      offset += static_cast<std::uint64_t>(n);
    }
  }
  void sync() override {}  // pwrite hands the bytes to the kernel
  void close() override {
    if (fd_ >= 0 && ::close(fd_) != 0) {
      fd_ = -1;
      fail("cannot close");
    }
    fd_ = -1;
  }

 private:
  [[noreturn]] void fail(const char* what) const {
    throw file_error(path_.string(), std::string(what) + ": " + std::strerror(errno));
  }
  std::filesystem::path path_;
  int fd_;
};

class SingleProcess final : public Communicator {
 public:
  [[nodiscard]] int rank() const override { return 0; }
  [[nodiscard]] int size() const override { return 1; }
  [[nodiscard]] int local_size() const override { return 1; }
  [[nodiscard]] bool any_thread_may_call() const override { return true; }
  void barrier() override {}
  void sleeping_barrier() override {}
  std::vector<std::uint64_t> exclusive_sum(std::span<const std::uint64_t> values) override {
    return std::vector<std::uint64_t>(values.size(), 0);
  }
  void sum(std::span<std::uint64_t> /*values*/) override {}
  void max(std::span<std::uint64_t> /*values*/) override {}
  void broadcast(std::string& /*bytes*/, int /*root*/) override {}
  std::vector<std::string> gather(std::string_view mine, int /*root*/) override {
    return {std::string(mine)};
  }
  void or_at_root(std::span<std::uint8_t> /*bytes*/, int /*root*/) override {}
  std::unique_ptr<SharedFile> open_shared(const std::filesystem::path& path) override {
    return std::make_unique<LocalFile>(path);
  }
  void send(int destination, int /*tag*/, std::uint64_t /*value*/) override {
    throw Error("send to process " + std::to_string(destination) + " in a one-process job");
  }
  std::uint64_t receive(int source, int /*tag*/) override {
    throw Error("receive from process " + std::to_string(source) + " in a one-process job");
  }
  std::optional<std::pair<int, std::uint64_t>> try_receive(int /*tag*/) override {
    return std::nullopt;
  }
  [[noreturn]] void abort(int exit_code) override { std::_Exit(exit_code); }
};

}  // namespace

std::unique_ptr<Communicator> single_process_communicator() {
  return std::make_unique<SingleProcess>();
}

}  // namespace owsim
