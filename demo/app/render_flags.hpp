// SPDX-License-Identifier: MIT
// The one place a command line's options become render_options (emcv-demo's headless and window runs,
// emcv-eval): the size, seed, inverse-CDF choice and tunables they parsed, and the clock the caller needs.
#pragma once

#include "render/render_options.hpp"

namespace emcv::demo::app {

/// `Options` is a parsed command line with width, height, seed, approximate_cdf, defines, resolve and jitter.
template <class Options>
render_options make_render_options(const Options& o, timing clock) {
    render_options ro;
    ro.width = o.width;
    ro.height = o.height;
    ro.seed = o.seed;
    ro.approximate_inverse_cdf = o.approximate_cdf;
    ro.defines = o.defines;
    ro.timing_mode = clock;
    ro.resolve = o.resolve;
    ro.jitter = o.jitter;
    return ro;
}

}  // namespace emcv::demo::app
