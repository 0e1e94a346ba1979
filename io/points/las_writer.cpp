#include "io/points/las_writer.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <limits>
#include <string>
#include <string_view>
#include <utility>

#include "geometry/error.hpp"
#include "geometry/exact_round.hpp"
#include "geometry/utm.hpp"
#include "io/files/little_endian.hpp"
#include "io/points/utm_wkt.hpp"
#include "owsim/version.hpp"

namespace owsim {
namespace {

constexpr std::size_t kBufferPoints = 34952;  // ≈ 1 MiB of 30-byte records
constexpr std::uint16_t kLasClassGround = 2;
constexpr std::uint16_t kLasClassHighVegetation = 5;
constexpr std::uint16_t kLasClassBuilding = 6;
constexpr std::uint16_t kLasClassLowNoise = 7;
constexpr std::uint16_t kLasClassWireConductor = 14;
constexpr std::uint16_t kLasClassTransmissionTower = 15;
constexpr std::uint16_t kLasClassHighNoise = 18;
constexpr int kLasMaxReturns = 15;
constexpr double kOffsetRoundingEnM = 1000.0;  // easting/northing offsets: whole kilometres
constexpr double kOffsetRoundingUpM = 1.0;     // height offset: whole metres

// Little-endian field writers over a byte array, at the spec's byte offsets.
template <typename UInt>
void put(unsigned char* bytes, std::size_t offset, UInt value) {
  store_little_endian(value, bytes + offset);
}
void put_double(unsigned char* bytes, std::size_t offset, double value) {
  store_little_endian(std::bit_cast<std::uint64_t>(value), bytes + offset);
}
void put_i32(unsigned char* bytes, std::size_t offset, std::int32_t value) {
  store_little_endian(static_cast<std::uint32_t>(value), bytes + offset);
}
// A char[size] field: the text, then nulls (the spec's rule for every character field).
void put_text(unsigned char* bytes, std::size_t offset, std::size_t size, std::string_view text) {
  std::memcpy(bytes + offset, text.data(), std::min(size, text.size()));
}

std::int32_t record_value(double coordinate_m, double offset_m, double scale_m,
                          const std::string& path, const PointRecord& point) {
  const double steps = round_half_away((coordinate_m - offset_m) / scale_m);
  if (!(std::abs(steps) <= static_cast<double>(std::numeric_limits<std::int32_t>::max()))) {
    throw input_error(
        path, "frame " + std::to_string(point.frame) + " pulse " + std::to_string(point.pulse) +
                  ": coordinate " + std::to_string(coordinate_m) + " m is further than LAS int32 " +
                  "coordinates reach from the offset " + std::to_string(offset_m) + " m");
  }
  return static_cast<std::int32_t>(steps);
}

}  // namespace

std::uint16_t las_intensity(double energy_rel, double full_scale) {
  if (!(energy_rel > 0)) return 0;  // also NaN
  const double fraction = std::min(energy_rel / full_scale, 1.0);
  return static_cast<std::uint16_t>(round_half_away(fraction * 65535.0));
}

std::uint8_t las_classification(std::optional<SurfaceClass> surface) {
  if (!surface) return 0;
  switch (*surface) {
    case SurfaceClass::wire:
      return kLasClassWireConductor;
    case SurfaceClass::pole:
      return kLasClassTransmissionTower;
    case SurfaceClass::tree:
      return kLasClassHighVegetation;
    case SurfaceClass::ground:
      return kLasClassGround;
    case SurfaceClass::building:
      return kLasClassBuilding;
    case SurfaceClass::fog:
      return kLasClassHighNoise;
    case SurfaceClass::noise:
      return kLasClassLowNoise;
  }
  return 0;
}

std::int16_t las_scan_angle(double scan_angle_deg) {
  if (std::isnan(scan_angle_deg)) return 0;
  const double units =
      std::clamp(round_half_away(scan_angle_deg / kLasScanAngleUnitDeg), -30000.0, 30000.0);
  return static_cast<std::int16_t>(units);
}

LasDate las_date_utc(std::int64_t seconds_since_epoch) {
  using namespace std::chrono;
  const sys_days day = floor<days>(sys_seconds(seconds(seconds_since_epoch)));
  const year_month_day date(day);
  const sys_days new_year = date.year() / January / 1;
  return {static_cast<int>((day - new_year).count()) + 1, static_cast<int>(date.year())};
}

LasPointEncoder::LasPointEncoder(std::string file, const LasWriterOptions& options)
    : file_(std::move(file)), intensity_full_scale_(options.intensity_full_scale) {
  if (!(options.scale_m > 0) || !std::isfinite(options.scale_m)) {
    throw input_error(file_, "LAS coordinate scale must be a positive number of metres");
  }
  if (!(intensity_full_scale_ > 0) || !std::isfinite(intensity_full_scale_)) {
    throw input_error(file_, "LAS intensity full scale must be a positive energy ratio");
  }
  validate_geodetic(options.origin, file_ + ": origin");
  const UtmPoint origin = utm_from_geodetic(options.origin.lat_deg, options.origin.lon_deg);
  grid_.zone = origin.zone;  // utm_grid_of, what frame_points' grid positions are in
  grid_.northp = origin.northp;
  grid_.scale_m = options.scale_m;
  grid_.offset_m = {std::round(origin.easting_m / kOffsetRoundingEnM) * kOffsetRoundingEnM,
                    std::round(origin.northing_m / kOffsetRoundingEnM) * kOffsetRoundingEnM,
                    std::round(options.origin.h_m / kOffsetRoundingUpM) * kOffsetRoundingUpM};
}

LasWriter::LasWriter(AtomicOutputFile file, const LasWriterOptions& options, LasDate creation_date)
    : file_(std::move(file)),
      format_(file_.final_path().string(), options),
      creation_date_(creation_date),
      buffer_(kBufferPoints * kLasPointRecordBytes) {
  const LasGrid& grid = format_.grid();
  const std::size_t wkt_bytes = utm_wkt(grid.zone, grid.northp).size() + 1;  // null-terminated
  offset_to_points_ = static_cast<std::uint32_t>(kLasHeaderBytes + kLasVlrHeaderBytes + wkt_bytes);
}

LasWriter::LasWriter(std::filesystem::path final_path, const LasWriterOptions& options)
    : LasWriter(AtomicOutputFile(std::move(final_path), options.file), options,
                options.creation_date.value_or(las_date_utc(std::time(nullptr)))) {
  const std::string wkt = utm_wkt(grid().zone, grid().northp);
  const std::size_t wkt_bytes = wkt.size() + 1;
  const auto header = header_bytes();
  file_.write(header.data(), header.size());
  std::array<unsigned char, kLasVlrHeaderBytes> vlr{};
  put_text(vlr.data(), 2, 16, "LASF_Projection");
  put<std::uint16_t>(vlr.data(), 18, 2112);
  put<std::uint16_t>(vlr.data(), 20, static_cast<std::uint16_t>(wkt_bytes));
  put_text(vlr.data(), 22, 32, "OGC coordinate system WKT");
  file_.write(vlr.data(), vlr.size());
  file_.write(wkt.c_str(), wkt_bytes);
}

LasWriter LasWriter::resume(std::filesystem::path final_path, const LasWriterOptions& options,
                            const LasCheckpoint& from) {
  std::uint64_t by_return = 0;
  for (const std::uint64_t count : from.points_by_return) by_return += count;
  LasWriter writer(
      AtomicOutputFile::resume(std::move(final_path), from.file.file_bytes, options.file), options,
      from.creation_date);
  if (by_return != from.file.records ||
      from.file.file_bytes != writer.offset_to_points_ + from.file.records * kLasPointRecordBytes) {
    throw input_error(writer.file_.final_path().string(),
                      "cannot resume: the checkpoint's " + std::to_string(from.file.file_bytes) +
                          " bytes do not hold its " + std::to_string(from.file.records) +
                          " points (" + std::to_string(by_return) + " by return)");
  }
  writer.points_written_ = from.file.records;
  writer.points_by_return_ = from.points_by_return;
  writer.min_record_ = from.min_record;
  writer.max_record_ = from.max_record;
  return writer;
}

LasCheckpoint LasWriter::checkpoint() {
  flush_buffer();
  file_.flush();
  return {{file_.bytes_written(), points_written_},
          points_by_return_,
          min_record_,
          max_record_,
          creation_date_};
}

std::array<unsigned char, kLasHeaderBytes> LasWriter::header_bytes() const {
  std::array<unsigned char, kLasHeaderBytes> header{};
  unsigned char* h = header.data();
  put_text(h, 0, 4, "LASF");
  put<std::uint16_t>(h, 4, 0);  // file source ID: not assigned
  put<std::uint16_t>(h, 6, kLasGlobalEncodingWkt);
  h[24] = 1;  // version 1.4
  h[25] = 4;
  put_text(h, 26, 32, "owsim");
  put_text(h, 58, 32, std::string("owsim ") + version_string);
  put<std::uint16_t>(h, 90, static_cast<std::uint16_t>(creation_date_.day_of_year));
  put<std::uint16_t>(h, 92, static_cast<std::uint16_t>(creation_date_.year));
  put<std::uint16_t>(h, 94, static_cast<std::uint16_t>(kLasHeaderBytes));
  put<std::uint32_t>(h, 96, offset_to_points_);
  put<std::uint32_t>(h, 100, 1);  // one VLR
  h[104] = kLasPointFormat;
  put<std::uint16_t>(h, 105, static_cast<std::uint16_t>(kLasPointRecordBytes));
  // 107: legacy point count and 111: legacy counts by return stay 0 (format ≥ 6).
  const LasGrid& grid = format_.grid();
  for (std::size_t axis = 0; axis < 3; ++axis) {
    put_double(h, 131 + 8 * axis, grid.scale_m);
    put_double(h, 155 + 8 * axis, grid.offset_m[axis]);
    const bool any = points_written_ > 0;
    const double max = any ? grid.offset_m[axis] + max_record_[axis] * grid.scale_m : 0.0;
    const double min = any ? grid.offset_m[axis] + min_record_[axis] * grid.scale_m : 0.0;
    put_double(h, 179 + 16 * axis, max);
    put_double(h, 187 + 16 * axis, min);
  }
  // 227: waveform data start, 235: first EVLR, 243: EVLR count — all 0.
  put<std::uint64_t>(h, 247, points_written_);
  for (std::size_t r = 0; r < points_by_return_.size(); ++r) {
    put<std::uint64_t>(h, 255 + 8 * r, points_by_return_[r]);
  }
  return header;
}

void LasPointEncoder::encode_point(const PointRecord& point, LasEncodedPoints& out) const {
  const std::string& path = file_;
  if (point.return_number < 1 || point.return_number > point.number_of_returns ||
      point.number_of_returns > kLasMaxReturns) {
    throw input_error(
        path, "frame " + std::to_string(point.frame) + " pulse " + std::to_string(point.pulse) +
                  ": return " + std::to_string(point.return_number) + " of " +
                  std::to_string(point.number_of_returns) + " is not a LAS return number");
  }
  // The grid position placed with the point (frame_points), or computed here exactly.
  Eigen::Vector2d en = point.grid_m;
  if (!en.allFinite()) {
    try {
      en = grid_from_geodetic({grid_.zone, grid_.northp}, point.geodetic.lat_deg,
                              point.geodetic.lon_deg);
    } catch (const std::exception& error) {
      throw input_error(path, "frame " + std::to_string(point.frame) + " pulse " +
                                  std::to_string(point.pulse) + ": not in " +
                                  utm_crs_name(grid_.zone, grid_.northp) + ": " + error.what());
    }
  }
  const double easting_m = en.x(), northing_m = en.y();
  const std::array<std::int32_t, 3> record = {
      record_value(easting_m, grid_.offset_m[0], grid_.scale_m, path, point),
      record_value(northing_m, grid_.offset_m[1], grid_.scale_m, path, point),
      record_value(point.geodetic.h_m, grid_.offset_m[2], grid_.scale_m, path, point)};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (out.points == 0 || record[axis] < out.min_record[axis]) out.min_record[axis] = record[axis];
    if (out.points == 0 || record[axis] > out.max_record[axis]) out.max_record[axis] = record[axis];
  }

