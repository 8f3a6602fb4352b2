// sparkle_stats METHOD.exr SMOOTH.exr [THRESHOLD]: statistics of D / D_smooth over the highlight from two
// `glimmer render --aov glint --env none` EXRs of the same view (engine/bench/sparkle_stats.h). One JSON line.
// tools/sparkle_stats.sh renders the EXRs and runs it for the methods and scenes of the docs' tables.
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "bench/sparkle_stats.h"

static bool readFirstChannel(const std::string& path, std::vector<float>& values, int& w, int& h) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        std::fprintf(stderr, "sparkle_stats: %s: cannot open (%s)\n", path.c_str(), OIIO::geterror().c_str());
        return false;
    }
    const OIIO::ImageSpec& spec = in->spec();
    w = spec.width;
    h = spec.height;
    std::vector<float> all(size_t(w) * h * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data())) {
        std::fprintf(stderr, "sparkle_stats: %s: cannot read pixels (%s)\n", path.c_str(), in->geterror().c_str());
        return false;
    }
    values.resize(size_t(w) * h);
    for (size_t i = 0; i < values.size(); ++i) values[i] = all[i * spec.nchannels];
    return true;
}

int main(int argc, char** argv) {
    if (argc < 3 || argc > 4) {
        std::fprintf(stderr, "usage: sparkle_stats METHOD.exr SMOOTH.exr [THRESHOLD (default 0.1)]\n");
        return 2;
    }
    std::vector<float> glint, smooth;
    int w0, h0, w1, h1;
    if (!readFirstChannel(argv[1], glint, w0, h0) || !readFirstChannel(argv[2], smooth, w1, h1)) return 1;
    if (w0 != w1 || h0 != h1) {
        std::fprintf(stderr, "sparkle_stats: %s and %s differ in size\n", argv[1], argv[2]);
        return 1;
    }
    double threshold = 0.1;
    if (argc == 4) {
        char* end = nullptr;
        threshold = std::strtod(argv[3], &end);
        if (*end != '\0' || !(threshold > 0.0 && threshold <= 1.0)) {
            std::fprintf(stderr, "sparkle_stats: THRESHOLD '%s' must be a number in (0, 1]\n", argv[3]);
            return 2;
        }
    }
    glimmer::SparkleStats s = glimmer::sparkleStats(glint, smooth, threshold);
    std::printf("{\"pixels\": %zu, \"mean_ratio\": %.4f, \"cv\": %.4f, \"p999_over_mean\": %.3f, "
                "\"zero_fraction\": %.4f}\n",
                s.pixels, s.meanRatio, s.cv, s.p999OverMean, s.zeroFraction);
    return 0;
}
