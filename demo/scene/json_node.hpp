// SPDX-License-Identifier: MIT
// A JSON value together with its JSON pointer and file, so that every check can fail with
// "<file>: <json pointer>: <problem>" (scene_error). Internal to the scene loader.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "load.hpp"

namespace emcv::demo {

class json_node {
public:
    json_node(const nlohmann::json& value, std::string pointer, const std::string& file)
        : value_(&value), pointer_(std::move(pointer)), file_(&file) {}

    const nlohmann::json& json() const { return *value_; }
    /// RFC 6901 pointer; the root is written "/" in messages so that the field is never empty.
    const std::string& pointer() const { return pointer_; }

    [[noreturn]] void fail(const std::string& problem) const;

    /// Checks that this is an object whose keys are those of scene_schema_object(kind): no unknown key, every
    /// required key present.
    void check_keys(std::string_view kind) const;

    json_node at(std::string_view key) const;               ///< required member (check_keys ran first)
    std::optional<json_node> find(std::string_view key) const;
    json_node element(std::size_t index) const;
    std::size_t array_size() const;                        ///< fails unless an array

    bool is_number() const { return value_->is_number(); }
    bool is_object() const { return value_->is_object(); }

    double number() const;                                 ///< finite number
    /// A finite number in the interval; `low_open` / `high_open` exclude the end points. Fails with
    /// "<what> must be in (lo, hi], got x".
    double number_in(double low, double high, bool low_open, bool high_open) const;
    int integer_in(int low, int high) const;               ///< integer in [low, high]
    bool boolean() const;
    std::string string() const;
    std::string non_empty_string() const;
    glm::vec3 vec3() const;                                ///< [x, y, z], finite
    glm::vec3 vec3_in(double low, double high, bool low_open, bool high_open) const;

private:
    const nlohmann::json* value_;
    std::string pointer_;
    const std::string* file_;
};

/// "a number", "an object", ... for "expected X, got Y" messages.
std::string json_type_phrase(const nlohmann::json& value);

}  // namespace emcv::demo
