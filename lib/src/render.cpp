// OpenGL 3.3 core rendering of TINs (render.hpp): the shaders and MeshPainter that draw into the
// current context, and the headless EGL context + framebuffer of Renderer. GL entry points come
// from GLVND's libOpenGL, which exports the whole core API and dispatches to the current context
// (EGL here, GLX in the viewer); it and libEGL are opened the first time something draws, so that
// a program linking this library loads neither until then.
//
// The wireframe overlay is the single-pass technique of Bærentzen et al., "Single-pass Wireframe
// Rendering" (SIGGRAPH 2006 sketch): a geometry shader gives each fragment its distance in pixels
// to the three edges of its triangle.
#include "tinlod/render.hpp"
#include "backends/backends.hpp"
#include "tinlod/error.hpp"
#include "tinlod/util.hpp"

#define EGL_EGL_PROTOTYPES 0
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <dlfcn.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cassert>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <mutex>

namespace tinlod {

namespace {

// The entry points this file calls, as pointers of the names the GL and EGL headers would declare.
#define TINLOD_GL_FUNCTIONS(X)                                                                     \
    X(PFNGLACTIVETEXTUREPROC, glActiveTexture)                                                     \
    X(PFNGLATTACHSHADERPROC, glAttachShader)                                                       \
    X(PFNGLBINDBUFFERPROC, glBindBuffer)                                                           \
    X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                                                 \
    X(PFNGLBINDRENDERBUFFERPROC, glBindRenderbuffer)                                               \
    X(PFNGLBINDTEXTUREPROC, glBindTexture)                                                         \
    X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray)                                                 \
    X(PFNGLBUFFERDATAPROC, glBufferData)                                                           \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, glCheckFramebufferStatus)                                   \
    X(PFNGLCLEARPROC, glClear)                                                                     \
    X(PFNGLCLEARCOLORPROC, glClearColor)                                                           \
    X(PFNGLCLEARDEPTHPROC, glClearDepth)                                                           \
    X(PFNGLCOMPILESHADERPROC, glCompileShader)                                                     \
    X(PFNGLCREATEPROGRAMPROC, glCreateProgram)                                                     \
    X(PFNGLCREATESHADERPROC, glCreateShader)                                                       \
    X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers)                                                     \
    X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)                                           \
    X(PFNGLDELETEPROGRAMPROC, glDeleteProgram)                                                     \
    X(PFNGLDELETERENDERBUFFERSPROC, glDeleteRenderbuffers)                                         \
    X(PFNGLDELETESHADERPROC, glDeleteShader)                                                       \
    X(PFNGLDELETETEXTURESPROC, glDeleteTextures)                                                   \
    X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays)                                           \
    X(PFNGLDEPTHFUNCPROC, glDepthFunc)                                                             \
    X(PFNGLDISABLEPROC, glDisable)                                                                 \
    X(PFNGLDRAWELEMENTSPROC, glDrawElements)                                                       \
    X(PFNGLENABLEPROC, glEnable)                                                                   \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, glEnableVertexAttribArray)                                 \
    X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, glFramebufferRenderbuffer)                                 \
    X(PFNGLGENBUFFERSPROC, glGenBuffers)                                                           \
    X(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers)                                                 \
    X(PFNGLGENRENDERBUFFERSPROC, glGenRenderbuffers)                                               \
    X(PFNGLGENTEXTURESPROC, glGenTextures)                                                         \
    X(PFNGLGENVERTEXARRAYSPROC, glGenVertexArrays)                                                 \
    X(PFNGLGETERRORPROC, glGetError)                                                               \
    X(PFNGLGETINTEGERVPROC, glGetIntegerv)                                                         \
    X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog)                                             \
    X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)                                                       \
    X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog)                                               \
    X(PFNGLGETSHADERIVPROC, glGetShaderiv)                                                         \
    X(PFNGLGETSTRINGPROC, glGetString)                                                             \
    X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation)                                           \
    X(PFNGLLINKPROGRAMPROC, glLinkProgram)                                                         \
    X(PFNGLPIXELSTOREIPROC, glPixelStorei)                                                         \
    X(PFNGLREADPIXELSPROC, glReadPixels)                                                           \
    X(PFNGLRENDERBUFFERSTORAGEPROC, glRenderbufferStorage)                                         \
    X(PFNGLSHADERSOURCEPROC, glShaderSource)                                                       \
    X(PFNGLTEXBUFFERPROC, glTexBuffer)                                                             \
    X(PFNGLTEXIMAGE2DPROC, glTexImage2D)                                                           \
    X(PFNGLTEXPARAMETERIPROC, glTexParameteri)                                                     \
    X(PFNGLUNIFORM1FPROC, glUniform1f)                                                             \
    X(PFNGLUNIFORM1IPROC, glUniform1i)                                                             \
    X(PFNGLUNIFORM2FPROC, glUniform2f)                                                             \
    X(PFNGLUNIFORM2FVPROC, glUniform2fv)                                                           \
    X(PFNGLUNIFORM3FPROC, glUniform3f)                                                             \
    X(PFNGLUNIFORM4FPROC, glUniform4f)                                                             \
    X(PFNGLUNIFORM4FVPROC, glUniform4fv)                                                           \
    X(PFNGLUNIFORMMATRIX4FVPROC, glUniformMatrix4fv)                                               \
    X(PFNGLUSEPROGRAMPROC, glUseProgram)                                                           \
    X(PFNGLVERTEXATTRIBPOINTERPROC, glVertexAttribPointer)                                         \
    X(PFNGLVIEWPORTPROC, glViewport)

