// The colour legend of the scalar renders (render.hpp draw_legend): a bar along the colour map
// with its two ends labelled and a title giving the quantity and its units, painted into the
// image on the CPU in a built-in 5x7 bitmap font (enough for numbers and lowercase labels).
#include "tinlod/render.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace tinlod {

namespace {

// One glyph per character of k_glyph_chars: 7 rows of 5 pixels, the leftmost in bit 4.
constexpr char k_glyph_chars[] = " %()+,-./0123456789:=>abcdefghijklmnopqrstuvwxyz";
constexpr std::uint8_t k_glyph_rows[][7] = {
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, //
    {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}, // %
    {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}, // (
    {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}, // )
    {0x00, 0x04, 0x04, 0x1f, 0x04, 0x04, 0x00}, // +
    {0x00, 0x00, 0x00, 0x00, 0x0c, 0x04, 0x08}, // ,
    {0x00, 0x00, 0x00, 0x1f, 0x00, 0x00, 0x00}, // -
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c}, // .
    {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}, // /
    {0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e}, // 0
    {0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e}, // 1
    {0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f}, // 2
    {0x1f, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0e}, // 3
    {0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02}, // 4
    {0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e}, // 5
    {0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e}, // 6
    {0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}, // 7
    {0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e}, // 8
    {0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c}, // 9
    {0x00, 0x0c, 0x0c, 0x00, 0x0c, 0x0c, 0x00}, // :
    {0x00, 0x00, 0x1f, 0x00, 0x1f, 0x00, 0x00}, // =
    {0x10, 0x08, 0x04, 0x02, 0x04, 0x08, 0x10}, // >
    {0x00, 0x00, 0x0e, 0x01, 0x0f, 0x11, 0x0f}, // a
    {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x1e}, // b
    {0x00, 0x00, 0x0e, 0x10, 0x10, 0x11, 0x0e}, // c
    {0x01, 0x01, 0x0d, 0x13, 0x11, 0x11, 0x0f}, // d
    {0x00, 0x00, 0x0e, 0x11, 0x1f, 0x10, 0x0e}, // e
    {0x06, 0x09, 0x08, 0x1c, 0x08, 0x08, 0x08}, // f
    {0x00, 0x0f, 0x11, 0x11, 0x0f, 0x01, 0x0e}, // g
    {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11}, // h
    {0x04, 0x00, 0x0c, 0x04, 0x04, 0x04, 0x0e}, // i
    {0x02, 0x00, 0x06, 0x02, 0x02, 0x12, 0x0c}, // j
    {0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12}, // k
    {0x0c, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0e}, // l
    {0x00, 0x00, 0x1a, 0x15, 0x15, 0x11, 0x11}, // m
    {0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11}, // n
    {0x00, 0x00, 0x0e, 0x11, 0x11, 0x11, 0x0e}, // o
    {0x00, 0x00, 0x1e, 0x11, 0x1e, 0x10, 0x10}, // p
    {0x00, 0x00, 0x0d, 0x13, 0x0f, 0x01, 0x01}, // q
    {0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10}, // r
    {0x00, 0x00, 0x0e, 0x10, 0x0e, 0x01, 0x1e}, // s
    {0x08, 0x08, 0x1c, 0x08, 0x08, 0x09, 0x06}, // t
    {0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0d}, // u
    {0x00, 0x00, 0x11, 0x11, 0x11, 0x0a, 0x04}, // v
    {0x00, 0x00, 0x11, 0x11, 0x15, 0x15, 0x0a}, // w
    {0x00, 0x00, 0x11, 0x0a, 0x04, 0x0a, 0x11}, // x
    {0x00, 0x00, 0x11, 0x11, 0x0f, 0x01, 0x0e}, // y
    {0x00, 0x00, 0x1f, 0x02, 0x04, 0x08, 0x1f}, // z
};

constexpr int k_glyph_w = 5, k_glyph_h = 7, k_advance = 6;

struct Rgb {
    float r, g, b;
};

