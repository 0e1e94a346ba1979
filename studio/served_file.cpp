#include "studio/served_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <memory>
#include <vector>

#include "geometry/error.hpp"
#include "io/files/confined_path.hpp"

namespace owsim::studio {
namespace {

constexpr std::size_t kPieceBytes = 64u << 10;

// A descriptor closed with the last answer that reads it.
class OpenFile {
 public:
  explicit OpenFile(int descriptor) : descriptor_(descriptor) {}
  OpenFile(const OpenFile&) = delete;
  OpenFile& operator=(const OpenFile&) = delete;
  ~OpenFile() { ::close(descriptor_); }
  [[nodiscard]] int descriptor() const { return descriptor_; }

 private:
  int descriptor_;
};

}  // namespace

void serve_file(httplib::Response& response, const std::filesystem::path& root,
                std::string_view name, const std::string& content_type) {
  const std::filesystem::path path = confined_file(root, name);
  // O_NONBLOCK: a FIFO put in the file's place does not block the open (and is refused below).
  const int descriptor = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
  if (descriptor < 0) throw Error(path.string() + ": " + std::strerror(errno));
  const auto file = std::make_shared<const OpenFile>(descriptor);
  struct stat facts {};
  if (::fstat(descriptor, &facts) != 0 || !S_ISREG(facts.st_mode)) {
    throw Error(path.string() + ": not a regular file");
  }
  if (facts.st_size == 0) {
    response.set_content("", content_type);
    return;
  }
  response.set_content_provider(
      static_cast<std::size_t>(facts.st_size), content_type,
      [file](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
        std::vector<char> piece(std::min(length, kPieceBytes));
        const ssize_t read =
            ::pread(file->descriptor(), piece.data(), piece.size(), static_cast<off_t>(offset));
        // A file cut short while it is sent ends the answer (and its connection) early.
        if (read <= 0) return false;
        return sink.write(piece.data(), static_cast<std::size_t>(read));
      });
}

}  // namespace owsim::studio
