#pragma once
// points.ply: the returns as a binary little-endian PLY point cloud (INTERFACE.md "`owsim run`
// outputs"; PLY as defined by Greg Turk's 1994 format description), written streaming.
//
// One element `vertex` with the properties, in this order, 29 bytes a vertex:
//   double x, double y, double z  local East-North-Up metres from the scenario origin
//   float intensity               energy_rel (ξ_rx/ξ_tx, SENSOR-SPEC §7 eq 7.13); NaN if unknown
//   uchar class                   0 wire, 1 pole, 2 tree, 3 ground, 4 building, 5 fog,
//                                 7 noise (INTERFACE.md: a false return), 255 unknown
// The vertex count is known only at the end, so the header has a fixed length: the line
// "element vertex N" is preceded by a comment line padded with spaces to make up for the digits
// of N (room for any 64-bit count), and finish() rewrites the header in place with the real
// count. Every header line is an ordinary PLY line (a keyword and single-space separated
// words), so strict readers accept it. Vertices go through a 1 MiB buffer into an
// AtomicOutputFile: nothing appears under the final name before finish(); checkpoint() and
// resume() let an interrupted run continue the file. Errors throw owsim::Error naming the path.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "geometry/scene.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/writer_checkpoint.hpp"
#include "io/points/point_record.hpp"

namespace owsim {

inline constexpr std::size_t kPlyVertexBytes = 29;
inline constexpr std::uint8_t kPlyClassUnknown = 255;
inline constexpr std::uint8_t kPlyClassNoise = 7;  // INTERFACE.md "PLY class 7", as LAS's low noise

class PlyWriter final : public PointSink {
 public:
  // Writes the header with a count of 0.
  explicit PlyWriter(std::filesystem::path final_path, AtomicOutputOptions options = {});
  // Continues the temporary file an interrupted writer left at `from` (bytes after it are cut
  // off). Throws owsim::Error naming the path if the temporary is missing or shorter, or if
  // `from` does not hold a header and whole vertices.
  [[nodiscard]] static PlyWriter resume(std::filesystem::path final_path,
                                        const WriterCheckpoint& from,
                                        AtomicOutputOptions options = {});

  void write(std::span<const PointRecord> points) override;
  // write() in two steps, so the encoding can run on other threads: encode() replaces `vertices`
  // with the 29-byte vertices of `points`; append() writes encoded vertices.
  static void encode(std::span<const PointRecord> points, std::vector<unsigned char>& vertices);
  void append(std::span<const unsigned char> vertices);
  // Counts `vertices` vertices as written that another process put into the temporary after the
  // ones written so far (a distributed run).
  void skip(std::uint64_t vertices);
  // Rewrites the header with the vertex count and renames the file to its final name.
  void finish() override;
  [[nodiscard]] std::uint64_t points_written() const override { return points_written_; }
  // Hands every vertex written so far to the kernel; where to resume from.
  [[nodiscard]] WriterCheckpoint checkpoint();

 private:
  PlyWriter(AtomicOutputFile file, std::uint64_t points_written);
  void flush_buffer();

  AtomicOutputFile file_;
  std::vector<unsigned char> buffer_;
  std::size_t buffered_bytes_ = 0;
  std::vector<unsigned char> vertices_;  // write()'s encoded vertices, reused
  std::uint64_t points_written_ = 0;
};

// The `class` byte: 0 wire, 1 pole, 2 tree, 3 ground, 4 building, 5 fog, 7 noise, 255 unknown.
[[nodiscard]] std::uint8_t ply_class(std::optional<SurfaceClass> surface);
// The whole header (through "end_header\n") for `vertex_count` vertices; its length does not
// depend on the count.
[[nodiscard]] std::string ply_header(std::uint64_t vertex_count);

}  // namespace owsim
