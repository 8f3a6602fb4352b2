#include "app/render_path.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/log.h"
#include "ui/recorded_path.h"

namespace glimmer {
namespace fs = std::filesystem;

std::string framePath(const std::string& pattern, int index) {
    // Exactly one '%', starting a field %d or %0Nd with at most two width digits (read by hand: a regular
    // expression recursing per digit overflowed the stack on long arguments).
    auto bad = [&] { return UsageError("--out: '" + pattern.substr(0, 200) + "' needs exactly one frame-number field such as %04d"); };
    size_t percent = pattern.find('%');
    if (percent == std::string::npos || pattern.find('%', percent + 1) != std::string::npos) throw bad();
    size_t at = percent + 1;
    while (at < pattern.size() && at - percent <= 3 && pattern[at] >= '0' && pattern[at] <= '9') ++at;
    if (at >= pattern.size() || pattern[at] != 'd') throw bad();
    if (pattern.size() > 4000) throw UsageError("--out: the pattern is longer than 4000 characters");
    char text[4096];
    std::snprintf(text, sizeof text, pattern.c_str(), index);
    return text;
}

// The program's full path when it is on PATH, else "".
static std::string findProgram(const std::string& name) {
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "";
    size_t start = 0;
    while (start <= dirs.size()) {
        size_t end = dirs.find(':', start);
        std::string dir = dirs.substr(start, end == std::string::npos ? std::string::npos : end - start);
        fs::path candidate = fs::path(dir.empty() ? "." : dir) / name;
        if (::access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate)) return candidate.string();
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return "";
}

void checkPathRenderOptions(const PathRenderOptions& options) {
    if (!(options.fps > 0.0 && options.fps <= 1000.0)) throw UsageError("--fps: expected a rate in (0, 1000]");
    if (!options.outPattern && !options.video) throw UsageError("render --path: --out DIR/%04d.png or --video FILE is required");
    if (options.outPattern) {
        std::string first = framePath(*options.outPattern, 0);
        if (imageFormatForPath(first, "--out") != ImageFormat::Png && options.video)
            throw UsageError("--video: frames must be .png (--out)");
        createOutputFolder(first, "--out");
        fs::path parent = fs::absolute(first).parent_path();
        if (!fs::is_directory(parent)) throw Error("--out: directory " + parent.string() + " does not exist");
    }
    if (options.video) {
        if (findProgram("ffmpeg").empty()) {
            if (!options.outPattern)
                throw Error("--video: the ffmpeg program is not installed (Debian: apt-get install ffmpeg)");
            log::warn("--video: the ffmpeg program is not installed: writing the --out frames only");
        }
        createOutputFolder(*options.video, "--video");
        fs::path parent = fs::absolute(*options.video).parent_path();
        if (!fs::is_directory(parent)) throw Error("--video: directory " + parent.string() + " does not exist");
    }
}

static void encodeVideo(const std::string& pattern, double fps, const std::string& video) {
    std::string ffmpeg = findProgram("ffmpeg");
    std::string rate = std::to_string(fps);
    std::vector<std::string> args = {ffmpeg, "-y", "-loglevel", "error", "-framerate", rate, "-i", pattern};
    std::string extension = fs::path(video).extension().string();
    // H.264 in yuv420p plays everywhere (needs even sizes: pad by one pixel when odd); GIF and WebM as ffmpeg's
    // defaults for the extension.
    if (extension == ".mp4" || extension == ".mkv" || extension == ".mov")
        args.insert(args.end(), {"-c:v", "libx264", "-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"});
    args.push_back(video);
    pid_t pid = fork();
    if (pid < 0) throw Error("--video: cannot start ffmpeg");
    if (pid == 0) {
        std::vector<char*> argv;
        for (std::string& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        execv(ffmpeg.c_str(), argv.data());
        _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw Error("--video: ffmpeg failed writing " + video);
}

// The most frames one path render may produce (as --frames): 9 hours at 30 fps.
constexpr double kMaxPathFrames = 1e6;

// A private folder for frames that only feed the video: mkdtemp makes it with a name nobody can predict and mode
// 0700, so another user cannot plant files or links in it.
static fs::path makeFramesFolder() {
    std::string name = (fs::temp_directory_path() / "glimmer-frames-XXXXXX").string();
    if (!::mkdtemp(name.data())) throw Error("--video: cannot create a folder for the frames in " + fs::temp_directory_path().string());
    return name;
}

std::string sceneOfPathFile(const std::string& pathFile) {
    ui::RecordedPath path = ui::RecordedPath::load(pathFile);
    if (path.sceneName.empty())
        throw UsageError("--path: " + pathFile + " names no scene: give --scene NAME");
    return path.sceneName;
}

int renderPathSequence(RenderRequest request, const PathRenderOptions& options) {
    ui::RecordedPath path = ui::RecordedPath::load(options.pathFile);
    // The derived count in double first: a long path at a high rate must be refused, not converted to int
    // (1e300 s gave "-2147483647 frames").
    const double wholePath = std::floor(path.duration() * options.fps + 1e-9) + 1.0;
    if (!options.frames && !(wholePath <= kMaxPathFrames)) {
        char text[256];
        std::snprintf(text, sizeof text, ": the path lasts %g s: %.0f frames at %g fps exceed the limit of %.0f (--frames N renders the first N)",
                      path.duration(), wholePath, options.fps, kMaxPathFrames);
        throw Error(options.pathFile + text);
    }
    const int frames = options.frames.value_or(int(wholePath));
    // Frame i is the path at i / fps: say what part of the path the frames cover (12 frames at 30 fps are 0.37 s
    // of a 7.3 s path).
    char coverage[256];
    std::snprintf(coverage, sizeof coverage, "render: %d frames at %g fps cover %.2f s of the path's %.2f s%s", frames,
                  options.fps, double(frames - 1) / options.fps, path.duration(),
                  double(frames - 1) / options.fps + 1e-9 < path.duration() ? " (--fps F spaces them 1/F s apart)" : "");
    log::info(coverage);
    // Frames for a video alone go to a temporary folder that is removed afterwards, whatever happens.
    fs::path temporary;
    struct RemoveFolder {
        const fs::path& folder;
        ~RemoveFolder() {
            std::error_code ec;
            if (!folder.empty()) fs::remove_all(folder, ec);
        }
    } removeFolder{temporary};
    std::string pattern;
    if (options.outPattern) {
        pattern = *options.outPattern;
    } else {
        temporary = makeFramesFolder();
        pattern = (temporary / "%05d.png").string();
    }
    request.frames = 1;
    request.cameraOverride = path.at(0.0);
    OffscreenSession session(request);
    for (int i = 0; i < frames; ++i) {
        // A fixed time step: frame i shows the path at i / fps seconds whatever the render took.
        request.cameraOverride = path.at(double(i) / options.fps);
        RenderResult result = session.render(request);
        std::string file = framePath(pattern, i);
        if (imageFormatForPath(file, "--out") == ImageFormat::Exr) writeExr(file, result.hdr.data(), result.width, result.height);
        else writePng(file, result.display.data(), result.width, result.height);
        if (options.outPattern) std::printf("%s\n", file.c_str());
    }
    if (options.video) {
        if (findProgram("ffmpeg").empty())
            throw Error("--video: the ffmpeg program is not installed (Debian: apt-get install ffmpeg); the " +
                        std::to_string(frames) + " frames are " + pattern);
        encodeVideo(pattern, options.fps, *options.video);
        std::printf("%s\n", options.video->c_str());
    }
    log::info("render: ", frames, " frames along ", options.pathFile, " (", path.duration(), " s at ", options.fps, " fps)");
    return 0;
}

}  // namespace glimmer
