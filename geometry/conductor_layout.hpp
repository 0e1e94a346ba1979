#pragma once
// Where the conductors of a span hang relative to its support line (SENSOR-SPEC §6: the
// single wire, the source's 3-wire "triWire" and 7-wire "septWire" of drawing 21, and tower
// templates given as data).
//
// An offset is (lateral, vertical) in metres in the plane across the span: lateral positive to
// the right looking from the span's `from` support to its `to` support, vertical relative to
// the support height (the top attachment point). Conductor n of a span (n = 1, 2, …) uses
// offset n − 1 of the list, and is named "<span id>/<n>" (INTERFACE.md).
//
// The source's drawing 21 lost its dimensions in the text, so "sept" is a Danube-type tower
// (Donaumast): the earth wire on top (0, 0); the upper crossarm (−6, −5), (6, −5); the lower
// crossarm (−11, −11), (−5, −11), (5, −11), (11, −11) — in that order. "tri" is three wires in
// one horizontal row 4 m apart: (−4, 0), (0, 0), (4, 0).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace owsim {

struct ConductorOffset {
  double lateral_m = 0.0;   // + to the right of from → to
  double vertical_m = 0.0;  // + up, relative to the support height
};

enum class LayoutKind { single, tri, sept, custom };

// The template offsets of a layout; `custom` has none (its offsets are the scenario's list)
// and throws owsim::Error.
[[nodiscard]] std::vector<ConductorOffset> conductor_offsets(LayoutKind kind);

// "single", "tri", "sept", "custom"
[[nodiscard]] std::string_view to_string(LayoutKind kind);
// The named templates "single", "tri", "sept"; anything else (including "custom") is nullopt.
[[nodiscard]] std::optional<LayoutKind> layout_kind_from_string(std::string_view name);

// The id of conductor n (1-based, layout order) of a span: "<span id>/<n>"  (INTERFACE.md)
[[nodiscard]] std::string conductor_id(std::string_view span_id, int n);

}  // namespace owsim
