#pragma once
// A typed, key-tracking reader over yaml-cpp nodes for owsim's input files (STYLE.md "What owsim
// takes" 4, after pbrt-v4's ParameterDictionary::ReportUnused): every key a reader asks for is
// marked, and once a mapping is read, any key nobody asked for is an error, so a misspelled key
// never passes silently. Typed getters turn a wrong value into one owsim::Error line,
//   "<file>:<line>: <dotted key path>: <problem>"   e.g.
//   "flight.yaml:12: sensor.threshold: expected a number, got 'abc'",
// with 1-based lines (yaml-cpp's marks are 0-based) and paths like scene.spans[1].conductor.
// A mapping that repeats a key is an error (yaml-cpp would keep the first silently). Numbers are
// parsed with std::from_chars (locale-independent) and must be finite; integers must be written
// as integers and fit their range. The text must be UTF-8 ("<file>:<line>: not UTF-8 text …").
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/error.hpp"

namespace owsim {

class YamlValue;

// One parsed YAML file and the line of every key read from it so far.
class YamlSource {
 public:
  // Reads and parses a file. Throws owsim::Error "<file>: cannot read …" or, for malformed YAML,
  // "<file>:<line>: malformed YAML: <yaml-cpp's message>".
  [[nodiscard]] static YamlSource from_file(const std::filesystem::path& path);
  // Parses text in memory; `file_name` names it in errors.
  [[nodiscard]] static YamlSource from_text(std::string_view text, std::string file_name);

  // The document's top-level value, path "" (an empty file is a null value).
  [[nodiscard]] YamlValue root() const;
  [[nodiscard]] const std::string& file_name() const { return file_name_; }

  // 1-based line of the key read at `key_path` ("sensor.counter.timeout_counts",
  // "scene.spans[0]") or, if that key was never read, of its nearest ancestor that was; 1 when
  // none was.
  [[nodiscard]] int line_of(std::string_view key_path) const;

  // Re-throws an error from a validation function whose message starts with a key path
  // ("sensor.prf_hz: must be …") as "<file>:<line>: <key path>: …", at the line of that key (or
  // its nearest read ancestor). `renamed` maps key paths the validator uses to the path the file
  // uses ("sensor.timeout_counts" → "sensor.counter.timeout_counts"). A message that does not
  // start with a read key path is put under `fallback_path`:
  // "<file>:<line of fallback_path>: <fallback_path>: <message>".
  [[noreturn]] void rethrow_at_key(const Error& error, std::string_view fallback_path,
                                   const std::map<std::string, std::string>& renamed = {}) const;

  // A check of every number read (YamlValue::number, integer, numbers): the problem with `value`
  // at `key_path`, or "" when it is fine (io/scenario/value_ranges.hpp for scenarios).
  using RangeCheck = std::string (*)(std::string_view key_path, double value);
  void check_ranges_with(RangeCheck check) { range_check_ = check; }
  [[nodiscard]] RangeCheck range_check() const { return range_check_; }

  // Records that `key_path` was read at `line` (1-based); YamlMap does this for every key.
  void note_key(const std::string& key_path, int line) const { lines_[key_path] = line; }

  YamlSource(YamlSource&&) = default;
  YamlSource& operator=(YamlSource&&) = default;
  YamlSource(const YamlSource&) = delete;
  YamlSource& operator=(const YamlSource&) = delete;

 private:
  YamlSource(YAML::Node root, std::string file_name)
      : root_(std::move(root)), file_name_(std::move(file_name)) {}

  YAML::Node root_;
  std::string file_name_;
  mutable std::map<std::string, int, std::less<>> lines_;
  RangeCheck range_check_ = nullptr;
};

// One value of the file with its key path and line. Keeps a pointer to its YamlSource, which
// must outlive it.
class YamlValue {
 public:
  YamlValue(const YamlSource& source, YAML::Node node, std::string path, int line)
      : source_(&source), node_(std::move(node)), path_(std::move(path)), line_(line) {}

  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] int line() const { return line_; }  // 1-based, of the key (or list item)
  [[nodiscard]] const YamlSource& source() const { return *source_; }
  [[nodiscard]] const YAML::Node& node() const { return node_; }

