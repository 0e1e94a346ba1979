// Protects the typed, key-tracking YAML reader (io/scenario/yaml_reader.hpp): typed values, 1-based
// lines, dotted key paths, unknown and repeated keys (pbrt's ReportUnused), and relocated validator
// errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "io/scenario/yaml_reader.hpp"

namespace owsim {
namespace {

// The message of the owsim::Error `action` throws; a failure if it throws none.
std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no owsim::Error thrown";
  return {};
}

constexpr const char* kText = R"(name: demo
sensor:
  threshold: 0.25
  prf_hz: 1e3
  count: +7
  big: 18446744073709551615
  on: yes
  model: hellas
  table: [1, -2.5, 3]
  word: abc
  nan: .nan
  inf: inf
  half: 1.5
  negative: -1
scene:
  spans:
    - id: a
    - id: b
      conductor: {diameter_mm: 20}
)";

TEST(YamlReader, TypedValuesAndPaths) {
  const YamlSource source = YamlSource::from_text(kText, "f.yaml");
  YamlMap root(source.root());
  EXPECT_EQ(root.require("name").text(), "demo");
  YamlMap sensor(root.require("sensor"));
  EXPECT_EQ(sensor.path(), "sensor");
  const YamlValue threshold = sensor.require("threshold");
  EXPECT_EQ(threshold.path(), "sensor.threshold");
  EXPECT_EQ(threshold.line(), 3);
  EXPECT_DOUBLE_EQ(threshold.number(), 0.25);
  EXPECT_DOUBLE_EQ(sensor.number_or("prf_hz", 0.0), 1000.0);
  EXPECT_EQ(sensor.require("count").integer(0, 10), 7);
  EXPECT_EQ(sensor.require("big").unsigned_integer(), 18446744073709551615ULL);
  EXPECT_TRUE(sensor.boolean_or("on", false));
  EXPECT_FALSE(sensor.boolean_or("absent", false));
  EXPECT_EQ(sensor.optional_number("absent"), std::nullopt);
  EXPECT_DOUBLE_EQ(sensor.number_or("absent", 4.5), 4.5);
  EXPECT_EQ(sensor.require("model").one_of({"milows", "hellas"}), "hellas");
  EXPECT_EQ(sensor.require("table").numbers(3), (std::vector<double>{1.0, -2.5, 3.0}));

  const std::vector<YamlValue> spans = YamlMap(root.require("scene")).require("spans").items();
  ASSERT_EQ(spans.size(), 2u);
  EXPECT_EQ(spans[1].path(), "scene.spans[1]");
  EXPECT_EQ(spans[1].line(), 18);
  YamlMap span(spans[1]);
  const YamlValue conductor = span.require("conductor");
  EXPECT_EQ(conductor.path(), "scene.spans[1].conductor");
  EXPECT_EQ(conductor.line(), 19);
  EXPECT_EQ(source.line_of("scene.spans[1].conductor.diameter_mm"), 19);  // nearest read ancestor
  EXPECT_EQ(source.line_of("scene.spans[0]"), 17);
  EXPECT_EQ(source.line_of("nowhere.at.all"), 1);
}