// Blends `c` with opacity `alpha` over the pixel (x, y), which may lie outside the image.
void blend(Image &image, int x, int y, Rgb c, float alpha = 1.0f) {
    if (x < 0 || y < 0 || x >= image.width || y >= image.height)
        return;
    std::uint8_t *p = &image.rgba[4 * (std::size_t(y) * std::size_t(image.width) + std::size_t(x))];
    const float rgb[3] = {c.r, c.g, c.b};
    for (int k = 0; k < 3; ++k) {
        const float v = alpha * std::clamp(rgb[k], 0.0f, 1.0f) * 255.0f + (1.0f - alpha) * p[k];
        p[k] = std::uint8_t(std::lround(v));
    }
    p[3] = 255;
}

void fill(Image &image, int x0, int y0, int w, int h, Rgb c, float alpha = 1.0f) {
    for (int y = y0; y < y0 + h; ++y)
        for (int x = x0; x < x0 + w; ++x)
            blend(image, x, y, c, alpha);
}

int text_width(const std::string &text, int scale) {
    return text.empty() ? 0 : (int(text.size()) * k_advance - 1) * scale;
}

// Draws `text` with its top-left corner at (x, y), each font pixel `scale` image pixels wide. A
// character the font lacks is drawn as a filled box, so it shows rather than vanishes.
void draw_text(Image &image, const std::string &text, int x, int y, int scale, Rgb c) {
    for (unsigned char ch : text) {
        const char *at = std::strchr(k_glyph_chars, std::tolower(ch));
        for (int row = 0; row < k_glyph_h; ++row)
            for (int col = 0; col < k_glyph_w; ++col) {
                const bool on =
                    at && *at ? (k_glyph_rows[at - k_glyph_chars][row] >> (k_glyph_w - 1 - col)) & 1
                              : true;
                if (on)
                    fill(image, x + col * scale, y + row * scale, scale, scale, c);
            }
        x += k_advance * scale;
    }
}

std::string label(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", double(value));
    return text;
}

} // namespace

void draw_legend(Image &image, float top, const std::string &title) {
    // Sizes in font pixels, scaled with the image height so the legend reads at any size.
    const int s = std::max(1, image.height / 400);
    const int margin = 8 * s, pad = 4 * s, gap = 4 * s, bar_w = 10 * s;
    const int bar_h = image.height / 4;
    const std::string top_label = label(top), bottom_label = "0";
    const int labels_w = std::max(text_width(top_label, s), text_width(bottom_label, s));
    const int panel_w = 2 * pad + std::max(text_width(title, s), bar_w + gap + labels_w);
    // Title, a gap, then the bar, whose end labels stand half a line above and below it.
    const int bar_top = pad + k_glyph_h * s + 2 * gap + k_glyph_h * s / 2;
    const int panel_h = bar_top + bar_h + k_glyph_h * s / 2 + pad;
    if (bar_h < 24 || panel_w + 2 * margin > image.width || panel_h + 2 * margin > image.height)
        return;
    const int x0 = image.width - margin - panel_w, y0 = margin;
    const Rgb ink{0.1f, 0.1f, 0.1f};
    fill(image, x0, y0, panel_w, panel_h, {1.0f, 1.0f, 1.0f}, 0.8f);
    draw_text(image, title, x0 + pad, y0 + pad, s, ink);
    const int bx = x0 + pad, by = y0 + bar_top;
    fill(image, bx - s, by - s, bar_w + 2 * s, bar_h + 2 * s, ink); // frame
    for (int r = 0; r < bar_h; ++r) {
        // Row r shows the map at its centre: the top row near `top`, the bottom row near 0.
        const glm::vec3 c = turbo(1.0f - (float(r) + 0.5f) / float(bar_h));
        fill(image, bx, by + r, bar_w, 1, {c.r, c.g, c.b});
    }
    const int lx = bx + bar_w + gap;
    draw_text(image, top_label, lx, by - k_glyph_h * s / 2, s, ink);
    draw_text(image, bottom_label, lx, by + bar_h - 1 - k_glyph_h * s / 2, s, ink);
}

} // namespace tinlod
