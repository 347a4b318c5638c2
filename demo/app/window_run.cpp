// SPDX-License-Identifier: MIT
#include "window_run.hpp"

#include "render_flags.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "gl/debug.hpp"
#include "gl/handles.hpp"
#include "heatmap.hpp"
#include "render/renderer.hpp"

#ifdef EMCV_DEMO_HAVE_GLFW
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#endif

namespace emcv::demo::app {

std::string window_key_help() {
    return "keys: M/N next/previous method, 1..9 toggle light, H heatmap, R restart, Esc/Q quit";
}

#ifdef EMCV_DEMO_HAVE_GLFW
namespace {

/// What the keys change; read by the loop after glfwPollEvents (inside context::present).
struct window_state {
    int method_step = 0;              ///< +1 / -1 pending method switches
    std::vector<bool> light_on;
    bool lights_changed = false;
    bool heatmap = false;
    bool restart = false;
};

/// One key press: changes `state`; Esc/Q closes the window.
void apply_key(GLFWwindow* window, window_state& state, int key) {
    if (key == GLFW_KEY_ESCAPE || key == GLFW_KEY_Q) glfwSetWindowShouldClose(window, GLFW_TRUE);
    else if (key == GLFW_KEY_M) ++state.method_step;
    else if (key == GLFW_KEY_N) --state.method_step;
    else if (key == GLFW_KEY_H) state.heatmap = !state.heatmap;
    else if (key == GLFW_KEY_R) state.restart = true;
    else if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) {
        const auto light = static_cast<std::size_t>(key - GLFW_KEY_1);
        if (light < state.light_on.size()) {
            state.light_on[light] = !state.light_on[light];
            state.lights_changed = true;
        }
    }
}

void on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
    if (action != GLFW_PRESS) return;
    if (auto* state = static_cast<window_state*>(glfwGetWindowUserPointer(window))) apply_key(window, *state, key);
}

/// $EMCV_DEMO_KEYS: comma-separated keys (M, N, H, R, Q, 1..9; empty: none) pressed one per frame after the
/// first, as if typed; how the Xvfb test drives the keys without an input device.
std::vector<int> scripted_keys() {
    std::vector<int> keys;
    const char* env = std::getenv("EMCV_DEMO_KEYS");
    if (!env) return keys;
    const std::string text = env;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, comma - start);
        if (item.size() != 1 || std::string("MNHRQ123456789").find(item[0]) == std::string::npos)
            throw std::runtime_error("EMCV_DEMO_KEYS: unknown key '" + item + "' (expected M, N, H, R, Q or 1..9)");
        keys.push_back(item[0] >= '1' && item[0] <= '9' ? GLFW_KEY_1 + (item[0] - '1')
                                                        : GLFW_KEY_A + (item[0] - 'A'));
        start = comma + 1;
    }
    return keys;
}

/// A texture with a framebuffer around it, for glBlitNamedFramebuffer to the window.
struct blit_source {
    gl::texture_2d texture;
    gl::framebuffer framebuffer;
};

blit_source make_blit_source(GLuint existing_texture, int width, int height) {
    blit_source b;
    GLuint texture = existing_texture;
    if (texture == 0) {
        b.texture = gl::texture_2d::create();
        glTextureStorage2D(b.texture.id(), 1, GL_RGBA8, width, height);
        texture = b.texture.id();
    }
    b.framebuffer = gl::framebuffer::create();
    glNamedFramebufferTexture(b.framebuffer.id(), GL_COLOR_ATTACHMENT0, texture, 0);
    return b;
}