TEST(YamlReader, WrongTypesNameFileLineAndKey) {
  const YamlSource source = YamlSource::from_text(kText, "f.yaml");
  YamlMap root(source.root());
  YamlMap sensor(root.require("sensor"));
  EXPECT_EQ(error_of([&] { (void)sensor.require("word").number(); }),
            "f.yaml:10: sensor.word: expected a number, got 'abc'");
  EXPECT_EQ(error_of([&] { (void)sensor.require("nan").number(); }),
            "f.yaml:11: sensor.nan: expected a number, got '.nan'");
  EXPECT_EQ(error_of([&] { (void)sensor.require("inf").number(); }),
            "f.yaml:12: sensor.inf: expected a finite number, got 'inf'");
  EXPECT_EQ(error_of([&] { (void)sensor.require("half").integer(0, 9); }),
            "f.yaml:13: sensor.half: expected an integer, got '1.5'");
  EXPECT_EQ(error_of([&] { (void)sensor.require("count").integer(0, 5); }),
            "f.yaml:5: sensor.count: must be an integer in [0, 5], got 7");
  EXPECT_EQ(error_of([&] { (void)sensor.require("negative").unsigned_integer(); }),
            "f.yaml:14: sensor.negative: expected a non-negative integer, got '-1'");
  EXPECT_EQ(error_of([&] { (void)sensor.require("word").boolean(); }),
            "f.yaml:10: sensor.word: expected true or false, got 'abc'");
  EXPECT_EQ(error_of([&] {
              (void)sensor.require("word").one_of({"x", "y"});
            }),
            "f.yaml:10: sensor.word: expected one of x | y, got 'abc'");
  EXPECT_EQ(error_of([&] { (void)sensor.require("table").numbers(2); }),
            "f.yaml:9: sensor.table: expected a list of 2 numbers, got a list of 3");
  EXPECT_EQ(error_of([&] { (void)sensor.require("table").text(); }),
            "f.yaml:9: sensor.table: expected a text, got a list");
  EXPECT_EQ(error_of([&] { (void)YamlMap(sensor.require("word")); }),
            "f.yaml:10: sensor.word: expected a mapping {key: value, ...}, got 'abc'");
  EXPECT_EQ(error_of([&] { (void)sensor.require("model").items(); }),
            "f.yaml:8: sensor.model: expected a list [...], got 'hellas'");
  EXPECT_EQ(error_of([&] { (void)sensor.require("missing"); }),
            "f.yaml:2: sensor.missing: required, but missing from sensor");
  EXPECT_EQ(error_of([&] { (void)root.require("origin"); }),
            "f.yaml:1: origin: required, but missing from the file");
}

TEST(YamlReader, UnknownKeysAreErrorsAtAnyDepth) {
  const YamlSource source = YamlSource::from_text(R"(sensor:
  treshold: 0.1
scene:
  spans:
    - id: a
      conductor: {diameter_mm: 20}
    - id: b
      conductor:
        diamter_mm: 20
        reflectivity: 0.4
extra: 1
)",
                                                  "g.yaml");
  YamlMap root(source.root());
  YamlMap sensor(root.require("sensor"));
  (void)sensor.get("threshold");
  EXPECT_EQ(error_of([&] { sensor.finish(); }),
            "g.yaml:2: sensor.treshold: unknown key 'treshold' in sensor (did you mean "
            "'threshold'?)");

  YamlMap scene(root.require("scene"));
  const std::vector<YamlValue> spans = scene.require("spans").items();
  for (const YamlValue& item : spans) {
    YamlMap span(item);
    (void)span.require("id");
    YamlMap conductor(span.require("conductor"));
    (void)conductor.get("diameter_mm");
    (void)conductor.get("reflectivity");
    if (item.path() == "scene.spans[1]") {
      EXPECT_EQ(error_of([&] { conductor.finish(); }),
                "g.yaml:9: scene.spans[1].conductor.diamter_mm: unknown key 'diamter_mm' in "
                "scene.spans[1].conductor (did you mean 'diameter_mm'?)");
    } else {
      EXPECT_NO_THROW(conductor.finish());
    }
    EXPECT_NO_THROW(span.finish());
  }
  EXPECT_NO_THROW(scene.finish());
  // A key far from every known one lists the known keys instead.
  EXPECT_EQ(error_of([&] { root.finish(); }),
            "g.yaml:11: extra: unknown key 'extra' in the file (known keys: scene, sensor)");
}

TEST(YamlReader, ContainsDoesNotMarkAKeyRead) {
  const YamlSource source = YamlSource::from_text("a: 1\nb: 2\n", "h.yaml");
  YamlMap root(source.root());
  EXPECT_TRUE(root.contains("a"));
  EXPECT_FALSE(root.contains("c"));
  (void)root.get("b");
  EXPECT_EQ(error_of([&] { root.finish(); }),
            "h.yaml:1: a: unknown key 'a' in the file (known keys: b)");
}

