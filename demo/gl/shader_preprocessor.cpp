// SPDX-License-Identifier: MIT
#include "shader_preprocessor.hpp"

#include <cctype>
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <string_view>

namespace emcv::gl {
namespace {

namespace fs = std::filesystem;

std::string_view trim_left(std::string_view s) {
    const auto p = s.find_first_not_of(" \t");
    return p == std::string_view::npos ? std::string_view() : s.substr(p);
}

bool is_identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

/// The identifier `text` starts with (empty if none): a directive's name, or its operand's macro (#ifndef,
/// #define, #undef).
std::string_view first_identifier(std::string_view text) {
    std::size_t n = 0;
    while (n < text.size() && is_identifier_char(text[n])) ++n;
    return text.substr(0, n);
}

/// Whether `line` is a preprocessor directive: '#', then its name (an identifier) in `name` and what follows
/// it, trimmed on the left, in `rest`. Views into `line`; nothing is allocated (most lines are not directives,
/// and every renderer preprocesses every program: this scan was most of a renderer's construction under ASan).
bool parse_directive(std::string_view line, std::string_view& name, std::string_view& rest) {
    line = trim_left(line);
    if (line.empty() || line[0] != '#') return false;
    line = trim_left(line.substr(1));
    name = first_identifier(line);
    rest = trim_left(line.substr(name.size()));
    return true;
}

bool opens_group(std::string_view name) { return name == "if" || name == "ifdef" || name == "ifndef"; }

/// A line that is blank or a whole-line // comment.
bool is_blank_or_comment(std::string_view line) {
    line = trim_left(line);
    return line.empty() || line.rfind("//", 0) == 0;
}

/// One shader file, read once per preprocess_file call, split into lines (views into `text`, '\r' dropped).
struct source_file {
    std::string text;
    std::vector<std::string_view> lines;
    /// The macro of a classic include guard around the whole file, empty if the file has none: its first
    /// directive is `#ifndef X` with `#define X` the next line that is not blank, the `#endif` that closes it is
    /// its last directive, and only blank lines and // comments lie outside them.
    std::string guard;
    std::size_t guard_line = 0;  ///< the `#ifndef X` line's index (when `guard` is set)
};

void find_include_guard(source_file& f) {
    std::size_t i = 0;
    while (i < f.lines.size() && is_blank_or_comment(f.lines[i])) ++i;
    std::string_view name, rest;
    if (i == f.lines.size() || !parse_directive(f.lines[i], name, rest) || name != "ifndef") return;
    const std::string_view macro = first_identifier(rest);
    if (macro.empty()) return;
    const std::size_t open = i;
    ++i;
    while (i < f.lines.size() && is_blank_or_comment(f.lines[i])) ++i;
    if (i == f.lines.size() || !parse_directive(f.lines[i], name, rest) || name != "define" || first_identifier(rest) != macro)
        return;
    int depth = 1;
    for (++i; i < f.lines.size() && depth > 0; ++i) {
        if (!parse_directive(f.lines[i], name, rest)) continue;
        if (opens_group(name)) ++depth;
        if (name == "endif") --depth;
        if ((name == "else" || name == "elif") && depth == 1) return;  // a branch beside the guard's
    }
    if (depth != 0) return;
    for (; i < f.lines.size(); ++i)
        if (!is_blank_or_comment(f.lines[i])) return;
    f.guard = std::string(macro);
    f.guard_line = open;
}

/// The #if groups open at a point of the text, outermost first, each branch (an #if, #ifdef or #ifndef, or an
/// #elif or #else after it) by its own number. A line reached with a context C is reached only when every
/// branch of C is taken; a later line whose context extends C is reached only if those branches were taken too.
using branch_context = std::vector<std::uint64_t>;

bool extends(const branch_context& later, const branch_context& earlier) {
    return earlier.size() <= later.size() && std::equal(earlier.begin(), earlier.end(), later.begin());
}

struct state {
    const preprocess_options& options;
    std::string version;
    std::vector<std::string> extensions;
    std::string body;
    std::vector<std::string> files;
    std::map<std::string, source_file> read;  ///< every file read so far, by canonical path
    std::vector<std::string> stack;
    /// The branches open along the include chain, not counting the include guard of a file on its first
    /// inclusion (which holds: nothing has defined its macro yet).
    branch_context branches;
    std::uint64_t next_branch = 0;
    /// The #pragma once files, each with the branches its first inclusion lay in.
    std::map<std::string, branch_context> pragma_once;
    /// The include guards of the files included so far, each with the branches its first inclusion lay in: where
    /// a later inclusion lies in those branches too, the guard's macro is defined there, the GLSL compiler would
    /// drop that inclusion, and it is left out here (GCC's multiple-include optimisation). The program text shrinks
    /// to about each header once (sss_burley's from 9200 lines to 2600), which the compiler no longer
    /// has to scan.
    std::map<std::string, branch_context, std::less<>> guards;
    std::set<std::string, std::less<>> undefined;  ///< every macro #undef'd so far: its guard is never trusted again
    /// Every macro defined so far (the injected ones, and each #define line, taken or not): a guard whose macro is
    /// among them on a file's first inclusion may hold nothing, and is counted as a branch.
    std::set<std::string, std::less<>> defined;
};

/// Whether an inclusion of a file with include guard `guard` (or #pragma once, `known`) at the current branches
/// would be dropped by the compiler: its first inclusion lay in branches the current ones extend.
template <class Map, class Key>
bool already_included(const state& st, const Map& known, const Key& key) {
    const auto it = known.find(key);
    return it != known.end() && extends(st.branches, it->second);
}

/// Notes that a file (its guard's macro, or its path for #pragma once) was included at `context`; of two
/// contexts the more general one (the other extends it) is kept.
template <class Map>
void remember_inclusion(Map& known, const std::string& key, const branch_context& context) {
    const auto [it, inserted] = known.emplace(key, context);
    if (!inserted && extends(it->second, context)) it->second = context;
}

int file_index(state& st, const std::string& s) {
    for (std::size_t i = 0; i < st.files.size(); ++i)
        if (st.files[i] == s) return static_cast<int>(i);
    st.files.push_back(s);
    return static_cast<int>(st.files.size() - 1);
}

/// Mesa prints "0:<line>" whatever the source-string number of #line says, so the file
/// index is also carried in the line number itself: line = index * kLinesPerFile + n.
constexpr long kLinesPerFile = 1000000;
long encode_line(int index, int n) { return static_cast<long>(index) * kLinesPerFile + n; }

void append_line_directive(state& st, int index, int n) {
    st.body += "#line ";
    st.body += std::to_string(encode_line(index, n));
    st.body += ' ';
    st.body += std::to_string(index);
    st.body += '\n';
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

/// The file at `path`, read and split once per preprocess_file call (a header is included from many files).
const source_file& load(state& st, const fs::path& path, const std::string& key) {
    if (auto it = st.read.find(key); it != st.read.end()) return it->second;
    std::ifstream in(path, std::ios::binary);
    if (!in) throw shader_error("cannot open shader file " + path.string());
    source_file& f = st.read[key];
    // One read of the whole file (a character iterator costs a call per byte in the sanitizer build).
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    in.seekg(0, std::ios::beg);
    f.text.resize(size > 0 ? static_cast<std::size_t>(size) : 0);
    if (size > 0 && !in.read(f.text.data(), size)) throw shader_error("cannot read shader file " + path.string());
    const std::string_view text(f.text);
    for (std::size_t start = 0; start < text.size();) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(start, end - start);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        f.lines.push_back(line);
        start = end + 1;
    }
    find_include_guard(f);
    return f;
}

void process(state& st, const fs::path& path) {
    const std::string key = path.string();
    if (already_included(st, st.pragma_once, key)) return;
    for (const auto& s : st.stack)
        if (s == key) throw shader_error("include cycle: " + key + " includes itself (through " + st.stack.back() + ")");
    if (st.stack.size() > 64) throw shader_error("includes nested deeper than 64 at " + key);
    const source_file& file = load(st, path, key);
    const branch_context at_inclusion = st.branches;
    st.stack.push_back(key);
    const int index = file_index(st, key);
    append_line_directive(st, index, 1);
    std::vector<bool> groups;  // this file's open groups: true for its own include guard
    for (std::size_t i = 0; i < file.lines.size(); ++i) {
        const std::string_view line = file.lines[i];
        const int number = static_cast<int>(i) + 1;
        std::string_view name, rest;
        if (!parse_directive(line, name, rest)) {
            st.body += line;
            st.body += '\n';
            continue;
        }
        if (name == "version") {
            const std::string v = "#version " + std::string(rest);
            if (!st.version.empty() && st.version != v)
                throw shader_error(where(path, number) + ": conflicting " + v + " (first: " + st.version + ")");
            st.version = v;
            st.body += '\n';
        } else if (name == "extension") {
            const std::string e = "#extension " + std::string(rest);
            bool seen = false;
            for (const auto& x : st.extensions) seen = seen || x == e;
            if (!seen) st.extensions.push_back(e);
            st.body += '\n';
        } else if (name == "pragma" && rest.rfind("once", 0) == 0) {
            remember_inclusion(st.pragma_once, key, at_inclusion);
            st.body += '\n';
        } else if (name == "include") {
            if (!rest.empty() && rest[0] == '<') {
                // C++-only system header (for example <glm/glm.hpp> in the port headers): nothing in GLSL.
                st.body += "// (C++ only) ";
                st.body += trim_left(line);
                st.body += '\n';
                continue;
            }
            const auto close = rest.find('"', 1);
            if (rest.empty() || rest[0] != '"' || close == std::string_view::npos)
                throw shader_error(where(path, number) + ": malformed #include: " + std::string(line));
            const fs::path target = resolve_include(st, path, std::string(rest.substr(1, close - 1)), number);
            const std::string target_key = target.string();
            const source_file& included = load(st, target, target_key);
            if (!included.guard.empty() && already_included(st, st.guards, included.guard) &&
                st.undefined.count(included.guard) == 0) {
                st.body += '\n';  // its guard's macro is defined here: the compiler would drop it
                continue;
            }
            process(st, target);
            append_line_directive(st, index, number + 1);
        } else {
            if (opens_group(name)) {
                const bool own_guard = i == file.guard_line && !file.guard.empty() && st.defined.count(file.guard) == 0;
                groups.push_back(own_guard);
                if (!own_guard) st.branches.push_back(st.next_branch++);
            } else if ((name == "elif" || name == "else") && !groups.empty() && !groups.back()) {
                st.branches.back() = st.next_branch++;  // another branch of the same group
            } else if (name == "endif" && !groups.empty()) {
                if (!groups.back()) st.branches.pop_back();
                groups.pop_back();
            } else if (name == "define") {
                st.defined.emplace(first_identifier(rest));
            } else if (name == "undef") {
                st.undefined.emplace(first_identifier(rest));
            }
            st.body += line;
            st.body += '\n';
        }
    }
    // Groups this file left open stay open: what follows its inclusion lies in them.
    if (!file.guard.empty()) remember_inclusion(st.guards, file.guard, at_inclusion);
    st.stack.pop_back();
}

}  // namespace

preprocessed_source preprocess_file(const std::filesystem::path& path, const preprocess_options& options) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw shader_error("shader file not found: " + path.string());
    state st{options, {}, {}, {}, {}, {}, {}, {}, 0, {}, {}, {}, {}};
    for (const auto& d : options.defines) st.defined.insert(d.first);
    process(st, fs::weakly_canonical(path, ec));
    std::string out = st.version.empty() ? options.default_version : st.version;
    out += '\n';
    for (const auto& e : st.extensions) out += e + "\n";
    for (const auto& [name, value] : options.defines) out += "#define " + name + " " + value + "\n";
    out += st.body;
    return preprocessed_source{std::move(out), st.files};
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
