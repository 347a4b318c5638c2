// SPDX-License-Identifier: MIT
#include "listings.hpp"

#include <algorithm>
#include <string>

#include "scene/load.hpp"

namespace emcv::demo::app {
namespace {

std::string joined(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
    return out;
}

void print_range(std::ostream& out, int first, int last, const std::vector<std::string>& passes) {
    out << "  frames " << first << '-' << last << ": " << joined(passes) << '\n';
}

}  // namespace

bool list_scenes(std::ostream& out) {
    bool all_loaded = true;
    std::size_t width = 0;
    const std::vector<std::string> names = builtin_scene_names();
    for (const std::string& name : names) width = std::max(width, name.size());
    for (const std::string& name : names) {
        out << name << std::string(width + 2 - name.size(), ' ');
        try {
            out << load_scene(builtin_scene_dir() / (name + ".json")).description << '\n';
        } catch (const scene_error& e) {
            out << "(does not load: " << e.what() << ")\n";
            all_loaded = false;
        }
    }
    return all_loaded;
}

void list_methods(std::ostream& out) {
    static const char* const passes[] = {"none", "burley", "separable", "adaptive"};
    for (const method_row& r : method_table()) {
        // `all`'s value where the row is part of it, else "-N" where the name needs a parameter
        const bool needs_n = !r.parameter.meaning.empty() && r.parameter.default_value == 0;
        const std::string name = r.in_all >= 0 ? method{r.type, r.in_all}.name() : std::string(r.name) + (needs_n ? "-N" : "");
        out << name << '\t' << passes[static_cast<int>(r.passes())] << '\t' << r.help << '\n';
    }
}

void print_passes(std::ostream& out, const scene& s, const std::vector<method>& methods, int frames, int width,
                  int height, resolve_mode resolve, const sampling_mode& sampling) {
    // The renderer's own planner, frame after frame as the renderer plans them (the reference's reuse
    // included): what is printed is what runs.
    const auto names = [&](const std::vector<planned_pass>& plan) {
        std::vector<std::string> out_names;
        for (const planned_pass& p : plan) out_names.push_back(pass_name(s, p));
        return out_names;
    };
    for (const method& m : methods) {
        out << "method " << m.name() << ":\n";
        frame_planner planner(s, m, width, height, resolve, sampling);
        std::vector<std::string> current = names(planner.plan(0));
        int first = 0;
        for (int frame = 1; frame < frames; ++frame) {
            std::vector<std::string> passes = names(planner.plan(frame));
            if (passes == current) continue;
            print_range(out, first, frame - 1, current);
            current = std::move(passes);
            first = frame;
        }
        print_range(out, first, frames - 1, current);
    }
}

}  // namespace emcv::demo::app
