#pragma once
// Who may talk to `owsim studio` (INTERFACE.md "Studio"; docs/studio.md "Security"), the model of
// Jupyter's server: a random session token printed with the address and required on every
// request (query `token`, header `X-Owsim-Token`, or the cookie the page sets), the Host header
// one of the loopback names with the studio's port (no DNS rebinding), and an Origin, when a
// browser sends one, the studio's own (no cross-site requests). Pure: the server hands over what
// the request says.
#include <optional>
#include <string>
#include <string_view>

namespace owsim::studio {

// 32 hex digits from the system's random source (std::random_device: getrandom on Linux).
[[nodiscard]] std::string new_session_token();

// What a request says about itself; an absent header is nullopt.
struct RequestFacts {
  std::optional<std::string> host;
  std::optional<std::string> origin;
  std::optional<std::string> token_query;
  std::optional<std::string> token_header;
  std::optional<std::string> cookie;  // the whole Cookie header
};

enum class Verdict { allowed, bad_host, bad_origin, no_token };

// Whether a request to the studio on `port` with `token` may be served.
[[nodiscard]] Verdict check_request(const RequestFacts& request, int port, std::string_view token);

// The name of the cookie that carries the token once the page has been opened with it.
inline constexpr std::string_view kTokenCookie = "owsim_token";

// One line for a refused request (the HTTP body).
[[nodiscard]] std::string_view verdict_text(Verdict verdict);

}  // namespace owsim::studio
