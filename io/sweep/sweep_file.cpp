#include "io/sweep/sweep_file.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <limits>

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

std::vector<PathStep> path_steps(const std::string& path) {
  std::vector<PathStep> steps;
  std::size_t begin = 0;
  while (begin <= path.size()) {
    const std::size_t dot = std::min(path.find('.', begin), path.size());
    std::string part = path.substr(begin, dot - begin);
    PathStep step;
    const std::size_t bracket = part.find('[');
    step.key = part.substr(0, bracket);
    for (std::size_t at = bracket; at != std::string::npos; at = part.find('[', at + 1)) {
      const std::size_t close = part.find(']', at);
      std::size_t index = 0;
      const auto result = std::from_chars(part.data() + at + 1, part.data() + close, index);
      if (close == std::string::npos || result.ptr != part.data() + close) {
        throw Error("a key path of dot-separated keys and [i] indices");
      }
      step.indices.push_back(index);
    }
    if (step.key.empty()) throw Error("a key path of dot-separated keys and [i] indices");
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
      value.fail(std::string("expected ") + e.what());
    }
    spec.vary.push_back(read_variation(key, value));
  }
  keys.finish();
  root.finish();
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
