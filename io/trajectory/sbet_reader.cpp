#include "io/trajectory/sbet_reader.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string_view>

#include "geometry/error.hpp"
#include "io/files/input_file.hpp"
#include "io/files/little_endian.hpp"
#include "sensor/trajectory.hpp"

namespace owsim {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr std::array<std::string_view, 17> kSbetFieldNames = {
    "time",           "latitude",       "longitude",      "altitude",       "x velocity",
    "y velocity",     "z velocity",     "roll",           "pitch",          "platform heading",
    "wander angle",   "x acceleration", "y acceleration", "z acceleration", "x angular rate",
    "y angular rate", "z angular rate"};
// The fields read, by their index (a scoped name: these sources build together, CMakeLists.txt).
struct SbetField {
  enum : std::size_t {
    time = 0,
    lat = 1,
    lon = 2,
    alt = 3,
    roll = 7,
    pitch = 8,
    heading = 9,
    wander = 10
  };
};

}  // namespace

std::vector<NavRecord> read_sbet(const std::string& path) {
  const std::string bytes = read_input_file(path, "SBET trajectory file", kMaxTrajectoryBytes);
  if (bytes.size() % kSbetRecordBytes != 0) {
    throw input_error(path, "truncated record at byte " +
                                std::to_string(bytes.size() / kSbetRecordBytes * kSbetRecordBytes) +
                                " (the file holds " + std::to_string(bytes.size()) +
                                " bytes, not a multiple of the 136-byte record)");
  }
  if (bytes.empty()) throw input_error(path, "holds no SBET records");
  const std::size_t count = bytes.size() / kSbetRecordBytes;
  std::vector<NavRecord> records(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t offset = i * kSbetRecordBytes;
    const std::string where =
        path + ": record " + std::to_string(i) + " at byte " + std::to_string(offset);
    std::array<double, 17> value{};
    for (std::size_t f = 0; f < value.size(); ++f) {
      value[f] = std::bit_cast<double>(load_little_endian<std::uint64_t>(
          reinterpret_cast<const unsigned char*>(bytes.data()) + offset + 8 * f));
      if (!std::isfinite(value[f])) {
        throw input_error(where, std::string(kSbetFieldNames[f]) + " is not a finite number");
      }
    }
    NavRecord& record = records[i];
    record.time_s = value[SbetField::time];
    record.position = {kDegPerRad * value[SbetField::lat], kDegPerRad * value[SbetField::lon],
                       value[SbetField::alt]};
    record.attitude = {
        kDegPerRad * value[SbetField::roll], kDegPerRad * value[SbetField::pitch],
        wrap_360_deg(kDegPerRad * (value[SbetField::heading] - value[SbetField::wander]))};
    validate_geodetic(record.position, where);
    if (i > 0 && !(record.time_s > records[i - 1].time_s)) {
      throw input_error(where, "time is not after the previous record's");
    }
  }
  return records;
}

}  // namespace owsim
