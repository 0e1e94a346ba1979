// Protects points.las (INTERFACE.md "`owsim run` outputs", ASPRS LAS 1.4 R15, point format 6):
// header fields at the spec's byte offsets, the WKT record, every point's fields, and an
// independent reader in Python (numpy structured dtype + pyproj UTM) that decodes the whole file
// and compares it with what was written; also the field mappings and the atomic-output rules.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/geodetic_frame.hpp"
#include "geometry/utm.hpp"
#include "io/files/little_endian.hpp"
#include "io/points/las_writer.hpp"
#include "io/points/utm_wkt.hpp"
#include "owsim/version.hpp"
#include "python_oracle.hpp"

namespace owsim {
namespace {

class LasWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = std::filesystem::temp_directory_path() /
                 ("owsim_test_las_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  [[nodiscard]] std::filesystem::path path() const { return directory_ / "points.las"; }

  std::filesystem::path directory_;
};

std::vector<unsigned char> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

template <typename UInt>
UInt field(const std::vector<unsigned char>& bytes, std::size_t offset) {
  return load_little_endian<UInt>(bytes.data() + offset);
}
double field_double(const std::vector<unsigned char>& bytes, std::size_t offset) {
  return std::bit_cast<double>(field<std::uint64_t>(bytes, offset));
}
std::string field_text(const std::vector<unsigned char>& bytes, std::size_t offset,
                       std::size_t size) {
  return {reinterpret_cast<const char*>(bytes.data() + offset), size};
}

// `count` returns scattered within ±spread_m of the origin, every class (and unknown), first and
// second returns, with energies, scan angles and times.
std::vector<PointRecord> scattered_points(const Geodetic& origin, int count, double spread_m,
                                          unsigned seed) {
  const LocalFrame frame(origin);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> horizontal(-spread_m, spread_m), up(-30.0, 120.0),
      energy(0.0, 0.6), beta(-30.0, 30.0);
  std::vector<PointRecord> points;
  for (int k = 0; k < count; ++k) {
    PointRecord p;
    p.frame = k / 100;
    p.pulse = k % 100;
    p.fiber = 1 + k % 127;
    p.number_of_returns = (k % 3 == 0) ? 2 : 1;
    p.return_number = (p.number_of_returns == 2 && k % 2 == 0) ? 2 : 1;
    p.time_s = 3600.0 + 0.0000163636 * k;
    p.enu_m = {horizontal(rng), horizontal(rng), up(rng)};
    p.geodetic = frame.geodetic_from_enu(p.enu_m);
    const int code = k % (static_cast<int>(kSurfaceClassCount) + 1);
    if (code < static_cast<int>(kSurfaceClassCount)) p.surface = static_cast<SurfaceClass>(code);
    p.energy_rel = (k % 17 == 0) ? std::numeric_limits<double>::quiet_NaN() : energy(rng);
    if (p.surface == SurfaceClass::noise) {  // a false return: energy_rel = T, no incidence
      p.energy_rel = 0.0029;
      p.object_index = kNoObject;
    }
    p.scan_angle_deg = beta(rng);
    points.push_back(p);
  }
  return points;
}

LasWriterOptions options_at(const Geodetic& origin) {
  LasWriterOptions options;
  options.origin = origin;
  options.creation_date = LasDate{60, 2024};
  return options;
}

constexpr Geodetic kLasOrigin{48.6881, 10.8447, 450.0};

TEST(LasFieldMappings, Intensity) {
  EXPECT_EQ(las_intensity(0.0, 1.0), 0);
  EXPECT_EQ(las_intensity(1.0, 1.0), 65535);
  EXPECT_EQ(las_intensity(2.5, 1.0), 65535);  // clipped at full scale
  EXPECT_EQ(las_intensity(0.5, 1.0), 32768);  // 32767.5 rounds up
  EXPECT_EQ(las_intensity(0.005, 1.0), 328);  // the default detection threshold
  EXPECT_EQ(las_intensity(0.125, 0.25), 32768);
  EXPECT_EQ(las_intensity(-0.1, 1.0), 0);
  EXPECT_EQ(las_intensity(std::numeric_limits<double>::quiet_NaN(), 1.0), 0);
}

TEST(LasFieldMappings, ClassificationScanAngleAndDate) {
  EXPECT_EQ(las_classification(SurfaceClass::ground), 2);
  EXPECT_EQ(las_classification(SurfaceClass::tree), 5);
  EXPECT_EQ(las_classification(SurfaceClass::wire), 14);
  EXPECT_EQ(las_classification(SurfaceClass::pole), 15);
  EXPECT_EQ(las_classification(SurfaceClass::building), 6);  // ASPRS "Building"
  EXPECT_EQ(las_classification(SurfaceClass::fog), 18);      // ASPRS "High Noise"
  EXPECT_EQ(las_classification(SurfaceClass::noise), 7);     // ASPRS "Low Point (noise)"
  EXPECT_EQ(las_classification(std::nullopt), 0);
  EXPECT_EQ(las_scan_angle(12.0), 2000);
  EXPECT_EQ(las_scan_angle(-30.0), -5000);
  EXPECT_EQ(las_scan_angle(0.0031), 1);
  EXPECT_EQ(las_scan_angle(500.0), 30000);
  EXPECT_EQ(las_scan_angle(-500.0), -30000);
  EXPECT_EQ(las_scan_angle(std::numeric_limits<double>::quiet_NaN()), 0);
  EXPECT_EQ(las_date_utc(0).day_of_year, 1);
  EXPECT_EQ(las_date_utc(0).year, 1970);
  EXPECT_EQ(las_date_utc(-1).day_of_year, 365);
  EXPECT_EQ(las_date_utc(-1).year, 1969);
  EXPECT_EQ(las_date_utc(951782400).day_of_year, 60);    // 2000-02-29
  EXPECT_EQ(las_date_utc(1735603200).day_of_year, 366);  // 2024-12-31
  EXPECT_EQ(las_date_utc(1735603200).year, 2024);
}

TEST_F(LasWriterTest, HeaderBytesAtTheSpecOffsets) {
  const auto points = scattered_points(kLasOrigin, 250, 1500.0, 7);
  LasWriter writer(path(), options_at(kLasOrigin));
  writer.write(std::span(points).first(100));
  writer.write(std::span(points).subspan(100));
  writer.finish();
  const auto bytes = read_bytes(path());
  const std::string wkt = utm_wkt(32, true);
  const std::size_t offset_to_points = 375 + 54 + wkt.size() + 1;
  ASSERT_EQ(bytes.size(), offset_to_points + 30 * points.size());

  EXPECT_EQ(field_text(bytes, 0, 4), "LASF");
  EXPECT_EQ(field<std::uint16_t>(bytes, 4), 0);       // file source ID
  EXPECT_EQ(field<std::uint16_t>(bytes, 6), 1 << 4);  // WKT; GPS week time
  EXPECT_EQ(bytes[24], 1);
  EXPECT_EQ(bytes[25], 4);
  EXPECT_EQ(field_text(bytes, 26, 32), std::string("owsim") + std::string(27, '\0'));
  const std::string software = std::string("owsim ") + version_string;
  EXPECT_EQ(field_text(bytes, 58, 32), software + std::string(32 - software.size(), '\0'));
  EXPECT_EQ(field<std::uint16_t>(bytes, 90), 60);
  EXPECT_EQ(field<std::uint16_t>(bytes, 92), 2024);
  EXPECT_EQ(field<std::uint16_t>(bytes, 94), 375);
  EXPECT_EQ(field<std::uint32_t>(bytes, 96), offset_to_points);
  EXPECT_EQ(field<std::uint32_t>(bytes, 100), 1u);
  EXPECT_EQ(bytes[104], 6);
  EXPECT_EQ(field<std::uint16_t>(bytes, 105), 30);
  for (std::size_t offset = 107; offset < 131; offset += 4) {
    EXPECT_EQ(field<std::uint32_t>(bytes, offset), 0u) << "legacy count at " << offset;
  }
  const UtmPoint origin = utm_from_geodetic(kLasOrigin.lat_deg, kLasOrigin.lon_deg);
  EXPECT_EQ(writer.grid().zone, 32);
  EXPECT_TRUE(writer.grid().northp);
  for (std::size_t axis = 0; axis < 3; ++axis) EXPECT_EQ(field_double(bytes, 131 + 8 * axis), 1e-4);
  EXPECT_EQ(field_double(bytes, 155), std::round(origin.easting_m / 1000.0) * 1000.0);
  EXPECT_EQ(field_double(bytes, 163), std::round(origin.northing_m / 1000.0) * 1000.0);
  EXPECT_EQ(field_double(bytes, 171), 450.0);
  EXPECT_EQ(field<std::uint64_t>(bytes, 227), 0u);  // no waveform data
  EXPECT_EQ(field<std::uint64_t>(bytes, 235), 0u);  // no EVLR
  EXPECT_EQ(field<std::uint32_t>(bytes, 243), 0u);
  EXPECT_EQ(field<std::uint64_t>(bytes, 247), points.size());
  std::array<std::uint64_t, 15> by_return{};
  for (const PointRecord& p : points) ++by_return[static_cast<std::size_t>(p.return_number - 1)];
  for (std::size_t r = 0; r < 15; ++r) {
    EXPECT_EQ(field<std::uint64_t>(bytes, 255 + 8 * r), by_return[r]) << "return " << r + 1;
  }
  EXPECT_GT(by_return[1], 0u);

  // The WKT record right after the header.
  EXPECT_EQ(field<std::uint16_t>(bytes, 375), 0);
  EXPECT_EQ(field_text(bytes, 377, 16), std::string("LASF_Projection") + '\0');
  EXPECT_EQ(field<std::uint16_t>(bytes, 393), 2112);
  EXPECT_EQ(field<std::uint16_t>(bytes, 395), wkt.size() + 1);
  EXPECT_EQ(field_text(bytes, 429, wkt.size() + 1), wkt + '\0');

  // The first point, field by field.
  const PointRecord& p = points[0];
  const UtmPoint utm = utm_from_geodetic(p.geodetic.lat_deg, p.geodetic.lon_deg);
  const std::size_t at = offset_to_points;
  EXPECT_EQ(static_cast<std::int32_t>(field<std::uint32_t>(bytes, at)),
            std::lround((utm.easting_m - field_double(bytes, 155)) / 1e-4));
  EXPECT_EQ(static_cast<std::int32_t>(field<std::uint32_t>(bytes, at + 4)),
            std::lround((utm.northing_m - field_double(bytes, 163)) / 1e-4));
  EXPECT_EQ(static_cast<std::int32_t>(field<std::uint32_t>(bytes, at + 8)),
            std::lround((p.geodetic.h_m - 450.0) / 1e-4));
  EXPECT_EQ(field<std::uint16_t>(bytes, at + 12), las_intensity(p.energy_rel, 1.0));
  EXPECT_EQ(bytes[at + 14], p.return_number | (p.number_of_returns << 4));
  EXPECT_EQ(bytes[at + 15], 0);
  EXPECT_EQ(bytes[at + 16], 14);  // point 0 is a wire
  EXPECT_EQ(bytes[at + 17], p.fiber);
  EXPECT_EQ(static_cast<std::int16_t>(field<std::uint16_t>(bytes, at + 18)),
            las_scan_angle(p.scan_angle_deg));
  EXPECT_EQ(field<std::uint16_t>(bytes, at + 20), 0);
  EXPECT_EQ(field_double(bytes, at + 22), p.time_s);
}

// The independent reader: the file as the spec describes it, decoded in Python with numpy, the
// coordinates checked against pyproj's UTM of each point's latitude and longitude.
constexpr const char* kPythonLasReader = R"PY(
import struct, sys
import numpy as np
from pyproj import CRS, Transformer

las_path, expected_path, epsg = sys.argv[1], sys.argv[2], int(sys.argv[3])
data = open(las_path, 'rb').read()
u = lambda fmt, off: struct.unpack_from('<' + fmt, data, off)
assert data[0:4] == b'LASF', data[0:4]
assert u('H', 6)[0] == 16, u('H', 6)
assert (data[24], data[25]) == (1, 4)
assert data[26:58].rstrip(b'\0') == b'owsim'
assert data[58:90].startswith(b'owsim ')
assert u('H', 94)[0] == 375
offset_to_points, n_vlr, fmt, rec_len = u('I', 96)[0], u('I', 100)[0], data[104], u('H', 105)[0]
assert (n_vlr, fmt, rec_len) == (1, 6, 30), (n_vlr, fmt, rec_len)
assert u('I', 107)[0] == 0 and u('5I', 111) == (0,) * 5  # legacy counts: 0 for format >= 6
scale = np.array(u('3d', 131)); offset = np.array(u('3d', 155))
max_x, min_x, max_y, min_y, max_z, min_z = u('6d', 179)
assert u('QQI', 227) == (0, 0, 0)
count = u('Q', 247)[0]
by_return = u('15Q', 255)
assert np.all(scale == 1e-4), scale

# VLR: LASF_Projection / 2112, null-terminated OGC WKT.
reserved, user_id, record_id, length, _ = struct.unpack_from('<H16sHH32s', data, 375)
assert reserved == 0 and user_id.rstrip(b'\0') == b'LASF_Projection' and record_id == 2112
wkt_bytes = data[375 + 54:375 + 54 + length]
assert wkt_bytes.endswith(b'\0') and wkt_bytes.count(b'\0') == 1
assert 375 + 54 + length == offset_to_points
crs = CRS(wkt_bytes[:-1].decode('utf-8'))
assert crs.to_epsg() == epsg, crs.to_epsg()

dtype = np.dtype([('x', '<i4'), ('y', '<i4'), ('z', '<i4'), ('intensity', '<u2'),
                  ('returns', 'u1'), ('flags', 'u1'), ('classification', 'u1'),
                  ('user_data', 'u1'), ('scan_angle', '<i2'), ('point_source', '<u2'),
                  ('gps_time', '<f8')])
assert dtype.itemsize == 30
assert len(data) == offset_to_points + count * 30, (len(data), offset_to_points, count)
pts = np.frombuffer(data, dtype=dtype, count=count, offset=offset_to_points)
xyz = np.stack([pts['x'], pts['y'], pts['z']], axis=1) * scale + offset

exp = np.loadtxt(expected_path, delimiter=',', ndmin=2)
lat, lon, h, cls, ret, nret, t, energy, beta, fiber = exp.T
assert count == len(exp), (count, len(exp))
to_utm = Transformer.from_crs('EPSG:4326', crs, always_xy=True)
e, n = to_utm.transform(lon, lat)
tolerance = 0.5e-4 + 2e-6
assert np.max(np.abs(xyz[:, 0] - e)) <= tolerance, np.max(np.abs(xyz[:, 0] - e))
assert np.max(np.abs(xyz[:, 1] - n)) <= tolerance, np.max(np.abs(xyz[:, 1] - n))
assert np.max(np.abs(xyz[:, 2] - h)) <= tolerance, np.max(np.abs(xyz[:, 2] - h))
assert (max_x, min_x) == (xyz[:, 0].max(), xyz[:, 0].min()), (max_x, min_x)
assert (max_y, min_y) == (xyz[:, 1].max(), xyz[:, 1].min()), (max_y, min_y)
assert (max_z, min_z) == (xyz[:, 2].max(), xyz[:, 2].min()), (max_z, min_z)

# wire, pole, tree, ground, building, fog (high noise), noise (low noise), unknown
codes = {0: 14, 1: 15, 2: 5, 3: 2, 4: 6, 5: 18, 6: 7, -1: 0}
assert set(int(c) for c in cls) == set(codes), sorted(set(cls))
assert np.array_equal(pts['classification'], [codes[int(c)] for c in cls])
assert np.array_equal(pts['returns'] & 0x0F, ret)
assert np.array_equal(pts['returns'] >> 4, nret)
assert by_return[0] == np.sum(ret == 1) and by_return[1] == np.sum(ret == 2)
assert all(v == 0 for v in by_return[2:])
assert np.array_equal(pts['gps_time'], t)
want_intensity = np.where(np.isnan(energy), 0,
                          np.floor(np.clip(np.nan_to_num(energy), 0, 1) * 65535 + 0.5))
assert np.array_equal(pts['intensity'], want_intensity)
assert np.array_equal(pts['scan_angle'], np.floor(beta / 0.006 + 0.5))
assert np.array_equal(pts['user_data'], fiber)
assert np.all(pts['flags'] == 0) and np.all(pts['point_source'] == 0)
print('OK', count)
)PY";

// Writes the points' expected values for the Python reader: lat, lon, h, class (owsim's code,
// geometry/scene.hpp; −1 unknown), return, returns, time, energy (nan), β, fiber; 17 digits, so
// every double reads back exactly.
void write_expected(const std::filesystem::path& path, const std::vector<PointRecord>& points) {
  std::ofstream out(path);
  out.precision(17);
  for (const PointRecord& p : points) {
    int surface = -1;
    if (p.surface) surface = static_cast<int>(*p.surface);
    out << p.geodetic.lat_deg << ',' << p.geodetic.lon_deg << ',' << p.geodetic.h_m << ','
        << surface << ',' << p.return_number << ',' << p.number_of_returns << ',' << p.time_s << ','
        << p.energy_rel << ',' << p.scan_angle_deg << ',' << p.fiber << '\n';
  }
}

// What the independent reader says of the LAS file `las` written from `points` in the grid
// `epsg`: "OK <count>\n", or the assertion it failed.
std::string python_reader_verdict(const std::filesystem::path& las,
                                  const std::vector<PointRecord>& points, int epsg) {
  const test::TempDir folder("owsim_las_oracle");
  write_expected(folder / "expected.csv", points);
  return test::run_python(kPythonLasReader,
                          {.arguments = las.string() + " " + (folder / "expected.csv").string() +
                                        " " + std::to_string(epsg),
                           .with_stderr = true});
}

TEST_F(LasWriterTest, AnIndependentPythonReaderDecodesEveryPoint) {
  const auto points = scattered_points(kLasOrigin, 400, 2000.0, 11);
  LasWriter writer(path(), options_at(kLasOrigin));
  writer.write(points);
  writer.finish();
  EXPECT_EQ(python_reader_verdict(path(), points, 32632), "OK 400\n");
}

TEST_F(LasWriterTest, AFlightAcrossTheZoneEdgeAndTheEquatorStaysInTheOriginsGrid) {
  // Origin in 32S just west of 12°E and south of the equator: the points spread into zone 33
  // and into the northern hemisphere, and are all stored in WGS 84 / UTM zone 32S.
  const Geodetic origin{-0.005, 11.995, 20.0};
  const auto points = scattered_points(origin, 300, 3000.0, 5);
  int in_zone_33 = 0, north = 0;
  for (const PointRecord& p : points) {
    const UtmPoint utm = utm_from_geodetic(p.geodetic.lat_deg, p.geodetic.lon_deg);
    if (utm.zone == 33) ++in_zone_33;
    if (utm.northp) ++north;
  }
  ASSERT_GT(in_zone_33, 0);
  ASSERT_GT(north, 0);
  LasWriter writer(path(), options_at(origin));
  EXPECT_EQ(writer.grid().zone, 32);
  EXPECT_FALSE(writer.grid().northp);
  writer.write(points);
  writer.finish();
  EXPECT_EQ(python_reader_verdict(path(), points, 32732), "OK 300\n");
}

TEST_F(LasWriterTest, NearThePoleTheGridIsUps) {
  const Geodetic origin{86.5, 30.0, 100.0};
  const auto points = scattered_points(origin, 200, 2500.0, 9);
  LasWriter writer(path(), options_at(origin));
  EXPECT_EQ(writer.grid().zone, 0);
  EXPECT_TRUE(writer.grid().northp);
  writer.write(points);
  writer.finish();
  EXPECT_EQ(python_reader_verdict(path(), points, 5041), "OK 200\n");
}

TEST_F(LasWriterTest, CreationDateDefaultsToTodayUtc) {
  LasWriterOptions options;
  options.origin = kLasOrigin;
  const LasDate before = las_date_utc(std::time(nullptr));
  {
    LasWriter writer(path(), options);
    writer.finish();
  }
  const LasDate after = las_date_utc(std::time(nullptr));
  const auto bytes = read_bytes(path());
  const int day = field<std::uint16_t>(bytes, 90), year = field<std::uint16_t>(bytes, 92);
  EXPECT_TRUE((day == before.day_of_year && year == before.year) ||
              (day == after.day_of_year && year == after.year))
      << day << " " << year;
  EXPECT_GE(year, 2024);
}

TEST_F(LasWriterTest, AnEmptyFileHasZeroCountsAndBounds) {
  LasWriter writer(path(), options_at(kLasOrigin));
  writer.finish();
  const auto bytes = read_bytes(path());
  ASSERT_EQ(bytes.size(), field<std::uint32_t>(bytes, 96));
  EXPECT_EQ(field<std::uint64_t>(bytes, 247), 0u);
  for (std::size_t offset = 179; offset < 227; offset += 8) {
    EXPECT_EQ(field_double(bytes, offset), 0.0) << offset;
  }
}

TEST_F(LasWriterTest, PointsBeyondTheInt32RangeOrWithBadReturnNumbersThrow) {
  LasWriter writer(path(), options_at(kLasOrigin));
  PointRecord far;
  far.geodetic = {kLasOrigin.lat_deg, kLasOrigin.lon_deg + 3.5, 450.0};  // ≈ 257 km east
  EXPECT_THROW(writer.write(std::span(&far, 1)), Error);
  PointRecord high;
  high.geodetic = {kLasOrigin.lat_deg, kLasOrigin.lon_deg, 450.0 + 215000.0};
  EXPECT_THROW(writer.write(std::span(&high, 1)), Error);
  PointRecord bad_return;
  bad_return.geodetic = kLasOrigin;
  bad_return.return_number = 2;
  bad_return.number_of_returns = 1;
  EXPECT_THROW(writer.write(std::span(&bad_return, 1)), Error);
  bad_return.return_number = 0;
  EXPECT_THROW(writer.write(std::span(&bad_return, 1)), Error);
  EXPECT_EQ(writer.points_written(), 0u);
}

TEST_F(LasWriterTest, BadOptionsThrow) {
  LasWriterOptions options = options_at(kLasOrigin);
  options.scale_m = 0;
  EXPECT_THROW({ LasWriter writer(path(), options); }, Error);
  options = options_at(kLasOrigin);
  options.intensity_full_scale = -1;
  EXPECT_THROW({ LasWriter writer(path(), options); }, Error);
  options = options_at({91.0, 0.0, 0.0});
  EXPECT_THROW({ LasWriter writer(path(), options); }, Error);
  EXPECT_FALSE(std::filesystem::exists(path()));
}

TEST_F(LasWriterTest, NothingUnderTheFinalNameBeforeFinishOrAfterAFailure) {
  const auto points = scattered_points(kLasOrigin, 10, 100.0, 3);
  {
    LasWriter writer(path(), options_at(kLasOrigin));
    writer.write(points);
    EXPECT_FALSE(std::filesystem::exists(path()));
    writer.finish();
    EXPECT_TRUE(std::filesystem::exists(path()));
  }
  const auto other = directory_ / "other.las";
  try {
    LasWriter writer(other, options_at(kLasOrigin));
    writer.write(points);
    throw std::runtime_error("simulation failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(std::filesystem::exists(other));
  EXPECT_FALSE(std::filesystem::exists(AtomicOutputFile::partial_path_for(other)));
}

}  // namespace
}  // namespace owsim
