#pragma once
// points.las: the returns as an ASPRS LAS 1.4 file (LAS Specification 1.4 – R15, ASPRS 2019;
// INTERFACE.md "`owsim run` outputs"), point data record format 6, written streaming.
//
// Layout: the 375-byte public header, one VLR (user "LASF_Projection", record 2112: the OGC WKT 1
// of the coordinate system, null-terminated, io/points/utm_wkt.hpp), then 30-byte point records.
// The header is written first with zero counts and rewritten by finish() with the point count, the
// counts by return and the bounds, so memory stays flat however many points.
//
// Coordinates: X, Y = UTM easting, northing on WGS-84 in the zone of the scenario origin (UPS
// near the poles; GeographicLib's standard zone of the origin), forced for every point so a
// flight across a zone edge stays in one grid; Z = WGS-84 ellipsoidal height (the WKT is the
// horizontal CRS, EPSG:326ZZ/327ZZ/5041/5042). Stored as int32 at scale 0.0001 m (0.1 mm)
// around an offset: the origin's easting and northing rounded to the kilometre, its height to
// the metre; so every point must lie within ±214.7 km (2^31 · 0.1 mm) of the offset, in each
// axis, or write() throws. Bounds are the extents of the stored (quantised) coordinates.
//
// Fields of a point: intensity = round(min(max(energy_rel, 0) / intensity_full_scale, 1) · 65535)
// with full scale energy_rel = 1 by default (all transmitted energy back: the physical maximum
// of SENSOR-SPEC §7 eq 7.13), unknown (NaN) energy → 0; return number / number of returns;
// classification 2 ground, 5 tree (high vegetation), 6 building, 14 wire (wire – conductor), 15
// pole (transmission tower), 18 fog (high noise), 7 noise (low noise: a false return, SENSOR-SPEC
// §11), 0 (created, never classified) when unknown; no classification flags,
// scanner channel 0, scan direction and edge-of-flight-line 0; user data = fiber (1..127); scan
// angle = β in 0.006° units, clamped to ±30000; point source ID 0; GPS time = the pulse time on
// the trajectory's clock in seconds. That is not GPS time (neither week seconds nor adjusted
// standard GPS time): global encoding bit 0 stays 0 ("GPS week time"), the closest the format
// has; bit 4 (WKT) is set, as format 6 requires. The legacy point counts are 0, as R15 requires
// for formats ≥ 6; the 64-bit counts hold the totals. System identifier "owsim", generating
// software "owsim <version>", file creation day and year (UTC) of today unless given.
// checkpoint() and resume() let an interrupted run continue the file: the checkpoint holds the
// header's statistics and creation day, so the finished file is the uninterrupted one's.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <vector>

#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/writer_checkpoint.hpp"
#include "io/points/point_record.hpp"

namespace owsim {

inline constexpr std::size_t kLasHeaderBytes = 375;      // LAS 1.4 public header block
inline constexpr std::size_t kLasVlrHeaderBytes = 54;    // variable length record header
inline constexpr std::size_t kLasPointRecordBytes = 30;  // point data record format 6
inline constexpr std::uint8_t kLasPointFormat = 6;
inline constexpr double kLasScanAngleUnitDeg = 0.006;  // format 6 scan angle increment
inline constexpr std::uint16_t kLasGlobalEncodingWkt = 1u << 4;

struct LasDate {
  int day_of_year = 1;  // 1..366, January 1 is day 1 (GMT)
  int year = 1970;
  friend bool operator==(const LasDate&, const LasDate&) = default;
};

struct LasWriterOptions {
  Geodetic origin;                       // the scenario origin: the UTM/UPS zone and the offsets
  double scale_m = 0.0001;               // coordinate resolution
  double intensity_full_scale = 1.0;     // energy_rel written as intensity 65535
  std::optional<LasDate> creation_date;  // default: today, UTC
  AtomicOutputOptions file;
};

// The grid a LAS file's coordinates are in.
struct LasGrid {
  int zone = 0;                      // 1..60 UTM, 0 UPS
  bool northp = true;                // hemisphere
  std::array<double, 3> offset_m{};  // X, Y, Z offsets of the header
  double scale_m = 0.0001;
};

// What a LasWriter must remember to continue a file: where the file stood (records = points)
// and the header's statistics so far.
struct LasCheckpoint {
  WriterCheckpoint file;
  std::array<std::uint64_t, 15> points_by_return{};
  std::array<std::int32_t, 3> min_record{};  // stored X, Y, Z; meaningful once a point is written
  std::array<std::int32_t, 3> max_record{};
  LasDate creation_date;
  friend bool operator==(const LasCheckpoint&, const LasCheckpoint&) = default;
};

// Points encoded by LasWriter::encode(): their 30-byte records and the header statistics they
// add. Reused from call to call (encode() clears it), so it allocates only while it grows.
struct LasEncodedPoints {
  std::vector<unsigned char> records;  // points · kLasPointRecordBytes
  std::uint64_t points = 0;
  std::array<std::uint64_t, 15> points_by_return{};
  std::array<std::int32_t, 3> min_record{};  // meaningful when points > 0
  std::array<std::int32_t, 3> max_record{};
};

// The point records points.las holds for points, without a file: what LasWriter::encode writes,
// for encoders that run where no writer is (the other processes of a distributed run).
class LasPointEncoder {
 public:
  // `file` names the file in errors. Throws owsim::Error on a bad origin, a scale that is not
  // positive, or a full scale that is not positive.
  LasPointEncoder(std::string file, const LasWriterOptions& options);
  // As LasWriter::encode.
  void encode(std::span<const PointRecord> points, LasEncodedPoints& out) const;
  [[nodiscard]] const LasGrid& grid() const { return grid_; }

