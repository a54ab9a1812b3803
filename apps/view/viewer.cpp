// The viewer window (viewer.hpp): GLFW window with a GL 3.3 core context, the terrain drawn by
// MeshPainter, the Dear ImGui experiment panel, input routed to CameraControl, the TIN computed by
// the LodWorker and swapped in when ready; and the scripted mode, which plays a camera path frame
// by frame, waiting for each TIN, into an offscreen framebuffer.
//
// GL entry points come from GLVND's libOpenGL, which dispatches to the GLX context GLFW makes
// current (as lib/src/render.cpp relies on); ImGui's OpenGL 3 backend loads its own.
#include "viewer.hpp"

#include "camera_control.hpp"

#include "tinlod/camera_path.hpp"
#include "tinlod/error.hpp"
#include "tinlod/render.hpp"
#include "tinlod/util.hpp"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

namespace tinlod::viewer {

namespace {

std::string glfw_last_error() {
    const char *text = nullptr;
    glfwGetError(&text);
    return text ? text : "unknown reason";
}

// GLFW itself: initialised once per run, terminated at the end.
struct GlfwSession {
    GlfwSession() {
        if (!glfwInit())
            throw Error("display", "cannot open a window: " + glfw_last_error());
    }
    ~GlfwSession() { glfwTerminate(); }
    GlfwSession(const GlfwSession &) = delete;
    GlfwSession &operator=(const GlfwSession &) = delete;
};

GLFWwindow *open_window(int width, int height, bool visible) {
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow *window = glfwCreateWindow(width, height, "tinlod-view", nullptr, nullptr);
    if (window == nullptr)
        throw Error("OpenGL", "no OpenGL 3.3 core context: " + glfw_last_error());
    glfwMakeContextCurrent(window);
    return window;
}

// Reads the bound framebuffer's colour into an Image (rows flipped: row 0 at the top).
Image read_pixels(int width, int height) {
    Image image;
    image.width = width;
    image.height = height;
    image.rgba.resize(std::size_t(width) * height * 4);
    std::vector<std::uint8_t> rows(image.rgba.size());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    const std::size_t stride = std::size_t(width) * 4;
    for (int y = 0; y < height; ++y)
        std::copy_n(rows.data() + std::size_t(height - 1 - y) * stride, stride,
                    image.rgba.data() + std::size_t(y) * stride);
    for (std::size_t i = 3; i < image.rgba.size(); i += 4)
        image.rgba[i] = 255;
    return image;
}

// An offscreen colour + depth framebuffer (scripted mode: independent of the window's pixels).
class Framebuffer {
  public:
    Framebuffer(int width, int height) {
        glGenFramebuffers(1, &fbo_);
        glGenRenderbuffers(2, buffers_);
        glBindRenderbuffer(GL_RENDERBUFFER, buffers_[0]);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
        glBindRenderbuffer(GL_RENDERBUFFER, buffers_[1]);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, width, height);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                  buffers_[0]);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                  buffers_[1]);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw Error("OpenGL", "cannot make an offscreen framebuffer");
    }
    ~Framebuffer() {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glDeleteRenderbuffers(2, buffers_);
        glDeleteFramebuffers(1, &fbo_);
    }
    Framebuffer(const Framebuffer &) = delete;
    Framebuffer &operator=(const Framebuffer &) = delete;
    void bind() const { glBindFramebuffer(GL_FRAMEBUFFER, fbo_); }

  private:
    GLuint fbo_ = 0;
    GLuint buffers_[2] = {0, 0};
};

bool same_view(const View &a, const View &b) {
    return a.eye == b.eye && a.at == b.at && a.fov_deg == b.fov_deg &&
           a.viewport_w == b.viewport_w && a.viewport_h == b.viewport_h;
}

// Near and far planes around the scene box known at load.
glm::dvec2 clip_for(const SceneInfo &scene, const View &view) {
    return clip_range(scene.lo, scene.hi, view);
}

// The start view: from above the south edge, looking north at the centre.
void home_view(const SceneInfo &scene, CameraControl &control) {
    const glm::dvec3 c = 0.5 * (scene.lo + scene.hi);
    const double size = std::max({scene.hi.x - scene.lo.x, scene.hi.y - scene.lo.y, 1e-3});
    const glm::dvec3 eye(c.x, scene.lo.y - 0.35 * (scene.hi.y - scene.lo.y),
                         scene.hi.z + 0.35 * size);
    control.look_at(eye, c);
    control.set_speed(size / 15.0);
    control.set_home();
}

