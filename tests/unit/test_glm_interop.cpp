// glm::vec<N, T> is accepted wherever a std::array<T, N> is (detected structurally; the library never
// includes GLM itself).
#include <emcv/emcv.hpp>

#include <catch2/catch_test_macros.hpp>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

TEST_CASE("glm vectors push like std::array", "[glm]") {
    emcv::emcm<float, 3> g(0.25f);
    emcv::emcm<float, 3> a(0.25f);
    const glm::vec3 xs[] = {{1.0f, 2.0f, 3.0f}, {2.0f, 0.5f, -1.0f}, {4.0f, 1.0f, 0.0f}};
    for (const auto& x : xs) {
        REQUIRE(g.push(x));
        a.push(std::array<float, 3>{x.x, x.y, x.z});
    }
    REQUIRE(g.mean() == a.mean());
    REQUIRE(g.covariance_matrix() == a.covariance_matrix());

    emcv::weighted_covariance<double, 2> w;
    REQUIRE(w.push(glm::dvec2(1.0, 2.0), 2.0, 1.0));
    REQUIRE(w.mean(1) == 2.0);
    emcv::running_covariance<double, 2> r;
    REQUIRE(r.push(glm::dvec2(1.0, 2.0)));
    REQUIRE_FALSE(r.push(glm::dvec2(1.0, std::numeric_limits<double>::quiet_NaN())));
}
