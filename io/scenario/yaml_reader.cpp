#include "io/scenario/yaml_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>

#include "io/files/input_file.hpp"
#include "io/files/utf8_text.hpp"

namespace owsim {
namespace {

// The key path one level up: "a.b[2]" → "a.b", "a.b" → "a", "a" → "".
std::string_view parent_path(std::string_view path) {
  const std::size_t cut = path.find_last_of(".[");
  return cut == std::string_view::npos ? std::string_view() : path.substr(0, cut);
}

std::string display_name(std::string_view path) {
  return path.empty() ? std::string("the file") : std::string(path);
}

std::string shown(std::string_view text) {
  constexpr std::size_t kShown = 40;
  std::string result = "'";
  result.append(text.substr(0, kShown));
  if (text.size() > kShown) result += "…";
  result += '\'';
  return result;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// " (did you mean 'x'?)" for a near miss, else " (known keys: a, b, …)", else "".
std::string suggestion(std::string_view key, const std::set<std::string, std::less<>>& known) {
  std::string best;
  std::size_t best_distance = 3;  // at most two edits
  for (const std::string& candidate : known) {
    // A missing unit suffix ("max_bank" for "max_bank_deg") counts as a near miss too.
    const bool prefix = key.size() >= 3 && candidate.starts_with(key);
    const std::size_t distance = prefix ? 1 : edit_distance(key, candidate);
    if (distance < best_distance && distance < std::max<std::size_t>(candidate.size() / 2, 1)) {
      best = candidate;
      best_distance = distance;
    }
  }
  if (!best.empty()) return " (did you mean '" + best + "'?)";
  if (known.empty()) return " (this mapping takes no keys here)";
  std::string list = " (known keys: ";
  for (auto it = known.begin(); it != known.end(); ++it) {
    if (it != known.begin()) list += ", ";
    list += *it;
  }
  return list + ")";
}

int line_1based(const YAML::Mark& mark) { return mark.is_null() ? 1 : mark.line + 1; }

}  // namespace

// ---- YamlSource ----

YamlSource YamlSource::from_file(const std::filesystem::path& path) {
  return from_text(read_input_file(path, "YAML file", kMaxScenarioBytes), path.string());
}

YamlSource YamlSource::from_text(std::string_view text, std::string file_name) {
  if (const auto bad = invalid_utf8_offset(text)) {
    const auto line =
        1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(*bad), '\n');
    char byte[8];
    std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(text[*bad]));
    throw input_error(file_name + ":" + std::to_string(line),
                      "not UTF-8 text (byte " + std::string(byte) +
                          "): owsim reads every text as UTF-8; save the file as UTF-8");
  }
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::Exception& error) {
    throw input_error(file_name + ":" + std::to_string(line_1based(error.mark)),
                      "malformed YAML: " + error.msg);
  }
  return YamlSource(std::move(root), std::move(file_name));
}

YamlValue YamlSource::root() const { return YamlValue(*this, root_, "", 1); }

int YamlSource::line_of(std::string_view key_path) const {
  for (std::string_view path = key_path;; path = parent_path(path)) {
    if (const auto found = lines_.find(path); found != lines_.end()) return found->second;
    if (path.empty()) return 1;
  }
}

void YamlSource::rethrow_at_key(const Error& error, std::string_view fallback_path,
                                const std::map<std::string, std::string>& renamed) const {
  std::string message = error.what();
  const std::size_t separator = message.find(": ");
  if (separator != std::string::npos) {
    std::string key = message.substr(0, separator);
    if (const auto found = renamed.find(key); found != renamed.end()) {
      message.replace(0, separator, found->second);
      key = found->second;
    }
    for (std::string_view path = key; !path.empty(); path = parent_path(path)) {
      if (const auto found = lines_.find(path); found != lines_.end()) {
        throw Error(file_name_ + ":" + std::to_string(found->second) + ": " + message);
      }
    }
    const std::string_view fallback = fallback_path;
    if (key == fallback || (key.size() > fallback.size() && key.starts_with(fallback) &&
                            (key[fallback.size()] == '.' || key[fallback.size()] == '['))) {
      throw Error(file_name_ + ":" + std::to_string(line_of(fallback)) + ": " + message);
    }
  }
  throw Error(file_name_ + ":" + std::to_string(line_of(fallback_path)) + ": " +
              display_name(fallback_path) + ": " + message);
}

