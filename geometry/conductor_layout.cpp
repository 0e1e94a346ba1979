#include "geometry/conductor_layout.hpp"

#include "geometry/error.hpp"

namespace owsim {

std::vector<ConductorOffset> conductor_offsets(LayoutKind kind) {
  switch (kind) {
    case LayoutKind::single:
      return {{0.0, 0.0}};
    case LayoutKind::tri:
      return {{-4.0, 0.0}, {0.0, 0.0}, {4.0, 0.0}};
    case LayoutKind::sept:  // Danube-type tower: earth wire, upper and lower crossarm
      return {{0.0, 0.0},    {-6.0, -5.0}, {6.0, -5.0},  {-11.0, -11.0},
              {-5.0, -11.0}, {5.0, -11.0}, {11.0, -11.0}};
    case LayoutKind::custom:
      break;
  }
  throw Error("a custom conductor layout has no template: its offsets come from the scenario");
}

std::string_view to_string(LayoutKind kind) {
  switch (kind) {
    case LayoutKind::single:
      return "single";
    case LayoutKind::tri:
      return "tri";
    case LayoutKind::sept:
      return "sept";
    case LayoutKind::custom:
      return "custom";
  }
  return "custom";
}

std::optional<LayoutKind> layout_kind_from_string(std::string_view name) {
  if (name == "single") return LayoutKind::single;
  if (name == "tri") return LayoutKind::tri;
  if (name == "sept") return LayoutKind::sept;
  return std::nullopt;
}

std::string conductor_id(std::string_view span_id, int n) {
  std::string id(span_id);
  id += '/';
  id += std::to_string(n);
  return id;
}

}  // namespace owsim
