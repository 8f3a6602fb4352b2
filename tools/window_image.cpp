// window_image: measures the image the window shows (engine/bench/window_image.h), for docs/window.md.
//   window_image still  [--scene S] [--camera C] [--size WxH] [--scale F] [--method M] [--frames N] [--set K=V ...]
//       frames N and N+8 of a still camera with the window's software defaults: how many glinty pixels change
//   window_image glints [same options]
//       glint pixels (HDR above 2x the smooth render) at --scale F and at scale 1, for every built-in method
// Prints one JSON line per measurement.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/window_image.h"
#include "core/clock.h"
#include "core/image_io.h"
#include "glints/methods.h"
#include "offscreen/offscreen.h"
#include "ui/window_defaults.h"

using namespace glimmer;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: window_image still|glints [--scene S] [--camera C] [--size WxH] [--scale F] "
                             "[--method M] [--frames N] [--set K=V ...] [--save PREFIX]\n");
        return 2;
    }
    std::string mode = argv[1];
    RenderRequest request;
    request.scene = "atrium";
    request.camera = "objects";
    request.width = 640;
    request.height = 360;
    request.settings.method = "deliot2023";
    float scale = 0.25f;
    int frames = 24;
    std::string save;
    std::vector<std::string> sets;
    for (int i = 2; i + 1 < argc; i += 2) {
        std::string flag = argv[i], value = argv[i + 1];
        if (flag == "--scene") request.scene = value;
        else if (flag == "--camera") request.camera = value;
        else if (flag == "--size") std::sscanf(value.c_str(), "%dx%d", &request.width, &request.height);
        else if (flag == "--scale") scale = std::strtof(value.c_str(), nullptr);
        else if (flag == "--method") request.settings.method = value;
        else if (flag == "--frames") frames = std::atoi(value.c_str());
        else if (flag == "--set") sets.push_back(value);
        else if (flag == "--save") save = value;
        else { std::fprintf(stderr, "window_image: unknown flag %s\n", flag.c_str()); return 2; }
    }
    for (const std::string& s : sets) request.settings.apply(s);
    ui::applyWindowDefaults(request.settings, true);
    request.renderScale = scale;
    OffscreenSession session(request);
    std::vector<uint8_t> mask = glintyPixelMask(session, request);
    size_t glinty = 0;
    for (uint8_t m : mask) glinty += m;

    if (mode == "still") {
        request.frames = frames;
        Stopwatch clock;
        RenderResult a = session.render(request);
        double ms = clock.elapsedMs() / frames;
        request.frames = 8;
        RenderResult b = session.render(request);
        StillImageChange hdr = stillImageChange(a.hdr, b.hdr, mask, 1e-3f);
        StillImageChange display = stillImageChange(a.display, b.display, mask);
        if (!save.empty()) {
            writePng(save + "_a.png", a.display.data(), a.width, a.height);
            writePng(save + "_b.png", b.display.data(), b.width, b.height);
            // Changed glinty pixels in red (> 10%) and yellow (> 2%) over a dimmed frame.
            std::vector<uint8_t> diff = b.display;
            for (size_t i = 0; i < mask.size(); ++i) {
                for (int c = 0; c < 3; ++c) diff[i * 4 + c] /= 3;
                if (!mask[i]) continue;
                double la = pixelLuminance(a.hdr, i), lb = pixelLuminance(b.hdr, i);
                double r = std::abs(la - lb) / std::max({la, lb, 1e-3});
                if (r > 0.02) diff[i * 4] = 255, diff[i * 4 + 1] = r > 0.1 ? 0 : 255, diff[i * 4 + 2] = 0;
            }
            writePng(save + "_diff.png", diff.data(), b.width, b.height);
        }
        nlohmann::json out = {{"method", request.settings.method}, {"scale", scale}, {"frames", frames},
                              {"glinty_pixels", glinty}, {"ms_per_frame", ms},
                              {"hdr", {{"above2", hdr.above2}, {"above10", hdr.above10}, {"max", hdr.maxRelative}}},
                              {"display", {{"above2", display.above2}, {"above10", display.above10}, {"max", display.maxRelative}}}};
        std::printf("%s\n", out.dump().c_str());
        return 0;
    }
    if (mode == "glints") {
        request.frames = frames;
        RenderRequest smooth = request;
        smooth.settings.method = "smooth";
        auto count = [&](RenderRequest r, float s) {
            r.renderScale = s;
            RenderRequest sm = smooth;
            sm.renderScale = s;
            RenderResult image = session.render(r);
            RenderResult base = session.render(sm);
            if (!save.empty())
                writePng(save + "_" + r.settings.method + "_" + std::to_string(s) + ".png", image.display.data(),
                         image.width, image.height);
            return glintPixelCount(image.hdr, base.hdr, mask);
        };
        size_t atScale = count(request, scale), atOne = count(request, 1.0f);
        nlohmann::json out = {{"method", request.settings.method}, {"scale", scale}, {"glinty_pixels", glinty},
                              {"glint_pixels_at_scale", atScale}, {"glint_pixels_at_1", atOne},
                              {"ratio", atOne ? double(atScale) / double(atOne) : 0.0}};
        std::printf("%s\n", out.dump().c_str());
        return 0;
    }
    std::fprintf(stderr, "window_image: unknown mode %s\n", mode.c_str());
    return 2;
}
