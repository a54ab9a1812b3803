// Camera path CSV in and out, and sampling a path into per-frame views.
#include "tinlod/camera_path.hpp"
#include "tinlod/error.hpp"
#include "tinlod/util.hpp"

#include <cassert>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace tinlod {

static const char *k_header = "t,eye_x,eye_y,eye_z,at_x,at_y,at_z";

static std::string trim(const std::string &s) {
    const auto b = s.find_first_not_of(" \t\r");
    const auto e = s.find_last_not_of(" \t\r");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

CameraPath parse_camera_path(const std::string &text, const std::string &source) {
    CameraPath path;
    std::istringstream in(text);
    std::string line;
    int number = 0;
    bool header = false;
    while (std::getline(in, line)) {
        ++number;
        line = trim(line);
        if (line.empty() || line[0] == '#')
            continue;
        const std::string where = "line " + std::to_string(number);
        if (!header) {
            std::string compact;
            for (char c : line)
                if (c != ' ' && c != '\t')
                    compact += c;
            if (compact != k_header)
                throw Error(source, where + ": expected the header '" + k_header + "'");
            header = true;
            continue;
        }
        double v[7];
        std::size_t pos = 0;
        for (int i = 0; i < 7; ++i) {
            const auto comma = line.find(',', pos);
            if ((i < 6) != (comma != std::string::npos))
                throw Error(source, where + ": expected 7 comma-separated numbers");
            const std::string field = trim(
                line.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos));
            char *end = nullptr;
            errno = 0;
            v[i] = std::strtod(field.c_str(), &end);
            if (field.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v[i]))
                throw Error(source, where + ": '" + field + "' is not a finite number");
            pos = comma + 1;
        }
        Keyframe k{v[0], {v[1], v[2], v[3]}, {v[4], v[5], v[6]}};
        if (!path.keys.empty() && !(k.t > path.keys.back().t))
            throw Error(source, where + ": t must increase from one line to the next");
        if (k.eye == k.at)
            throw Error(source, where + ": eye and look-at point coincide");
        path.keys.push_back(k);
    }
    if (!header)
        throw Error(source,
                    "empty camera path (expected the header '" + std::string(k_header) + "')");
    if (path.keys.empty())
        throw Error(source, "camera path has no keyframe");
    return path;
}

CameraPath read_camera_path(const std::string &file) {
    std::ifstream in(file, std::ios::binary);
    if (!in)
        throw Error(file, "cannot open camera path");
    std::ostringstream text;
    text << in.rdbuf();
    if (text.str().size() > (std::size_t(64) << 20))
        throw Error(file, "camera path larger than 64 MiB");
    return parse_camera_path(text.str(), file);
}

void write_camera_path(const CameraPath &path, const std::string &file) {
    write_atomically(file, [&](const std::string &tmp) {
        std::ofstream out(tmp);
        out.precision(17);
        out << k_header << '\n';
        for (const auto &k : path.keys)
            out << k.t << ',' << k.eye.x << ',' << k.eye.y << ',' << k.eye.z << ',' << k.at.x << ','
                << k.at.y << ',' << k.at.z << '\n';
        if (!out.flush())
            throw Error(file, "cannot write camera path: " + std::string(std::strerror(errno)));
    });
}

View CameraPath::at_time(double t, const View &base) const {
    assert(!keys.empty());
    View v = base;
    if (t <= keys.front().t || keys.size() == 1) {
        v.eye = keys.front().eye;
        v.at = keys.front().at;
        return v;
    }
    if (t >= keys.back().t) {
        v.eye = keys.back().eye;
        v.at = keys.back().at;
        return v;
    }
    std::size_t i = 1;
    while (keys[i].t < t)
        ++i;
    const Keyframe &a = keys[i - 1];
    const Keyframe &b = keys[i];
    const double s = (t - a.t) / (b.t - a.t);
    v.eye = glm::mix(a.eye, b.eye, s);
    v.at = glm::mix(a.at, b.at, s);
    return v;
}

std::vector<View> CameraPath::sample(int frames, const View &base) const {
    assert(frames >= 1 && !keys.empty());
    std::vector<View> views;
    views.reserve(std::size_t(frames));
    for (int i = 0; i < frames; ++i) {
        const double t =
            frames == 1 ? keys.front().t : keys.front().t + duration() * i / (frames - 1);
        views.push_back(at_time(t, base));
    }
    return views;
}

} // namespace tinlod
