#pragma once
// A file of the studio's output folder as the answer to `/out/NAME`: a regular file inside the
// folder (io/files/confined_path.hpp: no `..`, no link out of it), opened once (O_NOFOLLOW: not a
// link put in its place since) and sent in 64 KiB pieces read as the connection takes them, so
// that an answer never holds the file in memory (a point cloud can be gigabytes).
#include <filesystem>
#include <string>
#include <string_view>

// After every header that includes Eigen (httplib.h's <resolv.h> defines `_res`).
#include <httplib.h>

namespace owsim::studio {

// Sets `response` to stream `name` (relative to `root`) as `content_type`. Throws owsim::Error
// when `name` is not a regular file inside `root`.
void serve_file(httplib::Response& response, const std::filesystem::path& root,
                std::string_view name, const std::string& content_type);

}  // namespace owsim::studio
