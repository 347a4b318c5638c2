// SPDX-License-Identifier: MIT
// One command-line flag, written `--flag value` or `--flag=value`: how emcv-demo and emcv-toy read their
// arguments (one reader, so both accept and reject the same spellings).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace emcv::cli {

/// The flag at args[i]. `Error` is the caller's usage-error type (constructed from one message line).
template <class Error>
class flag_argument {
public:
    flag_argument(const std::vector<std::string>& args, std::size_t& i) : args_(args), i_(i), name_(args[i]) {
        if (const auto eq = name_.find('='); name_.rfind("--", 0) == 0 && eq != std::string::npos) {
            inline_value_ = name_.substr(eq + 1);
            name_ = name_.substr(0, eq);
            has_inline_value_ = true;
        }
    }

    /// The flag without any `=value` part.
    const std::string& name() const noexcept { return name_; }
    /// True for `--flag=value` (a flag that takes no value must refuse it).
    bool has_inline_value() const noexcept { return has_inline_value_; }
    /// The part after '=' (empty without one).
    const std::string& inline_value() const noexcept { return inline_value_; }

    /// The value: the part after '=', else the next argument, which is consumed (i advances).
    /// Throws Error("<flag>: missing value") when there is none.
    std::string value() {
        if (has_inline_value_) return inline_value_;
        if (i_ + 1 >= args_.size()) throw Error(name_ + ": missing value");
        return args_[++i_];
    }

private:
    const std::vector<std::string>& args_;
    std::size_t& i_;
    std::string name_;
    std::string inline_value_;
    bool has_inline_value_ = false;
};

}  // namespace emcv::cli