  unsigned char* p = out.records.data() + out.points * kLasPointRecordBytes;
  put_i32(p, 0, record[0]);
  put_i32(p, 4, record[1]);
  put_i32(p, 8, record[2]);
  put<std::uint16_t>(p, 12, las_intensity(point.energy_rel, intensity_full_scale_));
  p[14] = static_cast<unsigned char>(point.return_number | (point.number_of_returns << 4));
  p[15] = 0;  // classification flags, scanner channel 0, scan direction, edge of flight line
  p[16] = las_classification(point.surface);
  p[17] = static_cast<unsigned char>(std::clamp(point.fiber, 0, 255));  // user data: fiber
  put<std::uint16_t>(p, 18, static_cast<std::uint16_t>(las_scan_angle(point.scan_angle_deg)));
  put<std::uint16_t>(p, 20, 0);  // point source ID
  put_double(p, 22, point.time_s);

  ++out.points_by_return[static_cast<std::size_t>(point.return_number - 1)];
  ++out.points;
}

void LasWriter::write(std::span<const PointRecord> points) {
  encode(points, encoded_);
  append(encoded_);
}

void LasWriter::encode(std::span<const PointRecord> points, LasEncodedPoints& out) const {
  format_.encode(points, out);
}

void LasPointEncoder::encode(std::span<const PointRecord> points, LasEncodedPoints& out) const {
  out.records.resize(points.size() * kLasPointRecordBytes);
  out.points = 0;
  out.points_by_return.fill(0);
  for (const PointRecord& point : points) encode_point(point, out);
}

