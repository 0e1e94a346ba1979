#include "studio/request_guard.hpp"

#include <array>
#include <cstdint>
#include <random>

namespace owsim::studio {
namespace {

// Equal without leaking where they differ through the time taken.
bool same_secret(std::string_view given, std::string_view token) {
  if (given.size() != token.size() || token.empty()) return false;
  unsigned char difference = 0;
  for (std::size_t k = 0; k < token.size(); ++k) {
    difference |= static_cast<unsigned char>(given[k] ^ token[k]);
  }
  return difference == 0;
}

// The value of cookie `name` in a Cookie header ("a=1; b=2").
std::optional<std::string_view> cookie_value(std::string_view header, std::string_view name) {
  while (!header.empty()) {
    const std::size_t end = header.find(';');
    std::string_view pair = header.substr(0, end);
    header = end == std::string_view::npos ? std::string_view{} : header.substr(end + 1);
    while (!pair.empty() && pair.front() == ' ') pair.remove_prefix(1);
    const std::size_t equals = pair.find('=');
    if (equals != std::string_view::npos && pair.substr(0, equals) == name) {
      return pair.substr(equals + 1);
    }
  }
  return std::nullopt;
}

bool loopback_authority(std::string_view authority, int port) {
  std::string suffix(1, ':');  // built by appending: GCC 12 warns (falsely) on ":" + string
  suffix += std::to_string(port);
  for (const std::string_view name : {"127.0.0.1", "localhost", "[::1]"}) {
    if (authority.size() == name.size() + suffix.size() && authority.starts_with(name) &&
        authority.ends_with(suffix)) {
      return true;
    }
  }
  return false;
}

}  // namespace

std::string new_session_token() {
  std::random_device source;
  std::string token;
  constexpr std::array<char, 16> kHex = {'0', '1', '2', '3', '4', '5', '6', '7',
                                         '8', '9', 'a', 'b', 'c', 'd', 'e', 'f'};
  for (int word = 0; word < 4; ++word) {
    std::uint32_t bits = source();
    for (int digit = 0; digit < 8; ++digit, bits >>= 4) token += kHex[bits & 0xF];
  }
  return token;
}

Verdict check_request(const RequestFacts& request, int port, std::string_view token) {
  if (!request.host || !loopback_authority(*request.host, port)) return Verdict::bad_host;
  if (request.origin) {
    const std::string_view origin = *request.origin;
    constexpr std::string_view kScheme = "http://";
    if (!origin.starts_with(kScheme) || !loopback_authority(origin.substr(kScheme.size()), port)) {
      return Verdict::bad_origin;
    }
  }
  if (request.token_query && same_secret(*request.token_query, token)) return Verdict::allowed;
  if (request.token_header && same_secret(*request.token_header, token)) return Verdict::allowed;
  if (request.cookie) {
    if (const auto value = cookie_value(*request.cookie, kTokenCookie);
        value && same_secret(*value, token)) {
      return Verdict::allowed;
    }
  }
  return Verdict::no_token;
}

std::string_view verdict_text(Verdict verdict) {
  switch (verdict) {
    case Verdict::allowed:
      return "allowed";
    case Verdict::bad_host:
      return "refused: the Host header is not this studio's loopback address";
    case Verdict::bad_origin:
      return "refused: the request comes from another site (Origin)";
    case Verdict::no_token:
      return "refused: the session token is missing or wrong (open the address owsim studio "
             "printed)";
  }
  return "refused";
}

}  // namespace owsim::studio
