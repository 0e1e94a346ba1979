// Protects the conductor layouts of SENSOR-SPEC §6 (single, the 3-wire "tri", the 7-wire
// "sept" tower): their counts and offsets, conductor ids "<span>/<n>" in layout order
// (INTERFACE.md), and that a positive lateral offset lies to the right of from → to.
#include <gtest/gtest.h>

#include "geometry/conductor_layout.hpp"
#include "geometry/error.hpp"
#include "geometry/span.hpp"

namespace owsim {
namespace {

SpanSpec span_with(LayoutKind kind, Eigen::Vector2d from, Eigen::Vector2d to) {
  SpanSpec spec;
  spec.id = "line-a";
  spec.from_en = from;
  spec.to_en = to;
  spec.support_height_1_m = 40.0;
  spec.support_height_2_m = 40.0;
  spec.lowest_point_m = 30.0;
  spec.offsets = conductor_offsets(kind);
  return spec;
}

TEST(ConductorLayout, CountsAndOffsets) {
  EXPECT_EQ(conductor_offsets(LayoutKind::single).size(), 1u);
  ASSERT_EQ(conductor_offsets(LayoutKind::tri).size(), 3u);
  ASSERT_EQ(conductor_offsets(LayoutKind::sept).size(), 7u);
  const auto tri = conductor_offsets(LayoutKind::tri);
  EXPECT_EQ(tri[0].lateral_m, -4.0);
  EXPECT_EQ(tri[2].lateral_m, 4.0);
  for (const ConductorOffset& offset : tri) EXPECT_EQ(offset.vertical_m, 0.0);
  const auto sept = conductor_offsets(LayoutKind::sept);
  EXPECT_EQ(sept[0].lateral_m, 0.0);  // earth wire on top
  EXPECT_EQ(sept[0].vertical_m, 0.0);
  for (std::size_t i = 1; i < sept.size(); ++i) EXPECT_LT(sept[i].vertical_m, 0.0);
  EXPECT_EQ(sept[3].lateral_m, -11.0);
  EXPECT_EQ(sept[6].vertical_m, -11.0);
  EXPECT_THROW((void)conductor_offsets(LayoutKind::custom), Error);
}

TEST(ConductorLayout, NamesRoundTrip) {
  for (LayoutKind kind : {LayoutKind::single, LayoutKind::tri, LayoutKind::sept}) {
    EXPECT_EQ(layout_kind_from_string(to_string(kind)), kind);
  }
  EXPECT_FALSE(layout_kind_from_string("custom").has_value());
  EXPECT_FALSE(layout_kind_from_string("Sept").has_value());
  EXPECT_EQ(conductor_id("line-a", 3), "line-a/3");
}

TEST(ConductorLayout, SpanConductorsAreNamedInLayoutOrder) {
  const Terrain flat;
  for (auto [kind, count] : {std::pair{LayoutKind::single, 1}, std::pair{LayoutKind::tri, 3},
                             std::pair{LayoutKind::sept, 7}}) {
    const SpanObjects span = build_span(span_with(kind, {0, 0}, {0, 300}), flat);
    ASSERT_EQ(span.conductors.size(), static_cast<std::size_t>(count));
    for (int n = 1; n <= count; ++n) {
      EXPECT_EQ(span.conductors[n - 1].id, "line-a/" + std::to_string(n));
    }
  }
}

TEST(ConductorLayout, PositiveLateralOffsetIsToTheRight) {
  const Terrain flat;
  // Looking north, right is east.
  const SpanObjects north = build_span(span_with(LayoutKind::tri, {0, 0}, {0, 300}), flat);
  EXPECT_NEAR(north.conductors[2].points_enu_m.front().x(), 4.0, 1e-12);
  EXPECT_NEAR(north.conductors[0].points_enu_m.front().x(), -4.0, 1e-12);
  // Looking east, right is south.
  const SpanObjects east = build_span(span_with(LayoutKind::tri, {0, 0}, {300, 0}), flat);
  EXPECT_NEAR(east.conductors[2].points_enu_m.front().y(), -4.0, 1e-12);
  EXPECT_NEAR(east.conductors[2].points_enu_m.back().y(), -4.0, 1e-12);
  // Looking south-west, right is north-west.
  const SpanObjects south_west = build_span(span_with(LayoutKind::tri, {0, 0}, {-100, -100}), flat);
  const Eigen::Vector3d p = south_west.conductors[2].points_enu_m.front();
  EXPECT_NEAR(p.x(), -4.0 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(p.y(), 4.0 / std::sqrt(2.0), 1e-12);
  // Sept: the earth wire on top, the lower crossarm 11 m below it.
  const SpanObjects sept = build_span(span_with(LayoutKind::sept, {0, 0}, {0, 300}), flat);
  EXPECT_NEAR(sept.conductors[0].points_enu_m.front().z(), 40.0, 1e-9);
  EXPECT_NEAR(sept.conductors[6].points_enu_m.front().z(), 29.0, 1e-9);
  EXPECT_NEAR(sept.conductors[6].points_enu_m.front().x(), 11.0, 1e-12);
}

}  // namespace
}  // namespace owsim
