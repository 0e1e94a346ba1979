#include "evaluation/truth_table.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>

#include "geometry/error.hpp"
#include "geometry/number_text.hpp"
#include "geometry/scene.hpp"
#include "io/files/csv_cells.hpp"
#include "io/files/input_file.hpp"
#include "io/files/utf8_text.hpp"
#include "io/run/truth_csv.hpp"
#include "io/sweep/sweep_file.hpp"

namespace owsim {
namespace {

constexpr std::uintmax_t kMaxSweepTableBytes = std::uintmax_t{256} << 20;
// The longest row a run writes: its object id comes from a scenario file (at most
// kMaxScenarioBytes), quoted with its quotes doubled, and ten short cells more.
constexpr std::size_t kMaxRecordBytes = 2 * static_cast<std::size_t>(kMaxScenarioBytes) + 4096;
constexpr std::size_t kReadBlockBytes = std::size_t{1} << 20;
constexpr std::size_t kShownChars = 40;
// The most returns one object has in a frame: both returns of every pulse.
constexpr std::uint64_t kMaxRowReturns = kMaxReturnsPerPulse * kMaxPulsesPerFrame;
constexpr std::array kObjectClasses = {SurfaceClass::building, SurfaceClass::pole,
                                       SurfaceClass::tree, SurfaceClass::wire};

enum Column : std::size_t {
  kFrame,
  kTime,
  kObject,
  kClass,
  kRange,
  kAlpha,
  kBeta,
  kInView,
  kReturns,
  kClosing,
  kReach,
  kColumns
};
constexpr std::array<std::string_view, kColumns> kColumnNames = {
    "frame",          "time_s",   "object",  "class",   "range_m",
    "alpha_deg",      "beta_deg", "in_view", "returns", "closing_speed_mps",
    "time_to_reach_s"};

// A cell as a message shows it: quoted, control characters as '?', cut after kShownChars bytes
// (at a character's start), so the message stays one line of UTF-8.
std::string shown(std::string_view cell) {
  std::size_t cut = std::min(cell.size(), kShownChars);
  while (cut > 0 && cut < cell.size() && (static_cast<unsigned char>(cell[cut]) & 0xC0) == 0x80) {
    --cut;
  }
  std::string text = "'";
  for (const char c : cell.substr(0, cut)) {
    text += static_cast<unsigned char>(c) < 0x20 || c == 0x7F ? '?' : c;
  }
  if (cut < cell.size()) text += "…";
  return text + "'";
}

// Cuts text into records at the line breaks outside double quotes (an object id may hold one,
// quoted as RFC 4180 asks), each without its "\n" or "\r\n" and with the line it starts on; text
// after the last break is a record too. A record longer than kMaxRecordBytes is refused, so memory
// stays bounded whatever the file holds.
class Records {
 public:
  explicit Records(const std::string& name) : name_(name) {}

  template <typename Visit>
  void feed(std::string_view bytes, Visit&& visit) {
    while (!bytes.empty()) {
      const std::size_t end = bytes.find('\n');
      const std::string_view piece = bytes.substr(0, end);
      if (std::count(piece.begin(), piece.end(), '"') % 2 == 1) quoted_ = !quoted_;
      if (end == std::string_view::npos) {
        keep(piece);
        return;
      }
      bytes.remove_prefix(end + 1);
      ++breaks_;
      if (quoted_) {  // a line break inside a quoted cell
        keep(piece);
        keep("\n");
        continue;
      }
      std::string_view record = piece;
      if (started_) {
        keep(piece);
        record = pending_;
      }
      emit(record, visit);
    }
  }

  template <typename Visit>
  void finish(Visit&& visit) {
    if (started_) emit(pending_, visit);
  }

  // Lines read so far (line breaks, and the text after the last).
  [[nodiscard]] std::int64_t lines() const { return breaks_ + (started_ ? 1 : 0); }

 private:
  void keep(std::string_view piece) {
    if (pending_.size() + piece.size() > kMaxRecordBytes) too_long();
    pending_ += piece;
    started_ = true;
  }

  template <typename Visit>
  void emit(std::string_view record, Visit& visit) {
    if (record.size() > kMaxRecordBytes) too_long();
    if (!record.empty() && record.back() == '\r') record.remove_suffix(1);
    visit(first_line_, record);
    pending_.clear();
    started_ = false;
    first_line_ = breaks_ + 1;
  }

  [[noreturn]] void too_long() const {
    throw input_error(
        name_ + ":" + std::to_string(first_line_),
        "a row longer than " + std::to_string(kMaxRecordBytes) + " bytes (no run writes one)");
  }

