// SPDX-License-Identifier: MIT
// tests/hlsl/host_layout.cpp: prints, as JSON, the byte layout that emcv/port/host.hpp gives each shared struct
// (the std430 mirrors) and that the port's own C++ structs have, for check_hlsl.py's comparison with the
// Direct3D layouts. {"host": {struct: {"size": n, "members": {name: offset}}}, "port": {...}}
#include <cstddef>
#include <cstdio>

#include <emcv/port/host.hpp>

namespace {
bool first_member = true;
void member(const char* name, std::size_t offset) {
    std::printf("%s\"%s\": %zu", first_member ? "" : ", ", name, offset);
    first_member = false;
}
void begin(const char* name, std::size_t size, bool first) {
    std::printf("%s\"%s\": {\"size\": %zu, \"members\": {", first ? "" : ", ", name, size);
    first_member = true;
}
void end() { std::printf("}}"); }
}  // namespace

#define EMCV_MEMBER(T, m) member(#m, offsetof(T, m))

int main() {
    namespace host = emcv::port::host;
    namespace port = emcv::port;
    std::printf("{\"host\": {");
    begin("EmcvEmcm2", sizeof(host::EmcvEmcm2), true);
    EMCV_MEMBER(host::EmcvEmcm2, mean);
    EMCV_MEMBER(host::EmcvEmcm2, cov);
    EMCV_MEMBER(host::EmcvEmcm2, count);
    EMCV_MEMBER(host::EmcvEmcm2, rejected);
    EMCV_MEMBER(host::EmcvEmcm2, reseeded);
    end();
    begin("EmcvMovingStats", sizeof(host::EmcvMovingStats), false);
    EMCV_MEMBER(host::EmcvMovingStats, mean);
    EMCV_MEMBER(host::EmcvMovingStats, variance);
    EMCV_MEMBER(host::EmcvMovingStats, count);
    EMCV_MEMBER(host::EmcvMovingStats, rejected);
    EMCV_MEMBER(host::EmcvMovingStats, reseeded);
    end();
    begin("EmcvBudgetBlock", sizeof(host::EmcvBudgetBlock), false);
    EMCV_MEMBER(host::EmcvBudgetBlock, lambda);
    EMCV_MEMBER(host::EmcvBudgetBlock, planned);
    EMCV_MEMBER(host::EmcvBudgetBlock, default_pixels);
    EMCV_MEMBER(host::EmcvBudgetBlock, zero_pixels);
    EMCV_MEMBER(host::EmcvBudgetBlock, solves);
    EMCV_MEMBER(host::EmcvBudgetBlock, bin_count);
    EMCV_MEMBER(host::EmcvBudgetBlock, bin_fraction);
    EMCV_MEMBER(host::EmcvBudgetBlock, raw_count);
    EMCV_MEMBER(host::EmcvBudgetBlock, raw_inverse_frames);
    EMCV_MEMBER(host::EmcvBudgetBlock, mean_sigma2);
    EMCV_MEMBER(host::EmcvBudgetBlock, between_variance);
    end();
    std::printf("}, \"port\": {");
    // the port's C++ EmcvEmcm2 (glm::vec2, glm::vec3: 4-byte aligned, tightly packed)
    begin("EmcvEmcm2", sizeof(port::EmcvEmcm2), true);
    EMCV_MEMBER(port::EmcvEmcm2, mean);
    EMCV_MEMBER(port::EmcvEmcm2, cov);
    EMCV_MEMBER(port::EmcvEmcm2, count);
    EMCV_MEMBER(port::EmcvEmcm2, rejected);
    EMCV_MEMBER(port::EmcvEmcm2, reseeded);
    end();
    std::printf("}}\n");
    return 0;
}
