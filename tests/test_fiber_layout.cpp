// Protects the fiber array of SENSOR-SPEC §2: firing order (crosstalk re-sort and sequential),
// the α table 1 values, the reference fiber and the sawtooth β_FC.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "sensor/fiber_layout.hpp"

namespace owsim {
namespace {

TEST(FiberLayout, CrosstalkOrderIsOneToOneHundredTwentyEight) {
  const ScanParams p;
  ASSERT_EQ(p.fibers_per_line, 128);
  for (int slot = 0; slot < 128; ++slot) {
    EXPECT_EQ(fiber_at_slot(p, slot), slot + 1);
    EXPECT_EQ(slot_of_fiber(p, slot + 1), slot);
  }
  EXPECT_EQ(fiber_at_slot(p, 63), 64);  // left half ends at the centre
  EXPECT_EQ(fiber_at_slot(p, 64), 65);  // right half starts at the right edge
  EXPECT_EQ(fiber_at_slot(p, 126), 127);
  EXPECT_EQ(fiber_at_slot(p, 127), 128);  // then the reference
}

TEST(FiberLayout, ReferenceFiber) {
  const ScanParams p;
  EXPECT_TRUE(is_reference_fiber(p, 128));
  EXPECT_FALSE(is_reference_fiber(p, 127));
  EXPECT_FALSE(is_reference_fiber(p, 1));
  EXPECT_TRUE(std::isnan(fiber_alpha_deg(p, 128)));
}

TEST(FiberLayout, AlphaTableOne) {
  const ScanParams p;
  EXPECT_DOUBLE_EQ(fiber_alpha_deg(p, 1), -21.0);
  EXPECT_NEAR(fiber_alpha_deg(p, 2), -20.67, 0.005);
  EXPECT_DOUBLE_EQ(fiber_alpha_deg(p, 64), 0.0);
  EXPECT_DOUBLE_EQ(fiber_alpha_deg(p, 65), 21.0);
  // Table 1 prints 20.67 for fiber 66 too, but the right half has 63 fibers for the same 21°,
  // so the decided linear step 21/62° puts it at 20.661° — within 0.01° of the table.
  EXPECT_DOUBLE_EQ(fiber_alpha_deg(p, 66), 21.0 - 21.0 / 62.0);
  EXPECT_NEAR(fiber_alpha_deg(p, 66), 20.67, 0.01);
  EXPECT_DOUBLE_EQ(fiber_alpha_deg(p, 127), 0.0);
  // Linear within each half: steps 21/63° and 21/62°.
  for (int fiber = 2; fiber <= 64; ++fiber) {
    EXPECT_NEAR(fiber_alpha_deg(p, fiber) - fiber_alpha_deg(p, fiber - 1), 21.0 / 63.0, 1e-12);
  }
  for (int fiber = 66; fiber <= 127; ++fiber) {
    EXPECT_NEAR(fiber_alpha_deg(p, fiber) - fiber_alpha_deg(p, fiber - 1), -21.0 / 62.0, 1e-12);
  }
}

TEST(FiberLayout, DefaultTableMatchesPerFiberAlpha) {
  const ScanParams p;
  const std::vector<double> table = default_alpha_table_deg(128);
  ASSERT_EQ(table.size(), 127u);
  for (int fiber = 1; fiber <= 127; ++fiber) {
    EXPECT_EQ(table[static_cast<std::size_t>(fiber - 1)], fiber_alpha_deg(p, fiber));
  }
}

TEST(FiberLayout, DefaultTableGeneralisesToOtherArrays) {
  // 8 fibers: left half 1..4 (−21, −14, −7, 0), right half 5..7 (21, 10.5, 0), 8 the reference.
  const std::vector<double> eight = default_alpha_table_deg(8);
  const std::vector<double> expected = {-21.0, -14.0, -7.0, 0.0, 21.0, 10.5, 0.0};
  ASSERT_EQ(eight.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(eight[i], expected[i], 1e-12);
  // 3 fibers: one fiber a half, each at its edge.
  EXPECT_EQ(default_alpha_table_deg(3), (std::vector<double>{-21.0, 21.0}));
  EXPECT_EQ(default_alpha_table_deg(2), (std::vector<double>{-21.0}));
  EXPECT_TRUE(default_alpha_table_deg(1).empty());
}

TEST(FiberLayout, SequentialOrderIsSortedByAlpha) {
  ScanParams p;
  p.fiber_order = FiberOrder::sequential;
  EXPECT_EQ(fiber_at_slot(p, 0), 1);
  EXPECT_EQ(fiber_at_slot(p, 63), 64);
  EXPECT_EQ(fiber_at_slot(p, 64), 127);
  EXPECT_EQ(fiber_at_slot(p, 65), 126);
  EXPECT_EQ(fiber_at_slot(p, 126), 65);
  EXPECT_EQ(fiber_at_slot(p, 127), 128);
  std::vector<int> fibers;
  for (int slot = 0; slot < 127; ++slot) {
    fibers.push_back(fiber_at_slot(p, slot));
    EXPECT_EQ(slot_of_fiber(p, fibers.back()), slot);
    if (slot > 0) {
      EXPECT_LE(fiber_alpha_deg(p, fibers[static_cast<std::size_t>(slot - 1)]),
                fiber_alpha_deg(p, fibers.back()))
          << "slot " << slot;
    }
  }
  std::sort(fibers.begin(), fibers.end());
  for (int i = 0; i < 127; ++i) EXPECT_EQ(fibers[static_cast<std::size_t>(i)], i + 1);
}

TEST(FiberLayout, SlotAndFiberAreInversesForSmallArrays) {
  for (FiberOrder order : {FiberOrder::crosstalk_resorted, FiberOrder::sequential}) {
    for (int fibers = 2; fibers <= 17; ++fibers) {
      ScanParams p;
      p.fibers_per_line = fibers;
      p.fiber_order = order;
      for (int slot = 0; slot < fibers; ++slot) {
        const int fiber = fiber_at_slot(p, slot);
        ASSERT_GE(fiber, 1);
        ASSERT_LE(fiber, fibers);
        ASSERT_EQ(slot_of_fiber(p, fiber), slot) << fibers << " fibers, slot " << slot;
      }
      EXPECT_EQ(fiber_at_slot(p, fibers - 1), fibers);  // the reference fires last
    }
  }
}

TEST(FiberLayout, TableOverridesDefault) {
  ScanParams p;
  p.fibers_per_line = 4;
  p.alpha_table_deg = {-5.0, 1.5, 7.25};
  EXPECT_EQ(fiber_alpha_deg(p, 1), -5.0);
  EXPECT_EQ(fiber_alpha_deg(p, 2), 1.5);
  EXPECT_EQ(fiber_alpha_deg(p, 3), 7.25);
  EXPECT_TRUE(std::isnan(fiber_alpha_deg(p, 4)));
  p.alpha_table_deg = {-5.0, 1.5};
  try {
    (void)fiber_alpha_deg(p, 1);
    FAIL() << "a wrong-sized table must throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("sensor.alpha_table_deg"), std::string::npos);
  }
}

TEST(FiberLayout, OutOfRangeSlotOrFiberThrows) {
  const ScanParams p;
  EXPECT_THROW((void)fiber_at_slot(p, -1), Error);
  EXPECT_THROW((void)fiber_at_slot(p, 128), Error);
  EXPECT_THROW((void)slot_of_fiber(p, 0), Error);
  EXPECT_THROW((void)slot_of_fiber(p, 129), Error);
  EXPECT_THROW((void)fiber_alpha_deg(p, 0), Error);
}

TEST(FiberLayout, SawtoothAlternates) {
  ScanParams p;
  EXPECT_EQ(sawtooth_deg(p, 1), -0.134);
  EXPECT_EQ(sawtooth_deg(p, 2), 0.134);
  EXPECT_EQ(sawtooth_deg(p, 127), -0.134);
  EXPECT_EQ(sawtooth_deg(p, 128), 0.134);
  for (int slot = 1; slot < 128; ++slot) {
    EXPECT_EQ(sawtooth_deg(p, fiber_at_slot(p, slot)),
              -sawtooth_deg(p, fiber_at_slot(p, slot - 1)));
  }
  p.sawtooth_deg = 0.0;
  EXPECT_EQ(sawtooth_deg(p, 1), 0.0);
}

// The range image's rows, top to bottom: MilOWS α is up, so the top row is the fiber at +21° (65)
// and the bottom one at −21° (1); the two fibers at α = 0 (64 and 127) keep fiber order.
TEST(FiberLayout, FibersTopDownFollowAlpha) {
  const ScanParams scan;
  const std::vector<int> fibers = fibers_top_down(scan);
  ASSERT_EQ(fibers.size(), 127u);
  EXPECT_EQ(fibers.front(), 65);
  EXPECT_EQ(fibers.back(), 1);
  for (std::size_t i = 1; i < fibers.size(); ++i) {
    EXPECT_GE(fiber_alpha_deg(scan, fibers[i - 1]), fiber_alpha_deg(scan, fibers[i])) << i;
  }
  const auto at = [&](int fiber) { return std::find(fibers.begin(), fibers.end(), fiber); };
  EXPECT_LT(at(64), at(127));
  EXPECT_EQ(at(128), fibers.end());  // the reference fiber has no row
}

}  // namespace
}  // namespace owsim
