// SPDX-License-Identifier: MIT
// lighting: diffuse irradiance without albedo and specular, kept apart (the SSS passes scatter the first); on a
// frame with SSS passes also the SSS tile list and their indirect dispatch arguments (render/tiles.h).
#include "passes.hpp"

#include "render/bindings.h"

namespace emcv::demo::passes {

void lighting(const frame_context& c) {
    const gpu_resources& r = c.res;
    if (c.sss_passes) {
        // An empty tile list (the workgroups that find SSS pixels append to it and grow the dispatch) and zeroed
        // sample statistics: 32 bytes, no full-screen work.
        const GLuint header[4] = {0u, 0u, 1u, 0u};
        glNamedBufferSubData(r.tiles_ssbo.id(), 0, sizeof header, header);
        glClearNamedBufferData(r.stats_ssbo.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    }
    c.programs.lighting.use();
    glBindImageTexture(EMCV_RENDER_IMG_DIFFUSE, r.lit_diffuse.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(EMCV_RENDER_IMG_SPECULAR, r.lit_specular.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(c.groups_x, c.groups_y, 1);
    image_barrier_for_reads();
    if (c.sss_passes) glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace emcv::demo::passes
