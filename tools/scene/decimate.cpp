// SPDX-License-Identifier: MIT
// emcv-decimate: makes the small mesh copies committed in demo/assets/ from the full scans (scripts/
// make-demo-assets.sh records each command). Reads any mesh assimp reads, simplifies it with meshoptimizer
// (topology-preserving edge collapse, uv seams kept as borders), optionally places it (centred in x and z,
// bottom at y = 0, scaled to a height) and writes binary PLY (.ply) or OBJ (.obj) through assimp's exporter.
// Normals are not written: the loader computes smooth normals.
//
//   emcv-decimate IN OUT [--triangles N] [--fit-height H]
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <meshoptimizer.h>

namespace {

struct usage_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct options {
    std::filesystem::path input, output;
    std::size_t triangles = 0;  ///< 0: keep every triangle
    float fit_height = 0.0f;    ///< 0: keep the file's placement and scale
};

struct vertex_data {
    float position[3];
    float uv[2];
};

struct triangle_mesh {
    std::vector<vertex_data> vertices;
    std::vector<unsigned> indices;
    bool has_uv = false;
};

double parse_number(const std::string& flag, const std::string& text) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || errno != 0 || !std::isfinite(v) || v <= 0.0)
        throw usage_error(flag + " expects a positive number, got \"" + text + "\"");
    return v;
}

options parse_arguments(int argc, char** argv) {
    options o;
    std::vector<std::string> positional;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw usage_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--triangles") {
            const double n = parse_number(a, value());
            if (n != std::floor(n) || n > 1e8) throw usage_error("--triangles expects a whole number up to 1e8");
            o.triangles = static_cast<std::size_t>(n);
        } else if (a == "--fit-height") {
            o.fit_height = static_cast<float>(parse_number(a, value()));
        } else if (a == "--help" || a == "-h") {
            std::cout << "usage: emcv-decimate IN OUT [--triangles N] [--fit-height H]\n";
            std::exit(0);
        } else if (!a.empty() && a[0] == '-') {
            throw usage_error("unknown flag " + a);
        } else {
            positional.push_back(a);
        }
    }
    if (positional.size() != 2) throw usage_error("expected IN and OUT files");
    o.input = positional[0];
    o.output = positional[1];
    const auto ext = o.output.extension();
    if (ext != ".ply" && ext != ".obj") throw usage_error("OUT must end in .ply or .obj: " + o.output.string());
    return o;
}

/// True when the file is a PLY whose faces are triangle strips, which assimp 5.2 misreads (it keeps one
/// triangle of the strip).
bool is_ply_with_strips(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    if (!std::getline(in, line) || line.rfind("ply", 0) != 0) return false;
    while (std::getline(in, line) && line.rfind("end_header", 0) != 0)
        if (line.rfind("element tristrips", 0) == 0) return true;
    return false;
}

