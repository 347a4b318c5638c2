// SPDX-License-Identifier: MIT
#include "schema_keys.hpp"

#include <stdexcept>
#include <string>

namespace emcv::demo {

const std::vector<schema_object>& scene_schema() {
    constexpr bool required = true, optional = false;
    static const std::vector<schema_object> table{
        {"scene", {{"$schema", optional}, {"description", optional}, {"mm_per_unit", required}, {"frames", optional},
                   {"background", optional}, {"ambient", optional}, {"camera", required}, {"meshes", required},
                   {"materials", required}, {"objects", required}, {"lights", optional}}},
        {"camera", {{"position", required}, {"target", required}, {"up", optional}, {"fov_y_degrees", optional},
                    {"near", optional}, {"far", optional}, {"keys", optional}}},
        {"camera_key", {{"frame", required}, {"position", required}, {"target", required}}},
        {"mesh_sphere", {{"type", required}, {"name", required}, {"radius", optional}, {"segments", optional},
                         {"rings", optional}}},
        {"mesh_torus", {{"type", required}, {"name", required}, {"major_radius", optional},
                        {"minor_radius", optional}, {"segments", optional}, {"sides", optional}}},
        {"mesh_slab", {{"type", required}, {"name", required}, {"radius", optional}, {"angle_degrees", optional},
                       {"thickness", optional}, {"height", optional}, {"segments", optional}}},
        {"mesh_plane", {{"type", required}, {"name", required}, {"width", optional}, {"depth", optional},
                        {"subdivisions", optional}}},
        {"mesh_file", {{"type", required}, {"name", required}, {"path", required}}},
        {"material_diffuse", {{"type", required}, {"name", required}, {"albedo", optional},
                              {"albedo_texture", optional}, {"specular", optional}, {"roughness", optional}}},
        {"material_sss", {{"type", required}, {"name", required}, {"albedo", optional}, {"albedo_texture", optional},
                          {"mean_free_path_mm", required}, {"specular", optional}, {"roughness", optional}}},
        {"object", {{"name", required}, {"mesh", required}, {"material", required}, {"transform", optional}}},
        {"transform", {{"translate", optional}, {"rotate_degrees", optional}, {"scale", optional}}},
        {"light_directional", {{"type", required}, {"name", required}, {"color", optional}, {"intensity", optional},
                               {"direction", required}, {"casts_shadow", optional}}},
        {"light_point", {{"type", required}, {"name", required}, {"color", optional}, {"intensity", optional},
                         {"position", required}, {"casts_shadow", optional}}},
        {"light_spot", {{"type", required}, {"name", required}, {"color", optional}, {"intensity", optional},
                        {"position", required}, {"direction", required}, {"inner_cone_degrees", optional},
                        {"outer_cone_degrees", optional}, {"casts_shadow", optional}}},
        {"curve_constant", {{"type", required}, {"value", required}}},
        {"curve_steps", {{"type", required}, {"value", required}, {"steps", required}}},
        {"curve_step", {{"frame", required}, {"value", required}}},
        {"curve_flicker", {{"type", required}, {"value", required}, {"peak", required}, {"bursts", required},
                           {"burst_length", optional}}},
        {"curve_sinusoid", {{"type", required}, {"value", required}, {"amplitude", required},
                            {"period_frames", required}, {"phase", optional}}},
    };
    return table;
}

const schema_object& scene_schema_object(std::string_view kind) {
    for (const auto& o : scene_schema())
        if (o.kind == kind) return o;
    throw std::out_of_range("scene_schema_object: no kind " + std::string(kind));
}

}  // namespace emcv::demo
