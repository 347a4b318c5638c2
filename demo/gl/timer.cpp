// SPDX-License-Identifier: MIT
#include "timer.hpp"

#include <stdexcept>

namespace emcv::gl {

gpu_timer::gpu_timer(std::size_t ring_size) {
    if (ring_size == 0) throw std::invalid_argument("gpu_timer: ring_size must be >= 1");
    for (std::size_t i = 0; i < ring_size; ++i) queries_.push_back(query::create());
}

void gpu_timer::begin() {
    if (pending_ == queries_.size()) return;  // ring full: skip rather than stall
    glBeginQuery(GL_TIME_ELAPSED, queries_[head_].id());
    active_ = true;
}

void gpu_timer::end() {
    if (!active_) return;
    glEndQuery(GL_TIME_ELAPSED);
    active_ = false;
    head_ = (head_ + 1) % queries_.size();
    ++pending_;
}

std::optional<double> gpu_timer::pop_ms() {
    if (pending_ == 0) return std::nullopt;
    const std::size_t tail = (head_ + queries_.size() - pending_) % queries_.size();
    GLint available = 0;
    glGetQueryObjectiv(queries_[tail].id(), GL_QUERY_RESULT_AVAILABLE, &available);
    if (!available) return std::nullopt;
    GLuint64 ns = 0;
    glGetQueryObjectui64v(queries_[tail].id(), GL_QUERY_RESULT, &ns);
    --pending_;
    return static_cast<double>(ns) * 1e-6;
}

std::vector<double> gpu_timer::drain_ms() {
    std::vector<double> out;
    while (pending_ > 0) {
        const std::size_t tail = (head_ + queries_.size() - pending_) % queries_.size();
        GLuint64 ns = 0;
        glGetQueryObjectui64v(queries_[tail].id(), GL_QUERY_RESULT, &ns);  // waits
        --pending_;
        out.push_back(static_cast<double>(ns) * 1e-6);
    }
    return out;
}

}  // namespace emcv::gl