/// The one PLY layout assimp misreads, exactly as the Igea scan stores it: binary little endian, "element
/// vertex N" of float x y z (nothing else), "element tristrips 1" of "list int int vertex_indices" with -1
/// restarting the strip. Anything else is refused rather than guessed.
triangle_mesh read_ply_strips(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    const std::vector<std::string> expected_header{
        "ply", "format binary_little_endian 1.0", "element vertex", "property float x", "property float y",
        "property float z", "element tristrips 1", "property list int int vertex_indices", "end_header"};
    std::size_t vertex_count = 0;
    for (const std::string& want : expected_header) {
        std::string line;
        do {
            if (!std::getline(in, line)) throw std::runtime_error(path.string() + ": truncated PLY header");
            if (!line.empty() && line.back() == '\r') line.pop_back();
        } while (line.rfind("comment", 0) == 0 || line.rfind("obj_info", 0) == 0);
        if (line.rfind(want, 0) != 0)
            throw std::runtime_error(path.string() + ": unsupported PLY strip layout at \"" + line + "\"");
        if (want == "element vertex") vertex_count = std::stoul(line.substr(want.size()));
    }
    triangle_mesh out;
    out.vertices.resize(vertex_count);
    for (auto& v : out.vertices) {
        in.read(reinterpret_cast<char*>(v.position), sizeof v.position);
        v.uv[0] = v.uv[1] = 0.0f;
    }
    std::int32_t strip_length = 0;
    in.read(reinterpret_cast<char*>(&strip_length), sizeof strip_length);
    if (!in || strip_length < 3) throw std::runtime_error(path.string() + ": truncated PLY data");
    std::vector<std::int32_t> strip(static_cast<std::size_t>(strip_length));
    in.read(reinterpret_cast<char*>(strip.data()), static_cast<std::streamsize>(strip.size() * sizeof(std::int32_t)));
    if (!in) throw std::runtime_error(path.string() + ": truncated PLY strip");
    std::vector<unsigned> strip_indices(strip.size());
    for (std::size_t i = 0; i < strip.size(); ++i) {
        if (strip[i] >= static_cast<std::int32_t>(vertex_count) || strip[i] < -1)
            throw std::runtime_error(path.string() + ": strip index out of range");
        strip_indices[i] = strip[i] < 0 ? ~0u : static_cast<unsigned>(strip[i]);
    }
    out.indices.resize(meshopt_unstripifyBound(strip_indices.size()));
    out.indices.resize(meshopt_unstripify(out.indices.data(), strip_indices.data(), strip_indices.size(), ~0u));
    return out;
}

triangle_mesh read_mesh(const std::filesystem::path& path) {
    if (path.extension() == ".ply" && is_ply_with_strips(path)) return read_ply_strips(path);
    Assimp::Importer importer;
    // PreTransformVertices bakes the node hierarchy into one frame; JoinIdenticalVertices welds the file's
    // per-face-corner vertices (OBJ) so that simplification sees the connectivity.
    const aiScene* scene = importer.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                                                aiProcess_PreTransformVertices | aiProcess_SortByPType);
    if (!scene) throw std::runtime_error("cannot read " + path.string() + ": " + importer.GetErrorString());
    triangle_mesh out;
    out.has_uv = scene->mNumMeshes > 0 && std::all_of(scene->mMeshes, scene->mMeshes + scene->mNumMeshes,
                                                      [](const aiMesh* m) { return m->HasTextureCoords(0); });
    for (unsigned k = 0; k < scene->mNumMeshes; ++k) {
        const aiMesh& m = *scene->mMeshes[k];
        const auto first = static_cast<unsigned>(out.vertices.size());
        for (unsigned v = 0; v < m.mNumVertices; ++v) {
            vertex_data d{{m.mVertices[v].x, m.mVertices[v].y, m.mVertices[v].z}, {0.0f, 0.0f}};
            if (out.has_uv) d.uv[0] = m.mTextureCoords[0][v].x, d.uv[1] = m.mTextureCoords[0][v].y;
            out.vertices.push_back(d);
        }
        for (unsigned f = 0; f < m.mNumFaces; ++f)
            if (m.mFaces[f].mNumIndices == 3)
                for (unsigned c = 0; c < 3; ++c) out.indices.push_back(first + m.mFaces[f].mIndices[c]);
    }
    if (out.indices.empty()) throw std::runtime_error(path.string() + " has no triangles");
    return out;
}

void simplify(triangle_mesh& m, std::size_t target_triangles) {
    std::vector<unsigned> simplified(m.indices.size());
    float error = 0.0f;
    // target_error 1 (of the mesh extent): the triangle count is the only limit.
    const std::size_t count = meshopt_simplify(simplified.data(), m.indices.data(), m.indices.size(),
                                               m.vertices[0].position, m.vertices.size(), sizeof(vertex_data),
                                               target_triangles * 3u, 1.0f, 0, &error);
    simplified.resize(count);
    std::cerr << "emcv-decimate: " << m.indices.size() / 3u << " -> " << count / 3u
              << " triangles, relative error " << error << "\n";
    m.indices = std::move(simplified);
}

