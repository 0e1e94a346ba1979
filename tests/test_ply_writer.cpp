// Protects points.ply (INTERFACE.md "`owsim run` outputs"): a binary little-endian PLY whose
// fixed-length header holds the real vertex count after finish(), read back by a strict
// independent parser in Python (header grammar, property sizes, exact data length) and numpy;
// also the class codes and the atomic-output rules.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/points/ply_writer.hpp"
#include "python_oracle.hpp"

namespace owsim {
namespace {

using test::run_python;

class PlyWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = std::filesystem::temp_directory_path() /
                 ("owsim_test_ply_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  [[nodiscard]] std::filesystem::path path() const { return directory_ / "points.ply"; }

  std::filesystem::path directory_;
};

// A strict PLY reader: every header line must be exactly a PLY keyword line (single spaces, a
// count without sign or leading zeros, known scalar types); the body must be exactly
// count × record size bytes; then numpy reads it with the header's count and property list.
constexpr const char* kPythonPlyReader = R"PY(
import os, re, sys
import numpy as np

ply_path, expected_path = sys.argv[1], sys.argv[2]
data = open(ply_path, 'rb').read()
end = data.find(b'end_header\n')
assert end > 0
header = data[:end + len(b'end_header\n')].decode('ascii')
lines = header.split('\n')[:-1]
assert lines[0] == 'ply' and lines[1] == 'format binary_little_endian 1.0', lines[:2]
assert lines[-1] == 'end_header'
sizes = {'char': 1, 'uchar': 1, 'short': 2, 'ushort': 2, 'int': 4, 'uint': 4, 'float': 4,
         'double': 8, 'int8': 1, 'uint8': 1, 'int16': 2, 'uint16': 2, 'int32': 4, 'uint32': 4,
         'float32': 4, 'float64': 8}
numpy_type = {'double': '<f8', 'float': '<f4', 'uchar': 'u1'}
elements = []
for line in lines[2:-1]:
    if line.startswith('comment ') or line == 'comment':
        continue
    assert line == ' '.join(line.split()), repr(line)
    words = line.split(' ')
    if words[0] == 'element':
        assert len(words) == 3 and re.fullmatch(r'0|[1-9][0-9]*', words[2]), repr(line)
        elements.append((words[1], int(words[2]), []))
    elif words[0] == 'property':
        assert len(words) == 3 and words[1] in sizes and elements, repr(line)
        elements[-1][2].append((words[2], words[1]))
    else:
        raise AssertionError('not a PLY header line: ' + repr(line))
assert len(elements) == 1 and elements[0][0] == 'vertex', elements
name, count, properties = elements[0]
assert properties == [('x', 'double'), ('y', 'double'), ('z', 'double'),
                      ('intensity', 'float'), ('class', 'uchar')], properties
record = sum(sizes[t] for _, t in properties)
body = data[len(header):]
assert len(body) == count * record, (len(body), count, record)
dtype = np.dtype([(n, numpy_type[t]) for n, t in properties])
vertices = np.frombuffer(body, dtype=dtype, count=count)

exp = (np.loadtxt(expected_path, delimiter=',', ndmin=2) if os.path.getsize(expected_path)
       else np.zeros((0, 5)))
assert len(exp) == count, (len(exp), count)
assert np.array_equal(vertices['x'], exp[:, 0])
assert np.array_equal(vertices['y'], exp[:, 1])
assert np.array_equal(vertices['z'], exp[:, 2])
assert np.array_equal(vertices['intensity'], exp[:, 3].astype(np.float32), equal_nan=True)
assert np.array_equal(vertices['class'], exp[:, 4])
print('OK', count, 'noise', int(np.sum(vertices['class'] == 7)))
)PY";

std::vector<PointRecord> scattered_points(int count) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> coordinate(-3000.0, 3000.0), energy(0.0, 1.0);
  std::vector<PointRecord> points;
  for (int k = 0; k < count; ++k) {
    PointRecord p;
    p.enu_m = {coordinate(rng), coordinate(rng), coordinate(rng) / 10.0};
    p.energy_rel = (k % 13 == 0) ? std::numeric_limits<double>::quiet_NaN() : energy(rng);
    const int code = k % (static_cast<int>(kSurfaceClassCount) + 1);  // every class, unknown
    if (code < static_cast<int>(kSurfaceClassCount)) p.surface = static_cast<SurfaceClass>(code);
    if (p.surface == SurfaceClass::noise) p.energy_rel = 0.0029;  // a false return: T
    points.push_back(p);
  }
  return points;
}

