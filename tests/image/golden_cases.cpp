// SPDX-License-Identifier: MIT
#include "golden_cases.hpp"

#include <fstream>
#include <sstream>

namespace emcv::image {

std::string golden_case::stem() const { return scene + "." + method + ".f" + std::to_string(last_frame()); }

std::vector<golden_case> read_cases(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw cases_error(file.string() + ": cannot read the golden cases file");
    std::vector<golden_case> cases;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        const auto where = [&] { return file.string() + ":" + std::to_string(number) + ": "; };
        if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        std::istringstream fields(line);
        golden_case c;
        std::string size, extra;
        if (!(fields >> c.scene)) continue;  // blank or comment
        if (!(fields >> c.method >> c.frames >> size))
            throw cases_error(where() + "expected '<scene> <method> <frames> <W>x<H>'");
        if (fields >> extra) throw cases_error(where() + "unexpected '" + extra + "' after the size");
        if (c.frames < 1 || c.frames > 1000) throw cases_error(where() + "frames must be in 1..1000");
        char x = 0;
        std::istringstream wh(size);
        if (!(wh >> c.width >> x >> c.height) || x != 'x' || !wh.eof() || c.width < 1 || c.height < 1 ||
            c.width > 256 || c.height > 256)
            throw cases_error(where() + "size '" + size + "' is not WxH with sides in 1..256");
        for (const golden_case& seen : cases)
            if (seen.stem() == c.stem()) throw cases_error(where() + "duplicate case " + c.stem());
        cases.push_back(c);
    }
    return cases;
}

tolerance display_tolerance() {
    tolerance t;
    t.fail = 1.5f / 255.0f;  // one 8-bit step passes, two fail
    t.fail_percent = 0.05;   // ~4 pixels of a 96x96 image
    t.hard_fail = 0.25f;
    t.warn = 0.5f / 255.0f;  // any change at all warns
    t.warn_percent = 0.0;
    return t;
}

tolerance samples_tolerance() {
    tolerance t;
    t.fail = 0.5f / 65535.0f;
    t.fail_percent = 0.05;
    t.hard_fail = 4.5f / 65535.0f;
    t.warn = 0.5f / 65535.0f;
    t.warn_percent = 0.0;
    return t;
}

}  // namespace emcv::image