 private:
  void encode_point(const PointRecord& point, LasEncodedPoints& out) const;

  std::string file_;
  LasGrid grid_;
  double intensity_full_scale_ = 1.0;
};

class LasWriter final : public PointSink {
 public:
  // Writes the header and the WKT record. Throws owsim::Error on a bad origin, a scale that is
  // not positive, or a full scale that is not positive.
  LasWriter(std::filesystem::path final_path, const LasWriterOptions& options);
  // Continues the temporary file an interrupted writer with the same options left at `from`
  // (bytes after it are cut off; the creation date is the checkpoint's). Throws owsim::Error
  // naming the path for what the constructor rejects, a missing or shorter temporary, or a
  // checkpoint whose counts do not fit its size.
  [[nodiscard]] static LasWriter resume(std::filesystem::path final_path,
                                        const LasWriterOptions& options, const LasCheckpoint& from);

  // Throws owsim::Error if a point lies outside the int32 range around the offset, outside the
  // grid's valid range (GeographicLib UTMUPS), or has a return number outside
  // 1..number_of_returns ≤ 15.
  void write(std::span<const PointRecord> points) override;
  // write() in two steps, so the encoding can run on other threads: encode() turns `points` into
  // records (reads only what the constructor set, so it may run concurrently with itself and
  // with append(); throws as write()), append() writes them and adds their statistics.
  void encode(std::span<const PointRecord> points, LasEncodedPoints& out) const;
  void append(const LasEncodedPoints& encoded);
  // Adds the statistics of `placed`, whose records another process put into the temporary after
  // the ones written so far (a distributed run); its `records` are not read.
  void skip(const LasEncodedPoints& placed);
  // Completes the header (counts, bounds) and renames the file to its final name.
  void finish() override;
  [[nodiscard]] std::uint64_t points_written() const override { return points_written_; }
  [[nodiscard]] const LasGrid& grid() const { return format_.grid(); }
  // Hands every point written so far to the kernel; where to resume from.
  [[nodiscard]] LasCheckpoint checkpoint();

 private:
  LasWriter(AtomicOutputFile file, const LasWriterOptions& options, LasDate creation_date);
  void flush_buffer();
  void add_statistics(const LasEncodedPoints& encoded);
  [[nodiscard]] std::array<unsigned char, kLasHeaderBytes> header_bytes() const;

  AtomicOutputFile file_;
  LasPointEncoder format_;
  LasDate creation_date_;
  std::uint32_t offset_to_points_ = 0;
  std::vector<unsigned char> buffer_;
  std::size_t buffered_bytes_ = 0;
  LasEncodedPoints encoded_;  // write()'s, reused
  std::uint64_t points_written_ = 0;
  std::array<std::uint64_t, 15> points_by_return_{};
  std::array<std::int32_t, 3> min_record_{};
  std::array<std::int32_t, 3> max_record_{};
};

// round(min(max(energy_rel, 0) / full_scale, 1) · 65535); NaN → 0.
[[nodiscard]] std::uint16_t las_intensity(double energy_rel, double full_scale);
// 2 ground, 5 tree, 6 building, 14 wire, 15 pole, 18 fog, 7 noise; 0 unknown (ASPRS classes of
// format 6).
[[nodiscard]] std::uint8_t las_classification(std::optional<SurfaceClass> surface);
// round(β / 0.006°) clamped to ±30000 (±180°); NaN → 0.
[[nodiscard]] std::int16_t las_scan_angle(double scan_angle_deg);
// The day of year and year, UTC, of `seconds_since_epoch` (Unix time).
[[nodiscard]] LasDate las_date_utc(std::int64_t seconds_since_epoch);

}  // namespace owsim
