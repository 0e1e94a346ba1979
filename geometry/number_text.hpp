#pragma once
// Numbers in owsim's messages: printf's %.<digits>g (std::to_chars general with that precision),
// so "must be > 0, got -3" and "1.23456789e+19" read the same in every module.
#include <string>

namespace owsim {

[[nodiscard]] std::string number_text(double value, int significant_digits = 9);

}  // namespace owsim
