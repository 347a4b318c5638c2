// SPDX-License-Identifier: MIT
#include "shader_preprocessor.hpp"

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace emcv::gl {
namespace {

namespace fs = std::filesystem;

std::string trim_left(const std::string& s) {
    const auto p = s.find_first_not_of(" \t");
    return p == std::string::npos ? std::string() : s.substr(p);
}

bool starts_with_directive(const std::string& line, const char* name, std::string& rest) {
    std::string t = trim_left(line);
    if (t.empty() || t[0] != '#') return false;
    t = trim_left(t.substr(1));
    const std::string n(name);
    if (t.compare(0, n.size(), n) != 0) return false;
    if (t.size() > n.size() && t[n.size()] != ' ' && t[n.size()] != '\t' && t[n.size()] != '"' &&
        t[n.size()] != '<')
        return false;
    rest = trim_left(t.substr(n.size()));
    return true;
}

struct state {
    const preprocess_options& options;
    std::string version;
    std::vector<std::string> extensions;
    std::ostringstream body;
    std::vector<std::string> files;
    std::set<std::string> pragma_once;
    std::vector<std::string> stack;
};

int file_index(state& st, const fs::path& p) {
    const std::string s = p.string();
    for (std::size_t i = 0; i < st.files.size(); ++i)
        if (st.files[i] == s) return static_cast<int>(i);
    st.files.push_back(s);
    return static_cast<int>(st.files.size() - 1);
}

std::string where(const fs::path& file, int line) { return file.string() + ":" + std::to_string(line); }

fs::path resolve_include(state& st, const fs::path& includer, const std::string& name, int line) {
    std::vector<fs::path> tried;
    std::vector<fs::path> roots{includer.parent_path()};
    roots.insert(roots.end(), st.options.include_dirs.begin(), st.options.include_dirs.end());
    for (const auto& root : roots) {
        fs::path candidate = root / name;
        std::error_code ec;
        if (fs::is_regular_file(candidate, ec)) return fs::weakly_canonical(candidate, ec);
        tried.push_back(candidate);
    }
    std::string msg = where(includer, line) + ": #include \"" + name + "\" not found (searched:";
    for (const auto& t : tried) msg += " " + t.string();
    throw shader_error(msg + ")");
}

void process(state& st, const fs::path& path) {
    const std::string key = path.string();
    if (st.pragma_once.count(key)) return;
    for (const auto& s : st.stack)
        if (s == key) throw shader_error("include cycle: " + key + " includes itself (through " + st.stack.back() + ")");
    if (st.stack.size() > 64) throw shader_error("includes nested deeper than 64 at " + key);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw shader_error("cannot open shader file " + path.string());
    st.stack.push_back(key);
    const int index = file_index(st, path);
    st.body << "#line 1 " << index << "\n";
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::string rest;
        if (starts_with_directive(line, "version", rest)) {
            const std::string v = "#version " + rest;
            if (!st.version.empty() && st.version != v)
                throw shader_error(where(path, number) + ": conflicting " + v + " (first: " + st.version + ")");
            st.version = v;
            st.body << "\n";
        } else if (starts_with_directive(line, "extension", rest)) {
            const std::string e = "#extension " + rest;
            bool seen = false;
            for (const auto& x : st.extensions) seen = seen || x == e;
            if (!seen) st.extensions.push_back(e);
            st.body << "\n";
        } else if (starts_with_directive(line, "pragma", rest) && rest.rfind("once", 0) == 0) {
            st.pragma_once.insert(key);
            st.body << "\n";
        } else if (starts_with_directive(line, "include", rest)) {
            if (!rest.empty() && rest[0] == '<') {
                // C++-only system header (for example <glm/glm.hpp> in the port headers): nothing in GLSL.
                st.body << "// (C++ only) " << trim_left(line) << "\n";
                continue;
            }
            const auto close = rest.find('"', 1);
            if (rest.empty() || rest[0] != '"' || close == std::string::npos)
                throw shader_error(where(path, number) + ": malformed #include: " + line);
            const fs::path target = resolve_include(st, path, rest.substr(1, close - 1), number);
            process(st, target);
            st.body << "#line " << (number + 1) << " " << index << "\n";
        } else {
            st.body << line << "\n";
        }
    }
    st.stack.pop_back();
}

}  // namespace

preprocessed_source preprocess_file(const std::filesystem::path& path, const preprocess_options& options) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw shader_error("shader file not found: " + path.string());
    state st{options, {}, {}, {}, {}, {}, {}};
    process(st, fs::weakly_canonical(path, ec));
    std::ostringstream out;
    out << (st.version.empty() ? options.default_version : st.version) << "\n";
    for (const auto& e : st.extensions) out << e << "\n";
    for (const auto& [name, value] : options.defines) out << "#define " << name << " " << value << "\n";
    out << st.body.str();
    return preprocessed_source{out.str(), st.files};
}

std::string preprocessed_source::rewrite_log(const std::string& log) const {
    // "<index>:<line>" at the start of a line or after "ERROR: " / "WARNING: ".
    static const std::regex location(R"((^|\n|ERROR: |WARNING: )(\d+):(\d+))");
    std::string out;
    auto begin = std::sregex_iterator(log.begin(), log.end(), location);
    std::size_t last = 0;
    for (auto it = begin; it != std::sregex_iterator(); ++it) {
        const auto& m = *it;
        out += log.substr(last, static_cast<std::size_t>(m.position(0)) - last);
        const unsigned long idx = std::stoul(m[2].str());
        out += m[1].str();
        if (idx < files.size())
            out += files[idx] + ":" + m[3].str();
        else
            out += m[2].str() + ":" + m[3].str();
        last = static_cast<std::size_t>(m.position(0) + m.length(0));
    }
    out += log.substr(last);
    return out;
}

}  // namespace emcv::gl
