// Parsing and describing JSON from untrusted files (scene and material files): every failure is
// a ParameterError naming the file, never the JSON library's own exception, a stack overflow or
// bytes that are not UTF-8.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace bxdf::io {

// Deeper nesting is refused while parsing. Real files nest a few levels; the limit keeps every
// recursive walk over a parsed value (destruction, dump, the readers) far from the stack's end.
constexpr int kMaxJsonDepth = 256;

// Parses `text`; refuses invalid JSON, numbers past double range (1e999), nesting deeper than
// kMaxJsonDepth and duplicate keys in an object, with a ParameterError starting with `where`.
nlohmann::json parse_json(const std::string& text, const std::string& where);

// "a number (3.5)", "an array of 4 ([1, 2, [...], {...}])": one level only (nested values are
// elided, so this never recurses), at most about 60 characters.
std::string describe_json(const nlohmann::json& j);

}  // namespace bxdf::io
