// SPDX-License-Identifier: MIT
#include "timestamps.hpp"

#include <chrono>
#include <stdexcept>
#include <utility>

#include "gl.hpp"
#include "handles.hpp"

namespace emcv::gl {
namespace {

class gpu_timestamps final : public timestamp_source {
public:
    std::size_t size() const override { return queries_.size(); }
    void grow(std::size_t count) override {
        for (std::size_t i = 0; i < count; ++i) queries_.push_back(timestamp_query::create());
    }
    void stamp(std::size_t q) override { glQueryCounter(queries_.at(q).id(), GL_TIMESTAMP); }
    bool ready(std::size_t q) override {
        GLint available = 0;
        glGetQueryObjectiv(queries_.at(q).id(), GL_QUERY_RESULT_AVAILABLE, &available);
        return available != 0;
    }
    std::uint64_t nanoseconds(std::size_t q) override {
        GLuint64 ns = 0;
        glGetQueryObjectui64v(queries_.at(q).id(), GL_QUERY_RESULT, &ns);  // waits when not ready
        return ns;
    }

private:
    std::vector<timestamp_query> queries_;
};

class wall_timestamps final : public timestamp_source {
public:
    std::size_t size() const override { return stamps_.size(); }
    void grow(std::size_t count) override { stamps_.resize(stamps_.size() + count, 0); }
    void stamp(std::size_t q) override {
        glFinish();  // every command before the stamp has run
        const auto now = std::chrono::steady_clock::now().time_since_epoch();
        stamps_.at(q) = static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(now).count());
    }
    bool ready(std::size_t) override { return true; }
    std::uint64_t nanoseconds(std::size_t q) override { return stamps_.at(q); }

private:
    std::vector<std::uint64_t> stamps_;
};

}  // namespace

std::unique_ptr<timestamp_source> make_gpu_timestamps() { return std::make_unique<gpu_timestamps>(); }
std::unique_ptr<timestamp_source> make_wall_timestamps() { return std::make_unique<wall_timestamps>(); }

pass_timestamps::pass_timestamps(std::unique_ptr<timestamp_source> source) : source_(std::move(source)) {
    if (!source_) throw std::invalid_argument("pass_timestamps: no timestamp source");
}

std::size_t pass_timestamps::take_query() {
    if (free_.empty()) {  // every query is in flight: make as many again (at least 16), never drop a stamp
        const std::size_t before = source_->size();
        const std::size_t more = before < 16 ? 16 : before;
        source_->grow(more);
        for (std::size_t q = before + more; q-- > before;) free_.push_back(q);
    }
    const std::size_t q = free_.back();
    free_.pop_back();
    return q;
}

void pass_timestamps::begin_frame(int frame) {
    if (in_frame_) throw std::logic_error("pass_timestamps: begin_frame inside a frame");
    in_frame_ = true;
    open_.frame = frame;
    open_.queries.clear();
    open_.tags.clear();
    open_.queries.push_back(take_query());
    source_->stamp(open_.queries.back());
}

void pass_timestamps::end_pass(std::size_t tag) {
    if (!in_frame_) throw std::logic_error("pass_timestamps: end_pass outside a frame");
    open_.queries.push_back(take_query());
    open_.tags.push_back(tag);
    source_->stamp(open_.queries.back());
}

void pass_timestamps::end_frame() {
    if (!in_frame_) throw std::logic_error("pass_timestamps: end_frame outside a frame");
    in_frame_ = false;
    pending_.push_back(std::move(open_));
    open_ = {};
}

std::vector<timed_frame> pass_timestamps::collect(bool wait) {
    std::vector<timed_frame> out;
    while (!pending_.empty()) {
        frame_record& r = pending_.front();
        if (!wait)
            for (std::size_t q : r.queries)
                if (!source_->ready(q)) return out;  // frames complete in order: later ones are not ready either
        timed_frame t;
        t.frame = r.frame;
        t.tags = r.tags;
        t.ms.reserve(r.tags.size());
        std::uint64_t previous = source_->nanoseconds(r.queries.front());
        for (std::size_t i = 1; i < r.queries.size(); ++i) {
            const std::uint64_t now = source_->nanoseconds(r.queries[i]);
            // a clock that runs backwards (it must not) reads as 0 rather than as 584 years
            t.ms.push_back(now >= previous ? static_cast<double>(now - previous) * 1e-6 : 0.0);
            previous = now;
        }
        for (std::size_t q : r.queries) free_.push_back(q);
        out.push_back(std::move(t));
        pending_.pop_front();
    }
    return out;
}

}  // namespace emcv::gl
