// SPDX-License-Identifier: MIT
#include "json_node.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "duplicate_keys.hpp"
#include "schema_keys.hpp"

namespace emcv::demo {
namespace {

std::string format_number(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
}

std::string interval(double low, double high, bool low_open, bool high_open) {
    auto end = [](double x) {
        return std::isinf(x) ? std::string(x < 0 ? "-inf" : "inf") : format_number(x);
    };
    return std::string(low_open ? "(" : "[") + end(low) + ", " + end(high) + (high_open ? ")" : "]");
}

bool inside(double x, double low, double high, bool low_open, bool high_open) {
    const bool above = low_open ? x > low : x >= low;
    const bool below = high_open ? x < high : x <= high;
    return above && below;
}

}  // namespace

std::string json_type_phrase(const nlohmann::json& value) {
    switch (value.type()) {
    case nlohmann::json::value_t::null: return "null";
    case nlohmann::json::value_t::object: return "an object";
    case nlohmann::json::value_t::array: return "an array";
    case nlohmann::json::value_t::string: return "a string";
    case nlohmann::json::value_t::boolean: return "a boolean";
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned:
    case nlohmann::json::value_t::number_float: return "a number";
    default: return "an unsupported value";
    }
}

void json_node::fail(const std::string& problem) const {
    throw scene_error(*file_ + ": " + (pointer_.empty() ? std::string("/") : pointer_) + ": " + problem);
}

void json_node::check_keys(std::string_view kind) const {
    if (!value_->is_object()) fail("expected an object, got " + json_type_phrase(*value_));
    const schema_object& rule = scene_schema_object(kind);
    for (const auto& [key, member] : value_->items()) {
        const bool known = std::any_of(rule.keys.begin(), rule.keys.end(),
                                       [&wanted = key](const schema_key& k) { return k.name == wanted; });
        if (!known) {
            std::string allowed;
            for (const auto& k : rule.keys) allowed += (allowed.empty() ? "" : ", ") + std::string(k.name);
            json_node(member, pointer_ + "/" + escape_pointer_token(std::string(key)), *file_)
                .fail("unknown key \"" + key + "\" (allowed here: " + allowed + ")");
        }
    }
    for (const auto& k : rule.keys)
        if (k.required && !value_->contains(k.name)) fail("missing required key \"" + std::string(k.name) + "\"");
}

json_node json_node::at(std::string_view key) const {
    auto found = find(key);
    if (!found) fail("missing required key \"" + std::string(key) + "\"");
    return *found;
}

std::optional<json_node> json_node::find(std::string_view key) const {
    if (!value_->is_object()) fail("expected an object, got " + json_type_phrase(*value_));
    const auto it = value_->find(std::string(key));
    if (it == value_->end()) return std::nullopt;
    return json_node(*it, pointer_ + "/" + escape_pointer_token(std::string(key)), *file_);
}

json_node json_node::element(std::size_t index) const {
    return json_node((*value_)[index], pointer_ + "/" + std::to_string(index), *file_);
}

std::size_t json_node::array_size() const {
    if (!value_->is_array()) fail("expected an array, got " + json_type_phrase(*value_));
    return value_->size();
}

double json_node::number() const {
    if (!value_->is_number()) fail("expected a number, got " + json_type_phrase(*value_));
    const double x = value_->get<double>();
    if (!std::isfinite(x)) fail("expected a finite number");
    // Scenes are stored in fp32: a value beyond float range would silently become infinite.
    if (std::fabs(x) > static_cast<double>(std::numeric_limits<float>::max())) fail("number too large for fp32");
    return x;
}

double json_node::number_in(double low, double high, bool low_open, bool high_open) const {
    const double x = number();
    if (!inside(x, low, high, low_open, high_open))
        fail("out of range: must be in " + interval(low, high, low_open, high_open) + ", got " + format_number(x));
    return x;
}

int json_node::integer_in(int low, int high) const {
    if (!value_->is_number_integer()) fail("expected an integer, got " + json_type_phrase(*value_) +
                                           (value_->is_number() ? " with a fraction" : ""));
    // Compare as long long before narrowing: 1e12 must be "out of range", not wrap around.
    const bool is_unsigned = value_->is_number_unsigned();
    const long long x = is_unsigned ? (value_->get<unsigned long long>() >
                                               static_cast<unsigned long long>(std::numeric_limits<long long>::max())
                                           ? std::numeric_limits<long long>::max()
                                           : static_cast<long long>(value_->get<unsigned long long>()))
                                    : value_->get<long long>();
    if (x < low || x > high)
        fail("out of range: must be an integer in [" + std::to_string(low) + ", " + std::to_string(high) +
             "], got " + std::to_string(x));
    return static_cast<int>(x);
}

bool json_node::boolean() const {
    if (!value_->is_boolean()) fail("expected true or false, got " + json_type_phrase(*value_));
    return value_->get<bool>();
}

std::string json_node::string() const {
    if (!value_->is_string()) fail("expected a string, got " + json_type_phrase(*value_));
    return value_->get<std::string>();
}

std::string json_node::non_empty_string() const {
    std::string s = string();
    if (s.empty()) fail("expected a non-empty string");
    return s;
}

glm::vec3 json_node::vec3() const {
    if (!value_->is_array() || value_->size() != 3)
        fail("expected an array of 3 numbers, got " +
             (value_->is_array() ? "an array of " + std::to_string(value_->size()) : json_type_phrase(*value_)));
    glm::vec3 v;
    for (std::size_t i = 0; i < 3; ++i) v[static_cast<glm::length_t>(i)] = static_cast<float>(element(i).number());
    return v;
}

glm::vec3 json_node::vec3_in(double low, double high, bool low_open, bool high_open) const {
    const glm::vec3 v = vec3();
    for (std::size_t i = 0; i < 3; ++i) element(i).number_in(low, high, low_open, high_open);
    return v;
}

}  // namespace emcv::demo
