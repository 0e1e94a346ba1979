#pragma once
// A folder's next contents, written beside it and put in its place whole (docs/studio.md "Fly"):
// the studio's flight writes into a fresh hidden folder next to the output folder
// (`.<name>.<random>`), and only a flight that completes takes the output folder's place, in one
// rename (Linux's RENAME_EXCHANGE; two renames on a file system without it); the previous
// folder is then removed. A flight that fails or is cancelled removes its folder and leaves the
// previous flight's files exactly as they were — never some of each.
#include <filesystem>

namespace owsim::studio {

class FolderReplacement {
 public:
  // Creates the new folder beside `folder` (and `folder`'s parent if needed). Throws
  // owsim::FileError when it cannot.
  explicit FolderReplacement(std::filesystem::path folder);
  FolderReplacement(const FolderReplacement&) = delete;
  FolderReplacement& operator=(const FolderReplacement&) = delete;
  // Uncommitted: removes the new folder and what it holds.
  ~FolderReplacement();

  // Where the new contents go.
  [[nodiscard]] const std::filesystem::path& path() const { return staging_; }
  // The new folder becomes `folder`; the previous one, if any, is removed. Throws
  // owsim::FileError (and `folder` is as it was) when it cannot.
  void commit();

 private:
  std::filesystem::path folder_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

}  // namespace owsim::studio