#define TINLOD_EGL_FUNCTIONS(X)                                                                    \
    X(PFNEGLBINDAPIPROC, eglBindAPI)                                                               \
    X(PFNEGLCREATECONTEXTPROC, eglCreateContext)                                                   \
    X(PFNEGLDESTROYCONTEXTPROC, eglDestroyContext)                                                 \
    X(PFNEGLGETERRORPROC, eglGetError)                                                             \
    X(PFNEGLGETPROCADDRESSPROC, eglGetProcAddress)                                                 \
    X(PFNEGLINITIALIZEPROC, eglInitialize)                                                         \
    X(PFNEGLMAKECURRENTPROC, eglMakeCurrent)                                                       \
    X(PFNEGLQUERYSTRINGPROC, eglQueryString)

#define TINLOD_DEFINE_POINTER(type, name) type name = nullptr;
TINLOD_GL_FUNCTIONS(TINLOD_DEFINE_POINTER)
TINLOD_EGL_FUNCTIONS(TINLOD_DEFINE_POINTER)
#undef TINLOD_DEFINE_POINTER

// Opens `library` and sets its entry points (`bind` returns the name of one it lacks) once per
// process; throws Error("render", ...) when the library or an entry point is missing.
template <typename Bind>
void load_library(std::once_flag &once, std::string &failure, const char *library, Bind bind) {
    std::call_once(once, [&] {
        void *handle = dlopen(library, RTLD_NOW | RTLD_LOCAL);
        if (handle == nullptr) {
            const char *why = dlerror();
            failure = std::string("no OpenGL: cannot load ") + library + " (" +
                      (why ? why : "not found") + ")";
            return;
        }
        const char *missing = bind(handle);
        if (missing != nullptr)
            failure = std::string("no OpenGL: ") + library + " has no " + missing;
    });
    if (!failure.empty())
        throw Error("render", failure);
}

