// The interactive viewer window (GLFW + OpenGL 3.3 core + Dear ImGui) and its scripted mode.
#pragma once

#include "lod_worker.hpp"

#include <string>

namespace tinlod::viewer {

struct ViewerOptions {
    std::string input;      // file to open at start (may be empty in interactive mode)
    std::string script;     // scripted mode: camera path CSV to play
    std::string screenshot; // scripted mode: PNG written after the last frame
    std::string stats;      // scripted mode (optional): per-frame CSV t,nodes,triangles,...
    int frames = 0;         // scripted mode: frames over the path; 0: one per keyframe
    int width = 1280;       // window (and screenshot) size, pixels
    int height = 720;
    double fov_deg = 60.0;
    bool wire = false;
    bool ui = false; // scripted mode: draw the panel into the screenshot too
    LodSettings lod;
    LoadOptions load; // how DEMs are read (cell size, height scale, Terrain-RGB)
};

// Opens the window and runs until it is closed (interactive) or the path has played (scripted).
// Throws Error naming the display, OpenGL or the file at fault.
void run_viewer(const ViewerOptions &options);

} // namespace tinlod::viewer
