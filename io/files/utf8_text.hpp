#pragma once
// owsim's one policy for text (issue 17): every text input (scenario files, and through them
// object ids, names and paths) is UTF-8, checked where it is read, so no id that JSON, LAS or
// Python cannot carry reaches an output. RFC 3629: no overlong forms, no surrogates, nothing
// above U+10FFFF.
#include <cstddef>
#include <optional>
#include <string_view>

namespace owsim {

// The offset of the first byte that does not begin a valid UTF-8 sequence, or nullopt.
[[nodiscard]] std::optional<std::size_t> invalid_utf8_offset(std::string_view text);

}  // namespace owsim