void load_gl() {
    static std::once_flag once;
    static std::string failure;
    load_library(once, failure, "libOpenGL.so.0", [](void *handle) -> const char * {
#define TINLOD_BIND(type, name)                                                                    \
    if ((name = reinterpret_cast<type>(dlsym(handle, #name))) == nullptr)                          \
        return #name;
        TINLOD_GL_FUNCTIONS(TINLOD_BIND)
        return nullptr;
    });
}

void load_egl() {
    static std::once_flag once;
    static std::string failure;
    load_library(once, failure, "libEGL.so.1", [](void *handle) -> const char * {
        TINLOD_EGL_FUNCTIONS(TINLOD_BIND)
#undef TINLOD_BIND
        return nullptr;
    });
}

const char *k_vertex_shader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in float scalar;
uniform mat4 mvp;
uniform vec4 normal_uv;
out VertexData { vec3 normal; float scalar; float z; vec2 uv; } vs;
void main() {
    gl_Position = mvp * vec4(position, 1.0);
    vs.normal = normal;
    vs.scalar = scalar;
    vs.z = position.z;
    vs.uv = position.xy * normal_uv.xy + normal_uv.zw;
}
)";

const char *k_geometry_shader = R"(#version 330 core
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
in VertexData { vec3 normal; float scalar; float z; vec2 uv; } gs[];
out FragmentData { vec3 normal; float scalar; float z; vec2 uv; noperspective vec3 edge; } fs;
flat out int face;
uniform vec2 viewport;
void main() {
    // Distances in pixels from each corner to the opposite edge; a triangle crossing the eye plane
    // has no meaningful screen shape, so it gets no wire.
    vec3 h = vec3(1e6);
    if (gl_in[0].gl_Position.w > 0.0 && gl_in[1].gl_Position.w > 0.0 &&
        gl_in[2].gl_Position.w > 0.0) {
        vec2 p0 = 0.5 * viewport * gl_in[0].gl_Position.xy / gl_in[0].gl_Position.w;
        vec2 p1 = 0.5 * viewport * gl_in[1].gl_Position.xy / gl_in[1].gl_Position.w;
        vec2 p2 = 0.5 * viewport * gl_in[2].gl_Position.xy / gl_in[2].gl_Position.w;
        vec2 e0 = p2 - p1, e1 = p2 - p0, e2 = p1 - p0;
        float area = abs(e1.x * e2.y - e1.y * e2.x);
        h = vec3(area / max(length(e0), 1e-6), area / max(length(e1), 1e-6),
                 area / max(length(e2), 1e-6));
    }
    for (int i = 0; i < 3; ++i) {
        gl_Position = gl_in[i].gl_Position;
        fs.normal = gs[i].normal;
        fs.scalar = gs[i].scalar;
        fs.z = gs[i].z;
        fs.uv = gs[i].uv;
        fs.edge = vec3(i == 0 ? h.x : 0.0, i == 1 ? h.y : 0.0, i == 2 ? h.z : 0.0);
        face = gl_PrimitiveIDIn;
        EmitVertex();
    }
    EndPrimitive();
}
)";

const char *k_fragment_shader = R"(#version 330 core
in FragmentData { vec3 normal; float scalar; float z; vec2 uv; noperspective vec3 edge; } fs;
flat in int face;
uniform bool dem_normals;
uniform sampler2D normal_map;
uniform int mode; // 0 shade, 1 height, 2 vertex scalar, 3 face scalar
uniform bool wire;
uniform vec3 sun;
uniform float ambient;
uniform vec2 z_range;
uniform float scalar_max;
uniform samplerBuffer face_scalars;
out vec4 color;

uniform vec4 turbo4[3]; // k_turbo, per channel: the coefficients of 1, x, x^2, x^3
uniform vec2 turbo2[3]; // and of x^4, x^5

vec3 turbo(float x) {
    x = clamp(x, 0.0, 1.0);
    vec4 v4 = vec4(1.0, x, x * x, x * x * x);
    vec2 v2 = v4.zw * v4.z;
    return vec3(dot(v4, turbo4[0]) + dot(v2, turbo2[0]), dot(v4, turbo4[1]) + dot(v2, turbo2[1]),
                dot(v4, turbo4[2]) + dot(v2, turbo2[2]));
}

// Hypsometric tints: lowland green, upland tan, mountain brown, snow.
vec3 hypsometric(float t) {
    const vec3 c[5] = vec3[5](vec3(0.25, 0.50, 0.28), vec3(0.60, 0.68, 0.38),
                              vec3(0.80, 0.70, 0.48), vec3(0.62, 0.50, 0.40),
                              vec3(0.96, 0.96, 0.96));
    const float s[5] = float[5](0.0, 0.3, 0.55, 0.8, 1.0);
    t = clamp(t, 0.0, 1.0);
    for (int i = 1; i < 5; ++i)
        if (t <= s[i])
            return mix(c[i - 1], c[i], (t - s[i - 1]) / (s[i] - s[i - 1]));
    return c[4];
}

void main() {
    vec3 n;
    if (dem_normals) {
        n = normalize(texture(normal_map, fs.uv).xyz);
    } else {
        n = normalize(fs.normal);
        if (!gl_FrontFacing)
            n = -n;
    }
    float lambert = max(dot(n, sun), 0.0);
    float light = ambient + (1.0 - ambient) * lambert;
    vec3 base;
    if (mode == 0) {
        base = vec3(0.86, 0.84, 0.78) * light;
    } else if (mode == 1) {
        base = hypsometric((fs.z - z_range.x) / max(z_range.y - z_range.x, 1e-6)) * light;
    } else {
        float s = mode == 2 ? fs.scalar : texelFetch(face_scalars, face).r;
        base = turbo(s / scalar_max) * (0.6 + 0.4 * lambert);
    }
    if (wire) {
        float d = min(fs.edge.x, min(fs.edge.y, fs.edge.z));
        base = mix(base, vec3(0.08), 0.85 * (1.0 - smoothstep(0.0, 1.0, d)));
    }
    color = vec4(base, 1.0);
}
)";

// Turbo colour map, polynomial fit by A. Mikhailov (Google, 2019): per channel (r, g, b), the
// coefficients of 1, x, ..., x^5. One table for the shaders and for turbo().
constexpr float k_turbo[3][6] = {
    {0.13572138f, 4.61539260f, -42.66032258f, 132.13108234f, -152.94239396f, 59.28637943f},
    {0.09140261f, 2.19418839f, 4.84296658f, -14.18503333f, 4.27729857f, 2.82956604f},
    {0.10667330f, 12.64194608f, -60.58204836f, 110.36276771f, -89.90310912f, 27.34824973f}};

GLuint compile(GLenum kind, const char *source, const char *name) {
    const GLuint shader = glCreateShader(kind);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        throw Error("render", std::string(name) + " shader does not compile: " + log);
    }
    return shader;
}

