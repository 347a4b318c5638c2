// SPDX-License-Identifier: MIT
#include "duplicate_keys.hpp"

#include <set>
#include <vector>

#include <nlohmann/json.hpp>

namespace emcv::demo {
namespace {

/// SAX handler tracking the pointer of the value being read; stops at the first repeated key.
class duplicate_finder : public nlohmann::json_sax<nlohmann::json> {
public:
    std::optional<duplicate_key> found;

    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override { return open(false); }
    bool start_array(std::size_t) override { return open(true); }
    bool end_object() override { return close(); }
    bool end_array() override { return close(); }
    bool key(string_t& k) override {
        frame& top = frames_.back();
        if (!top.keys.insert(k).second) {
            found = duplicate_key{pointer() + "/" + escape_pointer_token(k), k};
            return false;  // stop parsing
        }
        top.current_key = k;
        return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

private:
    struct frame {
        std::string token;  ///< this container's reference token in its parent ("" for the root)
        bool array = false;
        std::size_t next_index = 0;
        std::string current_key;
        std::set<std::string> keys;
    };
    std::vector<frame> frames_;

    std::string pointer() const {
        std::string p;
        for (std::size_t i = 1; i < frames_.size(); ++i) p += "/" + frames_[i].token;
        return p;
    }
    std::string child_token() const {
        if (frames_.empty()) return "";
        const frame& top = frames_.back();
        return top.array ? std::to_string(top.next_index) : escape_pointer_token(top.current_key);
    }
    bool value() {
        if (!frames_.empty() && frames_.back().array) ++frames_.back().next_index;
        return true;
    }
    bool open(bool array) {
        frame f;
        f.token = child_token();
        f.array = array;
        frames_.push_back(std::move(f));
        return true;
    }
    bool close() {
        frames_.pop_back();
        return value();
    }
};

}  // namespace

std::string escape_pointer_token(const std::string& key) {
    std::string out;
    for (char c : key) {
        if (c == '~') out += "~0";
        else if (c == '/') out += "~1";
        else out += c;
    }
    return out;
}

std::optional<duplicate_key> find_duplicate_key(const std::string& json_text) {
    duplicate_finder finder;
    nlohmann::json::sax_parse(json_text, &finder);
    return finder.found;
}

}  // namespace emcv::demo
