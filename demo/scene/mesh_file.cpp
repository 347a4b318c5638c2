// SPDX-License-Identifier: MIT
#include "mesh_file.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

namespace emcv::demo {
namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

glm::mat4 to_glm(const aiMatrix4x4& m) {
    // assimp is row-major (a1..a4 is the first row); glm is column-major.
    return glm::mat4(m.a1, m.b1, m.c1, m.d1, m.a2, m.b2, m.c2, m.d2, m.a3, m.b3, m.c3, m.d3, m.a4, m.b4, m.c4, m.d4);
}

void append_node(const aiScene& scene, const aiNode& node, const glm::mat4& parent, mesh& out) {
    const glm::mat4 world = parent * to_glm(node.mTransformation);
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(world)));
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
        const aiMesh& m = *scene.mMeshes[node.mMeshes[i]];
        if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;  // point clouds, lines
        if (!m.HasNormals()) throw mesh_file_error("assimp computed no normals for a triangle mesh");
        if (out.vertices.size() + m.mNumVertices > std::numeric_limits<std::uint32_t>::max())
            throw mesh_file_error("too many vertices for 32-bit indices");
        const auto first = static_cast<std::uint32_t>(out.vertices.size());
        for (unsigned v = 0; v < m.mNumVertices; ++v) {
            const aiVector3D& p = m.mVertices[v];
            const aiVector3D& n = m.mNormals[v];  // present: aiProcess_GenSmoothNormals
            vertex out_v{};
            out_v.position = glm::vec3(world * glm::vec4(p.x, p.y, p.z, 1.0f));
            const glm::vec3 normal = normal_matrix * glm::vec3(n.x, n.y, n.z);
            const float length = glm::length(normal);
            if (!finite(out_v.position)) throw mesh_file_error("non-finite vertex position");
            // A vertex used only by degenerate triangles has no normal; any unit vector will do for it.
            out_v.normal = length > 0.0f && std::isfinite(length) ? normal / length : glm::vec3(0.0f, 1.0f, 0.0f);
            if (m.HasTextureCoords(0)) out_v.uv = {m.mTextureCoords[0][v].x, m.mTextureCoords[0][v].y};
            else out_v.uv = glm::vec2(0.0f);
            out.vertices.push_back(out_v);
        }
        for (unsigned f = 0; f < m.mNumFaces; ++f) {
            const aiFace& face = m.mFaces[f];
            if (face.mNumIndices != 3) continue;  // points and lines left by aiProcess_Triangulate
            for (unsigned k = 0; k < 3; ++k) out.indices.push_back(first + face.mIndices[k]);
        }
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c) append_node(scene, *node.mChildren[c], world, out);
}

}  // namespace

mesh read_mesh_file(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw mesh_file_error("mesh file not found: " + path.string());
    if (!std::filesystem::is_regular_file(path, ec)) throw mesh_file_error("not a regular file: " + path.string());
    Assimp::Importer importer;
    // Polygons to triangles; weld identical vertices (OBJ stores one per face corner); smooth normals only
    // where the file has none; points and lines split into meshes of their own (skipped below). The node
    // transforms are applied by append_node.
    const aiScene* scene = importer.ReadFile(
        path.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
                           aiProcess_SortByPType);
    if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
        throw mesh_file_error("cannot read mesh file " + path.string() + ": " + importer.GetErrorString());
    mesh out;
    out.name = path.filename().string();
    append_node(*scene, *scene->mRootNode, glm::mat4(1.0f), out);
    if (out.indices.empty()) throw mesh_file_error("mesh file has no triangles: " + path.string());
    return out;
}

}  // namespace emcv::demo