void LasWriter::append(const LasEncodedPoints& encoded) {
  if (encoded.points == 0) return;
  const std::size_t bytes = encoded.points * kLasPointRecordBytes;
  if (buffered_bytes_ + bytes > buffer_.size()) flush_buffer();
  if (bytes >= buffer_.size()) {
    file_.write(encoded.records.data(), bytes);
  } else {
    std::copy_n(encoded.records.data(), bytes, buffer_.data() + buffered_bytes_);
    buffered_bytes_ += bytes;
  }
  add_statistics(encoded);
}

void LasWriter::skip(const LasEncodedPoints& placed) {
  if (placed.points == 0) return;
  flush_buffer();
  file_.skip(placed.points * kLasPointRecordBytes);
  add_statistics(placed);
}

void LasWriter::add_statistics(const LasEncodedPoints& encoded) {
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (points_written_ == 0 || encoded.min_record[axis] < min_record_[axis]) {
      min_record_[axis] = encoded.min_record[axis];
    }
    if (points_written_ == 0 || encoded.max_record[axis] > max_record_[axis]) {
      max_record_[axis] = encoded.max_record[axis];
    }
  }
  for (std::size_t r = 0; r < points_by_return_.size(); ++r) {
    points_by_return_[r] += encoded.points_by_return[r];
  }
  points_written_ += encoded.points;
}

void LasWriter::flush_buffer() {
  file_.write(buffer_.data(), buffered_bytes_);
  buffered_bytes_ = 0;
}

void LasWriter::finish() {
  flush_buffer();
  const auto header = header_bytes();
  file_.write_at(0, header.data(), header.size());
  file_.commit();
}

}  // namespace owsim
