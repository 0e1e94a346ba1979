// Protects the Applanix SBET reader: 17 little-endian doubles per record, radians to degrees,
// true heading = platform heading − wander angle, and truncated or non-finite records reported
// with the file and byte.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "io/files/little_endian.hpp"
#include "io/trajectory/sbet_reader.hpp"

namespace owsim {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;
using SbetRecord = std::array<double, 17>;

SbetRecord record(double time_s, double lat_deg, double lon_deg, double h_m, double roll_deg,
                  double pitch_deg, double platform_heading_deg, double wander_deg) {
  SbetRecord r{};
  r[0] = time_s;
  r[1] = lat_deg * kRadPerDeg;
  r[2] = lon_deg * kRadPerDeg;
  r[3] = h_m;
  r[4] = 50.0;  // velocities, accelerations and rates: present, unused
  r[5] = -3.0;
  r[6] = 0.5;
  r[7] = roll_deg * kRadPerDeg;
  r[8] = pitch_deg * kRadPerDeg;
  r[9] = platform_heading_deg * kRadPerDeg;
  r[10] = wander_deg * kRadPerDeg;
  for (std::size_t i = 11; i < 17; ++i) r[i] = 0.01 * double(i);
  return r;
}

class SbetFile : public ::testing::Test {
 protected:
  std::string write(const std::vector<SbetRecord>& records, std::size_t extra_bytes = 0) {
    std::vector<unsigned char> bytes;
    for (const SbetRecord& r : records) {
      for (double value : r) {
        unsigned char word[8];
        store_little_endian(std::bit_cast<std::uint64_t>(value), word);
        bytes.insert(bytes.end(), word, word + 8);
      }
    }
    bytes.insert(bytes.end(), extra_bytes, 0x5a);
    std::ofstream(path_, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return path_;
  }
  std::string error_text(const std::vector<SbetRecord>& records, std::size_t extra_bytes = 0) {
    try {
      (void)read_sbet(write(records, extra_bytes));
    } catch (const Error& error) {
      return error.what();
    }
    return "no error";
  }
  void TearDown() override { std::filesystem::remove(path_); }
  std::string path_ = (std::filesystem::temp_directory_path() /
                       ("owsim_test_sbet_" + std::to_string(::getpid()) + ".out"))
                          .string();
};

TEST_F(SbetFile, KnownDoublesParse) {
  const std::vector<NavRecord> records = read_sbet(write({
      record(345600.125, 48.6881, 10.8447, 512.5, 3.5, -2.0, 95.0, 5.0),
      record(345600.130, -33.9, -70.25, 1200.0, -10.0, 4.0, 2.0, 7.5),  // 2 − 7.5 → 354.5
      record(345600.135, 60.0, 179.5, -20.0, 0.0, 0.0, 350.0, -15.0),   // 365 → 5
  }));
  ASSERT_EQ(records.size(), 3u);
  EXPECT_EQ(records[0].time_s, 345600.125);  // GPS seconds of week, as written
  EXPECT_NEAR(records[0].position.lat_deg, 48.6881, 1e-12);
  EXPECT_NEAR(records[0].position.lon_deg, 10.8447, 1e-12);
  EXPECT_EQ(records[0].position.h_m, 512.5);
  EXPECT_NEAR(records[0].attitude.roll_deg, 3.5, 1e-12);
  EXPECT_NEAR(records[0].attitude.pitch_deg, -2.0, 1e-12);
  EXPECT_NEAR(records[0].attitude.heading_deg, 90.0, 1e-12);
  EXPECT_NEAR(records[1].position.lat_deg, -33.9, 1e-12);
  EXPECT_NEAR(records[1].position.lon_deg, -70.25, 1e-12);
  EXPECT_NEAR(records[1].attitude.heading_deg, 354.5, 1e-12);
  EXPECT_NEAR(records[2].attitude.heading_deg, 5.0, 1e-12);
  EXPECT_EQ(records[2].position.h_m, -20.0);
}

TEST_F(SbetFile, TruncatedRecordNamesTheByte) {
  const SbetRecord r = record(1.0, 48.0, 10.0, 500.0, 0, 0, 0, 0);
  EXPECT_EQ(error_text({r, r}, 50), path_ +
                                        ": truncated record at byte 272 (the file holds 322 "
                                        "bytes, not a multiple of the 136-byte record)");
  EXPECT_NE(error_text({}, 135).find("truncated record at byte 0"), std::string::npos);
  EXPECT_EQ(error_text({}), path_ + ": holds no SBET records");
}

TEST_F(SbetFile, NonFiniteValueNamesRecordAndByte) {
  SbetRecord bad = record(2.0, 48.0, 10.0, 500.0, 0, 0, 0, 0);
  bad[8] = std::numeric_limits<double>::quiet_NaN();
  const SbetRecord good = record(1.0, 48.0, 10.0, 500.0, 0, 0, 0, 0);
  const SbetRecord later = record(1.5, 48.0, 10.0, 500.0, 0, 0, 0, 0);
  EXPECT_EQ(error_text({good, later, bad}),
            path_ + ": record 2 at byte 272: pitch is not a finite number");
  SbetRecord far = good;
  far[1] = 2.0;  // 114.6° latitude
  EXPECT_NE(error_text({far}).find(path_ + ": record 0 at byte 0: latitude 114.59"),
            std::string::npos)
      << error_text({far});
}

// Regression (issue 7): a time going back reached the spline as "trajectory record 2: …",
// naming neither the file nor the record's byte.
TEST_F(SbetFile, TimeNotIncreasingNamesRecordAndByte) {
  const SbetRecord first = record(1.0, 48.0, 10.0, 500.0, 0, 0, 0, 0);
  const SbetRecord second = record(2.0, 48.0, 10.0, 500.0, 0, 0, 0, 0);
  EXPECT_EQ(error_text({first, second, first}),
            path_ + ": record 2 at byte 272: time is not after the previous record's");
  EXPECT_EQ(error_text({first, first}),
            path_ + ": record 1 at byte 136: time is not after the previous record's");
}

TEST(SbetReader, MissingFileIsAnError) {
  EXPECT_THROW((void)read_sbet("/nonexistent/owsim/sbet.out"), Error);
}

}  // namespace
}  // namespace owsim