// ---- YamlValue ----

std::string YamlValue::location() const {
  return source_->file_name() + ":" + std::to_string(line_);
}

void YamlValue::fail(std::string_view problem) const {
  throw input_error(location() + ": " + display_name(path_), problem);
}

std::string YamlValue::describe() const {
  if (node_.IsScalar()) return shown(node_.Scalar());
  if (node_.IsSequence()) return "a list";
  if (node_.IsMap()) return "a mapping";
  return "nothing";
}

double YamlValue::number() const {
  if (!node_.IsScalar()) fail("expected a number, got " + describe());
  std::string_view text = node_.Scalar();
  if (text.size() > 1 && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, status] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (status != std::errc() || end != text.data() + text.size()) {
    fail("expected a number, got " + describe());
  }
  if (!std::isfinite(value)) fail("expected a finite number, got " + describe());
  check_range(value);
  return value;
}

void YamlValue::check_range(double value) const {
  if (source_->range_check() == nullptr) return;
  if (const std::string problem = source_->range_check()(path_, value); !problem.empty()) {
    fail(problem);
  }
}

std::int64_t YamlValue::integer(std::int64_t min, std::int64_t max) const {
  if (!node_.IsScalar()) fail("expected an integer, got " + describe());
  std::string_view text = node_.Scalar();
  if (text.size() > 1 && text.front() == '+') text.remove_prefix(1);
  std::int64_t value = 0;
  const auto [end, status] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (status == std::errc::result_out_of_range) {
    fail("must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
         describe());
  }
  if (status != std::errc() || end != text.data() + text.size()) {
    fail("expected an integer, got " + describe());
  }
  check_range(static_cast<double>(value));
  if (value < min || value > max) {
    fail("must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
         std::to_string(value));
  }
  return value;
}

std::uint64_t YamlValue::unsigned_integer() const {
  if (!node_.IsScalar()) fail("expected a non-negative integer, got " + describe());
  std::string_view text = node_.Scalar();
  if (text.size() > 1 && text.front() == '+') text.remove_prefix(1);
  std::uint64_t value = 0;
  const auto [end, status] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (status == std::errc::result_out_of_range) {
    fail("must be an integer in [0, 18446744073709551615], got " + describe());
  }
  if (status != std::errc() || end != text.data() + text.size()) {
    fail("expected a non-negative integer, got " + describe());
  }
  return value;
}

bool YamlValue::boolean() const {
  bool value = false;
  if (!node_.IsScalar() || !YAML::convert<bool>::decode(node_, value)) {
    fail("expected true or false, got " + describe());
  }
  return value;
}

std::string YamlValue::text() const {
  if (!node_.IsScalar()) fail("expected a text, got " + describe());
  return node_.Scalar();
}

std::string YamlValue::one_of(std::initializer_list<std::string_view> choices) const {
  std::string expected = "expected one of ";
  for (auto it = choices.begin(); it != choices.end(); ++it) {
    if (it != choices.begin()) expected += " | ";
    expected += *it;
  }
  if (!node_.IsScalar()) fail(expected + ", got " + describe());
  const std::string& text = node_.Scalar();
  if (std::find(choices.begin(), choices.end(), text) == choices.end()) {
    fail(expected + ", got " + describe());
  }
  return text;
}