GLuint link_program() {
    const GLuint shaders[3] = {compile(GL_VERTEX_SHADER, k_vertex_shader, "vertex"),
                               compile(GL_GEOMETRY_SHADER, k_geometry_shader, "geometry"),
                               compile(GL_FRAGMENT_SHADER, k_fragment_shader, "fragment")};
    const GLuint program = glCreateProgram();
    for (GLuint s : shaders)
        glAttachShader(program, s);
    glLinkProgram(program);
    for (GLuint s : shaders)
        glDeleteShader(s);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        glDeleteProgram(program);
        throw Error("render", std::string("shaders do not link: ") + log);
    }
    return program;
}

void check_gl(const char *stage) {
    const GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        char code[16];
        std::snprintf(code, sizeof code, "0x%04x", e);
        throw Error("render", std::string("OpenGL error ") + code + " while " + stage);
    }
}

struct Bounds {
    glm::dvec3 lo{std::numeric_limits<double>::infinity()};
    glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
    bool empty() const { return !(lo.x <= hi.x); }
};

Bounds live_bounds(const Mesh &mesh) {
    Bounds b;
    for (auto v : mesh.vertices()) {
        const auto &p = mesh.point(v);
        const glm::dvec3 q(p[0], p[1], p[2]);
        b.lo = glm::min(b.lo, q);
        b.hi = glm::max(b.hi, q);
    }
    return b;
}

} // namespace

glm::vec3 turbo(float x) {
    x = std::clamp(x, 0.0f, 1.0f);
    const glm::vec4 v4(1.0f, x, x * x, x * x * x);
    const glm::vec2 v2 = glm::vec2(v4.z, v4.w) * v4.z;
    glm::vec3 rgb;
    for (int c = 0; c < 3; ++c)
        rgb[c] =
            glm::dot(v4, glm::vec4(k_turbo[c][0], k_turbo[c][1], k_turbo[c][2], k_turbo[c][3])) +
            glm::dot(v2, glm::vec2(k_turbo[c][4], k_turbo[c][5]));
    return rgb;
}

glm::dvec2 clip_range(const Mesh &mesh, const View &view) {
    const Bounds b = live_bounds(mesh);
    if (b.empty())
        return {1.0, 2.0};
    return clip_range(b.lo, b.hi, view);
}

glm::dvec2 clip_range(const glm::dvec3 &lo, const glm::dvec3 &hi, const View &view) {
    double far = 0.0;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 corner(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        far = std::max(far, glm::length(corner - view.eye));
    }
    far = far * 1.01 + 1e-3;
    const double inside = glm::length(glm::clamp(view.eye, lo, hi) - view.eye);
    // A 32-bit float depth buffer keeps a far/near ratio of 1e5 well resolved.
    const double near = std::clamp(inside * 0.99, far * 1e-5, far * 0.5);
    return {near, far};
}

MeshPainter::MeshPainter() {
    load_gl();
    program_ = link_program();
    glGenVertexArrays(1, &vao_);
    glGenBuffers(1, &vertex_buffer_);
    glGenBuffers(1, &index_buffer_);
    glGenBuffers(1, &face_buffer_);
    glGenTextures(1, &face_texture_);
    glGenTextures(1, &normal_texture_);
    check_gl("creating the mesh buffers");
}

