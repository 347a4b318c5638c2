// SPDX-License-Identifier: MIT
// Fuzz target: the scene loader (demo/scene/load.hpp) on arbitrary bytes. The input is written to
// <scratch>/scenes/fuzz.json in a private scratch folder and given to load_scene unchanged. <scratch>/assets
// links to the repository's demo/assets, so that "../assets/bunny.ply" resolves as it does for the built-in
// scenes in demo/scenes/ (the seeds load whole, mesh and texture readers included) and nothing else on the
// machine (a /tmp/assets, say) changes what an input does.
// Invariants checked (demo/scene/load.hpp, docs/scenes.md):
//   - load_scene returns a scene or throws scene_error; no other exception type escapes;
//   - a scene_error's what() is "<file>: <json pointer>: <problem>": it starts with the file name as given,
//     then ": /" (a JSON pointer, "/" for the whole file), and the problem after the pointer is not empty;
//   - a returned scene has at least one object, every object names an existing mesh and material, and its
//     frame count is positive (the loader's all-or-nothing promise);
//   - crashes, hangs and sanitizer reports are libFuzzer's (and the replay's, under the sanitize preset).
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <typeinfo>
#include <unistd.h>

#include "fuzz_input.hpp"
#include "scene/load.hpp"

namespace {

namespace fs = std::filesystem;

/// One scratch folder per process, removed at exit.
struct scratch_folder {
    fs::path path = fs::temp_directory_path() / ("emcv-fuzz-scene-" + std::to_string(::getpid()));
    scratch_folder() {
        fs::remove_all(path);
        fs::create_directories(path / "scenes");
        fs::create_directory_symlink(EMCV_DEMO_ASSETS, path / "assets");
    }
    ~scratch_folder() {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
};

void check_error_message(const std::string& message, const std::string& file) {
    const std::string prefix = file + ": /";
    EMCV_FUZZ_ASSERT(message.compare(0, prefix.size(), prefix) == 0);
    const std::size_t problem = message.find(": ", prefix.size() - 1);
    EMCV_FUZZ_ASSERT(problem != std::string::npos && problem + 2 < message.size());
}

void check_scene(const emcv::demo::scene& s) {
    EMCV_FUZZ_ASSERT(!s.objects.empty());
    EMCV_FUZZ_ASSERT(s.frames >= 1);
    for (const auto& o : s.objects) {
        EMCV_FUZZ_ASSERT(o.mesh >= 0 && static_cast<std::size_t>(o.mesh) < s.meshes.size());
        EMCV_FUZZ_ASSERT(o.material >= 0 && static_cast<std::size_t>(o.material) < s.materials.size());
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const scratch_folder folder;
    const fs::path file = folder.path / "scenes" / "fuzz.json";
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        EMCV_FUZZ_ASSERT(static_cast<bool>(out));
    }
    try {
        check_scene(emcv::demo::load_scene(file));
    } catch (const emcv::demo::scene_error& e) {
        check_error_message(e.what(), file.string());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "emcv fuzz: load_scene threw a %s, not a scene_error: %s\n", typeid(e).name(), e.what());
        EMCV_FUZZ_ASSERT(false && "load_scene threw an exception other than scene_error");
    } catch (...) {
        EMCV_FUZZ_ASSERT(false && "load_scene threw a non-exception");
    }
    return 0;
}
