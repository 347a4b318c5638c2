// SPDX-License-Identifier: MIT
// The C++ side of tests/python/test_reference.py: the recipe of docs/integration.md (plan_frame, then
// sampling_update with the planned counts) over frames read from a file, through the C++ library alone, so that
// the Python module's results can be compared with it byte for byte.
//   emcv-python-reference ESTIMATOR MODE WIDTH HEIGHT FRAMES TARGET BUDGET N_MIN N_MAX ETA SEED INPUT OUTPUT
// ESTIMATOR spvg|cv|cv_notex, MODE quality_target|budget, ETA 0 for the estimator's default. INPUT holds, per
// frame, f and g (float32, WIDTH x HEIGHT each) and material (uint32). OUTPUT receives, per frame, the counts
// (int32), the pooled sigma2 (float32) and lambda (float32), then the final history states (the port's structs).
#include <emcv/adaptive_sampling.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

template <class T>
bool read(std::FILE* in, std::vector<T>& v) {
    return std::fread(v.data(), sizeof(T), v.size(), in) == v.size();
}

template <class T>
void write(std::FILE* out, const T* data, std::size_t n) {
    if (std::fwrite(data, sizeof(T), n, out) != n) {
        std::fprintf(stderr, "emcv-python-reference: write failed\n");
        std::exit(1);
    }
}

template <class State>
int run(const emcv::sampling_params& p, std::size_t width, std::size_t height, int frames, std::uint32_t seed,
        std::FILE* in, std::FILE* out, State empty) {
    const std::size_t pixels = width * height;
    std::vector<State> history(pixels, empty);
    std::vector<float> f(pixels), g(pixels), sigma2(pixels);
    std::vector<std::uint32_t> material(pixels);
    std::vector<int> counts(pixels);
    emcv::budget_prior prior;  // carried between frames, as emcv.History carries it
    for (int t = 0; t < frames; ++t) {
        if (!read(in, f) || !read(in, g) || !read(in, material)) {
            std::fprintf(stderr, "emcv-python-reference: the input ends before frame %d\n", t);
            return 1;
        }
        const emcv::frame_plan plan = emcv::plan_frame(p, history.data(), pixels, width, material.data(), nullptr,
                                                       static_cast<std::uint32_t>(t), seed, sigma2.data(),
                                                       counts.data(), prior);
        emcv::sampling_update(p, history.data(), pixels, width, material.data(), f.data(), g.data(), counts.data());
        write(out, counts.data(), pixels);
        write(out, sigma2.data(), pixels);
        write(out, &plan.lambda, 1);
    }
    write(out, history.data(), pixels);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 14) {
        std::fprintf(stderr,
                     "usage: %s ESTIMATOR MODE WIDTH HEIGHT FRAMES TARGET BUDGET N_MIN N_MAX ETA SEED INPUT OUTPUT\n", argv[0]);
        return 2;
    }
    emcv::sampling_params p;
    const std::string estimator = argv[1], mode = argv[2];
    p.estimator = estimator == "cv"     ? emcv::sampling_estimator::cv
                  : estimator == "spvg" ? emcv::sampling_estimator::spvg
                                        : emcv::sampling_estimator::cv_notex;
    p.mode = mode == "budget" ? emcv::sampling_mode::budget : emcv::sampling_mode::quality_target;
    const std::size_t width = std::strtoul(argv[3], nullptr, 10), height = std::strtoul(argv[4], nullptr, 10);
    const int frames = std::atoi(argv[5]);
    p.target = std::strtof(argv[6], nullptr);
    p.budget = std::strtof(argv[7], nullptr);
    p.n_min = std::atoi(argv[8]);
    p.n_max = std::atoi(argv[9]);
    const float eta = std::strtof(argv[10], nullptr);
    if (eta > 0.0f) p.eta = eta;
    const auto seed = static_cast<std::uint32_t>(std::strtoul(argv[11], nullptr, 10));
    std::FILE* in = std::fopen(argv[12], "rb");
    std::FILE* out = std::fopen(argv[13], "wb");
    if (in == nullptr || out == nullptr) {
        std::fprintf(stderr, "emcv-python-reference: cannot open %s or %s\n", argv[12], argv[13]);
        return 2;
    }
    const int rc = p.estimator == emcv::sampling_estimator::cv
                       ? run(p, width, height, frames, seed, in, out, emcv::port::emcv_emcm2_init())
                       : run(p, width, height, frames, seed, in, out, emcv::port::emcv_moving_stats_init());
    std::fclose(in);
    return std::fclose(out) == 0 ? rc : 1;
}
