// SPDX-License-Identifier: MIT
// Pass times from one timestamp at every pass boundary: a frame of P passes takes P + 1 stamps, and pass i
// lasts from stamp i to stamp i + 1. Two clocks behind one interface:
// - GPU timestamps (glQueryCounter GL_TIMESTAMP): the GPU's clock when the command stream reaches the stamp,
//   read back frames later; nothing waits in the measured path.
// - the wall clock: glFinish, then the steady clock, at every boundary (what a software renderer such as
//   llvmpipe needs: its timer queries do not cover compute dispatches).
// The ring grows when every query is in flight: a measurement is never dropped.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

namespace emcv::gl {

/// Where stamps come from. Query indices are dense from 0; grow() adds more.
class timestamp_source {
public:
    virtual ~timestamp_source() = default;
    /// Number of queries made so far.
    virtual std::size_t size() const = 0;
    /// Makes `count` more queries (indices size() .. size() + count - 1).
    virtual void grow(std::size_t count) = 0;
    /// Records a stamp into query `q` at the current point of the command stream.
    virtual void stamp(std::size_t q) = 0;
    /// True when query `q`'s stamp can be read without waiting.
    virtual bool ready(std::size_t q) = 0;
    /// Query `q`'s stamp in nanoseconds on the source's clock (waits for it when not ready).
    virtual std::uint64_t nanoseconds(std::size_t q) = 0;
};

/// GL_TIMESTAMP queries: the GPU's clock (needs a current GL context).
std::unique_ptr<timestamp_source> make_gpu_timestamps();
/// glFinish + std::chrono::steady_clock (needs a current GL context): every stamp is ready at once.
std::unique_ptr<timestamp_source> make_wall_timestamps();

/// One frame's measured passes: the tag the caller gave each pass, and its time in milliseconds.
struct timed_frame {
    int frame = 0;
    std::vector<std::size_t> tags;  ///< as given to end_pass, in recording order
    std::vector<double> ms;         ///< ms[i]: stamp i to stamp i + 1
};

/// Stamps at every pass boundary of every frame, read back in frame order once the GPU has written them.
class pass_timestamps {
public:
    explicit pass_timestamps(std::unique_ptr<timestamp_source> source);

    /// Stamps the start of `frame` (its first pass starts here). Throws std::logic_error inside a frame.
    void begin_frame(int frame);
    /// Stamps the end of the current pass, which the caller names with `tag`; the next pass starts here.
    void end_pass(std::size_t tag);
    /// Closes the frame: it becomes pending until its stamps arrive. Throws std::logic_error outside a frame.
    void end_frame();

    /// The frames whose stamps have all arrived, oldest first, each once. `wait`: every closed frame, waiting
    /// for its stamps (end of a run).
    std::vector<timed_frame> collect(bool wait);
    /// Frames closed and not yet collected.
    std::size_t pending_frames() const { return pending_.size(); }
    /// Queries made so far (grows, never drops).
    std::size_t query_count() const { return source_->size(); }

private:
    struct frame_record {
        int frame = 0;
        std::vector<std::size_t> queries;  // P + 1
        std::vector<std::size_t> tags;     // P
    };
    std::size_t take_query();

    std::unique_ptr<timestamp_source> source_;
    std::vector<std::size_t> free_;  // query indices not in flight
    std::deque<frame_record> pending_;
    frame_record open_;
    bool in_frame_ = false;
};

}  // namespace emcv::gl
