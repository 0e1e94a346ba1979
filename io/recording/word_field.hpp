#pragma once
// The check both sensor words (MilOWS and HELLAS) make on every field they pack, once a pulse:
// the value fits its bits. Inline; the error message is built only when it throws.
namespace owsim {

// Throws owsim::Error "<word> word: <field> = <value> does not fit its field (max <max>)".
[[noreturn, gnu::cold]] void throw_field_too_wide(const char* word, const char* field,
                                                  unsigned value, unsigned max);

inline void require_field_width(const char* word, const char* field, unsigned value, unsigned max) {
  if (value > max) [[unlikely]]
    throw_field_too_wide(word, field, value, max);
}

}  // namespace owsim
