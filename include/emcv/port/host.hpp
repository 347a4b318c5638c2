// SPDX-License-Identifier: MIT
/// \file
/// emcv/port/host.hpp — host (C++) mirrors of the port's structs in their GPU storage-buffer layout (std430),
/// for uploading states to a shader and reading them back. C++ only (GLSL declares the structs itself).
//
// ABOUT      The port's C++ structs (emcv::port::EmcvEmcm2, ...) are the CPU's layout, not the GPU's: std430
//            aligns a vec3 to 16 bytes and rounds a struct's size up to its largest alignment, so EmcvEmcm2 is
//            48 bytes per element in a std430 buffer (mean at 0, cov at 16, count at 28, size 48) but 32 bytes as
//            emcv::port::EmcvEmcm2 (glm::vec3 at 8). Reading a buffer of EmcvEmcm2 back through the port's
//            struct gives garbage from the second element on; read it through emcv::port::host::EmcvEmcm2 and
//            convert. Structs whose members are all 4-byte scalars (EmcvMovingStats, EmcvBudgetBlock) have the
//            same layout on both sides: their mirrors are the port's structs.
//            The offsets below are checked against glslang's own std430 layout (spirv-cross --reflect) by
//            tests/port (test_host_layout.cpp), and by a compute shader on llvmpipe in ctest -L package.
// USAGE      std::vector<emcv::port::host::EmcvEmcm2> gpu(n);  // glGetNamedBufferSubData(buf, 0, n * 48, gpu.data())
//            emcv::port::EmcvEmcm2 s = emcv::port::host::to_port(gpu[i]);
#ifndef EMCV_PORT_HOST_HPP
#define EMCV_PORT_HOST_HPP

#include <cstddef>
#include <cstdint>

#include "budget.h"
#include "ema.h"

/// \namespace emcv::port::host
/// Host mirrors of the port's structs in the std430 layout of a GPU storage buffer (emcv/port/host.hpp).
namespace emcv { namespace port { namespace host {

/// EmcvEmcm2 as a std430 storage buffer holds it: 48 bytes, 16-aligned (the vec3's alignment).
struct alignas(16) EmcvEmcm2 {
    float mean[2];               ///< (mu_f, mu_G), offset 0 (vec2)
    float padding_mean[2];       ///< std430 puts the vec3 at the next multiple of 16
    float cov[3];                ///< (C_ff, C_fG, C_GG), offset 16 (vec3)
    std::uint32_t count;         ///< accepted samples, offset 28 (packed after the vec3's 12 bytes)
    std::uint32_t rejected;      ///< refused non-finite samples, offset 32
    std::uint32_t reseeded;      ///< invalid stored states replaced by a first sample, offset 36
    std::uint32_t padding_end[2];  ///< the struct's size is rounded up to its alignment, 16
};
static_assert(sizeof(EmcvEmcm2) == 48 && alignof(EmcvEmcm2) == 16, "std430 EmcvEmcm2: 48 bytes, 16-aligned");
static_assert(offsetof(EmcvEmcm2, mean) == 0 && offsetof(EmcvEmcm2, cov) == 16 && offsetof(EmcvEmcm2, count) == 28 &&
                  offsetof(EmcvEmcm2, rejected) == 32 && offsetof(EmcvEmcm2, reseeded) == 36,
              "std430 EmcvEmcm2 member offsets");

/// EmcvMovingStats: five 4-byte scalars, 20 bytes in std430 and in C++ alike, so the port's struct itself.
using EmcvMovingStats = emcv::port::EmcvMovingStats;
static_assert(sizeof(EmcvMovingStats) == 20 && offsetof(EmcvMovingStats, variance) == 4 &&
                  offsetof(EmcvMovingStats, count) == 8 && offsetof(EmcvMovingStats, rejected) == 12 &&
                  offsetof(EmcvMovingStats, reseeded) == 16,
              "std430 EmcvMovingStats: the port's C++ struct has its layout");

/// EmcvBudgetBlock: 4-byte scalars and uint arrays (stride 4), the same in std430 and C++: the port's struct.
using EmcvBudgetBlock = emcv::port::EmcvBudgetBlock;
static_assert(offsetof(EmcvBudgetBlock, planned) == 4 && offsetof(EmcvBudgetBlock, default_pixels) == 8 &&
                  offsetof(EmcvBudgetBlock, zero_pixels) == 12 && offsetof(EmcvBudgetBlock, solves) == 16 &&
                  offsetof(EmcvBudgetBlock, bin_count) == 20 &&
                  offsetof(EmcvBudgetBlock, bin_fraction) == 20 + 4 * EMCV_BUDGET_BINS &&
                  offsetof(EmcvBudgetBlock, raw_count) == 20 + 8 * EMCV_BUDGET_BINS &&
                  offsetof(EmcvBudgetBlock, raw_inverse_frames) == 20 + 12 * EMCV_BUDGET_BINS &&
                  offsetof(EmcvBudgetBlock, mean_sigma2) == 24 + 12 * EMCV_BUDGET_BINS &&
                  offsetof(EmcvBudgetBlock, between_variance) == 28 + 12 * EMCV_BUDGET_BINS &&
                  sizeof(EmcvBudgetBlock) == 32 + 12 * EMCV_BUDGET_BINS,
              "std430 EmcvBudgetBlock: the port's C++ struct has its layout");

/// The port's state in the GPU layout (padding zeroed).
inline EmcvEmcm2 to_host(const emcv::port::EmcvEmcm2& s) {
    EmcvEmcm2 h{};
    h.mean[0] = s.mean.x;
    h.mean[1] = s.mean.y;
    h.cov[0] = s.cov.x;
    h.cov[1] = s.cov.y;
    h.cov[2] = s.cov.z;
    h.count = s.count;
    h.rejected = s.rejected;
    h.reseeded = s.reseeded;
    return h;
}

/// A state read back from the GPU as the port's C++ struct.
inline emcv::port::EmcvEmcm2 to_port(const EmcvEmcm2& h) {
    emcv::port::EmcvEmcm2 s = emcv::port::emcv_emcm2_init();
    s.mean = glm::vec2(h.mean[0], h.mean[1]);
    s.cov = glm::vec3(h.cov[0], h.cov[1], h.cov[2]);
    s.count = h.count;
    s.rejected = h.rejected;
    s.reseeded = h.reseeded;
    return s;
}

/// EmcvMovingStats needs no conversion (same layout); the identity, for generic code.
inline EmcvMovingStats to_host(const emcv::port::EmcvMovingStats& s) { return s; }
/// The identity (see to_host).
inline emcv::port::EmcvMovingStats to_port(const EmcvMovingStats& h) { return h; }

} } }  // namespace emcv::port::host

#endif  // #ifndef EMCV_PORT_HOST_HPP
