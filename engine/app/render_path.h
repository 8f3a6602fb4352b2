// `glimmer render --path FILE`: a frame sequence along a recorded camera path (ui/recorded_path.h) at a fixed
// time step, so the same path gives the same images on every run; `--video FILE.mp4` encodes them with the
// ffmpeg program.
#pragma once
#include <optional>
#include <string>

#include "offscreen/offscreen.h"

namespace glimmer {

struct PathRenderOptions {
    std::string pathFile;
    std::optional<int> frames;          // default: the whole path at `fps`
    double fps = 30.0;
    std::optional<std::string> outPattern;  // printf pattern with one integer field, e.g. frames/%04d.png
    std::optional<std::string> video;       // .mp4 / .webm / .gif, encoded by ffmpeg
};

// The frame file for frame `index` of `pattern` (one %d / %0Nd field; throws UsageError for anything else).
std::string framePath(const std::string& pattern, int index);
// The scene a camera path file names ("scene"); throws UsageError naming the file when it names none.
std::string sceneOfPathFile(const std::string& pathFile);
// Checks the options, and that ffmpeg is installed when a video alone is asked for (before any rendering; with
// --out the frames are rendered and the missing ffmpeg is reported at the end).
void checkPathRenderOptions(const PathRenderOptions& options);
int renderPathSequence(RenderRequest request, const PathRenderOptions& options);

}  // namespace glimmer
