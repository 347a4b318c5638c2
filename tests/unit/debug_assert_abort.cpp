// The default EMCV_ASSERT of a build without NDEBUG: mean(7) of a 2-D estimator prints the message and aborts
// (tests/unit/CMakeLists.txt expects that message in the output).
#undef NDEBUG
#include <emcv/emcm.hpp>

#include <csignal>
#include <cstdio>
#include <cstdlib>

int main() {
    // CTest counts a signal as a crash whatever the output says: turn the abort into an exit status
    std::signal(SIGABRT, [](int) { std::_Exit(134); });
    emcv::emcm<double, 2> e(0.1);
    e.push({1.0, 2.0});
    std::printf("mean(7) = %g\n", e.mean(7));  // never printed: the assertion aborts first
    return 0;
}