ColorMode color_mode(ColorBy by) {
    switch (by) {
    case ColorBy::shade:
        return ColorMode::shade;
    case ColorBy::height:
        return ColorMode::height;
    case ColorBy::sp:
        return ColorMode::vertex_scalar;
    case ColorBy::level:
    case ColorBy::error:
        return ColorMode::face_scalar;
    }
    return ColorMode::shade;
}

std::string timestamp_name(const char *prefix, const char *extension) {
    const std::time_t now = std::time(nullptr);
    char text[64];
    std::strftime(text, sizeof text, "%Y%m%d-%H%M%S", std::localtime(&now));
    return std::string(prefix) + text + extension;
}

// Everything that lives while a window is open.
class Viewer {
  public:
    Viewer(const ViewerOptions &options, GLFWwindow *window)
        : options_(options), window_(window), settings_(options.lod) {
        base_.fov_deg = options.fov_deg;
        base_.viewport_w = options.width;
        base_.viewport_h = options.height;
        painter_ = std::make_unique<MeshPainter>();
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr;
        ImGui::StyleColorsDark();
        glfwSetWindowUserPointer(window_, this);
        glfwSetScrollCallback(window_, [](GLFWwindow *w, double, double dy) {
            static_cast<Viewer *>(glfwGetWindowUserPointer(w))->scroll_ += dy;
        });
        glfwSetKeyCallback(window_, [](GLFWwindow *w, int key, int, int action, int) {
            if (action == GLFW_PRESS)
                static_cast<Viewer *>(glfwGetWindowUserPointer(w))->taps_.push_back(key);
        });
        glfwSetDropCallback(window_, [](GLFWwindow *w, int count, const char **paths) {
            if (count > 0)
                static_cast<Viewer *>(glfwGetWindowUserPointer(w))->dropped_ = paths[0];
        });
        // Installed after ours, ImGui's callbacks chain to them.
        ImGui_ImplGlfw_InitForOpenGL(window_, true);
        ImGui_ImplOpenGL3_Init("#version 330 core");
        wire_ = options.wire;
    }