  const std::string& name_;
  std::string pending_;  // the record so far, when it spans lines or blocks
  bool started_ = false;
  bool quoted_ = false;  // inside a quoted cell
  std::int64_t breaks_ = 0;
  std::int64_t first_line_ = 1;
};

// The rows, checked cell by cell against what a run writes (io/run/truth_csv.hpp), the wanted
// objects' kept.
class TruthRows {
 public:
  TruthRows(const std::string& name, const FlightFacts& facts, const WantedObject& wanted)
      : name_(name), facts_(facts), wanted_(wanted) {}

  void add(std::int64_t line, std::string_view record) {
    line_ = line;
    if (line == 1) {
      if (without_utf8_bom(record) != kTruthCsvHeader) {
        throw input_error(where(), "not an owsim truth.csv header (expected '" +
                                       std::string(kTruthCsvHeader) + "')");
      }
      return;
    }
    if (record.empty()) return;
    split_csv_cells(record, cells_);
    if (cells_.size() != kColumns) {
      throw input_error(
          where(), std::to_string(cells_.size()) + " cells, expected " + std::to_string(kColumns));
    }
    TruthEntry entry;
    if (facts_.frames < 1) bad(kFrame, "lies outside a flight of no frames");
    entry.frame = static_cast<std::int64_t>(
        whole(kFrame, static_cast<std::uint64_t>(facts_.frames) - 1,
              " (summary.json counts " + std::to_string(facts_.frames) + " frames)"));
    entry.time_s = finite(kTime);
    const std::string_view object_class = cells_[kClass];
    if (std::none_of(kObjectClasses.begin(), kObjectClasses.end(),
                     [&](SurfaceClass c) { return to_string(c) == object_class; })) {
      bad(kClass, "must be building, pole, tree or wire");
    }
    entry.range_m = within(kRange, 0.0, kMaxRangeM, " m");
    within(kAlpha, -90.0, 90.0, "°");
    within(kBeta, -180.0, 180.0, "°");
    if (cells_[kInView] != "0" && cells_[kInView] != "1") bad(kInView, "must be 0 or 1");
    entry.in_view = cells_[kInView] == "1";
    entry.returns = whole(kReturns, kMaxRowReturns, "");
    entry.closing_speed_mps = finite(kClosing);
    // The writer gives the time to reach exactly when the aircraft closes on the object.
    if (cells_[kReach].empty()) {
      if (entry.closing_speed_mps > 0.0) bad(kReach, "empty, though the aircraft closes");
    } else {
      within(kReach, 0.0, std::numeric_limits<double>::max(), " s");
      if (entry.closing_speed_mps < 0.0) bad(kReach, "given, though the aircraft opens the range");
    }

    std::string_view id = cells_[kObject];
    if (id.starts_with('"')) {
      id_text_ = csv_cell_text(id);
      id = id_text_;
    }
    auto known = objects_.find(id);
    if (known == objects_.end()) {
      if (id.empty()) bad(kObject, "must not be empty");
      if (invalid_utf8_offset(id)) bad(kObject, "must be UTF-8 text");
      std::optional<std::size_t> track;
      if (wanted_(id, object_class)) {
        track = tracks_.size();
        tracks_.push_back({std::string(id), std::string(object_class), {}});
      }
      known = objects_.emplace(std::string(id), Known{std::string(object_class), track}).first;
    } else if (known->second.object_class != object_class) {
      bad(kClass,
          "object " + shown(id) + " is a " + known->second.object_class + " on an earlier row");
    }
    if (!known->second.track) return;
    std::vector<TruthEntry>& rows = tracks_[*known->second.track].rows;
    if (!rows.empty() && entry.frame <= rows.back().frame) {
      throw input_error(where(), "frame " + std::to_string(entry.frame) + " of " + shown(id) +
                                     " after frame " + std::to_string(rows.back().frame));
    }
    rows.push_back(entry);
  }

  std::vector<ObjectTrack> finish(std::int64_t lines) {
    if (lines == 0) throw input_error(name_, "empty: no header");
    return std::move(tracks_);
  }

 private:
  struct Known {
    std::string object_class;
    std::optional<std::size_t> track;  // in tracks_, when wanted
  };

  [[nodiscard]] std::string where() const { return name_ + ":" + std::to_string(line_); }

  [[noreturn]] void bad(Column column, std::string_view problem) const {
    throw input_error(where(), std::string(kColumnNames[column]) + ": " + std::string(problem) +
                                   ", got " + shown(cells_[column]));
  }

  std::uint64_t whole(Column column, std::uint64_t most, const std::string& note) const {
    const std::string_view cell = cells_[column];
    std::uint64_t value = 0;
    const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
    if (cell.empty() || error != std::errc() || end != cell.data() + cell.size() || value > most) {
      bad(column, "must be a whole number in [0, " + std::to_string(most) + "]" + note);
    }
    return value;
  }

  [[nodiscard]] std::optional<double> number(Column column) const {
    const std::string_view cell = cells_[column];
    double value = 0.0;
    const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
    if (cell.empty() || error != std::errc() || end != cell.data() + cell.size() ||
        !std::isfinite(value)) {
      return std::nullopt;
    }
    return value;
  }