MeshPainter::~MeshPainter() {
    glDeleteTextures(1, &normal_texture_);
    glDeleteTextures(1, &face_texture_);
    glDeleteBuffers(1, &face_buffer_);
    glDeleteBuffers(1, &index_buffer_);
    glDeleteBuffers(1, &vertex_buffer_);
    glDeleteVertexArrays(1, &vao_);
    glDeleteProgram(program_);
}

void MeshPainter::upload(const Mesh &mesh, const RenderOptions &options) {
    const std::size_t nv = mesh.n_vertices();
    const bool by_vertex = options.color == ColorMode::vertex_scalar;
    const bool by_face = options.color == ColorMode::face_scalar;
    if (by_vertex && options.vertex_scalar.size() != nv)
        throw Error("render", "colour by vertex needs one value per vertex (" + std::to_string(nv) +
                                  "), got " + std::to_string(options.vertex_scalar.size()));
    if (by_face && options.face_scalar.size() != mesh.n_faces())
        throw Error("render", "colour by face needs one value per face (" +
                                  std::to_string(mesh.n_faces()) + "), got " +
                                  std::to_string(options.face_scalar.size()));

    const Bounds b = live_bounds(mesh);
    offset_ = b.empty() ? glm::dvec3(0.0) : 0.5 * (b.lo + b.hi);
    z_range_ = b.empty() ? glm::vec2(0.0f)
                         : glm::vec2(float(b.lo.z - offset_.z), float(b.hi.z - offset_.z));

    // Area-weighted vertex normals in double, so they do not depend on the face order's rounding.
    std::vector<glm::dvec3> normals(nv, glm::dvec3(0.0));
    std::vector<GLuint> indices;
    std::vector<float> face_values;
    indices.reserve(3 * mesh.n_faces());
    for (auto f : mesh.faces()) {
        if (mesh.status(f).deleted())
            continue;
        GLuint id[3];
        glm::dvec3 p[3];
        int i = 0;
        for (auto v : f.vertices()) {
            const auto &q = mesh.point(v);
            id[i] = static_cast<GLuint>(v.idx());
            p[i++] = glm::dvec3(q[0], q[1], q[2]);
        }
        const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
        for (int k = 0; k < 3; ++k) {
            normals[id[k]] += n;
            indices.push_back(id[k]);
        }
        if (by_face)
            face_values.push_back(options.face_scalar[f.idx()]);
    }
    index_count_ = static_cast<std::int64_t>(indices.size());

    std::vector<float> vertices(7 * nv);
    for (auto v : mesh.vertices()) {
        const auto &q = mesh.point(v);
        const glm::dvec3 n = glm::length(normals[v.idx()]) > 0.0 ? glm::normalize(normals[v.idx()])
                                                                 : glm::dvec3(0.0, 0.0, 1.0);
        float *out = &vertices[7 * static_cast<std::size_t>(v.idx())];
        out[0] = float(q[0] - offset_.x);
        out[1] = float(q[1] - offset_.y);
        out[2] = float(q[2] - offset_.z);
        out[3] = float(n.x);
        out[4] = float(n.y);
        out[5] = float(n.z);
        out[6] = by_vertex ? options.vertex_scalar[v.idx()] : 0.0f;
    }

    float top = options.scalar_max;
    if (!(top > 0.0f)) {
        top = 0.0f;
        for (float s : by_vertex ? options.vertex_scalar : face_values)
            top = std::max(top, s);
        if (!(top > 0.0f))
            top = 1.0f;
    }
    scalar_max_ = top;
    if (face_values.empty())
        face_values.push_back(0.0f);

    glBindVertexArray(vao_);
    glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(float)), vertices.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 7 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 7 * sizeof(float),
                          reinterpret_cast<const void *>(3 * sizeof(float)));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, 7 * sizeof(float),
                          reinterpret_cast<const void *>(6 * sizeof(float)));
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_buffer_);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(GLuint)),
                 indices.data(), GL_STATIC_DRAW);
    glBindVertexArray(0);

    glBindBuffer(GL_TEXTURE_BUFFER, face_buffer_);
    glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(face_values.size() * sizeof(float)),
                 face_values.data(), GL_STATIC_DRAW);
    glBindTexture(GL_TEXTURE_BUFFER, face_texture_);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_R32F, face_buffer_);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    check_gl("uploading the mesh");
    upload_normal_map(options.normal_source);
}

