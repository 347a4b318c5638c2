// SPDX-License-Identifier: MIT
#include "golden_render.hpp"

#include <cmath>
#include <stdexcept>

#include "image/image_file.hpp"
#include "render/renderer.hpp"
#include "scene/load.hpp"

namespace emcv::image {
namespace {

// GL rows are bottom-up, files top-down. `to_file_value` maps a float onto the file's integer range.
template <typename T, typename Convert>
OIIO::ImageBuf to_file_image(const gl::float_image& img, int channels, OIIO::TypeDesc type, Convert to_file_value) {
    OIIO::ImageBuf buf(OIIO::ImageSpec(img.width, img.height, channels, type));
    std::vector<T> values(static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) *
                          static_cast<std::size_t>(channels));
    std::size_t i = 0;
    for (int y = img.height - 1; y >= 0; --y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < channels; ++c) {
                const std::size_t at = (static_cast<std::size_t>(y) * static_cast<std::size_t>(img.width) +
                                        static_cast<std::size_t>(x)) * static_cast<std::size_t>(img.channels) +
                                       static_cast<std::size_t>(c);
                values[i++] = static_cast<T>(to_file_value(img.pixels[at]));
            }
    buf.set_pixels(OIIO::ROI::All(), type, values.data());
    return buf;
}

bool adaptive(const demo::method& m) {
    return m.type == demo::method::kind::spvg || m.type == demo::method::kind::cv ||
           m.type == demo::method::kind::cv_notex;
}

}  // namespace

golden_images render_case(const golden_case& c, std::uint32_t seed) {
    const std::optional<demo::method> m = demo::parse_method(c.method);
    if (!m) throw std::runtime_error(c.stem() + ": unknown or unimplemented method '" + c.method + "'");
    const demo::scene s = demo::load_scene_argument(c.scene);
    demo::render_options options;
    options.width = c.width;
    options.height = c.height;
    options.seed = seed;
    options.timing_mode = demo::timing::wall;
    demo::renderer r(s, *m, options);
    for (int frame = 0; frame <= c.last_frame(); ++frame) r.render(frame);

    golden_images out;
    // The display image is sRGB-encoded already: stored as emcv-demo's PNG frames store it (no transfer).
    const gl::float_image display = r.display();
    out.display = to_file_image<unsigned char>(display, 3, OIIO::TypeDesc::UINT8, quantise_unorm8);
    if (adaptive(*m)) {
        const gl::float_image counts = r.sample_counts();
        out.sample_counts = to_file_image<unsigned short>(counts, 1, OIIO::TypeDesc::UINT16,
                                                          [](float n) { return std::lround(n); });
    }
    return out;
}

}  // namespace emcv::image
