#pragma once
// The path of a request to the studio as the routes see it: the request target's path (before
// `?`), percent-decoded strictly (RFC 3986: `%` and two hex digits, nothing else; no `%uXXXX`)
// and then UTF-8 text (io/files/utf8_text.hpp: no overlong forms such as %c0%ae, no surrogates)
// without control characters (NUL, newlines, DEL). A target that fails any of these names no
// page and no file: the server answers it with a plain 404 before any route sees it.
#include <optional>
#include <string>
#include <string_view>

namespace owsim::studio {

// The decoded path of `target` ("/out/a%20b.csv?run=1" → "/out/a b.csv"), or nullopt.
[[nodiscard]] std::optional<std::string> request_path(std::string_view target);

}  // namespace owsim::studio
