#include "geometry/number_text.hpp"

#include <charconv>

namespace owsim {

std::string number_text(double value, int significant_digits) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof text, value, std::chars_format::general,
                                    significant_digits);
  return std::string(text, result.ptr);
}

}  // namespace owsim