void compact(triangle_mesh& m) {
    meshopt_optimizeVertexCache(m.indices.data(), m.indices.data(), m.indices.size(), m.vertices.size());
    const std::size_t used = meshopt_optimizeVertexFetch(m.vertices.data(), m.indices.data(), m.indices.size(),
                                                         m.vertices.data(), m.vertices.size(), sizeof(vertex_data));
    m.vertices.resize(used);
}

void fit_height(triangle_mesh& m, float height) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (const auto& v : m.vertices)
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], v.position[a]), hi[a] = std::max(hi[a], v.position[a]);
    if (!(hi[1] > lo[1])) throw std::runtime_error("--fit-height: the mesh has no height");
    const float scale = height / (hi[1] - lo[1]);
    const float offset[3] = {0.5f * (lo[0] + hi[0]), lo[1], 0.5f * (lo[2] + hi[2])};
    for (auto& v : m.vertices)
        for (int a = 0; a < 3; ++a) v.position[a] = (v.position[a] - offset[a]) * scale;
}

void write_mesh(const triangle_mesh& m, const std::filesystem::path& path) {
    auto scene = std::make_unique<aiScene>();
    scene->mNumMaterials = 1;
    scene->mMaterials = new aiMaterial*[1]{new aiMaterial()};
    scene->mNumMeshes = 1;
    scene->mMeshes = new aiMesh*[1]{new aiMesh()};
    scene->mRootNode = new aiNode();
    scene->mRootNode->mNumMeshes = 1;
    scene->mRootNode->mMeshes = new unsigned[1]{0};
    aiMesh& out = *scene->mMeshes[0];
    out.mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    out.mMaterialIndex = 0;
    out.mNumVertices = static_cast<unsigned>(m.vertices.size());
    out.mVertices = new aiVector3D[out.mNumVertices];
    if (m.has_uv) {
        out.mTextureCoords[0] = new aiVector3D[out.mNumVertices];
        out.mNumUVComponents[0] = 2;
    }
    for (unsigned v = 0; v < out.mNumVertices; ++v) {
        const auto& d = m.vertices[v];
        out.mVertices[v] = aiVector3D(d.position[0], d.position[1], d.position[2]);
        if (m.has_uv) out.mTextureCoords[0][v] = aiVector3D(d.uv[0], d.uv[1], 0.0f);
    }
    out.mNumFaces = static_cast<unsigned>(m.indices.size() / 3u);
    out.mFaces = new aiFace[out.mNumFaces];
    for (unsigned f = 0; f < out.mNumFaces; ++f) {
        out.mFaces[f].mNumIndices = 3;
        out.mFaces[f].mIndices = new unsigned[3]{m.indices[3u * f], m.indices[3u * f + 1u], m.indices[3u * f + 2u]};
    }
    const bool ply = path.extension() == ".ply";
    // Written beside the target and renamed: a failure leaves no half-written asset.
    const std::filesystem::path tmp = path.string() + ".tmp" + path.extension().string();
    Assimp::Exporter exporter;
    if (exporter.Export(scene.get(), ply ? "plyb" : "objnomtl", tmp.string()) != AI_SUCCESS) {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw std::runtime_error("cannot write " + path.string() + ": " + exporter.GetErrorString());
    }
    std::filesystem::rename(tmp, path);
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const options o = parse_arguments(argc, argv);
        triangle_mesh m = read_mesh(o.input);
        if (o.triangles > 0 && o.triangles < m.indices.size() / 3u) simplify(m, o.triangles);
        compact(m);
        if (o.fit_height > 0.0f) fit_height(m, o.fit_height);
        write_mesh(m, o.output);
        std::cerr << "emcv-decimate: wrote " << o.output.string() << " (" << m.vertices.size() << " vertices, "
                  << m.indices.size() / 3u << " triangles)\n";
        return 0;
    } catch (const usage_error& e) {
        std::cerr << "emcv-decimate: " << e.what() << " (--help for usage)\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "emcv-decimate: " << e.what() << "\n";
        return 1;
    }
}
