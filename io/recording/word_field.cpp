#include "io/recording/word_field.hpp"

#include <string>

#include "geometry/error.hpp"

namespace owsim {

void throw_field_too_wide(const char* word, const char* field, unsigned value, unsigned max) {
  throw Error(std::string(word) + " word: " + field + " = " + std::to_string(value) +
              " does not fit its field (max " + std::to_string(max) + ")");
}

}  // namespace owsim
