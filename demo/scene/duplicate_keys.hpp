// SPDX-License-Identifier: MIT
// JSON allows an object to repeat a key, and nlohmann-json keeps the last value silently; in a hand-edited
// scene file that is a mistake (two "intensity" entries: which one did the author mean?). This finds one.
#pragma once

#include <optional>
#include <string>

namespace emcv::demo {

struct duplicate_key {
    std::string pointer;  ///< JSON pointer of the repeated member, e.g. "/lights/0/intensity"
    std::string key;
};

/// The first repeated key of any object in `json_text` (which must be valid JSON), or nothing.
std::optional<duplicate_key> find_duplicate_key(const std::string& json_text);

/// RFC 6901 escaping of one reference token ("~" -> "~0", "/" -> "~1").
std::string escape_pointer_token(const std::string& key);

}  // namespace emcv::demo
