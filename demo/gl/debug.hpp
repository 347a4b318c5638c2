// SPDX-License-Identifier: MIT
// KHR_debug: a callback that prints messages and counts GL errors, and RAII debug groups per pass.
#pragma once

#include <cstdint>
#include <string>

namespace emcv::gl {

/// Installs a synchronous GL debug callback on the current context for its lifetime.
/// Every GL_DEBUG_TYPE_ERROR message is printed to stderr and counted; programs exit non-zero when
/// error_count() > 0 (see exit_status()), so CTest catches any GL error.
class debug_messenger {
public:
    /// verbose: also print non-error messages of medium and high severity.
    explicit debug_messenger(bool verbose = false);
    ~debug_messenger();
    debug_messenger(const debug_messenger&) = delete;
    debug_messenger& operator=(const debug_messenger&) = delete;

    std::uint64_t error_count() const noexcept { return errors_; }
    /// The last error message (empty when none).
    const std::string& last_error() const noexcept { return last_error_; }
    /// 0 when no GL error was reported, 1 otherwise.
    int exit_status() const noexcept { return errors_ == 0 ? 0 : 1; }

    // internal: called by the GL callback
    void on_message(unsigned type, unsigned severity, const char* message);

private:
    bool verbose_;
    std::uint64_t errors_ = 0;
    std::string last_error_;
};

/// glPushDebugGroup / glPopDebugGroup for one scope (one render pass).
class debug_group {
public:
    explicit debug_group(const char* name);
    ~debug_group();
    debug_group(const debug_group&) = delete;
    debug_group& operator=(const debug_group&) = delete;
};

}  // namespace emcv::gl
