#include "io/files/confined_path.hpp"

#include <cctype>
#include <string>
#include <system_error>

#include "geometry/error.hpp"

namespace owsim {
namespace {

// "scheme:" at the start: a URL (http://, ftp://, file://) or a GDAL connection string (WMS:,
// PG:, GPKG:, MEM:::…). A local file whose name has a colon in its first component can be given
// as "./name".
bool looks_like_url_or_connection(std::string_view name) {
  if (name.empty() || std::isalpha(static_cast<unsigned char>(name[0])) == 0) return false;
  for (std::size_t i = 1; i < name.size(); ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (c == ':') return true;
    if (std::isalnum(c) == 0 && c != '+' && c != '-' && c != '.' && c != '_') return false;
  }
  return false;
}

// GDAL reads a path that starts with /vsi… through its virtual file systems (curl, s3, zip, mem).
bool gdal_virtual_file_system(std::string_view name) { return name.starts_with("/vsi"); }

}  // namespace

bool inside_tree(const std::filesystem::path& root, const std::filesystem::path& path) {
  auto r = root.begin();
  auto p = path.begin();
  for (; r != root.end(); ++r, ++p) {
    if (r->empty()) continue;  // a trailing separator
    if (p == path.end() || *p != *r) return false;
  }
  return true;
}

std::filesystem::path confined_file(const std::filesystem::path& root, std::string_view given) {
  const std::string shown(given);
  if (given.empty()) throw Error("expected a file name, got ''");
  if (given.find('\0') != std::string_view::npos) {
    throw Error("a file name with a NUL byte is refused");
  }
  if (looks_like_url_or_connection(given)) {
    throw Error(shown + ": a URL or a connection string; a scenario reads only local files");
  }
  if (gdal_virtual_file_system(given)) {
    throw Error(shown + ": a GDAL virtual file system; a scenario reads only local files");
  }
  std::error_code error;
  const std::filesystem::path base = root.empty() ? std::filesystem::current_path() : root;
  const std::filesystem::path base_real = std::filesystem::canonical(base, error);
  if (error) throw Error(base.string() + ": the scenario's folder: " + error.message());
  const std::filesystem::path path(shown);
  const std::filesystem::path joined = path.is_absolute() ? path : base / path;
  const auto outside = [&] {
    return Error(joined.string() + ": outside the folder " + base_real.string() +
                 "; a scenario reads only files in its own folder tree");
  };
  // By its name first (../x.tif is refused whether or not it exists), then with links followed.
  if (!inside_tree(base_real, std::filesystem::absolute(joined).lexically_normal()) &&
      !inside_tree(base.lexically_normal(), joined.lexically_normal())) {
    throw outside();
  }
  const std::filesystem::path real = std::filesystem::canonical(joined, error);
  if (error == std::errc::too_many_symbolic_link_levels) {
    throw Error(joined.string() + ": a symbolic link loop");
  }
  if (error == std::errc::no_such_file_or_directory || error == std::errc::not_a_directory) {
    throw Error("no such file: " + joined.string());
  }
  if (error) throw Error(joined.string() + ": " + error.message());
  if (!inside_tree(base_real, real) || gdal_virtual_file_system(real.string())) throw outside();
  if (!std::filesystem::is_regular_file(real, error)) {
    throw Error(joined.string() + ": not a regular file (a device, a FIFO or a folder)");
  }
  return real;
}

}  // namespace owsim