    ~Viewer() {
        worker_.reset();
        painter_.reset();
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    Viewer(const Viewer &) = delete;
    Viewer &operator=(const Viewer &) = delete;

    // Opens `path` (replacing the current scene); throws Error naming it.
    void open(const std::string &path) {
        SceneInfo info;
        auto engine = open_scene(path, info, options_.load);
        show(std::move(engine), info);
    }
    // Shows a scene already opened.
    void show(std::unique_ptr<LodEngine> engine, const SceneInfo &info) {
        worker_.reset();
        current_.reset();
        scene_ = info;
        if (scene_.kind == "mesh" && settings_.color == ColorBy::error)
            settings_.color = ColorBy::height;
        worker_ = std::make_unique<LodWorker>(std::move(engine));
        home_view(scene_, control_);
        clearance_ = 0.002 * std::max(scene_.hi.x - scene_.lo.x, scene_.hi.y - scene_.lo.y);
        requested_.reset();
        frozen_.reset();
    }

    void run_interactive();
    void run_script(const CameraPath &path);

  private:
    void swap_in(std::unique_ptr<LodResult> result);
    void draw_scene(const View &view) const;
    void handle_input(double dt);
    void panel(double frame_ms);
    void save_screenshot(const std::string &path);
    // Freezes the LOD at the view of the TIN on screen, or thaws it.
    void toggle_freeze() {
        if (frozen_)
            frozen_.reset();
        else if (current_)
            frozen_ = current_->view;
    }

    const ViewerOptions &options_;
    GLFWwindow *window_;
    std::unique_ptr<MeshPainter> painter_;
    std::unique_ptr<LodWorker> worker_;
    SceneInfo scene_;
    std::unique_ptr<LodResult> current_; // the TIN on the GPU
    RenderOptions uploaded_;             // its colour mode (the scalars live on the GPU)
    LodSettings settings_;
    View base_;
    CameraControl control_;
    PathRecorder recorder_;
    PathPlayer player_;
    std::optional<View> requested_; // the view of the last request
    std::optional<LodSettings> requested_settings_;
    std::optional<View> frozen_; // LOD frozen at this view
    bool wire_ = false;
    bool follow_ = false;
    double clearance_ = 1.0;
    double scroll_ = 0.0;
    std::string dropped_;
    double upload_ms_ = 0.0, fps_ = 0.0;
    std::string message_;
    char open_path_[512] = {};
    char path_file_[512] = "path.csv";
    bool screenshot_due_ = false;
    std::vector<int> taps_; // keys pressed since the last frame
};

void Viewer::swap_in(std::unique_ptr<LodResult> result) {
    Stopwatch clock;
    RenderOptions ro;
    ro.color = color_mode(result->settings.color);
    ro.vertex_scalar = std::move(result->vertex_scalar);
    ro.face_scalar = std::move(result->face_scalar);
    ro.scalar_max = result->scalar_max;
    painter_->upload(result->mesh, ro);
    uploaded_ = RenderOptions{};
    uploaded_.color = ro.color;
    upload_ms_ = clock.ms();
    current_ = std::move(result);
}

void Viewer::draw_scene(const View &view) const {
    RenderOptions ro = uploaded_;
    ro.wire = wire_;
    ro.z_min = float(scene_.lo.z);
    ro.z_max = float(scene_.hi.z);
    if (current_) {
        painter_->draw(view, clip_for(scene_, view), ro);
        return;
    }
    glViewport(0, 0, view.viewport_w, view.viewport_h);
    glClearColor(ro.sky.r, ro.sky.g, ro.sky.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void Viewer::save_screenshot(const std::string &path) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    write_image(path, read_pixels(w, h));
    message_ = "saved " + path;
}

void Viewer::handle_input(double dt) {
    const ImGuiIO &io = ImGui::GetIO();
    auto down = [&](int key) { return glfwGetKey(window_, key) == GLFW_PRESS; };
    // Presses come from the key callback: a tap shorter than a frame still counts.
    auto pressed = [&](int key) {
        return std::find(taps_.begin(), taps_.end(), key) != taps_.end();
    };
    if (!io.WantCaptureKeyboard) {
        MoveKeys keys;
        keys.forward = down(GLFW_KEY_W);
        keys.back = down(GLFW_KEY_S);
        keys.left = down(GLFW_KEY_A);
        keys.right = down(GLFW_KEY_D);
        keys.up = down(GLFW_KEY_E) || down(GLFW_KEY_SPACE);
        keys.down = down(GLFW_KEY_Q) || down(GLFW_KEY_LEFT_CONTROL);
        if (keys.forward || keys.back || keys.left || keys.right || keys.up || keys.down)
            player_.stop();
        control_.update(keys, dt);
        if (pressed(GLFW_KEY_R))
            control_.reset();
        if (pressed(GLFW_KEY_F))
            toggle_freeze();
        if (pressed(GLFW_KEY_O))
            control_.set_mode(control_.mode() == NavMode::fly ? NavMode::orbit : NavMode::fly,
                              current_ ? current_->focal.point : control_.view(base_).at);
        if (pressed(GLFW_KEY_G))
            follow_ = !follow_;
        if (pressed(GLFW_KEY_P) || pressed(GLFW_KEY_F12))
            screenshot_due_ = true;
    }
    taps_.clear();
    if (!io.WantCaptureMouse) {
        const bool look = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                          (control_.mode() == NavMode::orbit &&
                           glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS);
        if (look && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
            player_.stop();
            control_.drag(io.MouseDelta.x, io.MouseDelta.y);
        }
        if (scroll_ != 0.0)
            control_.scroll(scroll_);
    }
    scroll_ = 0.0;
}

void Viewer::run_interactive() {
    double last = glfwGetTime();
    double frame_ms = 16.0;
    while (!glfwWindowShouldClose(window_)) {
        glfwPollEvents();
        const double now = glfwGetTime();
        const double dt = std::min(now - last, 0.25);
        frame_ms = 0.9 * frame_ms + 0.1 * (now - last) * 1000.0;
        fps_ = 1000.0 / std::max(frame_ms, 1e-3);
        last = now;
        if (!dropped_.empty()) {
            const std::string path = std::exchange(dropped_, std::string());
            try {
                open(path);
                message_ = "opened " + path;
            } catch (const std::exception &e) {
                message_ = e.what();
            }
        }
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();

        glfwGetFramebufferSize(window_, &base_.viewport_w, &base_.viewport_h);
        base_.viewport_w = std::max(base_.viewport_w, 1);
        base_.viewport_h = std::max(base_.viewport_h, 1);
        handle_input(dt);
        if (auto v = player_.view(now, base_))
            control_.look_at(v->eye, v->at);
        if (follow_)
            if (const auto ground =
                    current_ ? ground_height(*current_, scene_, control_.eye().x, control_.eye().y)
                             : std::nullopt)
                control_.keep_above(*ground, clearance_);
        const View view = control_.view(base_);
        recorder_.sample(now, view);

        if (worker_) {
            const View lod_view = frozen_ ? *frozen_ : view;
            if (!requested_ || !same_view(*requested_, lod_view) ||
                requested_settings_ != settings_) {
                worker_->request(lod_view, settings_);
                requested_ = lod_view;
                requested_settings_ = settings_;
            }
            if (auto result = worker_->take())
                swap_in(std::move(result));
        }
        draw_scene(view);
        panel(frame_ms);
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (screenshot_due_) {
            screenshot_due_ = false;
            try {
                save_screenshot(timestamp_name("tinlod-view-", ".png"));
            } catch (const std::exception &e) {
                message_ = e.what();
            }
        }
        glfwSwapBuffers(window_);
    }
}

void Viewer::panel(double frame_ms) {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSizeConstraints(ImVec2(300, 100),
                                        ImVec2(600, ImGui::GetIO().DisplaySize.y - 20));
    ImGui::Begin("tinlod-view", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    if (ImGui::CollapsingHeader("Stats", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (current_) {
            ImGui::Text("nodes %lld   triangles %lld", static_cast<long long>(current_->nodes),
                        static_cast<long long>(current_->triangles));
            ImGui::Text("retrieve %.1f ms  erase %.1f ms  colour %.1f ms", current_->retrieve_ms,
                        current_->erase_ms, current_->color_ms);
            ImGui::Text("worker %.1f ms  upload %.1f ms", current_->total_ms, upload_ms_);
            if (current_->settings.stages == LodStages::retrieve_erase)
                ImGui::Text("erase bound reached %.2f px", current_->erase_max_px);
            else if (current_->settings.stages == LodStages::refine)
                ImGui::Text("refiner: every deviation <= %.2f px", current_->settings.tol_px);
            else if (scene_.kind != "mesh")
                ImGui::Text("retrieval bound %.2f px", current_->bound_px);
        }
        ImGui::Text("%.0f FPS (%.1f ms/frame)   peak memory %.0f MiB", fps_, frame_ms,
                    peak_rss_mb());
        if (worker_ && worker_->busy())
            ImGui::TextDisabled("computing the next TIN...");
        if (worker_)
            if (const std::string e = worker_->error(); !e.empty())
                ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%s", e.c_str());
    }

    if (ImGui::CollapsingHeader("File", scene_.path.empty() ? ImGuiTreeNodeFlags_DefaultOpen : 0)) {
        if (scene_.path.empty())
            ImGui::TextUnformatted("no file: drop a DEM, store or mesh here");
        else
            ImGui::TextWrapped("%s (%s, %lld nodes)", scene_.path.c_str(), scene_.kind.c_str(),
                               static_cast<long long>(scene_.input_nodes));
        ImGui::InputText("##open", open_path_, sizeof open_path_);
        ImGui::SameLine();
        if (ImGui::Button("Open"))
            dropped_ = open_path_;
    }

    if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) {
        int mode = control_.mode() == NavMode::orbit ? 1 : 0;
        const glm::dvec3 pivot = current_ ? current_->focal.point : control_.view(base_).at;
        if (ImGui::RadioButton("fly", &mode, 0))
            control_.set_mode(NavMode::fly, pivot);
        ImGui::SameLine();
        if (ImGui::RadioButton("orbit (O)", &mode, 1))
            control_.set_mode(NavMode::orbit, pivot);
        ImGui::SameLine();
        if (ImGui::Button("reset (R)"))
            control_.reset();
        const glm::dvec3 e = control_.eye();
        ImGui::Text("eye    %.1f, %.1f, %.1f", e.x, e.y, e.z);
        if (current_)
            ImGui::Text("focal  %.1f, %.1f, %.1f%s", current_->focal.point.x,
                        current_->focal.point.y, current_->focal.point.z,
                        current_->focal.hit ? "" : " (axis misses the surface)");
        float speed = float(control_.speed());
        if (ImGui::DragFloat("speed (wheel)", &speed, speed * 0.01f, 1e-3f, 1e9f, "%.1f /s"))
            control_.set_speed(speed);
        ImGui::Checkbox("follow terrain (G)", &follow_);
        ImGui::SameLine();
        float clearance = float(clearance_);
        ImGui::SetNextItemWidth(90);
        if (ImGui::DragFloat("clearance", &clearance, 1.0f, 0.0f, 1e7f, "%.0f"))
            clearance_ = clearance;
        ImGui::TextDisabled("W/S/A/D move, E/Q up/down, right drag: look");
    }

    if (ImGui::CollapsingHeader("Level of detail", ImGuiTreeNodeFlags_DefaultOpen)) {
        float tol = float(settings_.tol_px);
        if (ImGui::SliderFloat("tau (px)", &tol, 0.25f, 64.0f, "%.2f",
                               ImGuiSliderFlags_Logarithmic))
            settings_.tol_px = tol;
        int stages = int(settings_.stages);
        const bool grid = scene_.kind != "mesh";
        if (ImGui::RadioButton(grid ? "retrieval" : "whole mesh", &stages, 0))
            settings_.stages = LodStages::retrieve;
        ImGui::SameLine();
        if (ImGui::RadioButton("+ erase", &stages, 1))
            settings_.stages = LodStages::retrieve_erase;
        if (grid) {
            ImGui::SameLine();
            if (ImGui::RadioButton("+ recovery", &stages, 2))
                settings_.stages = LodStages::refine;
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("one TIN kept between frames: nodes erased and recovered");
        }
        if (grid)
            ImGui::Checkbox("cull outside the frustum", &settings_.cull);
        int model = settings_.model == SpModel::paper ? 1 : 0;
        if (ImGui::Combo("SP model", &model, "screen\0paper\0"))
            settings_.model = model == 1 ? SpModel::paper : SpModel::screen;
        SignificanceOptions &sp = settings_.significance;
        auto slider = [](const char *label, double &value, float lo, float hi) {
            float v = float(value);
            if (ImGui::SliderFloat(label, &v, lo, hi, "%.2f"))
                value = v;
        };
        if (settings_.model == SpModel::paper) {
            slider("w distance", sp.w_distance, 0.0f, 4.0f);
            slider("w angle", sp.w_angle, 0.0f, 4.0f);
            slider("w ration", sp.w_ration, 0.0f, 4.0f);
        } else {
            slider("falloff (deg)", sp.falloff_deg, 1.0f, 90.0f);
            slider("floor", sp.floor, 0.0f, 1.0f);
        }
        bool frozen = frozen_.has_value();
        if (ImGui::Checkbox("freeze LOD (F)", &frozen))
            toggle_freeze();
    }

    if (ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::Checkbox("wireframe", &wire_);
        int color = static_cast<int>(settings_.color);
        const char *names = scene_.error_colors ? "shade\0height\0SP\0level\0error (px)\0"
                                                : "shade\0height\0SP\0level\0";
        if (ImGui::Combo("colour", &color, names))
            settings_.color = static_cast<ColorBy>(color);
        if (current_) {
            const float lo = current_->scalar_min, hi = lo + current_->scalar_max;
            switch (current_->settings.color) {
            case ColorBy::sp:
                ImGui::TextDisabled("blue 0 .. red %.3g (SP, 95th percentile)", hi);
                break;
            case ColorBy::level:
                ImGui::TextDisabled("blue level %.0f .. red level %.0f", lo, hi);
                break;
            case ColorBy::error:
                ImGui::TextDisabled("blue 0 .. red %.3g px (face error vs the DEM)", hi);
                break;
            case ColorBy::shade:
            case ColorBy::height:
                break;
            }
        }
        if (ImGui::Button("screenshot (P)"))
            screenshot_due_ = true;
    }

    if (ImGui::CollapsingHeader("Camera path")) {
        ImGui::InputText("CSV", path_file_, sizeof path_file_);
        const double now = glfwGetTime();
        if (!recorder_.recording()) {
            if (ImGui::Button("record"))
                recorder_.start(now);
        } else if (ImGui::Button("stop and save")) {
            try {
                const CameraPath path = recorder_.stop(now, control_.view(base_));
                write_camera_path(path, path_file_);
                message_ =
                    "saved " + std::to_string(path.keys.size()) + " keyframes to " + path_file_;
            } catch (const std::exception &e) {
                message_ = e.what();
            }
        }
        ImGui::SameLine();
        if (!player_.playing()) {
            if (ImGui::Button("play")) {
                try {
                    player_.start(read_camera_path(path_file_), now);
                } catch (const std::exception &e) {
                    message_ = e.what();
                }
            }
        } else if (ImGui::Button("stop playing")) {
            player_.stop();
        }
        if (recorder_.recording())
            ImGui::Text("recording: %zu keyframes", recorder_.path().keys.size());
    }

    if (!message_.empty())
        ImGui::TextWrapped("%s", message_.c_str());
    ImGui::End();
}

void Viewer::run_script(const CameraPath &path) {
    const int frames = options_.frames > 0 ? options_.frames : static_cast<int>(path.keys.size());
    Framebuffer target(options_.width, options_.height);
    std::ostringstream stats;
    stats << "frame,t,nodes,triangles,retrieve_ms,erase_ms,worker_ms,upload_ms,draw_ms\n";
    for (int i = 0; i < frames; ++i) {
        const double t = frames == 1 ? path.keys.front().t
                                     : path.keys.front().t + path.duration() * i / (frames - 1);
        const View view = path.at_time(t, base_);
        validate(view, options_.script);
        const std::uint64_t serial = worker_->request(view, settings_);
        auto result = worker_->wait(serial);
        if (!result)
            throw Error(scene_.path, worker_->error());
        stats << i << ',' << t << ',' << result->nodes << ',' << result->triangles << ','
              << result->retrieve_ms << ',' << result->erase_ms << ',' << result->total_ms << ',';
        swap_in(std::move(result));
        target.bind();
        Stopwatch clock;
        draw_scene(view);
        glFinish();
        const double draw_ms = clock.ms();
        stats << upload_ms_ << ',' << draw_ms << '\n';
        if (options_.ui) {
            // The panel shows the drawing rate: a scripted frame waits for its TIN.
            fps_ = 1000.0 / std::max(draw_ms, 1e-3);
            control_.look_at(view.eye, view.at);
            ImGui_ImplOpenGL3_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            ImGui::NewFrame();
            if (i == 0) {
                // ImGui sizes an auto-resizing window on its first frame and shows it from the
                // second: lay the panel out once before the first picture.
                panel(draw_ms);
                ImGui::EndFrame();
                ImGui_ImplOpenGL3_NewFrame();
                ImGui_ImplGlfw_NewFrame();
                ImGui::NewFrame();
            }
            panel(draw_ms);
            ImGui::Render();
            ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        }
    }
    write_image(options_.screenshot, read_pixels(options_.width, options_.height));
    if (!options_.stats.empty())
        write_atomically(options_.stats, [&](const std::string &tmp) {
            std::ofstream out(tmp);
            out << stats.str();
            if (!out.flush())
                throw Error(options_.stats, "cannot write");
        });
}

} // namespace

void run_viewer(const ViewerOptions &options) {
    // Files first, so a bad file is reported as such even where no window can open.
    SceneInfo info;
    std::unique_ptr<LodEngine> engine;
    if (!options.input.empty())
        engine = open_scene(options.input, info, options.load);
    std::optional<CameraPath> path;
    if (!options.script.empty())
        path = read_camera_path(options.script);

    GlfwSession glfw;
    GLFWwindow *window = open_window(options.width, options.height, !path);
    struct Closer {
        GLFWwindow *w;
        ~Closer() { glfwDestroyWindow(w); }
    } closer{window};
    glfwSwapInterval(1);
    Viewer viewer(options, window);
    if (engine)
        viewer.show(std::move(engine), info);
    if (path)
        viewer.run_script(*path);
    else
        viewer.run_interactive();
}

} // namespace tinlod::viewer
