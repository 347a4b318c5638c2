// SPDX-License-Identifier: MIT
#include "program.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace emcv::gl {
namespace {

// The info log of a shader or a program: glGet{Shader,Program}iv and glGet{Shader,Program}InfoLog.
std::string info_log(GLuint id, void (*get_iv)(GLuint, GLenum, GLint*),
                     void (*get_log)(GLuint, GLsizei, GLsizei*, GLchar*)) {
    GLint n = 0;
    get_iv(id, GL_INFO_LOG_LENGTH, &n);
    std::string s(static_cast<std::size_t>(n > 0 ? n : 1), '\0');
    get_log(id, n, nullptr, s.data());
    s.resize(std::char_traits<char>::length(s.c_str()));
    return s;
}

std::string shader_log(GLuint id) { return info_log(id, glGetShaderiv, glGetShaderInfoLog); }
std::string program_log(GLuint id) { return info_log(id, glGetProgramiv, glGetProgramInfoLog); }

const char* stage_name(GLenum stage) {
    switch (stage) {
        case GL_COMPUTE_SHADER: return "compute";
        case GL_VERTEX_SHADER: return "vertex";
        case GL_FRAGMENT_SHADER: return "fragment";
        default: return "shader";
    }
}

program_handle link(const std::vector<GLuint>& shaders, const std::string& what) {
    program_handle p = program_handle::create();
    for (GLuint s : shaders) glAttachShader(p.id(), s);
    glLinkProgram(p.id());
    GLint ok = 0;
    glGetProgramiv(p.id(), GL_LINK_STATUS, &ok);
    for (GLuint s : shaders) glDetachShader(p.id(), s);
    if (!ok) throw shader_error("link failed for " + what + ":\n" + program_log(p.id()));
    return p;
}

}  // namespace

shader_handle compile_shader(GLenum stage, const preprocessed_source& source) {
    shader_handle s(glCreateShader(stage));
    const char* text = source.text.c_str();
    glShaderSource(s.id(), 1, &text, nullptr);
    glCompileShader(s.id());
    GLint ok = 0;
    glGetShaderiv(s.id(), GL_COMPILE_STATUS, &ok);
    if (!ok) {
        const std::string main = source.files.empty() ? std::string("<source>") : source.files.front();
        throw shader_error(std::string(stage_name(stage)) + " shader " + main + " failed to compile:\n" +
                           source.rewrite_log(shader_log(s.id())));
    }
    return s;
}

void program::use() const {
    if (!handle_.id()) throw std::logic_error("gl::program: use() of a program that was never built");
    glUseProgram(handle_.id());
}

program program::compute(const preprocessed_source& source) {
    shader_handle s = compile_shader(GL_COMPUTE_SHADER, source);
    program p;
    p.handle_ = link({s.id()}, source.files.empty() ? std::string("<source>") : source.files.front());
    return p;
}

program program::compute(const std::filesystem::path& path, const preprocess_options& options) {
    return compute(preprocess_file(path, options));
}

program program::graphics(const std::filesystem::path& vertex, const std::filesystem::path& fragment,
                          const preprocess_options& options) {
    shader_handle v = compile_shader(GL_VERTEX_SHADER, preprocess_file(vertex, options));
    shader_handle f = compile_shader(GL_FRAGMENT_SHADER, preprocess_file(fragment, options));
    program p;
    p.handle_ = link({v.id(), f.id()}, vertex.string() + " + " + fragment.string());
    return p;
}

}  // namespace emcv::gl