void MeshPainter::upload_normal_map(const Heightfield *hf) {
    normal_map_ = hf != nullptr;
    if (!normal_map_)
        return;
    GLint largest = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &largest);
    if (hf->width > largest || hf->height > largest)
        throw Error("render", "DEM of " + std::to_string(hf->width) + "x" +
                                  std::to_string(hf->height) +
                                  " samples is larger than the OpenGL texture limit of " +
                                  std::to_string(largest) + " for its normals");
    const int w = hf->width, h = hf->height;
    std::vector<float> normals(std::size_t(w) * h * 3);
    for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c) {
            const int c0 = std::max(c - 1, 0), c1 = std::min(c + 1, w - 1);
            const int r0 = std::max(r - 1, 0), r1 = std::min(r + 1, h - 1);
            const double gx = (double(hf->at(c1, r)) - hf->at(c0, r)) / ((c1 - c0) * hf->dx);
            const double gy = (double(hf->at(c, r1)) - hf->at(c, r0)) / ((r1 - r0) * hf->dy);
            const glm::dvec3 n = glm::normalize(glm::dvec3(-gx, -gy, 1.0));
            float *out = &normals[3 * (std::size_t(r) * w + c)];
            out[0] = float(n.x);
            out[1] = float(n.y);
            out[2] = float(n.z);
        }
    // Texel centres sit on the samples: u = (x / dx + 0.5) / width, with x = xy + offset.
    normal_uv_ =
        glm::vec4(float(1.0 / (hf->dx * w)), float(1.0 / (hf->dy * h)),
                  float((offset_.x / hf->dx + 0.5) / w), float((offset_.y / hf->dy + 0.5) / h));
    glBindTexture(GL_TEXTURE_2D, normal_texture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, w, h, 0, GL_RGB, GL_FLOAT, normals.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    check_gl("uploading the DEM normals");
}

void MeshPainter::draw(const View &view, glm::dvec2 clip, const RenderOptions &options) const {
    const glm::dmat4 mvp = view.projection_matrix(clip.x, clip.y) * view.view_matrix() *
                           glm::translate(glm::dmat4(1.0), offset_);
    const glm::mat4 mvp_f(mvp);
    const glm::vec3 sun =
        glm::length(options.sun) > 0.0f ? glm::normalize(options.sun) : glm::vec3(0.0f, 0.0f, 1.0f);
    glm::vec2 z_range = z_range_;
    if (std::isfinite(options.z_min) && std::isfinite(options.z_max))
        z_range = glm::vec2(float(options.z_min - offset_.z), float(options.z_max - offset_.z));
    const int mode = options.color == ColorMode::shade           ? 0
                     : options.color == ColorMode::height        ? 1
                     : options.color == ColorMode::vertex_scalar ? 2
                                                                 : 3;

    glViewport(0, 0, view.viewport_w, view.viewport_h);
    glClearColor(options.sky.r, options.sky.g, options.sky.b, 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glUseProgram(program_);
    glUniformMatrix4fv(glGetUniformLocation(program_, "mvp"), 1, GL_FALSE, glm::value_ptr(mvp_f));
    glUniform2f(glGetUniformLocation(program_, "viewport"), float(view.viewport_w),
                float(view.viewport_h));
    glUniform1i(glGetUniformLocation(program_, "mode"), mode);
    glUniform1i(glGetUniformLocation(program_, "wire"), options.wire ? 1 : 0);
    glUniform3f(glGetUniformLocation(program_, "sun"), sun.x, sun.y, sun.z);
    glUniform1f(glGetUniformLocation(program_, "ambient"), std::clamp(options.ambient, 0.0f, 1.0f));
    glUniform2f(glGetUniformLocation(program_, "z_range"), z_range.x, z_range.y);
    glUniform1f(glGetUniformLocation(program_, "scalar_max"), scalar_max_);
    float turbo4[3][4], turbo2[3][2];
    for (int c = 0; c < 3; ++c) {
        std::copy(k_turbo[c], k_turbo[c] + 4, turbo4[c]);
        std::copy(k_turbo[c] + 4, k_turbo[c] + 6, turbo2[c]);
    }
    glUniform4fv(glGetUniformLocation(program_, "turbo4"), 3, &turbo4[0][0]);
    glUniform2fv(glGetUniformLocation(program_, "turbo2"), 3, &turbo2[0][0]);
    glUniform1i(glGetUniformLocation(program_, "face_scalars"), 0);
    glUniform1i(glGetUniformLocation(program_, "normal_map"), 1);
    glUniform1i(glGetUniformLocation(program_, "dem_normals"), normal_map_ ? 1 : 0);
    glUniform4f(glGetUniformLocation(program_, "normal_uv"), normal_uv_.x, normal_uv_.y,
                normal_uv_.z, normal_uv_.w);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, normal_texture_);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_BUFFER, face_texture_);
    glBindVertexArray(vao_);
    glDrawElements(GL_TRIANGLES, GLsizei(index_count_), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    glUseProgram(0);
    check_gl("drawing the mesh");
}