// The class column INTERFACE.md gives, by owsim's class code (geometry/scene.hpp): wire, pole,
// tree, ground, building, fog, noise ("PLY class 7").
constexpr int kExpectedPlyClass[] = {0, 1, 2, 3, 4, 5, 7};

void write_expected(const std::filesystem::path& path, const std::vector<PointRecord>& points) {
  std::ofstream out(path);
  out.precision(17);
  for (const PointRecord& p : points) {
    const int expected_class = p.surface ? kExpectedPlyClass[static_cast<int>(*p.surface)] : 255;
    out << p.enu_m.x() << ',' << p.enu_m.y() << ',' << p.enu_m.z() << ',' << p.energy_rel << ','
        << expected_class << '\n';
  }
}

TEST(PlyHeader, LengthDoesNotDependOnTheCount) {
  const std::size_t length = ply_header(0).size();
  EXPECT_EQ(ply_header(42).size(), length);
  EXPECT_EQ(ply_header(123456789012).size(), length);
  EXPECT_EQ(ply_header(std::numeric_limits<std::uint64_t>::max()).size(), length);
  EXPECT_NE(ply_header(42).find("\nelement vertex 42\n"), std::string::npos);
  EXPECT_NE(ply_header(std::numeric_limits<std::uint64_t>::max())
                .find("\nelement vertex 18446744073709551615\n"),
            std::string::npos);
}

TEST(PlyHeader, ClassCodes) {
  EXPECT_EQ(ply_class(SurfaceClass::wire), 0);
  EXPECT_EQ(ply_class(SurfaceClass::pole), 1);
  EXPECT_EQ(ply_class(SurfaceClass::tree), 2);
  EXPECT_EQ(ply_class(SurfaceClass::ground), 3);
  EXPECT_EQ(ply_class(SurfaceClass::building), 4);
  EXPECT_EQ(ply_class(SurfaceClass::fog), 5);
  EXPECT_EQ(ply_class(SurfaceClass::noise), 7);  // INTERFACE.md "PLY class 7"
  EXPECT_EQ(ply_class(std::nullopt), 255);
}

TEST_F(PlyWriterTest, AStrictPythonReaderAndNumpyReadEveryVertex) {
  const auto points = scattered_points(50000);  // more than the 1 MiB buffer
  PlyWriter writer(path());
  for (std::size_t first = 0; first < points.size(); first += 20352) {
    writer.write(
        std::span(points).subspan(first, std::min<std::size_t>(20352, points.size() - first)));
  }
  writer.finish();
  EXPECT_EQ(writer.points_written(), points.size());
  EXPECT_EQ(std::filesystem::file_size(path()), ply_header(0).size() + 29 * points.size());
  write_expected(directory_ / "expected.csv", points);
  EXPECT_EQ(run_python(kPythonPlyReader,
                       {.arguments = path().string() + " " + (directory_ / "expected.csv").string(),
                        .with_stderr = true}),
            "OK 50000 noise 6250\n");
}

TEST_F(PlyWriterTest, AnEmptyCloudIsAValidFile) {
  PlyWriter writer(path());
  writer.finish();
  std::ofstream(directory_ / "expected.csv");
  EXPECT_EQ(run_python(kPythonPlyReader,
                       {.arguments = path().string() + " " + (directory_ / "expected.csv").string(),
                        .with_stderr = true}),
            "OK 0 noise 0\n");
}

TEST_F(PlyWriterTest, NothingUnderTheFinalNameBeforeFinishOrAfterAFailure) {
  const auto points = scattered_points(10);
  {
    PlyWriter writer(path());
    writer.write(points);
    EXPECT_FALSE(std::filesystem::exists(path()));
    writer.finish();
    EXPECT_TRUE(std::filesystem::exists(path()));
  }
  const auto other = directory_ / "other.ply";
  try {
    PlyWriter writer(other);
    writer.write(points);
    throw std::runtime_error("simulation failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(std::filesystem::exists(other));
  EXPECT_FALSE(std::filesystem::exists(AtomicOutputFile::partial_path_for(other)));
}

}  // namespace
}  // namespace owsim
