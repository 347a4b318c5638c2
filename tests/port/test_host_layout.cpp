// SPDX-License-Identifier: MIT
// emcv/port/host.hpp against glslang's std430 layout: host_layout.comp.glsl declares each port struct that
// crosses a storage buffer; glslangValidator compiles it to SPIR-V (OpenGL and Vulkan), spirv-cross --reflect
// gives each member's offset, type and array stride, and every one must equal the host mirror's offsetof and
// sizeof, the element stride its sizeof. A mirror with a missing or extra padding word fails here.
#include <catch2/catch_test_macros.hpp>

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <emcv/port/host.hpp>

#include "../support/run_command.hpp"

namespace fs = std::filesystem;
namespace host = emcv::port::host;

namespace {

/// One member of a host mirror: its GLSL name, offsetof and sizeof.
struct member_layout {
    std::string name;
    std::size_t offset;
    std::size_t size;
};

#define EMCV_HOST_MEMBER(T, m) member_layout{#m, offsetof(T, m), sizeof(T::m)}

/// The std430 size of a scalar or vector type as spirv-cross names it.
std::size_t glsl_type_size(const std::string& type) {
    static const std::map<std::string, std::size_t> sizes = {
        {"float", 4}, {"uint", 4}, {"int", 4}, {"vec2", 8}, {"vec3", 12}, {"vec4", 16},
        {"uvec2", 8}, {"uvec3", 12}, {"uvec4", 16}, {"ivec2", 8}, {"ivec3", 12}, {"ivec4", 16}};
    const auto it = sizes.find(type);
    if (it == sizes.end()) FAIL("host_layout.comp.glsl uses a member type this test cannot size: " << type);
    return it->second;
}

/// spirv-cross's reflection of the shader compiled for `target` ("-G --target-env opengl" or "-V ...").
nlohmann::json reflect(const std::string& target, const std::string& tag) {
    const fs::path dir = fs::path(EMCV_TEST_OUTPUT_DIR);
    fs::create_directories(dir);
    const fs::path spv = dir / ("host_layout." + tag + ".spv");
    const emcv_test::command_result compiled =
        emcv_test::run_command(std::string(EMCV_GLSLANG_VALIDATOR) + " " + target + " -I" + EMCV_INCLUDE_DIR + " " +
                               EMCV_HOST_LAYOUT_SHADER + " -o " + spv.string());
    INFO(compiled.output());
    REQUIRE(compiled.exit_code == 0);
    const emcv_test::command_result reflected =
        emcv_test::run_command(std::string(EMCV_SPIRV_CROSS) + " " + spv.string() + " --reflect");
    INFO(reflected.output());
    REQUIRE(reflected.exit_code == 0);
    return nlohmann::json::parse(reflected.out);
}

/// The reflected type named `name` (a struct or a block).
const nlohmann::json& type_named(const nlohmann::json& reflection, const std::string& name) {
    for (const auto& item : reflection.at("types").items())
        if (item.value().at("name") == name) return item.value();
    FAIL("no type " << name << " in the reflection");
    throw std::logic_error("unreachable");
}

/// Checks every member of struct `glsl_struct` against `mirror` (same names, same order), and returns how many.
std::size_t check_members(const nlohmann::json& reflection, const std::string& glsl_struct,
                          const std::vector<member_layout>& mirror) {
    const nlohmann::json& members = type_named(reflection, glsl_struct).at("members");
    REQUIRE(members.size() == mirror.size());
    for (std::size_t i = 0; i < mirror.size(); ++i) {
        const nlohmann::json& m = members[i];
        INFO(glsl_struct << "." << m.at("name").get<std::string>() << " (member " << i << ")");
        CHECK(m.at("name") == mirror[i].name);
        CHECK(m.at("offset").get<std::size_t>() == mirror[i].offset);
        std::size_t size = glsl_type_size(m.at("type").get<std::string>());
        if (m.contains("array")) {
            REQUIRE(m.at("array").size() == 1);
            size = m.at("array_stride").get<std::size_t>() * m.at("array")[0].get<std::size_t>();
        }
        CHECK(size == mirror[i].size);
    }
    return members.size();
}

/// The array stride of the block member `member` of block `block` (a runtime array of a port struct).
std::size_t element_stride(const nlohmann::json& reflection, const std::string& block, const std::string& member) {
    for (const auto& m : type_named(reflection, block).at("members"))
        if (m.at("name") == member) return m.at("array_stride").get<std::size_t>();
    FAIL("block " << block << " has no member " << member);
    throw std::logic_error("unreachable");
}

/// block_size of the storage block named `block`.
std::size_t block_size(const nlohmann::json& reflection, const std::string& block) {
    for (const auto& ssbo : reflection.at("ssbos"))
        if (type_named(reflection, block) == reflection.at("types").at(ssbo.at("type").get<std::string>()))
            return ssbo.at("block_size").get<std::size_t>();
    FAIL("no storage block " << block);
    throw std::logic_error("unreachable");
}

void check_all(const nlohmann::json& r) {
    check_members(r, "EmcvEmcm2",
                  {EMCV_HOST_MEMBER(host::EmcvEmcm2, mean), EMCV_HOST_MEMBER(host::EmcvEmcm2, cov),
                   EMCV_HOST_MEMBER(host::EmcvEmcm2, count), EMCV_HOST_MEMBER(host::EmcvEmcm2, rejected),
                   EMCV_HOST_MEMBER(host::EmcvEmcm2, reseeded)});
    CHECK(element_stride(r, "Emcm2Buffer", "emcm2") == sizeof(host::EmcvEmcm2));

    check_members(r, "EmcvMovingStats",
                  {EMCV_HOST_MEMBER(host::EmcvMovingStats, mean), EMCV_HOST_MEMBER(host::EmcvMovingStats, variance),
                   EMCV_HOST_MEMBER(host::EmcvMovingStats, count), EMCV_HOST_MEMBER(host::EmcvMovingStats, rejected),
                   EMCV_HOST_MEMBER(host::EmcvMovingStats, reseeded)});
    CHECK(element_stride(r, "MovingStatsBuffer", "moving_stats") == sizeof(host::EmcvMovingStats));

    check_members(r, "EmcvBudgetBlock",
                  {EMCV_HOST_MEMBER(host::EmcvBudgetBlock, lambda), EMCV_HOST_MEMBER(host::EmcvBudgetBlock, planned),
                   EMCV_HOST_MEMBER(host::EmcvBudgetBlock, default_pixels),
                   EMCV_HOST_MEMBER(host::EmcvBudgetBlock, zero_pixels),
                   EMCV_HOST_MEMBER(host::EmcvBudgetBlock, solves),
                   EMCV_HOST_MEMBER(host::EmcvBudgetBlock, bin_count),
                   EMCV_HOST_MEMBER(host::EmcvBudgetBlock, bin_fraction),
                   EMCV_HOST_MEMBER(host::EmcvBudgetBlock, raw_count),
                   EMCV_HOST_MEMBER(host::EmcvBudgetBlock, raw_inverse_frames),
                   EMCV_HOST_MEMBER(host::EmcvBudgetBlock, mean_sigma2),
                   EMCV_HOST_MEMBER(host::EmcvBudgetBlock, between_variance)});
    CHECK(block_size(r, "BudgetBuffer") == sizeof(host::EmcvBudgetBlock));
}

}  // namespace

