#include "io/report/report_page.hpp"

#include <zlib.h>

#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "io/files/atomic_output_file.hpp"

namespace owsim {
namespace {

std::string base64(std::span<const std::uint8_t> bytes) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const std::uint32_t v = (std::uint32_t{bytes[i]} << 16) | (std::uint32_t{bytes[i + 1]} << 8) |
                            std::uint32_t{bytes[i + 2]};
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += kDigits[(v >> 6) & 63];
    out += kDigits[v & 63];
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const std::uint32_t v =
        (std::uint32_t{bytes[i]} << 16) | (two ? std::uint32_t{bytes[i + 1]} << 8 : 0);
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += two ? kDigits[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

// The JSON text made safe inside <script>: "</" cannot end the element early.
std::string script_safe(std::string_view json) {
  std::string out;
  out.reserve(json.size());
  for (std::size_t i = 0; i < json.size(); ++i) {
    out += json[i];
    if (json[i] == '<' && i + 1 < json.size() && json[i + 1] == '/') out += "\\";
  }
  return out;
}

std::string html_text(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

std::string deflate_base64(std::span<const std::uint8_t> bytes) {
  uLongf size = compressBound(static_cast<uLong>(bytes.size()));
  std::vector<std::uint8_t> packed(size);
  if (compress2(packed.data(), &size, bytes.data(), static_cast<uLong>(bytes.size()), 6) != Z_OK) {
    throw Error("report: deflate failed");
  }
  packed.resize(size);
  return base64(packed);
}

std::uint64_t write_report_page(const std::filesystem::path& path, std::string_view title,
                                std::string_view meta_json, std::string_view frames_blob,
                                std::string_view cloud_blob) {
  AtomicOutputOptions options;
  options.sync_on_commit = false;
  AtomicOutputFile file(path, options);
  std::string head =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<meta name=\"generator\" content=\"owsim view\">\n<title>";
  head += html_text(title);
  head +=
      "</title>\n</head>\n<body>\n<noscript>This report needs JavaScript.</noscript>\n"
      "<div id=\"owsim-report\"></div>\n<script type=\"application/json\" id=\"owsim-meta\">";
  file.write(head);
  file.write(script_safe(meta_json));
  file.write("</script>\n<script type=\"application/octet-stream\" id=\"owsim-frames\">");
  file.write(frames_blob);
  file.write("</script>\n<script type=\"application/octet-stream\" id=\"owsim-cloud\">");
  file.write(cloud_blob);
  file.write("</script>\n<script>");
  file.write(report_script());
  file.write("</script>\n</body>\n</html>\n");
  file.commit();
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) throw file_error(path.string(), "written but cannot be read back: " + error.message());
  return size;
}

}  // namespace owsim
