#include "bxdf/io/json_text.h"

#include <set>
#include <vector>

#include "bxdf/input_file.h"
#include "bxdf/params.h"

namespace bxdf::io {

using nlohmann::json;

json parse_json(const std::string& text, const std::string& where) {
  std::vector<std::set<std::string>> keys_of_open_objects;
  std::string problem;
  const json::parser_callback_t check = [&](int depth, json::parse_event_t event, json& parsed) {
    using E = json::parse_event_t;
    if ((event == E::object_start || event == E::array_start) && depth >= kMaxJsonDepth) {
      problem = "nesting deeper than " + std::to_string(kMaxJsonDepth) + " levels";
      throw ParameterError(problem);
    }
    if (event == E::object_start) keys_of_open_objects.emplace_back();
    if (event == E::object_end && !keys_of_open_objects.empty()) keys_of_open_objects.pop_back();
    if (event == E::key && !keys_of_open_objects.empty() &&
        !keys_of_open_objects.back().insert(parsed.get<std::string>()).second) {
      problem = "duplicate key \"" + printable(parsed.get<std::string>()) +
                "\" in an object (at nesting level " + std::to_string(depth) + ")";
      throw ParameterError(problem);
    }
    return true;
  };
  try {
    return json::parse(text, check);
  } catch (const ParameterError&) {
    throw ParameterError(where + ": " + problem);
  } catch (const json::exception& e) {
    // Parse errors quote the bytes read so far, which need not be UTF-8.
    throw ParameterError(where + ": not valid JSON: " + printable(e.what()));
  }
}

std::string describe_json(const json& j) {
  const auto scalar_text = [](const json& v) -> std::string {
    if (v.is_array()) return v.empty() ? "[]" : "[...]";
    if (v.is_object()) return v.empty() ? "{}" : "{...}";
    return v.dump(-1, ' ', false, json::error_handler_t::replace);
  };
  std::string text;
  if (j.is_array() || j.is_object()) {
    text = j.is_array() ? "[" : "{";
    for (auto it = j.begin(); it != j.end() && text.size() < 60; ++it) {
      if (text.size() > 1) text += ", ";
      if (j.is_object()) text += "\"" + it.key() + "\": ";
      text += scalar_text(it.value());
    }
    text += j.is_array() ? "]" : "}";
  } else {
    text = scalar_text(j);
  }
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  text = printable(text);
  if (j.is_array()) return "an array of " + std::to_string(j.size()) + " (" + text + ")";
  return std::string(j.is_object() || j.is_array() ? "an " : "a ") + j.type_name() + " (" + text + ")";
}

}  // namespace bxdf::io
