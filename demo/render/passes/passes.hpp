// SPDX-License-Identifier: MIT
// The frame's passes, one module each (pass_list.hpp names them, in order). Each records itself from the frame
// context: binds what only it reads and writes, dispatches, and leaves the barrier its readers need. What every
// pass shares (the frame's buffers, the targets the compute passes sample, the SSS tile list as the indirect
// dispatch buffer) is bound once per frame by bind_frame_resources.
#pragma once

#include "render/pass_list.hpp"
#include "render/resources.hpp"

namespace emcv::demo::passes {

void gbuffer(const frame_context& c);
void shadow(const frame_context& c, const planned_pass& p);
void lighting(const frame_context& c);
void sss_adaptive_samples(const frame_context& c);
/// `variant`: an adaptive method's program (planned_pass::burley; the others have one).
void sss_burley(const frame_context& c, burley_variant variant = burley_variant::updates);
/// direction 0: horizontal, from the lighting; 1: vertical, from the horizontal pass's result.
void sss_separable(const frame_context& c, int direction);
void composite(const frame_context& c);
void resolve(const frame_context& c);

/// Records the planned pass `p` (the renderer's loop over frame_planner::plan).
void record(const planned_pass& p, const frame_context& c);

/// Binds, once per frame before the first pass, what the passes share: the frame's uniform and storage buffers,
/// the vertex array, the targets the compute passes read through samplers (G-buffer, shadow maps, lighting)
/// and the SSS tile list as the indirect dispatch buffer. Binding the targets while the raster passes render
/// into them makes no feedback loop: those programs sample only the albedo map's unit.
void bind_frame_resources(const frame_context& c);
/// Makes image stores visible to later texture fetches and image loads.
void image_barrier_for_reads();

}  // namespace emcv::demo::passes
