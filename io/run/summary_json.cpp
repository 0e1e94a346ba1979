#include "io/run/summary_json.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <string>
#include <string_view>

#include "geometry/error.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/json_text.hpp"

namespace owsim {
namespace {

constexpr std::size_t kFlushBytes = std::size_t{1} << 20;
constexpr std::array kObjectClasses = {SurfaceClass::building, SurfaceClass::pole,
                                       SurfaceClass::tree, SurfaceClass::wire};

// Text goes into a buffer, the buffer into the file whenever it passes kFlushBytes.
class StreamedText {
 public:
  explicit StreamedText(AtomicOutputFile& file) : file_(&file) { text_.reserve(2 * kFlushBytes); }
  void operator+=(std::string_view text) {
    text_ += text;
    if (text_.size() >= kFlushBytes) flush();
  }
  void flush() {
    file_->write(text_);
    text_.clear();
  }

 private:
  AtomicOutputFile* file_;
  std::string text_;
};

void append_integer(std::string& out, std::uint64_t value) {
  std::array<char, 24> digits{};
  const auto end = std::to_chars(digits.data(), digits.data() + digits.size(), value).ptr;
  out.append(digits.data(), end);
}

// A JSON string as nlohmann::json writes it; ids need no escapes but for rare characters.
void append_string(std::string& out, std::string_view text) {
  const bool plain = std::none_of(text.begin(), text.end(), [](char c) {
    return static_cast<unsigned char>(c) < 0x20 || c == '"' || c == '\\';
  });
  if (plain) {
    out += '"';
    out += text;
    out += '"';
  } else {
    out += json_text(nlohmann::json(text));
  }
}

// One entry of the objects array, at the array's depth. In weather (SENSOR-SPEC §10) it also says
// how many returns saw the object through fog and when it was first seen without that.
void append_object(std::string& out, std::string_view id, SurfaceClass surface,
                   const ObjectTruth& truth, bool weather) {
  const auto number_if = [&](bool known, double value) {
    if (known) {
      out += json_text(nlohmann::json(value));
    } else {
      out += "null";
    }
  };
  const auto number = [&](double value) { number_if(truth.seen(), value); };
  out += "    {\n      \"class\": \"";
  out += to_string(surface);
  if (weather) {
    out += "\",\n      \"first_seen_clear_range_m\": ";
    number_if(truth.seen_clear(), truth.first_seen_clear_range_m);
    out += ",\n      \"first_seen_clear_s\": ";
    number_if(truth.seen_clear(), truth.first_seen_clear_s);
    out += ",\n      \"first_seen_range_m\": ";
  } else {
    out += "\",\n      \"first_seen_range_m\": ";
  }
  number(truth.first_seen_range_m);
  out += ",\n      \"first_seen_s\": ";
  number(truth.first_seen_s);
  out += ",\n      \"frames_seen\": ";
  append_integer(out, truth.frames_seen);
  out += ",\n      \"id\": ";
  append_string(out, id);
  out += ",\n      \"min_range_m\": ";
  number(truth.min_range_m);
  out += ",\n      \"returns\": ";
  append_integer(out, truth.returns);
  if (weather) {
    out += ",\n      \"seen_through_fog\": ";
    append_integer(out, truth.seen_through_fog);
  }
  out += "\n    }";
}

// The receiver's false returns (class noise, SENSOR-SPEC §11) per pulse fired; 0 with no pulse.
double false_returns_per_pulse(const FlightSummary& summary) {
  if (summary.pulses() == 0) return 0.0;
  return static_cast<double>(summary.returns_of(SurfaceClass::noise)) /
         static_cast<double>(summary.pulses());
}

// Everything but the objects: the run facts, the totals and the per-class counts.
nlohmann::json head_of(const FlightSummary& summary, const Scene& scene,
                       const nlohmann::json& run_facts) {
  nlohmann::json head = run_facts;
  head["frames"] = summary.frames();
  head["pulses"] = summary.pulses();
  head["second_returns"] = summary.second_returns();
  for (const SurfaceClass surface : kSurfaceClasses) {
    // Fog returns are counted where the scenario has weather (SENSOR-SPEC §10) only.
    if (surface == SurfaceClass::fog && scene.fog.empty()) continue;
    head["returns"][std::string(to_string(surface))] = summary.returns_of(surface);
  }
  head["false_returns_per_pulse"] = false_returns_per_pulse(summary);
  std::array<std::uint64_t, kSurfaceClassCount> objects{};
  std::array<std::uint64_t, kSurfaceClassCount> seen{};
  const auto count = [&](SurfaceClass surface, const ObjectTruth& truth) {
    ++objects[static_cast<std::size_t>(surface)];
    if (truth.seen()) ++seen[static_cast<std::size_t>(surface)];
  };
  const std::span<const ObjectTruth> truths = summary.objects();
  for (std::size_t i = 0; i < truths.size(); ++i) count(named_object_class(scene, i), truths[i]);
  for (const SurfaceClass surface : kObjectClasses) {
    const auto c = static_cast<std::size_t>(surface);
    head["objects_by_class"][std::string(to_string(surface))] = {{"objects", objects[c]},
                                                                 {"seen", seen[c]}};
  }
  return head;
}

}  // namespace

void write_summary_json(const std::filesystem::path& path, const FlightSummary& summary,
                        const Scene& scene, const nlohmann::json& run_facts) {
  const std::span<const ObjectTruth> truths = summary.objects();
  if (truths.size() != named_object_count(scene)) {
    throw Error(path.string() + ": the summary tallies " + std::to_string(truths.size()) +
                " objects, the scene has " + std::to_string(named_object_count(scene)));
  }
  AtomicOutputFile file(path);
  StreamedText out(file);
  // The head as nlohmann::json writes it, its closing brace left off to add the objects last.
  std::string head = json_text(head_of(summary, scene, run_facts), 2);
  head.resize(head.size() - 2);  // "\n}"
  out += head;
  if (truths.empty()) {
    out += ",\n  \"objects\": []\n}\n";
  } else {
    out += ",\n  \"objects\": [\n";
    std::string entry;
    for (std::size_t i = 0; i < truths.size(); ++i) {
      entry.clear();
      if (i > 0) entry += ",\n";
      append_object(entry, named_object_id(scene, i), named_object_class(scene, i), truths[i],
                    !scene.fog.empty());
      out += entry;
    }
    out += "\n  ]\n}\n";
  }
  out.flush();
  file.commit();
}

}  // namespace owsim