void blit_to_window(const blit_source& source, int width, int height) {
    gl::debug_group group("window-blit");
    glBlitNamedFramebuffer(source.framebuffer.id(), 0, 0, 0, width, height, 0, 0, width, height,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

std::string title(const scene& s, const renderer& r, int frame, const frame_stats& stats, bool heatmap) {
    char text[256];
    std::snprintf(text, sizeof text, "emcv-demo  %s  %s  frame %d  sss %.2f ms  frame %.2f ms  spp %.1f%s",
                  s.name.c_str(), r.current_method().name().c_str(), frame, stats.times.sss_ms, stats.times.frame_ms,
                  stats.mean_spp, heatmap ? "  [heatmap " : "");
    // The heatmap's scale in the title: the window shows the colours without a legend.
    return heatmap ? text + heatmap_scale_text(samples_heatmap_scale) + ", black to red]" : text;
}

}  // namespace

int run_window(gl::context& ctx, const scene& s, const options& o, std::optional<int> frame_limit) {
    GLFWwindow* window = glfwGetCurrentContext();
    if (!window) throw std::runtime_error("--window: no GLFW window is current");
    window_state state;
    state.light_on.assign(s.lights.size(), true);
    glfwSetWindowUserPointer(window, &state);
    glfwSetKeyCallback(window, on_key);

    const render_options ro = make_render_options(o, o.timing == timing_request::wall ? timing::wall : timing::gpu);  // gpu never stalls: the title shows the newest measured frame
    std::size_t method_index = 0;
    renderer r(s, o.methods[method_index], ro);
    // What a frame shows is the composite's image or, after the temporal resolve, the resolved one: the blit
    // source follows renderer::display_texture when it changes (the first resolved frame, a method switch).
    GLuint display_id = r.display_texture();
    blit_source display = make_blit_source(display_id, o.width, o.height);
    const blit_source heat = make_blit_source(0, o.width, o.height);

    const std::vector<int> script = scripted_keys();
    int shown = 0;
    int frame = 0;
    const int sequence = std::max(1, s.frames);
    while (!frame_limit || shown < *frame_limit) {
        const window_state before = state;
        if (shown >= 1 && static_cast<std::size_t>(shown - 1) < script.size())
            apply_key(window, state, script[static_cast<std::size_t>(shown - 1)]);
        if (glfwWindowShouldClose(window)) break;
        // Each change is reported on stdout, so a run under Xvfb shows what the keys did.
        if (state.heatmap != before.heatmap) std::printf("frame %d: heatmap %s\n", shown, state.heatmap ? "on" : "off");
        for (std::size_t i = 0; i < state.light_on.size(); ++i)
            if (state.light_on[i] != before.light_on[i])
                std::printf("frame %d: light %s %s\n", shown, s.lights[i].name.c_str(), state.light_on[i] ? "on" : "off");
        if (state.restart) std::printf("frame %d: restart\n", shown);
        if (state.method_step != 0) {
            const auto count = static_cast<long>(o.methods.size());
            const long next = ((static_cast<long>(method_index) + state.method_step) % count + count) % count;
            method_index = static_cast<std::size_t>(next);
            state.method_step = 0;
            r.set_method(o.methods[method_index]);  // resets histories
            frame = 0;
            std::printf("frame %d: method %s\n", shown, r.current_method().name().c_str());
        }
        if (state.restart || frame >= sequence) {
            r.set_method(r.current_method());  // the sequence loops: start it again with fresh histories
            frame = 0;
            state.restart = false;
        }
        if (state.lights_changed) {
            for (std::size_t i = 0; i < state.light_on.size(); ++i) r.set_light_scale(i, state.light_on[i] ? 1.0f : 0.0f);
            state.lights_changed = false;
        }
        const frame_stats stats = r.render(frame);
        if (state.heatmap) {
            const gl::float_image colours = sample_heatmap(r.sample_counts(), samples_heatmap_scale);
            glTextureSubImage2D(heat.texture.id(), 0, 0, 0, o.width, o.height, GL_RGBA, GL_FLOAT,
                                colours.pixels.data());
            blit_to_window(heat, o.width, o.height);
        } else {
            if (r.display_texture() != display_id) {
                display_id = r.display_texture();
                display = make_blit_source(display_id, o.width, o.height);
            }
            blit_to_window(display, o.width, o.height);
        }
        glfwSetWindowTitle(window, title(s, r, frame, stats, state.heatmap).c_str());
        ++shown;
        ++frame;
        if (!ctx.present()) break;  // swaps and polls events (the key callback runs here)
    }
    glfwSetKeyCallback(window, nullptr);
    glfwSetWindowUserPointer(window, nullptr);
    return shown;
}

#else

int run_window(gl::context&, const scene&, const options&, std::optional<int>) {
    throw std::runtime_error("--window: this build has no GLFW (install libglfw3-dev and rebuild)");
}

#endif

}  // namespace emcv::demo::app
