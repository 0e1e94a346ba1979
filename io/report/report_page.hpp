#pragma once
// report.html of `owsim view`: one self-contained page that opens offline from file://. The
// page's script and style (web/src, bundled with its pinned npm packages at build time into
// report_script()) read everything from the page itself:
//   <script type="application/json" id="owsim-meta">   what the flight is (owsim/flight_report.cpp)
//   <script type="application/octet-stream" id="owsim-frames">  range image cells, deflate + base64
//   <script type="application/octet-stream" id="owsim-cloud">   3D points, deflate + base64
// Nothing is loaded from the network. The file appears complete under its name or not at all.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace owsim {

// RFC 4648 base64 of zlib's deflate (RFC 1950, what the browsers' DecompressionStream('deflate')
// reads) of `bytes`.
[[nodiscard]] std::string deflate_base64(std::span<const std::uint8_t> bytes);

// The bundled script (web/src/report.js and its npm packages, minified), generated at build time.
[[nodiscard]] std::string_view report_script();

// Writes the page to `path` atomically. `meta_json` is a JSON object's text; the blobs are already
// deflate_base64. Returns the page's size in bytes. Throws owsim::FileError if it cannot be
// written.
std::uint64_t write_report_page(const std::filesystem::path& path, std::string_view title,
                                std::string_view meta_json, std::string_view frames_blob,
                                std::string_view cloud_blob);

}  // namespace owsim
