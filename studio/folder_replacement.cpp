#include "studio/folder_replacement.hpp"

#include <fcntl.h>
#include <stdio.h>  // renameat2 (glibc ≥ 2.28)
#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <random>
#include <string>
#include <system_error>
#include <utility>

#include "geometry/error.hpp"

namespace owsim::studio {
namespace {

// `folder`'s hidden sibling with a random suffix: ".<name>.<8 hex digits><suffix>".
std::filesystem::path sibling(const std::filesystem::path& folder, const char* suffix) {
  static thread_local std::mt19937 random{std::random_device{}()};
  char digits[9];
  std::snprintf(digits, sizeof digits, "%08x", static_cast<unsigned>(random()));
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "." + string&&.
  std::string name = ".";
  name.append(folder.filename().string()).append(".").append(digits).append(suffix);
  return folder.parent_path() / name;
}

std::string why() { return std::strerror(errno); }

}  // namespace

FolderReplacement::FolderReplacement(std::filesystem::path folder) : folder_(std::move(folder)) {
  std::error_code error;
  std::filesystem::create_directories(folder_.parent_path(), error);
  if (error) {
    throw file_error(folder_.parent_path().string(),
                     "cannot create the output folder's parent: " + error.message());
  }
  // mkdir makes a new folder or fails: it never reuses or follows what is already there.
  for (int attempt = 0;; ++attempt) {
    staging_ = sibling(folder_, "");
    if (::mkdir(staging_.c_str(), 0777) == 0) return;
    if (errno != EEXIST || attempt == 100) {
      throw file_error(staging_.string(), "cannot create the flight's folder: " + why());
    }
  }
}

FolderReplacement::~FolderReplacement() {
  if (committed_) return;
  std::error_code ignored;
  std::filesystem::remove_all(staging_, ignored);
}

void FolderReplacement::commit() {
  std::filesystem::path previous = staging_;  // where the previous folder ends up, if any
  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, folder_.c_str(), RENAME_EXCHANGE) != 0) {
    if (errno == ENOENT) {
      // No previous folder.
      if (::rename(staging_.c_str(), folder_.c_str()) != 0) {
        throw file_error(folder_.string(), "cannot put the flight's folder in place: " + why());
      }
    } else if (errno == EINVAL || errno == ENOSYS) {
      // A file system without RENAME_EXCHANGE: the previous folder aside, the new one in.
      const std::filesystem::path aside = sibling(folder_, ".previous");
      if (::rename(folder_.c_str(), aside.c_str()) != 0) {
        throw file_error(folder_.string(), "cannot move the previous flight aside: " + why());
      }
      if (::rename(staging_.c_str(), folder_.c_str()) != 0) {
        const std::string reason = why();
        ::rename(aside.c_str(), folder_.c_str());
        throw file_error(folder_.string(), "cannot put the flight's folder in place: " + reason);
      }
      previous = aside;
    } else {
      throw file_error(folder_.string(), "cannot replace the output folder: " + why());
    }
  }
  committed_ = true;
  std::error_code ignored;
  std::filesystem::remove_all(previous, ignored);
}

}  // namespace owsim::studio
