// SPDX-License-Identifier: MIT
// GPU pass timing with a ring of GL_TIME_ELAPSED queries (Fwog TimerQueryAsync idea): results are read only
// when available, so timing never stalls the frame. Timings are printed, never asserted.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "handles.hpp"

namespace emcv::gl {

class gpu_timer {
public:
    /// ring_size queries in flight at most (4 lets a result be ready every frame on real GPUs).
    explicit gpu_timer(std::size_t ring_size = 4);

    /// Starts timing; if every query of the ring is still pending, this measurement is dropped (no stall).
    void begin();
    void end();
    /// Oldest finished measurement in milliseconds, if one is available now.
    std::optional<double> pop_ms();
    /// Waits for every pending measurement (end of program only) and returns them in order.
    std::vector<double> drain_ms();

private:
    std::vector<query> queries_;
    std::size_t head_ = 0;     // next query to begin
    std::size_t pending_ = 0;  // begun and not yet read
    bool active_ = false;
};

}  // namespace emcv::gl
