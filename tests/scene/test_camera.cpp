// SPDX-License-Identifier: MIT
// Camera paths (scene.hpp): keyframes interpolate linearly and hold outside their range.
#include <catch2/catch_test_macros.hpp>

#include "scene/scene.hpp"

using emcv::demo::camera;

namespace {

camera three_keys() {
    camera c;
    c.keys = {{0, {0.0f, 0.0f, 4.0f}, {0.0f, 0.0f, 0.0f}},
              {10, {4.0f, 0.0f, 0.0f}, {0.0f, 2.0f, 0.0f}},
              {30, {0.0f, 0.0f, -4.0f}, {0.0f, 0.0f, 0.0f}}};
    return c;
}

}  // namespace

TEST_CASE("without keys the camera stays at its position and target") {
    camera c;
    c.position = {1.0f, 2.0f, 3.0f};
    c.target = {0.0f, 1.0f, 0.0f};
    for (int f : {0, 7, 1000}) {
        CHECK(c.at(f).first == c.position);
        CHECK(c.at(f).second == c.target);
    }
    CHECK(c.is_static());
}

TEST_CASE("keyframes interpolate linearly between keys and hold outside them") {
    const camera c = three_keys();
    CHECK(c.at(0).first == glm::vec3(0.0f, 0.0f, 4.0f));
    CHECK(c.at(10).first == glm::vec3(4.0f, 0.0f, 0.0f));
    CHECK(c.at(10).second == glm::vec3(0.0f, 2.0f, 0.0f));
    CHECK(c.at(5).first == glm::vec3(2.0f, 0.0f, 2.0f));    // halfway between keys 0 and 1
    CHECK(c.at(5).second == glm::vec3(0.0f, 1.0f, 0.0f));
    CHECK(c.at(20).first == glm::vec3(2.0f, 0.0f, -2.0f));  // halfway between keys 1 and 2 (uneven spacing)
    CHECK(c.at(25).second == glm::vec3(0.0f, 0.5f, 0.0f));  // three quarters from key 1 to key 2
    CHECK(c.at(-5).first == glm::vec3(0.0f, 0.0f, 4.0f));   // before the first key
    CHECK(c.at(31).first == glm::vec3(0.0f, 0.0f, -4.0f));  // after the last key
    CHECK(c.at(1000).second == glm::vec3(0.0f));
    CHECK_FALSE(c.is_static());
}

TEST_CASE("a camera is static with fewer than two keys or identical keys") {
    camera one;
    one.keys = {{5, {1.0f, 1.0f, 1.0f}, {0.0f, 0.0f, 0.0f}}};
    CHECK(one.is_static());
    CHECK(one.at(0).first == glm::vec3(1.0f));
    camera same;
    same.keys = {{0, {1.0f, 1.0f, 1.0f}, {0.0f, 0.0f, 0.0f}}, {10, {1.0f, 1.0f, 1.0f}, {0.0f, 0.0f, 0.0f}}};
    CHECK(same.is_static());
    camera turning = same;
    turning.keys[1].target = {0.0f, 1.0f, 0.0f};  // only the target moves
    CHECK_FALSE(turning.is_static());
}
