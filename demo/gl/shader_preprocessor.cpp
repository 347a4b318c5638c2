// SPDX-License-Identifier: MIT
#include "shader_preprocessor.hpp"

#include <cstdlib>

#include <fstream>
#include <cctype>
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

/// Mesa prints "0:<line>" whatever the source-string number of #line says, so the file
/// index is also carried in the line number itself: line = index * kLinesPerFile + n.
constexpr long kLinesPerFile = 1000000;
long encode_line(int index, int n) { return static_cast<long>(index) * kLinesPerFile + n; }

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
    st.body << "#line " << encode_line(index, 1) << " " << index << "\n";
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
            st.body << "#line " << encode_line(index, number + 1) << " " << index << "\n";
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
    // A location is "<index>:<line>" at the start of a line or right after "ERROR: " / "WARNING: ".
    // (Hand-written rather than std::regex: GCC 12 reports false maybe-uninitialized warnings inside <regex>
    // under -fsanitize, and the project builds with -Werror.)
    auto digits_at = [&log](std::size_t p) {
        std::size_t q = p;
        while (q < log.size() && std::isdigit(static_cast<unsigned char>(log[q]))) ++q;
        return q;
    };
    std::string out;
    std::size_t i = 0;
    bool at_line_start = true;
    while (i < log.size()) {
        std::size_t p = i;
        if (!at_line_start) {
            for (const char* tag : {"ERROR: ", "WARNING: "}) {
                const std::size_t n = std::char_traits<char>::length(tag);
                if (log.compare(i, n, tag) == 0) {
                    out += log.substr(i, n);
                    p = i + n;
                    break;
                }
            }
        }
        if (at_line_start || p != i) {
            const std::size_t e1 = digits_at(p);
            if (e1 > p && e1 < log.size() && log[e1] == ':') {
                const std::size_t e2 = digits_at(e1 + 1);
                if (e2 > e1 + 1) {
                    unsigned long idx = std::stoul(log.substr(p, e1 - p));
                    unsigned long line = std::stoul(log.substr(e1 + 1, e2 - e1 - 1));
                    if (line >= static_cast<unsigned long>(kLinesPerFile)) {  // index encoded in the line
                        idx = line / static_cast<unsigned long>(kLinesPerFile);
                        line %= static_cast<unsigned long>(kLinesPerFile);
                    }
                    if (idx < files.size())
                        out += files[idx] + ":" + std::to_string(line);
                    else
                        out += log.substr(p, e2 - p);
                    i = e2;
                    at_line_start = false;
                    continue;
                }
            }
            i = p;
            at_line_start = false;
            continue;
        }
        at_line_start = log[i] == '\n';
        out += log[i];
        ++i;
    }
    return out;
}

std::filesystem::path shader_source_dir(const std::filesystem::path& option, const char* environment,
                                        const std::filesystem::path& compiled) {
    if (!option.empty()) return option;
    if (const char* value = std::getenv(environment); value != nullptr && *value != '\0') return value;
    return compiled;
}

}  // namespace emcv::gl
