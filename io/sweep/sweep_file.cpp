#include "io/sweep/sweep_file.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>
#include <system_error>

#include "geometry/error.hpp"
#include "geometry/keyed_random.hpp"
#include "io/files/confined_path.hpp"
#include "io/files/input_file.hpp"
#include "io/scenario/yaml_reader.hpp"

namespace owsim {
namespace {

constexpr std::int64_t kMaxMembers = 10'000'000;

// A value as YAML text: scalars as written, anything else in flow style.
std::string yaml_text(const YAML::Node& node) {
  if (node.IsScalar()) return node.Scalar();
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out.SetSeqFormat(YAML::Flow);
  out << node;
  return out.c_str();
}

std::string shortest_text(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

// FNV-1a 64 of the key path, cut to the 56 bits a RandomKey's pulse carries.
std::int64_t key_stream(const std::string& key) {
  std::uint64_t hash = 0xcbf29ce484222325u;
  for (const unsigned char c : key) {
    hash ^= c;
    hash *= 0x100000001b3u;
  }
  return static_cast<std::int64_t>(hash >> 8);
}

SweepVariation read_variation(const std::string& key, const YamlValue& value) {
  SweepVariation variation;
  variation.key = key;
  variation.line = value.line();
  YamlMap how(value);
  int given = 0;
  for (const char* name : {"uniform", "normal", "choice", "values", "member"}) {
    given += how.contains(name) ? 1 : 0;
  }
  if (given != 1) how.fail("expected one of uniform, normal, choice, values, member");
  if (const auto uniform = how.get("uniform")) {
    const std::vector<double> bounds = uniform->numbers(2);
    if (!(bounds[0] < bounds[1])) uniform->fail("[a, b] needs a < b");
    variation = {key, SweepVariation::Kind::uniform, bounds[0], bounds[1], {}, value.line()};
  } else if (const auto normal = how.get("normal")) {
    const std::vector<double> moments = normal->numbers(2);
    if (!(moments[1] >= 0)) normal->fail("[mean, standard deviation] needs a deviation ≥ 0");
    variation = {key, SweepVariation::Kind::normal, moments[0], moments[1], {}, value.line()};
  } else if (const auto member = how.get("member")) {
    if (!member->boolean()) member->fail("only `member: true` is meaningful");
  } else {
    const bool choice = how.contains("choice");
    const YamlValue list = how.require(choice ? "choice" : "values");
    if (!list.is_list() || list.items().empty()) list.fail("expected a list of one or more items");
    variation.kind = choice ? SweepVariation::Kind::choice : SweepVariation::Kind::values;
    for (const YamlValue& item : list.items()) variation.items.push_back(yaml_text(item.node()));
  }
  how.finish();
  return variation;
}

// One step of a key path: a map key and the list indices after it ("spans[0]" → spans, {0}).
struct PathStep {
  std::string key;
  std::vector<std::size_t> indices;
};

// "scene.spans[0].id" → {scene}, {spans, 0}, {id}: keys of one or more characters other than
// '.', '[' and ']', each followed by any number of [i], i a decimal index that fits size_t.
std::vector<PathStep> path_steps(const std::string& path) {
  const auto syntax = [] {
    return Error("expected a key path of dot-separated keys and [i] indices");
  };
  std::vector<PathStep> steps;
  std::size_t begin = 0;
  while (begin <= path.size()) {
    const std::size_t dot = std::min(path.find('.', begin), path.size());
    const std::string_view part = std::string_view(path).substr(begin, dot - begin);
    PathStep step;
    const std::size_t bracket = std::min(part.find('['), part.size());
    step.key = std::string(part.substr(0, bracket));
    if (step.key.empty() || step.key.find(']') != std::string::npos) throw syntax();
    for (std::size_t at = bracket; at < part.size();) {
      const std::size_t close = part.find(']', at);
      if (part[at] != '[' || close == std::string_view::npos) throw syntax();
      const std::string_view digits = part.substr(at + 1, close - at - 1);
      std::size_t index = 0;
      const auto [end, error] =
          std::from_chars(digits.data(), digits.data() + digits.size(), index);
      if (error == std::errc::result_out_of_range) {
        throw Error("list index " + std::string(digits.substr(0, 40)) + " is too large");
      }
      if (digits.empty() || error != std::errc() || end != digits.data() + digits.size()) {
        throw syntax();
      }
      step.indices.push_back(index);
      at = close + 1;
    }
    steps.push_back(std::move(step));
    begin = dot + 1;
  }
  return steps;
}

}  // namespace

SweepSpec read_sweep_file(const std::filesystem::path& path) {
  SweepSpec spec;
  spec.file = path;
  spec.text = read_input_file(path, "sweep file", kMaxScenarioBytes);
  const YamlSource source = YamlSource::from_text(spec.text, path.string());
  YamlMap root(source.root());
  const YamlValue base = root.require("base");
  try {
    spec.base = confined_file(path.parent_path(), base.text());
    spec.base_text = read_input_file(spec.base, "base scenario", kMaxScenarioBytes);
  } catch (const Error& e) {
    base.fail(e.what());
  }
  std::error_code error;
  if (std::filesystem::equivalent(spec.base, path, error)) {
    base.fail("names this sweep file: the base is the scenario every member starts from");
  }
  spec.count = root.require("count").integer(1, kMaxMembers);
  if (const auto seed = root.get("seed")) spec.seed = seed->unsigned_integer();
  if (const auto outputs = root.get("outputs")) spec.outputs = outputs->text();
  const YamlValue vary = root.require("vary");
  YamlMap keys(vary);
  for (const auto& entry : vary.node()) {
    const std::string key = entry.first.Scalar();
    const YamlValue value = keys.require(key);
    try {
      static_cast<void>(path_steps(key));
    } catch (const Error& e) {
      value.fail(e.what());
    }
    spec.vary.push_back(read_variation(key, value));
  }
  keys.finish();
  root.finish();
  // Every key path leads through the base scenario (as member 0's values leave it): refused here,
  // before anything is written, rather than when a member is made.
  static_cast<void>(member_scenario_text(spec, 0));
  return spec;
}

std::vector<std::string> member_values(const SweepSpec& spec, std::int64_t member) {
  std::vector<std::string> values;
  for (const SweepVariation& variation : spec.vary) {
    const RandomKey key{spec.seed, member, key_stream(variation.key), RandomPurpose::sweep_draw};
    switch (variation.kind) {
      case SweepVariation::Kind::uniform:
        values.push_back(shortest_text(variation.a + (variation.b - variation.a) * uniform01(key)));
        break;
      case SweepVariation::Kind::normal:
        values.push_back(shortest_text(variation.a + variation.b * standard_normal(key)));
        break;
      case SweepVariation::Kind::choice: {
        const auto n = variation.items.size();
        const auto pick =
            std::min(n - 1, static_cast<std::size_t>(uniform01(key) * static_cast<double>(n)));
        values.push_back(variation.items[pick]);
        break;
      }
      case SweepVariation::Kind::values:
        values.push_back(
            variation.items[static_cast<std::size_t>(member) % variation.items.size()]);
        break;
      case SweepVariation::Kind::member:
        values.push_back(std::to_string(member));
        break;
    }
  }
  return values;
}

std::string member_scenario_text(const SweepSpec& spec, std::int64_t member) {
  YAML::Node root;
  try {
    root = YAML::Load(spec.base_text);
  } catch (const YAML::Exception& e) {
    throw input_error(spec.base.string(), std::string("malformed YAML: ") + e.msg);
  }
  const std::vector<std::string> values = member_values(spec, member);
  for (std::size_t v = 0; v < spec.vary.size(); ++v) {
    const SweepVariation& variation = spec.vary[v];
    const auto fail = [&](const std::string& problem) {
      throw Error(spec.file.string() + ":" + std::to_string(variation.line) + ": vary." +
                  variation.key + ": " + problem);
    };
    const std::vector<PathStep> steps = path_steps(variation.key);
    YAML::Node node = root;
    std::string reached;
    for (std::size_t s = 0; s < steps.size(); ++s) {
      const PathStep& step = steps[s];
      const bool last = s + 1 == steps.size() && step.indices.empty();
      if (!node.IsMap()) fail("the base scenario has no mapping at '" + reached + "'");
      if (!reached.empty()) reached += '.';
      reached += step.key;
      if (!last && !node[step.key]) fail("the base scenario has no '" + reached + "'");
      YAML::Node next = node[step.key];
      for (const std::size_t index : step.indices) {
        reached += '[';
        reached += std::to_string(index);
        reached += ']';
        if (!next.IsSequence() || index >= next.size()) {
          fail("the base scenario has no '" + reached + "'");
        }
        next.reset(next[index]);
      }
      if (s + 1 == steps.size()) {
        next = YAML::Load(values[v]);
      }
      node.reset(next);
    }
  }
  YAML::Emitter out;
  out << root;
  return std::string(out.c_str()) + "\n";
}

std::string member_folder_name(const SweepSpec& spec, std::int64_t member) {
  return member_folder_name(spec.count, member);
}

std::string member_folder_name(std::int64_t count, std::int64_t member) {
  const std::size_t digits = std::to_string(std::max<std::int64_t>(count - 1, 0)).size();
  std::string name = std::to_string(member);
  if (name.size() < digits) name.insert(0, digits - name.size(), '0');
  return name;
}

}  // namespace owsim
