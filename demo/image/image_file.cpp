// SPDX-License-Identifier: MIT
#include "image_file.hpp"

#ifndef EMCV_IMAGE_NO_FILES
#include <dlfcn.h>

#include "oiio_module.hpp"
#endif

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace emcv::image {

#ifdef EMCV_IMAGE_NO_FILES
// Built with -DEMCV_GL_IMAGE_FILES=OFF (a build for a machine without OpenImageIO, e.g. GPU timing runs that
// write metrics only): every image file operation fails with a line that says why.
void write_image(const std::filesystem::path& path, const float_image&, const std::string&) {
    throw image_error("write_image " + path.string() + ": built without OpenImageIO (EMCV_GL_IMAGE_FILES=OFF)");
}

float_image read_image(const std::filesystem::path& path) {
    throw image_error("read_image " + path.string() + ": built without OpenImageIO (EMCV_GL_IMAGE_FILES=OFF)");
}

std::string read_image_description(const std::filesystem::path& path) {
    throw image_error("read_image_description " + path.string() +
                      ": built without OpenImageIO (EMCV_GL_IMAGE_FILES=OFF)");
}

bool draw_text(float_image&, int, int, const std::string&, int, int, const std::string&) { return false; }

void require_image_files() {
    throw image_error("image files: built without OpenImageIO (EMCV_GL_IMAGE_FILES=OFF)");
}
#else
namespace {

/// Where the OpenImageIO module is looked for: $EMCV_IMAGE_MODULE alone when it is set and not empty; else beside
/// the running executable (the build puts it in bin/ with them, and a build tree copied elsewhere keeps it
/// there), then where this build put it.
std::vector<std::filesystem::path> module_candidates() {
    if (const char* chosen = std::getenv("EMCV_IMAGE_MODULE"); chosen != nullptr && *chosen != '\0') return {chosen};
    std::vector<std::filesystem::path> out;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    const std::filesystem::path built(EMCV_IMAGE_OIIO_MODULE);
    if (!ec) out.push_back(exe.parent_path() / built.filename());
    out.push_back(built);
    return out;
}

/// Loads the module once (never unloaded: OpenImageIO keeps state for the process's life). Throws image_error
/// naming every path tried and why it failed; the next call tries again.
const oiio_functions& load_module() {
    std::string why;
    for (const std::filesystem::path& candidate : module_candidates()) {
        void* module = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!module) {
            const char* error = dlerror();
            why += std::string(" [") + (error ? error : candidate.string()) + "]";
            continue;
        }
        void* entry = dlsym(module, EMCV_IMAGE_OIIO_ENTRY);
        if (!entry) {
            why += " [" + candidate.string() + ": no " EMCV_IMAGE_OIIO_ENTRY "]";
            continue;
        }
        const oiio_functions* (*get)() = nullptr;
        static_assert(sizeof get == sizeof entry, "a function pointer as wide as dlsym's result");
        std::memcpy(&get, &entry, sizeof get);  // POSIX: dlsym's result is the function's address
        return *get();
    }
    throw image_error("cannot load the OpenImageIO module (build the target emcv_image_oiio):" + why);
}

const oiio_functions& oiio() {
    static const oiio_functions& functions = load_module();
    return functions;
}

/// Throws image_error with the module's message, if it returned one.
void check(const std::string& error) {
    if (!error.empty()) throw image_error(error);
}

}  // namespace

void require_image_files() { (void)oiio(); }

void write_image(const std::filesystem::path& path, const float_image& image, const std::string& description) {
    check(oiio().write_image(path, image, description));
}

float_image read_image(const std::filesystem::path& path) {
    float_image image;
    check(oiio().read_image(path, image));
    return image;
}

std::string read_image_description(const std::filesystem::path& path) {
    std::string description;
    check(oiio().read_image_description(path, description));
    return description;
}

bool draw_text(float_image& image, int x, int baseline_from_top, const std::string& text, int font_px, int max_width,
               const std::string& font) {
    bool drawn = false;
    check(oiio().draw_text(image, x, baseline_from_top, text, font_px, max_width, font, drawn));
    return drawn;
}
#endif  // #ifdef EMCV_IMAGE_NO_FILES

}  // namespace emcv::image
