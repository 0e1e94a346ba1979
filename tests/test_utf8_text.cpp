// Protects owsim's one text policy (io/files/utf8_text.hpp, issue 17): the UTF-8 check against
// RFC 3629's edge cases; a scenario holding a Latin-1 id is refused at its line, and one built in
// code at its key; JSON written with a non-UTF-8 path replaces the bad bytes instead of throwing
// after the other outputs were committed.
#include <gtest/gtest.h>

#include <string>

#include "geometry/error.hpp"
#include "io/files/json_text.hpp"
#include "io/files/utf8_text.hpp"
#include "io/scenario/scenario_check.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "minimal_scenario.hpp"

namespace owsim {
namespace {

TEST(Utf8Text, AcceptsEveryValidFormAndPointsAtTheFirstBadByte) {
  EXPECT_EQ(invalid_utf8_offset(""), std::nullopt);
  EXPECT_EQ(invalid_utf8_offset("pole-1"), std::nullopt);
  EXPECT_EQ(invalid_utf8_offset("Mast \xC3\xA9 \xE2\x82\xAC \xF0\x9F\x9A\x81"), std::nullopt);
  EXPECT_EQ(invalid_utf8_offset("\xF4\x8F\xBF\xBF"), std::nullopt);  // U+10FFFF
  EXPECT_EQ(invalid_utf8_offset("Mast \xE9"), 5u);                   // Latin-1 é
  EXPECT_EQ(invalid_utf8_offset("a\xC0\xAF"), 1u);                   // overlong '/'
  EXPECT_EQ(invalid_utf8_offset("ab\xE0\x80\xAF"), 2u);              // overlong, 3 bytes
  EXPECT_EQ(invalid_utf8_offset("\xED\xA0\x80"), 0u);                // a surrogate
  EXPECT_EQ(invalid_utf8_offset("\xF4\x90\x80\x80"), 0u);            // above U+10FFFF
  EXPECT_EQ(invalid_utf8_offset("ok\xE2\x82"), 2u);                  // cut short
  EXPECT_EQ(invalid_utf8_offset("\x80"), 0u);                        // a lone continuation
}

constexpr const char* kMinimalUtf8 = test::kMinimalScenario;

TEST(Utf8Text, ALatin1IdIsRefusedAtItsLine) {
  const std::string yaml = std::string(kMinimalUtf8) +
                           "scene:\n  poles:\n    - {id: \"Mast \xE9\", at: {e: 1, n: 1}, "
                           "height_m: 5, diameter_m: 1}\n";
  try {
    (void)load_scenario_text(yaml, "s.yaml");
    FAIL() << "accepted a Latin-1 id";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "s.yaml:9: not UTF-8 text (byte 0xE9): owsim reads every text as UTF-8; save the "
              "file as UTF-8");
  }
  Scenario scenario = load_scenario_text(kMinimalUtf8, "s.yaml");
  scenario.name = "Flug \xFC";
  try {
    validate_scenario(scenario);
    FAIL() << "accepted a Latin-1 name";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "name: not UTF-8 text");
  }
}

TEST(Utf8Text, JsonWithANonUtf8PathReplacesTheBadBytes) {
  const nlohmann::json value = {{"scenario", "/data/Fl\xFCge/a.yaml"}};
  EXPECT_EQ(json_text(value), "{\"scenario\":\"/data/Fl\xEF\xBF\xBDge/a.yaml\"}");
}

}  // namespace
}  // namespace owsim
