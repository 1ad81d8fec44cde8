#include "io/quoted_token.h"

namespace hermite {

namespace {

// Bytes of `token` to show: at most kQuotedTokenLength, not cutting a UTF-8 character.
std::size_t shownLength(std::string_view token) {
  std::size_t n = kQuotedTokenLength;
  while (n > 0 && (static_cast<unsigned char>(token[n]) & 0xC0) == 0x80) --n;
  return n;
}

}  // namespace

std::string shortenedToken(std::string_view token) {
  if (token.size() <= kQuotedTokenLength) return std::string(token);
  std::string out(token.substr(0, shownLength(token)));
  out.append("… (").append(std::to_string(token.size())).append(" bytes)");
  return out;
}

std::string quotedToken(std::string_view token) {
  std::string out = "'";
  if (token.size() <= kQuotedTokenLength) return out.append(token).append("'");
  out.append(token.substr(0, shownLength(token)));
  return out.append("…' (").append(std::to_string(token.size())).append(" bytes)");
}

}  // namespace hermite