  // Throws owsim::Error "<file>:<line>: <path>: <problem>".
  [[noreturn]] void fail(std::string_view problem) const;
  // "<file>:<line>" of this value, for messages that carry their own key path.
  [[nodiscard]] std::string location() const;

  [[nodiscard]] bool is_null() const { return node_.IsNull(); }
  [[nodiscard]] bool is_scalar() const { return node_.IsScalar(); }
  [[nodiscard]] bool is_list() const { return node_.IsSequence(); }
  [[nodiscard]] bool is_map() const { return node_.IsMap(); }

  // A finite number ("expected a number, got 'abc'").
  [[nodiscard]] double number() const;
  // An integer in [min, max] ("expected an integer, got '1.5'"; "… must be in [min, max] …").
  [[nodiscard]] std::int64_t integer(std::int64_t min, std::int64_t max) const;
  // A non-negative integer up to 2^64 − 1.
  [[nodiscard]] std::uint64_t unsigned_integer() const;
  // true/false (also yes/no, on/off, as YAML 1.1 writes them).
  [[nodiscard]] bool boolean() const;
  // A scalar as written, e.g. a name or a path.
  [[nodiscard]] std::string text() const;
  // A scalar that must be one of `choices` ("expected one of a | b, got 'c'").
  [[nodiscard]] std::string one_of(std::initializer_list<std::string_view> choices) const;
  // The items of a list, paths "<path>[i]".
  [[nodiscard]] std::vector<YamlValue> items() const;
  // A list of finite numbers; exactly `count` of them unless count is nullopt.
  [[nodiscard]] std::vector<double> numbers(std::optional<std::size_t> count = std::nullopt) const;

  // What the value is, for messages: "'abc'", "a list", "a mapping", "nothing".
  [[nodiscard]] std::string describe() const;

 private:
  void check_range(double value) const;  // the source's RangeCheck, if it has one

  const YamlSource* source_;
  YAML::Node node_;
  std::string path_;
  int line_;
};

// A mapping being read: get()/require() mark keys as read; finish() rejects every other key.
class YamlMap {
 public:
  // Throws owsim::Error unless `value` is a mapping whose keys are distinct scalars. Messages
  // name the mapping by its path ("sensor", "scene.spans[1].conductor"; the root is "the file").
  explicit YamlMap(const YamlValue& value);

  [[nodiscard]] const std::string& path() const { return value_.path(); }
  [[noreturn]] void fail(std::string_view problem) const { value_.fail(problem); }

  // The value under `key`, marking it read; nullopt when absent.
  [[nodiscard]] std::optional<YamlValue> get(std::string_view key);
  // The value under `key`, marking it read. Throws "<path>.<key>: required, but missing …".
  [[nodiscard]] YamlValue require(std::string_view key);
  // Whether `key` is present, without marking it read.
  [[nodiscard]] bool contains(std::string_view key) const;
  // Throws "<file>:<line>: <path>.<key>: unknown key '<key>' in <path> (did you mean …?)" for the
  // first key in file order that no get()/require() read.
  void finish() const;

  // Shorthands: the value under `key` as the type, or `fallback` when absent.
  [[nodiscard]] double number_or(std::string_view key, double fallback);
  [[nodiscard]] std::optional<double> optional_number(std::string_view key);
  [[nodiscard]] bool boolean_or(std::string_view key, bool fallback);

 private:
  struct Entry {
    std::string key;
    YAML::Node value;
    int line;  // 1-based, of the key
  };
  [[nodiscard]] const Entry* find(std::string_view key) const;
  [[nodiscard]] std::string child_path(std::string_view key) const;

  YamlValue value_;
  std::vector<Entry> entries_;  // file order
  std::set<std::string, std::less<>> read_;
  std::set<std::string, std::less<>> asked_;
};

}  // namespace owsim