TEST_CASE("host.hpp mirrors have glslang's std430 offsets, sizes and strides (OpenGL SPIR-V)") {
    check_all(reflect("-G --target-env opengl", "gl"));
}

TEST_CASE("host.hpp mirrors have glslang's std430 offsets, sizes and strides (Vulkan SPIR-V)") {
    check_all(reflect("-V --target-env vulkan1.0", "vk"));
}

TEST_CASE("the port's C++ EmcvEmcm2 is not the GPU layout; to_host and to_port round-trip it") {
    // Why the mirror exists: std430 aligns the vec3 to 16 and the struct to its size, C++ packs the glm::vec3.
    CHECK(sizeof(emcv::port::EmcvEmcm2) != sizeof(host::EmcvEmcm2));
    emcv::port::EmcvEmcm2 s = emcv::port::emcv_emcm2_init();
    emcv::port::emcv_emcm2_push(s, glm::vec2(1.0f, 2.0f), 0.25f);
    emcv::port::emcv_emcm2_push(s, glm::vec2(-3.0f, 0.5f), 0.25f);
    s.rejected = 7u;
    s.reseeded = 9u;
    const host::EmcvEmcm2 h = host::to_host(s);
    CHECK(h.mean[0] == s.mean.x);
    CHECK(h.mean[1] == s.mean.y);
    CHECK(h.cov[0] == s.cov.x);
    CHECK(h.cov[1] == s.cov.y);
    CHECK(h.cov[2] == s.cov.z);
    CHECK(h.count == 2u);
    CHECK(h.rejected == 7u);
    CHECK(h.reseeded == 9u);
    const emcv::port::EmcvEmcm2 back = host::to_port(h);
    CHECK(back.mean == s.mean);
    CHECK(back.cov == s.cov);
    CHECK(back.count == s.count);
    CHECK(back.rejected == s.rejected);
    CHECK(back.reseeded == s.reseeded);
}
