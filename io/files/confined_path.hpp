#pragma once
// Files named by data from someone else — a scenario, a sweep file, a mesh's own references —
// are opened only when they are local regular files inside the folder tree the data came from
// (issue 33; CONTRIBUTING "Inputs are data"). A name is refused, before anything is opened, when
// it is a URL or a GDAL connection string ("http://…", "WMS:…"), a GDAL virtual file system
// ("/vsicurl/…", "/vsizip/…"), resolves (symbolic links followed) outside the root's tree, or is
// not a regular file (a device, a FIFO, a folder, a symbolic link loop).
#include <filesystem>
#include <string_view>

namespace owsim {

// The canonical path of `given` (relative names against `root`; an empty root is the current
// folder), after the checks above. Throws owsim::Error with the problem in one line; the caller
// adds the data's file and key.
[[nodiscard]] std::filesystem::path confined_file(const std::filesystem::path& root,
                                                  std::string_view given);

// True when `path` (canonical) lies in `root`'s tree (canonical), root itself included.
[[nodiscard]] bool inside_tree(const std::filesystem::path& root,
                               const std::filesystem::path& path);

}  // namespace owsim