  double finite(Column column) const {
    const std::optional<double> value = number(column);
    if (!value) bad(column, "must be a finite number");
    return *value;
  }

  double within(Column column, double lo, double hi, std::string_view unit) const {
    const std::optional<double> value = number(column);
    if (!value || *value < lo || *value > hi) {
      bad(column, "must be a number in [" + number_text(lo) + ", " +
                      (hi == std::numeric_limits<double>::max() ? std::string("∞)")
                                                                : number_text(hi) + "]") +
                      std::string(unit));
    }
    return *value;
  }

  const std::string& name_;
  const FlightFacts& facts_;
  const WantedObject& wanted_;
  std::int64_t line_ = 0;
  std::vector<std::string_view> cells_;
  std::string id_text_;
  std::map<std::string, Known, std::less<>> objects_;  // every object seen
  std::vector<ObjectTrack> tracks_;
};

}  // namespace

std::vector<CampaignFlight> campaign_flights(const std::filesystem::path& directory) {
  std::error_code error;
  const std::filesystem::path table = directory / "sweep.csv";
  if (std::filesystem::is_regular_file(table, error)) {
    const std::string text = read_input_file(table, "sweep table", kMaxSweepTableBytes);
    std::vector<std::int64_t> numbers;
    std::vector<std::string_view> cells;
    for_each_line(text, [&](std::int64_t line, std::string_view row) {
      if (line == 1) {
        split_csv_cells(row, cells);
        if (cells.empty() || cells.front() != "member") {
          throw input_error(table.string() + ":1", "not an owsim sweep table (no member column)");
        }
        return;
      }
      if (row.empty()) return;
      split_csv_cells(row, cells);
      const std::string_view member = cells.front();
      std::int64_t number = -1;
      const auto [parsed_to, failed] =
          std::from_chars(member.data(), member.data() + member.size(), number);
      if (failed != std::errc() || parsed_to != member.data() + member.size() || number < 0) {
        throw input_error(table.string() + ":" + std::to_string(line),
                          "member " + shown(member) + " is not a member number");
      }
      // owsim sweep lists each member once, in order: a repeated one would count twice.
      if (!numbers.empty() && number <= numbers.back()) {
        throw input_error(table.string() + ":" + std::to_string(line),
                          "member " + std::to_string(number) + " after member " +
                              std::to_string(numbers.back()) + " (each member once, in order)");
      }
      numbers.push_back(number);
    });
    if (numbers.empty()) throw input_error(table.string(), "lists no member");
    // Member folders are named as owsim sweep names them: zero-padded to the widest number.
    const auto count = static_cast<std::int64_t>(numbers.size());
    std::vector<CampaignFlight> members;
    for (const std::int64_t number : numbers) {
      const std::string name = member_folder_name(count, number);
      members.push_back({name, directory / name});
    }
    return members;
  }
  if (std::filesystem::is_regular_file(directory / "summary.json", error)) {
    const std::filesystem::path absolute = std::filesystem::absolute(directory).lexically_normal();
    std::string name = absolute.filename().string();
    if (name.empty()) name = absolute.parent_path().filename().string();
    return {{name, directory}};
  }
  throw input_error(directory.string(),
                    "neither a run folder (summary.json) nor a sweep folder (sweep.csv)");
}

std::vector<ObjectTrack> parse_truth_csv(std::string_view text, const std::string& name,
                                         const FlightFacts& facts, const WantedObject& wanted) {
  TruthRows rows(name, facts, wanted);
  Records records(name);
  const auto add = [&](std::int64_t line, std::string_view record) { rows.add(line, record); };
  records.feed(text, add);
  records.finish(add);
  return rows.finish(records.lines());
}

std::vector<ObjectTrack> read_truth_csv(const std::filesystem::path& truth_csv,
                                        const FlightFacts& facts, const WantedObject& wanted) {
  std::error_code error;
  if (!std::filesystem::exists(truth_csv, error)) {
    throw input_error(truth_csv.string(),
                      "missing: the run wrote no ground truth (add truth to its outputs)");
  }
  require_input_file(truth_csv, "ground truth");
  std::ifstream in(truth_csv, std::ios::binary);
  if (!in) throw file_error(truth_csv.string(), "cannot open the ground truth");
  const std::string name = truth_csv.string();
  TruthRows rows(name, facts, wanted);
  Records records(name);
  const auto add = [&](std::int64_t line, std::string_view record) { rows.add(line, record); };
  std::string block(kReadBlockBytes, '\0');
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    records.feed(std::string_view(block.data(), static_cast<std::size_t>(in.gcount())), add);
  }
  if (in.bad()) throw file_error(name, "cannot read the ground truth");
  records.finish(add);
  return rows.finish(records.lines());
}

}  // namespace owsim
