#pragma once
// A token from an input file, quoted for an error message: 'abc' as it is, or, when longer than
// kQuotedTokenLength bytes, its start and its length: 'abcd…' (20000000 bytes). A 20 MB token
// is never echoed whole.

#include <cstddef>
#include <string>
#include <string_view>

namespace hermite {

constexpr std::size_t kQuotedTokenLength = 60;  // bytes shown of a longer token

std::string quotedToken(std::string_view token);

// `token` itself when short, else its first bytes (whole UTF-8 characters) + "… (N bytes)";
// for texts that are not wrapped in quotes, such as a JSON key path component.
std::string shortenedToken(std::string_view token);

}  // namespace hermite