struct Renderer::Context {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    GLuint fbo = 0, color = 0, depth = 0;
    int width = 0, height = 0;

    Context() = default;
    Context(const Context &) = delete;
    Context &operator=(const Context &) = delete;
    // The display stays initialised: other Renderers on this thread share it.
    ~Context() {
        if (context == EGL_NO_CONTEXT)
            return;
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, context);
    }
    void make_current() const {
        if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
            throw Error("render", "cannot make the EGL context current");
    }
};

static std::string egl_error_text(const char *what) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", eglGetError());
    return std::string(what) + " (EGL error " + code + ")";
}

static bool has_extension(const char *list, const char *name) {
    if (list == nullptr)
        return false;
    const std::size_t n = std::strlen(name);
    for (const char *p = std::strstr(list, name); p != nullptr; p = std::strstr(p + n, name))
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return true;
    return false;
}

Renderer::Renderer() : context_(std::make_unique<Context>()) {
    load_egl();
    load_gl();
    Context &c = *context_;
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!has_extension(client, "EGL_MESA_platform_surfaceless"))
        throw Error("render", "no OpenGL: EGL has no surfaceless platform "
                              "(EGL_MESA_platform_surfaceless; install libegl1-mesa-dev and "
                              "libgl1-mesa-dri)");
    auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_display == nullptr)
        throw Error("render", "no OpenGL: eglGetPlatformDisplayEXT is missing");
    c.display = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major = 0, minor = 0;
    if (c.display == EGL_NO_DISPLAY || !eglInitialize(c.display, &major, &minor))
        throw Error("render", egl_error_text("no OpenGL: cannot open the surfaceless EGL display"));
    const char *extensions = eglQueryString(c.display, EGL_EXTENSIONS);
    if (!has_extension(extensions, "EGL_KHR_surfaceless_context") ||
        !has_extension(extensions, "EGL_KHR_no_config_context"))
        throw Error("render", "no OpenGL: the EGL display cannot make a context without a surface");
    if (!eglBindAPI(EGL_OPENGL_API))
        throw Error("render", egl_error_text("no OpenGL: EGL does not offer desktop OpenGL"));
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                 3,
                                 EGL_CONTEXT_MINOR_VERSION,
                                 3,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_NONE};
    c.context = eglCreateContext(c.display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (c.context == EGL_NO_CONTEXT)
        throw Error("render",
                    egl_error_text("no OpenGL: cannot create an OpenGL 3.3 core context"));
    c.make_current();
    glGenFramebuffers(1, &c.fbo);
    glGenRenderbuffers(1, &c.color);
    glGenRenderbuffers(1, &c.depth);
    painter_ = std::make_unique<MeshPainter>();
}

Renderer::~Renderer() {
    const Context &c = *context_;
    if (eglMakeCurrent(c.display, EGL_NO_SURFACE, EGL_NO_SURFACE, c.context)) {
        painter_.reset();
        glDeleteRenderbuffers(1, &c.depth);
        glDeleteRenderbuffers(1, &c.color);
        glDeleteFramebuffers(1, &c.fbo);
    }
}

std::string Renderer::gl_description() const {
    context_->make_current();
    return std::string(reinterpret_cast<const char *>(glGetString(GL_RENDERER))) + ", " +
           reinterpret_cast<const char *>(glGetString(GL_VERSION));
}