std::vector<YamlValue> YamlValue::items() const {
  if (!node_.IsSequence()) fail("expected a list [...], got " + describe());
  std::vector<YamlValue> result;
  result.reserve(node_.size());
  std::size_t index = 0;
  for (const YAML::Node& item : node_) {
    std::string item_path = path_ + "[" + std::to_string(index++) + "]";
    const int item_line = item.Mark().is_null() ? line_ : line_1based(item.Mark());
    source_->note_key(item_path, item_line);
    result.emplace_back(*source_, item, std::move(item_path), item_line);
  }
  return result;
}

std::vector<double> YamlValue::numbers(std::optional<std::size_t> count) const {
  if (count && !(node_.IsSequence() && node_.size() == *count)) {
    fail("expected a list of " + std::to_string(*count) + " numbers, got " +
         (node_.IsSequence() ? "a list of " + std::to_string(node_.size()) : describe()));
  }
  std::vector<double> result;
  for (const YamlValue& item : items()) result.push_back(item.number());
  return result;
}

// ---- YamlMap ----

YamlMap::YamlMap(const YamlValue& value) : value_(value) {
  const YAML::Node& node = value.node();
  if (!node.IsMap()) value.fail("expected a mapping {key: value, ...}, got " + value.describe());
  for (auto it = node.begin(); it != node.end(); ++it) {
    const int line = line_1based(it->first.Mark());
    if (!it->first.IsScalar()) {
      throw input_error(value.source().file_name() + ":" + std::to_string(line) + ": " +
                            display_name(value.path()),
                        "a key must be a plain name, got " +
                            std::string(it->first.IsSequence() ? "a list" : "a mapping"));
    }
    std::string key = it->first.Scalar();
    if (const Entry* earlier = find(key)) {
      throw input_error(
          value.source().file_name() + ":" + std::to_string(line) + ": " + child_path(key),
          "key '" + key + "' given twice in " + display_name(value.path()) + " (first at line " +
              std::to_string(earlier->line) + ")");
    }
    entries_.push_back(Entry{std::move(key), it->second, line});
  }
}

const YamlMap::Entry* YamlMap::find(std::string_view key) const {
  const auto found = std::find_if(entries_.begin(), entries_.end(),
                                  [&](const Entry& entry) { return entry.key == key; });
  return found == entries_.end() ? nullptr : &*found;
}

std::string YamlMap::child_path(std::string_view key) const {
  return value_.path().empty() ? std::string(key) : value_.path() + "." + std::string(key);
}

std::optional<YamlValue> YamlMap::get(std::string_view key) {
  asked_.emplace(key);
  const Entry* entry = find(key);
  if (entry == nullptr) return std::nullopt;
  read_.emplace(key);
  std::string path = child_path(key);
  value_.source().note_key(path, entry->line);
  return YamlValue(value_.source(), entry->value, std::move(path), entry->line);
}

YamlValue YamlMap::require(std::string_view key) {
  std::optional<YamlValue> found = get(key);
  if (!found) {
    throw input_error(value_.location() + ": " + child_path(key),
                      "required, but missing from " + display_name(value_.path()));
  }
  return *std::move(found);
}

bool YamlMap::contains(std::string_view key) const { return find(key) != nullptr; }

void YamlMap::finish() const {
  for (const Entry& entry : entries_) {
    if (read_.contains(entry.key)) continue;
    throw input_error(value_.source().file_name() + ":" + std::to_string(entry.line) + ": " +
                          child_path(entry.key),
                      "unknown key '" + entry.key + "' in " + display_name(value_.path()) +
                          suggestion(entry.key, asked_));
  }
}

double YamlMap::number_or(std::string_view key, double fallback) {
  const std::optional<YamlValue> found = get(key);
  return found ? found->number() : fallback;
}

std::optional<double> YamlMap::optional_number(std::string_view key) {
  const std::optional<YamlValue> found = get(key);
  if (!found) return std::nullopt;
  return found->number();
}

bool YamlMap::boolean_or(std::string_view key, bool fallback) {
  const std::optional<YamlValue> found = get(key);
  return found ? found->boolean() : fallback;
}

}  // namespace owsim
