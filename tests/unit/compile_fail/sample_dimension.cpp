// Pushes of a sample whose component count differs from the estimator's dimension N. Each CASE_* must fail to
// compile with sample_vector's static_assert (tests/unit/CMakeLists.txt runs the compiler on each); without a
// CASE_* defined the file is the valid uses and must compile.
#include <emcv/emcv.hpp>

#include <array>

int main() {
    emcv::emcm<float, 2> two(0.05f);
    emcv::weighted_covariance<double, 2> weighted;
    emcv::running_covariance<double, 3> three;
    const float f = 1.0f;
#if defined(CASE_BRACED_TOO_SHORT)
    two.push({f});  // would push (f, 0) through a std::array<float, 2> parameter
#elif defined(CASE_BRACED_TOO_LONG)
    two.push({f, f, f});
#elif defined(CASE_SCALAR_FOR_TWO)
    two.push(f);
#elif defined(CASE_STD_ARRAY_WRONG_SIZE)
    two.push(std::array<float, 3>{f, f, f});
#elif defined(CASE_C_ARRAY_WRONG_SIZE)
    const float c[1] = {f};
    two.push(c);
#elif defined(CASE_WEIGHTED_TOO_SHORT)
    weighted.push({1.0}, 2.0);
#elif defined(CASE_RUNNING_TOO_SHORT)
    three.push({1.0, 2.0});
#else
    const float c[2] = {f, f};
    two.push({f, f});
    two.push(std::array<float, 2>{f, f});
    two.push(c);
    weighted.push({1.0, 2.0}, 2.0, 0.5);
    three.push({1, 2, 3});
    emcv::moving_stats<double> one(0.2);
    one.push(1.0);
#endif
    return 0;
}