Image Renderer::render(const Mesh &mesh, const View &view, const RenderOptions &options) {
    validate(view, "render");
    Context &c = *context_;
    c.make_current();
    if (c.width != view.viewport_w || c.height != view.viewport_h) {
        GLint largest = 0;
        glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &largest);
        if (view.viewport_w > largest || view.viewport_h > largest)
            throw Error("render", "viewport larger than the OpenGL limit of " +
                                      std::to_string(largest) + " pixels a side");
        glBindRenderbuffer(GL_RENDERBUFFER, c.color);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, view.viewport_w, view.viewport_h);
        glBindRenderbuffer(GL_RENDERBUFFER, c.depth);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, view.viewport_w,
                              view.viewport_h);
        glBindRenderbuffer(GL_RENDERBUFFER, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, c.fbo);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, c.color);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, c.depth);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw Error("render", "cannot make a " + std::to_string(view.viewport_w) + "x" +
                                      std::to_string(view.viewport_h) + " framebuffer");
        c.width = view.viewport_w;
        c.height = view.viewport_h;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, c.fbo);
    const glm::dvec2 clip = options.clip.x > 0.0 && options.clip.y > options.clip.x
                                ? options.clip
                                : clip_range(mesh, view);
    painter_->upload(mesh, options);
    painter_->draw(view, clip, options);

    Image image;
    image.width = c.width;
    image.height = c.height;
    const std::size_t w = static_cast<std::size_t>(c.width), h = static_cast<std::size_t>(c.height);
    std::vector<std::uint8_t> rows(w * h * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, c.width, c.height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    // GL rows run bottom-up; images top-down.
    image.rgba.resize(rows.size());
    for (std::size_t r = 0; r < h; ++r)
        std::memcpy(&image.rgba[r * w * 4], &rows[(h - 1 - r) * w * 4], w * 4);
    if (options.depth) {
        std::vector<float> d(w * h);
        glReadPixels(0, 0, c.width, c.height, GL_DEPTH_COMPONENT, GL_FLOAT, d.data());
        const double n = clip.x, f = clip.y;
        image.depth.resize(w * h);
        for (std::size_t r = 0; r < h; ++r)
            for (std::size_t x = 0; x < w; ++x) {
                const double window = d[(h - 1 - r) * w + x];
                const double ndc = 2.0 * window - 1.0;
                image.depth[r * w + x] = window >= 1.0
                                             ? std::numeric_limits<float>::infinity()
                                             : float(2.0 * n * f / (f + n - ndc * (f - n)));
            }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    check_gl("reading the image back");
    if (!options.legend.empty() &&
        (options.color == ColorMode::vertex_scalar || options.color == ColorMode::face_scalar))
        draw_legend(image, painter_->scalar_max(), options.legend);
    return image;
}

bool render_available(std::string *why) {
    static std::once_flag once;
    static std::string reason;
    std::call_once(once, [] {
        try {
            Renderer probe;
        } catch (const std::exception &e) {
            reason = e.what();
            if (reason.empty())
                reason = "render: no OpenGL context";
        }
    });
    if (why != nullptr)
        *why = reason;
    return reason.empty();
}

static void write_pixels(const std::string &path, const backends::PixelView &pixels) {
    backends::ImageFiles &images = backends::image_files();
    write_atomically(path, [&](const std::string &tmp) { images.write_image(path, tmp, pixels); });
}

void write_image(const std::string &path, const Image &image) {
    assert(image.rgba.size() == std::size_t(image.width) * image.height * 4);
    write_pixels(path, {image.width, image.height, 4, false, image.rgba.data()});
}

void write_depth(const std::string &path, const Image &image) {
    if (image.depth.size() != std::size_t(image.width) * image.height)
        throw Error(path, "the image has no depth (render with depth = true)");
    write_pixels(path, {image.width, image.height, 1, true, image.depth.data()});
}

Image read_image(const std::string &path) {
    int width = 0, height = 0, channels = 0;
    const std::vector<std::uint8_t> pixels =
        backends::image_files().read_image(path, width, height, channels);
    Image image;
    image.width = width;
    image.height = height;
    image.rgba.resize(std::size_t(width) * height * 4);
    for (std::size_t i = 0, n = std::size_t(width) * height; i < n; ++i) {
        const std::uint8_t *p = &pixels[i * channels];
        std::uint8_t *q = &image.rgba[i * 4];
        q[0] = p[0];
        q[1] = channels >= 3 ? p[1] : p[0];
        q[2] = channels >= 3 ? p[2] : p[0];
        q[3] = channels == 4 ? p[3] : channels == 2 ? p[1] : 255;
    }
    return image;
}

} // namespace tinlod