TEST(YamlReader, RepeatedKeyIsAnError) {
  const YamlSource source =
      YamlSource::from_text("a: 1\nsensor:\n  x: 1\n  y: 2\n  x: 3\n", "d.yaml");
  YamlMap root(source.root());
  EXPECT_EQ(error_of([&] { (void)YamlMap(root.require("sensor")); }),
            "d.yaml:5: sensor.x: key 'x' given twice in sensor (first at line 3)");
}

TEST(YamlReader, MalformedYamlNamesTheLine) {
  const std::string message =
      error_of([] { (void)YamlSource::from_text("a: 1\nb: [1, 2\nc: 3\n", "bad.yaml"); });
  EXPECT_EQ(message.rfind("bad.yaml:", 0), 0u) << message;
  EXPECT_NE(message.find("malformed YAML"), std::string::npos) << message;
  const std::string tabs =
      error_of([] { (void)YamlSource::from_text("a:\n  b: 1\n c: 2\n", "indent.yaml"); });
  EXPECT_EQ(tabs.rfind("indent.yaml:3: malformed YAML: ", 0), 0u) << tabs;
}

TEST(YamlReader, EmptyDocumentIsNotAMapping) {
  const YamlSource source = YamlSource::from_text("", "empty.yaml");
  EXPECT_EQ(error_of([&] { (void)YamlMap(source.root()); }),
            "empty.yaml:1: the file: expected a mapping {key: value, ...}, got nothing");
}

TEST(YamlReader, UnreadableFile) {
  EXPECT_EQ(error_of([] { (void)YamlSource::from_file("/nonexistent/owsim/x.yaml"); }),
            "/nonexistent/owsim/x.yaml: cannot read the YAML file: no such file");
}

TEST(YamlReader, FromFileReadsTheFile) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "owsim_yaml_reader.yaml";
  { std::ofstream(path) << "# comment\nvalue: 3\n"; }
  const YamlSource source = YamlSource::from_file(path);
  YamlMap root(source.root());
  const YamlValue value = root.require("value");
  EXPECT_EQ(value.number(), 3.0);
  EXPECT_EQ(value.location(), path.string() + ":2");
  std::filesystem::remove(path);
}

TEST(YamlReader, ValidatorErrorsMoveToTheKeyLine) {
  const YamlSource source = YamlSource::from_text(R"(sensor:
  prf_hz: -5
  counter:
    timeout_counts: 9
trajectory:
  start_s: 1
)",
                                                  "v.yaml");
  YamlMap root(source.root());
  YamlMap sensor(root.require("sensor"));
  (void)sensor.get("prf_hz");
  YamlMap counter(sensor.require("counter"));
  (void)counter.get("timeout_counts");
  (void)YamlMap(root.require("trajectory")).get("start_s");
  const std::map<std::string, std::string> renamed = {
      {"sensor.timeout_counts", "sensor.counter.timeout_counts"}};

  // The key itself was read.
  EXPECT_EQ(error_of([&] { source.rethrow_at_key(Error("sensor.prf_hz: must be > 0"), "sensor"); }),
            "v.yaml:2: sensor.prf_hz: must be > 0");
  // Renamed to the file's path.
  EXPECT_EQ(error_of([&] {
              source.rethrow_at_key(Error("sensor.timeout_counts: too big"), "sensor", renamed);
            }),
            "v.yaml:4: sensor.counter.timeout_counts: too big");
  // A defaulted key: the line of its nearest read ancestor.
  EXPECT_EQ(error_of([&] { source.rethrow_at_key(Error("sensor.sweep_deg: too wide"), "sensor"); }),
            "v.yaml:1: sensor.sweep_deg: too wide");
  // A message that names no key goes under the fallback path.
  EXPECT_EQ(error_of([&] {
              source.rethrow_at_key(Error("UTM position \"x\": bad zone"), "trajectory.start_s");
            }),
            "v.yaml:6: trajectory.start_s: UTM position \"x\": bad zone");
  EXPECT_EQ(error_of([&] { source.rethrow_at_key(Error("plain sentence"), "trajectory"); }),
            "v.yaml:5: trajectory: plain sentence");
}

}  // namespace
}  // namespace owsim
