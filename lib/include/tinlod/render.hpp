// Rendering TINs and meshes with OpenGL 3.3 core: hill shading (optionally on a height colour
// ramp), colour by a per-vertex or per-face scalar through a colour map, a wireframe overlay, and
// depth. `MeshPainter` draws into whatever GL context is current (the interactive viewer's GLFW
// window); `Renderer` owns a headless EGL context on Mesa (llvmpipe) and an offscreen framebuffer.
#pragma once

#include "tinlod/raster.hpp"
#include "tinlod/tin.hpp"
#include "tinlod/view.hpp"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tinlod {

enum class ColorMode {
    shade,         // hill shade on a neutral terrain colour
    height,        // hill shade on a hypsometric colour ramp over [z_min, z_max]
    vertex_scalar, // RenderOptions::vertex_scalar through the colour map, interpolated over faces
    face_scalar,   // RenderOptions::face_scalar through the colour map, one colour per face
};

struct RenderOptions {
    ColorMode color = ColorMode::shade;
    bool wire = false;                       // overlay the triangle edges, about 1 px wide
    glm::vec3 sun{-1.0f, 1.0f, 1.41421356f}; // direction toward the sun, world frame, any length
                                             // (default: from the north-west, 45 degrees high)
    float ambient = 0.3f;                    // light on faces turned away from the sun, 0..1
    std::vector<float> vertex_scalar; // vertex_scalar mode: one value per vertex (index = idx())
    std::vector<float> face_scalar;   // face_scalar mode: one value per face (index = idx())
    float scalar_max = 0.0f;          // value at the top of the colour map (0 maps to the bottom);
                                      // <= 0: the largest value given
    float z_min = NAN, z_max = NAN;   // height range of the ramp, world units; NaN: the mesh's
    glm::vec3 sky{0.62f, 0.77f, 0.92f};         // background colour, 0..1
    const Heightfield *normal_source = nullptr; // when set: shade with this DEM's normals (central
                                                // differences, bilinear at each pixel's xy in the
                                                // DEM's local frame) instead of the mesh's vertex
                                                // normals, so a TIN's render differs from the full
                                                // one only where its surface moves on screen
    glm::dvec2 clip{0.0, 0.0};                  // near, far planes, world units; 0, 0: clip_range()
    bool depth = false;                         // also read back depth (Image::depth)
    std::string legend; // scalar modes, Renderer only: when not empty, a colour legend titled
                        // with this (the quantity and its units, e.g. "error (m)") is drawn
                        // into the image's top-right corner (see draw_legend)
};

// An RGBA8 picture, row 0 at the TOP, and optionally its depth.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba; // width*height*4
    std::vector<float> depth;       // empty, or width*height distances from the eye along the
                                    // observation axis, world units; +infinity where no surface
};

// The colour map of the scalar modes (Turbo): x in [0, 1] (clamped) to RGB in [0, 1]. The shaders
// evaluate the same polynomial; the scalar modes show it times (0.6 + 0.4 * lambert).
glm::vec3 turbo(float x);

// Draws a colour legend into the top-right corner of `image`: a bar running the colour map from 0
// at its bottom to `top` at its top, both ends labelled, under `title` (quantity and units). Draws
// nothing when the image is too small to hold it (under about 100 pixels high).
void draw_legend(Image &image, float top, const std::string &title);

// Near and far clipping distances (world units) that enclose every point of `mesh` seen from
// `view`: far just beyond the farthest bounding-box corner, near at the distance to the box (or a
// small fraction of far when the eye is inside it).
glm::dvec2 clip_range(const Mesh &mesh, const View &view);
// The same for the box [lo, hi] (world units).
glm::dvec2 clip_range(const glm::dvec3 &lo, const glm::dvec3 &hi, const View &view);

// Draws meshes into the GL 3.3 core context current on this thread (GL objects live in it).
// Construct, use and destroy it only while that context is current.
class MeshPainter {
  public:
    MeshPainter(); // compiles the shaders; throws Error("render", ...) when they do not build
    ~MeshPainter();
    MeshPainter(const MeshPainter &) = delete;
    MeshPainter &operator=(const MeshPainter &) = delete;

    // Uploads the live faces of `mesh` with the scalars `options` asks for (checked against the
    // mesh: throws Error("render", ...) when a scalar array has the wrong length).
    void upload(const Mesh &mesh, const RenderOptions &options);
    // Clears the bound framebuffer to the sky and draws the uploaded mesh for `view` into a
    // viewport of view.viewport_w x view.viewport_h pixels, with clipping planes `clip`.
    void draw(const View &view, glm::dvec2 clip, const RenderOptions &options) const;
    // The value at the top of the colour map for the uploaded scalars (RenderOptions::scalar_max
    // or, when that is <= 0, the largest value).
    float scalar_max() const { return scalar_max_; }

  private:
    void upload_normal_map(const Heightfield *hf);

    unsigned program_ = 0, vao_ = 0, vertex_buffer_ = 0, index_buffer_ = 0;
    unsigned face_buffer_ = 0, face_texture_ = 0, normal_texture_ = 0;
    bool normal_map_ = false;   // a normal_source was uploaded
    glm::vec4 normal_uv_{0.0f}; // texture coordinate = xy * normal_uv_.xy + normal_uv_.zw
    std::int64_t index_count_ = 0;
    glm::dvec3 offset_{0.0};  // uploaded positions are relative to this point (float precision)
    glm::vec2 z_range_{0.0f}; // of the uploaded mesh
    float scalar_max_ = 1.0f;
};

// Offscreen rendering through a headless EGL context (EGL_PLATFORM_SURFACELESS_MESA, so no display
// server is needed). Not thread-safe: one Renderer per thread.
class Renderer {
  public:
    // Throws Error("render", reason) when no OpenGL 3.3 core context can be made.
    Renderer();
    ~Renderer();
    Renderer(const Renderer &) = delete;
    Renderer &operator=(const Renderer &) = delete;

    // Renders `mesh` (faces with the deleted status are skipped) as seen from `view`, at the
    // view's viewport size. Deterministic: the same input gives the same bytes.
    Image render(const Mesh &mesh, const View &view, const RenderOptions &options = {});
    // "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6", for reports.
    std::string gl_description() const;

  private:
    struct Context;
    std::unique_ptr<Context> context_;
    std::unique_ptr<MeshPainter> painter_;
};

// True when a Renderer can be made here; otherwise `why` (optional) receives the reason.
bool render_available(std::string *why = nullptr);

// Writes the colour of `image` to `path` (format by extension: .png, .tif, .exr, ...), atomically.
// Throws Error naming the file when it cannot be written.
void write_image(const std::string &path, const Image &image);
// Writes the depth of `image` as a one-channel float image (use .exr or .tif), atomically.
void write_depth(const std::string &path, const Image &image);
// Reads an image file into RGBA8 (grey or RGB get opaque alpha); throws Error naming the file.
Image read_image(const std::string &path);

} // namespace tinlod
