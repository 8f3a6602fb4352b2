#include "app/walkthrough.h"
#include "app/window_resolution.h"

#include <glad/gl.h>
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>

#include "core/clock.h"
#include "core/error.h"
#include "core/file_watcher.h"
#include "core/files.h"
#include "core/image_io.h"
#include "core/log.h"
#include "gl/program.h"
#include "glints/user/user_methods.h"
#include "platform/glfw_window.h"
#include "render/aov.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "ui/camera_controller.h"
#include "ui/font.h"
#include "ui/input_script.h"
#include "ui/key_holds.h"
#include "ui/player_motion.h"
#include "ui/recorded_path.h"
#include "scene/builtin_scenes.h"
#include "scene/character_collision.h"
#include "ui/settings_panel.h"
#include "ui/ui.h"
#include "ui/ui_renderer.h"

namespace glimmer {
namespace {

constexpr float kLookRadiansPerPixel = 0.0025f;
constexpr float kWalkingSpeed = 1.8f;  // m/s, a brisk walk
constexpr float kWheelSpeedFactor = 1.2f;
constexpr double kMessageSeconds = 4.0;
constexpr float kDividerGrabPixels = 6.0f;

// The window image: the renderer's display image with the UI drawn over it. Rendering the overlay into our own
// texture (not the window) keeps screenshots independent of the window system.
class PresentTarget {
public:
    void resize(int width, int height) {
        if (width == width_ && height == height_) return;
        width_ = width;
        height_ = height;
        texture_ = gl::createTexture2D(GL_RGBA8, width, height);
        framebuffer_ = gl::createFramebuffer("walkthrough present", {texture_.id()});
    }
    GLuint framebuffer() const { return framebuffer_.id(); }
    int width() const { return width_; }
    int height() const { return height_; }
    std::vector<uint8_t> read() const {
        std::vector<uint8_t> pixels(size_t(width_) * height_ * 4);
        glGetTextureImage(texture_.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
        for (size_t i = 3; i < pixels.size(); i += 4) pixels[i] = 255;
        return pixels;
    }

private:
    int width_ = 0, height_ = 0;
    gl::Texture texture_;
    gl::Framebuffer framebuffer_;
};

// Splits `text` into lines of at most `columns` characters (breaking at spaces where possible).
std::vector<std::string> wrapText(const std::string& text, size_t columns) {
    std::vector<std::string> lines;
    std::string rest = text;
    while (rest.size() > columns) {
        size_t cut = rest.rfind(' ', columns);
        if (cut == std::string::npos || cut < columns / 2) cut = columns;
        lines.push_back(rest.substr(0, cut));
        rest = rest.substr(cut == columns ? cut : cut + 1);
    }
    lines.push_back(rest);
    return lines;
}

std::string formatMs(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", ms);
    return text;
}

// Three significant digits at most (the stats line lists every pass: it must fit 1280 pixels).
std::string formatMsShort(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, ms >= 100.0 ? "%.0f" : (ms >= 10.0 ? "%.1f" : "%.2f"), ms);
    return text;
}

class Walkthrough {
public:
    explicit Walkthrough(const ViewOptions& options)
        : options_(options),
          baseScene_(loadScene(options.request.scene)),
          window_(options.request.width, options.request.height, "Glimmer - " + baseScene_.name,
                  options.frameLimit == 0) {
        const Camera& start = baseScene_.camera(options.request.camera);
        if (options.request.environment) baseScene_.environment = *options.request.environment;
        scene_ = baseScene_;
        applySceneOverrides(options.request.settings, scene_);
        gpuScene_ = std::make_unique<GpuScene>(scene_);
        std::filesystem::path shaderRoot =
            options.request.shaderRoot.empty() ? defaultShaderDir() : options.request.shaderRoot;
        std::string rendererName = window_.rendererString();
        softwareRenderer_ = rendererName.find("llvmpipe") != std::string::npos ||
                            rendererName.find("softpipe") != std::string::npos;
        RenderSettings settings = options.request.settings;
        // On a software renderer the interactive window reads material textures trilinearly unless told otherwise:
        // llvmpipe's anisotropic filtering was about half the frame at render scale 0.25 (docs/performance.md).
        // Screenshot runs keep the offscreen default so that they equal `glimmer render`.
        if (softwareRenderer_ && !options.screenshot && !settings.isSet(param::texture_anisotropy))
            settings.apply("texture_anisotropy=1");
        // Likewise shadows at every second pixel (shadow.half_res, docs/shadows.md#cost: the frame with shadows
        // 1.04-1.12x the frame without at 1280x720 instead of 1.22-1.42x), at the price of shadow and light
        // features under two pixels.
        if (softwareRenderer_ && !options.screenshot && !settings.isSet(param::shadow_half_res))
            settings.apply("shadow.half_res=1");
        // And ambient occlusion at every second pixel (ao.half_res, docs/ambient_occlusion.md#half-resolution-aohalf_res).
        if (softwareRenderer_ && !options.screenshot && !settings.isSet(param::ao_half_res))
            settings.apply("ao.half_res=1");
        // And TAA resolved at the render size, its post passes (bloom, exposure, tone mapping) there too, with the
        // window's Catmull-Rom upscale after them (taa.upsample=0): at scale 0.25 in a 1280x720 window the
        // upsampling resolve and the post passes at the window's size took about half of the frame
        // (docs/performance.md). GPUs keep TAA upsampling.
        if (softwareRenderer_ && !options.screenshot && !settings.isSet(param::taa_upsample))
            settings.apply("taa.upsample=0");
        // And the geometry at the level of detail that keeps its error within a pixel of the render size
        // (lod.pixel_error=1): the G-buffer's vertex work is serial on llvmpipe.
        if (softwareRenderer_ && !options.screenshot && !settings.isSet(param::lod_pixel_error))
            settings.apply("lod.pixel_error=1");
        // Every window shades glinty and other pixels with separate programs (render/frame/lighting_pass.h).
        if (!options.screenshot && !settings.isSet(param::lighting_split_glinty)) settings.apply("lighting.split_glinty=1");
        renderer_ = std::make_unique<Renderer>(shaderRoot, settings);
        renderer_->setAsyncGpuTimers(true);
        uiRenderer_ = std::make_unique<ui::UiRenderer>(shaderRoot);
        // Headless runs (--frames) build once and fail on any error; the interactive window watches shaders/.
        if (options.frameLimit == 0) {
            try {
                watcher_ = std::make_unique<FileWatcher>(shaderRoot);
                log::info("view: watching ", watcher_->root().string(), " for shader edits (",
                          watcher_->mode() == FileWatcher::Mode::Inotify ? "inotify" : "modification times", ")");
            } catch (const std::exception& e) {
                log::warn("view: no shader hot reload: ", e.what());
            }
            watchMethodFolders();
        }
        refreshMethodFileChoices();
        if (options.splitMethod) {
            splitMethod_ = findGlintMethod(*options.splitMethod).id;
            splitFraction_ = std::clamp(options.splitPosition, 0.0f, 1.0f);
            split_ = true;
        }
        startScene(start);
        if (options.inputScript) script_ = std::make_unique<ui::ScriptPlayer>(ui::readInputScript(*options.inputScript));
        controls_.moveSpeed = preferredMode_ == ui::MoveMode::Walk
                                  ? kWalkingSpeed
                                  : std::clamp(glm::length(start.target - start.position) * 0.5f, 0.05f, 20.0f);

        controls_.vsync = options.vsync && options.frameLimit == 0;
        window_.setVsync(controls_.vsync);
        uiHidden_ = options.hideUi;
        log::info("view: ", rendererName, ", ", window_.versionString());
        resolution_ = std::make_unique<WindowResolution>(shaderRoot, softwareRenderer_, options.screenshot.has_value(),
                                                         options.renderScale, options.targetFps);
        if (options.playWalkthrough) toggleWalkthrough();
    }

    ~Walkthrough() {
        window_.makeCurrent();  // GL objects die with the context current
    }

    int run() {
        // One clock for frames, key holds and the input script: seconds since the first frame began.
        double start = glfwGetTime();
        double previous = 0.0;
        for (int frame = 0; !window_.shouldClose() && (options_.frameLimit == 0 || frame < options_.frameLimit);
             ++frame) {
            glfwPollEvents();
            double now = glfwGetTime() - start;
            double dt = now - previous;
            frameMs_ = frame == 0 ? dt * 1e3 : frameMs_ * 0.9 + dt * 1e3 * 0.1;
            now_ = now;
            if (frame >= 2) resolution_->addFrame(dt * 1e3);   // frame 0 builds shaders and the environment
            int width = 0, height = 0;
            window_.framebufferSize(width, height);
            WindowEvents events = window_.takeEvents();
            takeKeyChanges(events, start, now);
            if (width <= 0 || height <= 0) {  // minimised: wait for events instead of spinning
                glfwWaitEventsTimeout(0.1);
                continue;
            }
            pollShaderChanges();
            ui::Input uiInput = handleKeys(events, width, height);
            uiInput.focusMove += std::exchange(pendingScriptInput_.focusMove, 0);
            uiInput.adjust += std::exchange(pendingScriptInput_.adjust, 0);
            uiInput.activate |= std::exchange(pendingScriptInput_.activate, false);
            buildUi(uiInput, width, height);
            moveCamera(events, previous, now, width, height);
            previous = now;
            // Eye adaptation: the metered exposure moves towards each frame's target with a 0.5 s time constant
            // (headless --frames runs converge at once, like offscreen renders).
            renderer_->setExposureAdaptation(options_.frameLimit == 0 && frame > 0 ? float(1.0 - std::exp(-dt / 0.5)) : 1.0f);
            drawFrame(width, height);
            if (options_.screenshot && frame + 1 == options_.frameLimit) writeScreenshot(*options_.screenshot);
            window_.swapBuffers();
            if (scriptQuit_ && scriptScreenshot_.empty()) window_.requestClose();  // after a pending screenshot
            // The script's clock starts once the first frame (shader builds, environment precomputation) is done.
            if (script_ && scriptOffset_ < 0.0) scriptOffset_ = glfwGetTime() - start;
        }
        if (options_.printStats) printStats();
        return 0;
    }

    void printStats() const {
        nlohmann::json stats = resolution_->statsJson();
        stats["scene"] = baseScene_.name;
        stats["camera"] = options_.request.camera;
        stats["method"] = renderer_->settings().method;
        int w = 0, h = 0;
        window_.framebufferSize(w, h);
        stats["window"] = {w, h};
        stats["gl_renderer"] = window_.rendererString();
        stats["walkthrough"] = options_.playWalkthrough;
        stats["vsync"] = controls_.vsync;
        std::printf("%s\n", stats.dump().c_str());
    }

private:
    // ---- hot reload ----
    void pollShaderChanges() {
        if (!watcher_) return;
        std::vector<std::filesystem::path> changed = watcher_->poll();
        for (auto& [folder, watcher] : methodWatchers_)
            for (const auto& f : watcher->poll())
                if (std::find(changed.begin(), changed.end(), f) == changed.end()) changed.push_back(f);
        if (changed.empty()) return;
        for (const auto& f : changed) log::info("view: shader changed: ", f.string());
        replacedMethods_.clear();
        reloadMethodHeaders(changed);
        reloadShaders(changed, false);
        // A new header whose body does not compile: the last good program runs on, so its header (the parameter
        // block's layout) comes back too.
        for (const auto& [method, settings] : replacedMethods_) {
            bool failed = false;
            for (const auto& [program, error] : renderer_->shaderErrors()) failed |= program.find("lighting/") == 0;
            if (!failed) continue;
            registerGlintMethod(method);
            applySettings(settings);
        }
        watchMethodFolders();
        refreshMethodFileChoices();
    }

    // User methods (--method-file, glints/user/user_methods.h) may live anywhere: their folders and the folders of the
    // files they include from outside the shader root are watched too (without subfolders).
    void watchMethodFolders() {
        if (!watcher_) return;
        std::vector<std::filesystem::path> files = renderer_->shaderDependencies();
        if (splitRenderer_) for (const auto& f : splitRenderer_->shaderDependencies()) files.push_back(f);
        for (const GlintMethod& m : glintMethods())
            if (m.isUserMethod()) files.push_back(m.sourceFile);
        for (const auto& file : files) {
            std::filesystem::path folder = file.parent_path();
            auto rel = std::filesystem::relative(folder, watcher_->root());
            bool underRoot = !rel.empty() && *rel.begin() != "..";
            if (underRoot || methodWatchers_.count(folder)) continue;
            try {
                methodWatchers_[folder] = std::make_unique<FileWatcher>(folder, std::chrono::milliseconds(60),
                                                                        FileWatcher::Mode::Inotify, false);
                log::info("view: watching ", folder.string(), " for method edits");
            } catch (const std::exception& e) {
                log::warn("view: cannot watch ", folder.string(), ": ", e.what());
            }
        }
    }

    // A changed user method file: its header is parsed again before the program is rebuilt. A header that does
    // not parse keeps the last good method and program (the error, file:line, stays on screen until fixed); a
    // good one replaces the table entry, and the parameter values that still exist are kept (clamped).
    void reloadMethodHeaders(std::vector<std::filesystem::path>& changed) {
        for (auto it = changed.begin(); it != changed.end();) {
            const GlintMethod* old = userMethodForFile(*it);
            if (!old) { ++it; continue; }
            const std::filesystem::path file = *it;
            GlintMethod fresh;
            try {
                fresh = readUserMethodFile(file);
                replacedMethods_.push_back({*old, renderer_->settings()});
                std::string previous = registerGlintMethod(fresh);
                methodFileErrors_.erase(file);
                RenderSettings next = renderer_->settings();
                ParamValues values = carryParamValues(next.methodValues(previous), fresh);
                next.methods.erase(previous);
                next.methods[fresh.id] = values;
                if (next.method == previous) next.method = fresh.id;
                if (splitMethod_ == previous) splitMethod_ = fresh.id;
                // Same method id: only values change (the program is rebuilt below); a renamed method rebuilds.
                applySettings(next);
                std::string note = "method " + fresh.id + ": header read (" + std::to_string(fresh.params.size()) + " parameters)";
                log::info("view: ", note);
                showMessage(note);
                ++it;
            } catch (const std::exception& e) {
                methodFileErrors_[file] = e.what();
                log::error("view: ", e.what());
                it = changed.erase(it);   // keep the last good program: do not rebuild from a broken header
            }
        }
    }

    // The panel's "load" buttons: method files of content/methods/ and of the folders of loaded methods.
    void refreshMethodFileChoices() {
        std::vector<std::filesystem::path> folders = {defaultContentDir() / "methods"};
        for (const GlintMethod& m : glintMethods())
            if (m.isUserMethod() && std::find(folders.begin(), folders.end(), m.sourceFile.parent_path()) == folders.end())
                folders.push_back(m.sourceFile.parent_path());
        methodFileChoices_.clear();
        controls_.methodFileChoices.clear();
        for (const auto& folder : folders)
            for (const auto& file : methodFilesIn(folder)) {
                if (userMethodForFile(file) || methodFileChoices_.size() >= 6) continue;
                methodFileChoices_.push_back(file);
                controls_.methodFileChoices.push_back(file.filename().string());
            }
    }

    void loadMethodFile(const std::filesystem::path& file) {
        try {
            std::string id = loadUserMethodFile(file);
            methodFileErrors_.erase(file);
            RenderSettings next = renderer_->settings();
            next.method = id;
            applySettings(next);
            showMessage("method " + id + " from " + displayPath(file));
        } catch (const std::exception& e) {
            methodFileErrors_[file] = e.what();
            showMessage(e.what());
        }
        watchMethodFolders();
        refreshMethodFileChoices();
    }

    // Rebuilds the programs using `changed` (or all, for F5). Errors stay in the overlay until fixed.
    void reloadShaders(const std::vector<std::filesystem::path>& changed, bool all) {
        std::vector<std::filesystem::path> files = changed;
        if (all) {
            files = renderer_->shaderDependencies();
            files.insert(files.end(), uiRenderer_->dependencies().begin(), uiRenderer_->dependencies().end());
        }
        Stopwatch clock;
        std::vector<std::string> rebuilt = renderer_->reloadChangedPrograms(files);
        if (splitRenderer_) splitRenderer_->reloadChangedPrograms(files);
        ++settingsVersion_;   // a rebuilt shader starts a new accumulation
        try {
            if (uiRenderer_->reloadIfChanged(files)) rebuilt.push_back("ui");
            uiError_.clear();
        } catch (const std::exception& e) {
            uiError_ = e.what();
        }
        if (!rebuilt.empty()) {
            std::string names;
            for (const auto& n : rebuilt) names += (names.empty() ? "" : ", ") + n;
            log::info("view: rebuilt ", names, " in ", formatMs(clock.elapsedMs()), " ms");
            showMessage("rebuilt " + names);
        }
        for (const auto& [program, error] : renderer_->shaderErrors()) log::error("shader ", program, ": ", error);
        if (!uiError_.empty()) log::error("shader ui: ", uiError_);
    }

    // ---- input ----
    // Walking collides with the scene's triangles (Bullet BVH, built once here); a scene without any flies.
    void buildCollision() {
        Stopwatch clock;
        try {
            collision_ = std::make_unique<SceneCollision>(scene_);
            log::info("view: collision mesh of ", collision_->triangleCount(), " triangles in ",
                      formatMs(clock.elapsedMs()), " ms");
        } catch (const std::exception& e) {
            log::warn("view: no walking: ", e.what());
        }
    }

    // Key presses and releases (window and input script) into the hold record; times relative to `start`.
    void takeKeyChanges(WindowEvents& events, double start, double now) {
        if (events.focusLost) keys_.releaseAll(now);
        for (const WindowEvents::KeyChange& change : events.changes) {
            if (change.down) keys_.press(change.key, change.seconds - start);
            else keys_.release(change.key, change.seconds - start);
        }
    }

    bool panelScriptInputPending() const {
        return pendingScriptInput_.focusMove != 0 || pendingScriptInput_.adjust != 0 || pendingScriptInput_.activate;
    }

    // One input-script event at frame-clock time `t`: keys go through the same paths as the window's.
    void applyScriptEvent(const ui::ScriptEvent& e, double t, int width, int height) {
        auto action = [&](int key) {
            WindowEvents single;
            single.keys.push_back({key, shiftHeld() ? GLFW_MOD_SHIFT : 0, false});
            ui::Input input = handleKeys(single, width, height);
            pendingScriptInput_.focusMove += input.focusMove;
            pendingScriptInput_.adjust += input.adjust;
            pendingScriptInput_.activate |= input.activate;
        };
        switch (e.kind) {
        case ui::ScriptEvent::Kind::Down:
            keys_.press(e.key, t);
            action(e.key);
            break;
        case ui::ScriptEvent::Kind::Up: keys_.release(e.key, t); break;
        case ui::ScriptEvent::Kind::Press:
            keys_.press(e.key, t);
            keys_.release(e.key, t);
            action(e.key);
            break;
        case ui::ScriptEvent::Kind::Look:
            motion_->turn(e.dx * kLookRadiansPerPixel, -e.dy * kLookRadiansPerPixel);
            break;
        case ui::ScriptEvent::Kind::Print: {
            const glm::vec3& p = motion_->camera().position;
            std::printf("time %.3f position %.4f %.4f %.4f mode %s speed %.4f\n", e.seconds, p.x, p.y, p.z,
                        motion_->mode() == ui::MoveMode::Walk ? "walk" : "fly", double(controls_.moveSpeed));
            std::fflush(stdout);
            break;
        }
        case ui::ScriptEvent::Kind::Screenshot:
            // Written at the end of the next frame, whose panel and stats strip have seen every earlier event.
            scriptScreenshot_ = e.path;
            scriptScreenshotDelay_ = 1;
            break;
        case ui::ScriptEvent::Kind::Quit: scriptQuit_ = true; break;
        }
    }

    bool shiftHeld() const { return keys_.down(GLFW_KEY_LEFT_SHIFT) || keys_.down(GLFW_KEY_RIGHT_SHIFT); }

    double heldSeconds(ui::MoveKey key, double from, double to) const {
        auto held = [&](int k) { return keys_.heldSeconds(k, from, to); };
        switch (key) {
        case ui::MoveKey::Forward: return held(GLFW_KEY_W);
        case ui::MoveKey::Back: return held(GLFW_KEY_S);
        case ui::MoveKey::Left: return held(GLFW_KEY_A);
        case ui::MoveKey::Right: return held(GLFW_KEY_D);
        case ui::MoveKey::Up: return held(GLFW_KEY_E);
        case ui::MoveKey::Down: return held(GLFW_KEY_Q);
        case ui::MoveKey::Fast: return std::min(to - from, held(GLFW_KEY_LEFT_SHIFT) + held(GLFW_KEY_RIGHT_SHIFT));
        }
        return 0.0;
    }

    // F: walking (collision, gravity, standing eye height) or flying (free, through everything).
    void toggleWalking() {
        ui::MoveMode next = motion_->mode() == ui::MoveMode::Walk ? ui::MoveMode::Fly : ui::MoveMode::Walk;
        stopWalkthrough();
        if (!motion_->setMode(next)) {
            showMessage("no floor below the camera: flying");
            return;
        }
        preferredMode_ = next;
        controls_.walking = next == ui::MoveMode::Walk;
        if (controls_.walking && controls_.moveSpeed > 4.0f * kWalkingSpeed) controls_.moveSpeed = kWalkingSpeed;
        showMessage(controls_.walking ? "walking (F flies)" : "flying (F walks)");
    }

    ui::Input handleKeys(const WindowEvents& events, int width, int height) {
        ui::Input input;
        GLFWwindow* w = window_.glfwHandle();
        for (const WindowEvents::Key& key : events.keys) {
            bool shift = key.mods & GLFW_MOD_SHIFT;
            // Arrows repeat while held (panel navigation); other keys act once per press.
            switch (key.key) {
            case GLFW_KEY_UP: input.focusMove -= 1; continue;
            case GLFW_KEY_DOWN: input.focusMove += 1; continue;
            case GLFW_KEY_LEFT: input.adjust -= 1; continue;
            case GLFW_KEY_RIGHT: input.adjust += 1; continue;
            default: break;
            }
            if (key.repeat) continue;
            switch (key.key) {
            case GLFW_KEY_ENTER:
            case GLFW_KEY_KP_ENTER: input.activate = true; break;
            case GLFW_KEY_ESCAPE:
                if (captured_) setCaptured(false);
                else window_.requestClose();
                break;
            case GLFW_KEY_F5: reloadShaders({}, true); break;
            case GLFW_KEY_F12: pendingScreenshot_ = shift ? 2 : 1; break;
            case GLFW_KEY_H: uiHidden_ = !uiHidden_; break;
            case GLFW_KEY_C: setCaptured(!captured_); break;
            case GLFW_KEY_V:
                controls_.vsync = !controls_.vsync;
                window_.setVsync(controls_.vsync);
                break;
            case GLFW_KEY_P: toggleWalkthrough(); break;
            case GLFW_KEY_F: toggleWalking(); break;
            case GLFW_KEY_R: toggleRecording(); break;
            case GLFW_KEY_M: cycleMethod(shift ? -1 : 1); break;
            case GLFW_KEY_N: cycleDebugView(shift ? -1 : 1); break;
            case GLFW_KEY_B:
                if (shift) cycleSplitMethod();
                else split_ = !split_;
                if (split_) showMessage("split: " + renderer_->settings().method + " | " + splitMethodId());
                break;
            case GLFW_KEY_I: cycleIblMode(shift ? -1 : 1); break;
            default:
                if (key.key >= GLFW_KEY_1 && key.key <= GLFW_KEY_9) jumpToCamera(key.key - GLFW_KEY_1);
                break;
            }
        }
        // Mouse in framebuffer pixels (the window size differs from the framebuffer on scaled displays).
        double cx = 0, cy = 0;
        window_.cursorPosition(cx, cy);
        int ww = 1, wh = 1;
        window_.windowSize(ww, wh);
        bool looking = captured_ || rightLook_;
        if (!looking) {
            input.mouse = {float(cx * width / std::max(ww, 1)), float(cy * height / std::max(wh, 1))};
            input.mouseDown = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
            input.mousePressed = events.leftPressed;
            input.rightPressed = events.rightPressed;
            input.scroll = float(events.scrollY);
            // The split divider: grab it within a few pixels (outside the panel), drag while the button is held.
            float dividerX = splitFraction_ * float(width);
            if (split_ && events.leftPressed && std::abs(input.mouse.x - dividerX) <= kDividerGrabPixels &&
                !(showUi() && ui_.mouseOverUi()))
                draggingDivider_ = true;
            if (!input.mouseDown) draggingDivider_ = false;
            if (draggingDivider_) {
                splitFraction_ = std::clamp(input.mouse.x / float(std::max(width, 1)), 0.0f, 1.0f);
                input.mousePressed = input.mouseDown = false;  // the panel must not see the drag
            }
        }
        return input;
    }

    void setCaptured(bool captured) {
        captured_ = captured;
        window_.setCursorCaptured(captured_ || rightLook_);
        lookStarted_ = false;
    }

    void moveCamera(const WindowEvents& events, double from, double to, int width, int height) {
        GLFWwindow* w = window_.glfwHandle();
        // Right button held outside the panel: mouse look (the cursor is hidden while it is held).
        bool rightDown = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
        if (events.rightPressed && !(showUi() && ui_.mouseOverUi()) && !rightLook_) {
            rightLook_ = true;
            window_.setCursorCaptured(true);
            lookStarted_ = false;
        }
        if (rightLook_ && !rightDown) {
            rightLook_ = false;
            window_.setCursorCaptured(captured_);
        }
        double cx = 0, cy = 0;
        window_.cursorPosition(cx, cy);
        if (captured_ || rightLook_) {
            if (lookStarted_ && (cx != lastCursor_.x || cy != lastCursor_.y)) {
                motion_->turn(float(cx - lastCursor_.x) * kLookRadiansPerPixel, -float(cy - lastCursor_.y) * kLookRadiansPerPixel);
                stopWalkthrough();
            }
            lookStarted_ = true;
        }
        lastCursor_ = {cx, cy};

        if (events.scrollY != 0.0 && !(showUi() && ui_.mouseOverUi())) {
            ParamSpec speed = ui::moveSpeedSpec();
            controls_.moveSpeed = std::clamp(controls_.moveSpeed * std::pow(kWheelSpeedFactor, float(events.scrollY)),
                                             speed.minValue, speed.maxValue);
        }
        // Script events apply at their own times, with the motion advanced exactly up to each one. At most one panel
        // key per frame: the panel folds a frame's keys into one input (moves summed, then activate), so "enter, up"
        // in one long frame would act as "up, enter"; the rest waits for the next frame, in order.
        double at = from;
        if (script_ && scriptOffset_ >= 0.0)
            while (!panelScriptInputPending()) {
                const ui::ScriptEvent* e = script_->nextDue(to - scriptOffset_);
                if (!e) break;
                double t = std::max(at, e->seconds + scriptOffset_);
                advanceTo(at, t);
                at = t;
                applyScriptEvent(*e, t, width, height);
            }
        advanceTo(at, to);
        keys_.forgetBefore(to);
    }

    // Motion over [from, to]: the camera path while it plays, else the held keys (and recording).
    void advanceTo(double from, double to) {
        if (!(to > from)) return;
        float dt = float(to - from);
        bool keysHeld = false;
        for (int key : {GLFW_KEY_W, GLFW_KEY_A, GLFW_KEY_S, GLFW_KEY_D, GLFW_KEY_Q, GLFW_KEY_E})
            keysHeld |= keys_.heldSeconds(key, from, to) > 0.0;
        if (keysHeld) stopWalkthrough();
        if (controls_.walkthroughPlaying) {
            walkthroughTime_ += dt;
            bool recorded = !recorded_.empty() && !controls_.recording;
            motion_->setCamera(recorded ? recorded_.at(walkthroughTime_) : path_->at(walkthroughTime_), ui::MoveMode::Fly);
            if (walkthroughTime_ >= (recorded ? float(recorded_.duration()) : path_->duration())) stopWalkthrough();
        } else {
            motion_->advance([&](ui::MoveKey key, double a, double b) { return heldSeconds(key, a, b); }, from, to,
                             controls_.moveSpeed);
        }
        if (controls_.recording) recorded_.add(to - recordStart_, motion_->camera());
    }

    // P: the recorded (or --path) camera path when there is one, else the scene's cameras in order.
    void toggleWalkthrough() {
        if (controls_.walkthroughPlaying) { stopWalkthrough(); return; }
        if (controls_.recording) toggleRecording();
        walkthroughTime_ = 0.0f;
        if (!recorded_.empty()) {
            controls_.walkthroughPlaying = true;
            showMessage("path " + pathFile_.string() + ": " + formatMs(recorded_.duration()) + " s");
            return;
        }
        path_ = std::make_unique<ui::CameraPath>(baseScene_.cameras, std::max(controls_.moveSpeed, 0.2f));
        if (path_->empty()) return;
        controls_.walkthroughPlaying = true;
        showMessage("walkthrough: " + std::to_string(baseScene_.cameras.size()) + " cameras, " +
                    formatMs(path_->duration()) + " s");
    }

    // R: starts recording the camera, or stops and saves the path as JSON (--path FILE, else beside the scene).
    void toggleRecording() {
        if (!controls_.recording) {
            stopWalkthrough();
            recorded_ = ui::RecordedPath();
            recordStart_ = now_;
            controls_.recording = true;
            showMessage("recording a camera path (R stops)");
            return;
        }
        controls_.recording = false;
        controls_.hasRecordedPath = !recorded_.empty();
        try {
            recorded_.save(pathFile_, baseScene_.name);
            log::info("view: wrote camera path ", pathFile_.string(), " (", recorded_.samples().size(), " samples)");
            showMessage("wrote " + pathFile_.string());
        } catch (const std::exception& e) {
            log::error("view: ", e.what());
            showMessage(e.what());
        }
    }

    // Where a recorded path goes: --path FILE, else <scene>.path.json in the scene file's folder (the content
    // folder for scenes described there, the current folder for generated ones).
    std::filesystem::path defaultPathFile() const {
        if (options_.pathFile) return *options_.pathFile;
        std::filesystem::path scene(options_.request.scene);
        std::error_code ec;
        if (std::filesystem::is_regular_file(scene, ec)) return scene.parent_path() / (scene.stem().string() + ".path.json");
        if (std::filesystem::is_regular_file(defaultContentDir() / (baseScene_.name + ".json"), ec))
            return defaultContentDir() / (baseScene_.name + ".path.json");
        return baseScene_.name + ".path.json";
    }

    void loadRecordedPath() {
        pathFile_ = defaultPathFile();
        recorded_ = ui::RecordedPath();
        std::error_code ec;
        if (std::filesystem::exists(pathFile_, ec)) {
            recorded_ = ui::RecordedPath::load(pathFile_);
            log::info("view: camera path ", pathFile_.string(), " (", recorded_.samples().size(), " samples): P plays it");
        }
        controls_.hasRecordedPath = !recorded_.empty();
    }

    // The panel's scene selector: loads the scene, its collision mesh and cameras; settings stay.
    void switchScene(const std::string& name) {
        Scene loaded;
        try {
            loaded = loadScene(name);
        } catch (const std::exception& e) {
            showMessage(e.what());
            return;
        }
        stopWalkthrough();
        if (controls_.recording) toggleRecording();
        baseScene_ = std::move(loaded);
        if (options_.request.environment) baseScene_.environment = *options_.request.environment;
        scene_ = baseScene_;
        applySceneOverrides(renderer_->settings(), scene_);
        gpuScene_ = std::make_unique<GpuScene>(scene_);
        options_.request.scene = name;
        options_.pathFile.reset();
        startScene(baseScene_.cameras.front());
        ++settingsVersion_;
        glfwSetWindowTitle(window_.glfwHandle(), ("Glimmer - " + baseScene_.name).c_str());
        showMessage("scene " + baseScene_.name);
    }

    // Collision, motion mode, camera list and camera path of the current scene, starting at `start`.
    void startScene(const Camera& start) {
        buildCollision();
        motion_ = std::make_unique<ui::PlayerMotion>(collision_.get());
        // Scripted input has exact times: no frame counts as a stall, so results do not depend on machine load.
        if (options_.inputScript) motion_->setStallSeconds(std::numeric_limits<double>::infinity());
        preferredMode_ = motion_->setCamera(start, ui::MoveMode::Walk);
        controls_.walking = preferredMode_ == ui::MoveMode::Walk;
        controls_.cameraNames.clear();
        for (const Camera& c : baseScene_.cameras) controls_.cameraNames.push_back(c.name);
        controls_.cameraIndex = 0;
        for (size_t i = 0; i < baseScene_.cameras.size(); ++i)
            if (baseScene_.cameras[i].name == start.name) controls_.cameraIndex = int(i);
        controls_.sceneNames = builtinSceneNames();
        auto it = std::find(controls_.sceneNames.begin(), controls_.sceneNames.end(), options_.request.scene);
        if (it == controls_.sceneNames.end()) {
            controls_.sceneNames.push_back(options_.request.scene);
            it = controls_.sceneNames.end() - 1;
        }
        controls_.sceneIndex = int(it - controls_.sceneNames.begin());
        loadRecordedPath();
    }

    void stopWalkthrough() {
        if (!controls_.walkthroughPlaying) return;
        controls_.walkthroughPlaying = false;
        motion_->setCamera(motion_->camera(), preferredMode_);  // walks on from here if it stands on a floor
    }

    void jumpToCamera(int index) {
        if (index < 0 || index >= int(baseScene_.cameras.size())) return;
        stopWalkthrough();
        motion_->setCamera(baseScene_.cameras[size_t(index)], preferredMode_);
        controls_.cameraIndex = index;
        controls_.walking = motion_->mode() == ui::MoveMode::Walk;
        showMessage("camera " + baseScene_.cameras[size_t(index)].name);
    }

    void cycleMethod(int step) {
        const auto& methods = glintMethods();
        int n = int(methods.size()), current = 0;
        for (int i = 0; i < n; ++i)
            if (methods[size_t(i)].id == renderer_->settings().method) current = i;
        RenderSettings next = renderer_->settings();
        const GlintMethod& chosen = methods[size_t(((current + step) % n + n) % n)];
        // The IBL mode follows the method's default while it is the previous one's (GlintMethod::defaultIbl).
        if (next.ibl == defaultIblOf(methods[size_t(current)])) next.ibl = defaultIblOf(chosen);
        next.method = chosen.id;
        applySettings(next);
        showMessage("method " + renderer_->settings().method);
    }

    // The right-hand method of the split: the one chosen, else the first method differing from the left one.
    std::string splitMethodId() const {
        if (!splitMethod_.empty()) return splitMethod_;
        for (const GlintMethod& m : glintMethods())
            if (m.id != renderer_->settings().method) return m.id;
        return renderer_->settings().method;
    }

    void cycleSplitMethod() {
        const auto& methods = glintMethods();
        int n = int(methods.size()), current = 0;
        for (int i = 0; i < n; ++i)
            if (methods[size_t(i)].id == splitMethodId()) current = i;
        splitMethod_ = methods[size_t((current + 1) % n)].id;
        split_ = true;
    }

    void cycleIblMode(int step) {
        const auto& modes = iblModes();
        int n = int(modes.size()), current = 0;
        for (int i = 0; i < n; ++i)
            if (modes[size_t(i)].id == renderer_->settings().ibl) current = i;
        RenderSettings next = renderer_->settings();
        next.ibl = modes[size_t(((current + step) % n + n) % n)].id;
        applySettings(next);
        showMessage("ibl " + next.ibl + (renderer_->settings().ibl == next.ibl ? "" : ": " + methodError_));
    }

    void cycleDebugView(int step) {
        const auto& views = aovTable();
        int n = int(views.size()), current = 0;
        for (int i = 0; i < n; ++i)
            if (views[size_t(i)].viewId == renderer_->settings().debugView) current = i;
        RenderSettings next = renderer_->settings();
        const AovInfo& view = views[size_t(((current + step) % n + n) % n)];
        next.debugView = view.viewId;
        applySettings(next);
        showMessage("debug view " + view.name + ": " + view.meaning);
    }

    // Live edits: renderer settings (method, parameters, view) and the scene's material/light overrides.
    void applySettings(const RenderSettings& next) {
        ++settingsVersion_;
        bool commonChanged = next.common != renderer_->settings().common;
        try {
            renderer_->setSettings(next);
            methodError_.clear();
        } catch (const std::exception& e) {
            methodError_ = "method " + next.method + ": " + e.what();
            log::error("view: ", methodError_);
        }
        if (commonChanged) {
            scene_ = baseScene_;
            applySceneOverrides(renderer_->settings(), scene_);
            gpuScene_->updateMaterialsAndLights(scene_);
        }
    }

    // ---- UI ----
    bool showUi() const { return !uiHidden_; }

    void showMessage(const std::string& text) {
        message_ = text;
        messageUntil_ = now_ + kMessageSeconds;
    }

    std::vector<std::string> errors() const {
        std::vector<std::string> all;
        for (const auto& [program, error] : renderer_->shaderErrors()) all.push_back(error + "  [" + program + "]");
        if (!uiError_.empty()) all.push_back(uiError_ + "  [ui]");
        if (!methodError_.empty()) all.push_back(methodError_);
        for (const auto& [file, error] : methodFileErrors_) all.push_back(error + "  [method file]");
        return all;
    }

    void buildUi(const ui::Input& input, int width, int height) {
        int scale = ui::panelLayout(width, height, 0).scale;
        ui_.begin(input, width, height, scale);
        float line = ui_.lineHeight();
        float margin = float(4 * scale);
        size_t columns = size_t(std::max(10.0f, (float(width) - 2.0f * margin) / float(ui::kCellWidth * scale)));

        // Shader errors show even with the UI hidden: the user is looking at the picture, not at the log.
        std::vector<std::string> lines;
        for (const std::string& error : errors())
            for (const std::string& l : wrapText("SHADER ERROR " + error, columns)) lines.push_back(l);
        std::vector<StatsLine> stats = showUi() ? statsText(float(width) - 2.0f * margin) : std::vector<StatsLine>{};
        float statsHeight = showUi() ? float(stats.size()) * line + 2.0f * margin : 0.0f;
        if (!lines.empty()) {
            float boxHeight = float(lines.size()) * line + 2.0f * margin;
            float top = float(height) - statsHeight - boxHeight;
            ui_.box({0.0f, top, float(width), boxHeight}, ui::palette::kErrorBack);
            for (size_t i = 0; i < lines.size(); ++i)
                ui_.textAt({margin, top + margin + float(i) * line}, lines[i], ui::palette::kError);
        }
        if (showUi()) {
            RenderSettings edited = renderer_->settings();
            ui::PanelResult result =
                ui::settingsPanel(ui_, edited, controls_, margin, margin, float(height) - statsHeight - 2.0f * margin);
            if (result.settingsChanged) applySettings(edited);
            if (result.vsyncChanged) window_.setVsync(controls_.vsync);
            if (result.cameraRequested >= 0) jumpToCamera(result.cameraRequested);
            if (result.toggleWalkthrough) toggleWalkthrough();
            if (result.toggleWalking) toggleWalking();
            if (result.toggleRecording) toggleRecording();
            if (result.sceneRequested >= 0 && result.sceneRequested != controls_.sceneIndex)
                switchScene(controls_.sceneNames[size_t(result.sceneRequested)]);
            if (result.reloadShaders) reloadShaders({}, true);
            if (result.loadMethodFile >= 0 && size_t(result.loadMethodFile) < methodFileChoices_.size())
                loadMethodFile(methodFileChoices_[size_t(result.loadMethodFile)]);
            if (result.screenshot) pendingScreenshot_ = 1;
            drawStats(stats, width, height, statsHeight, margin, line);
            if (split_) drawSplitLabels(width, margin, line);
        }
        ui_.end();
    }

    // Method names on both sides of the divider, at the top.
    void drawSplitLabels(int width, float margin, float line) {
        float dividerX = splitFraction_ * float(width);
        std::string left = renderer_->settings().method, right = splitMethodId();
        float leftW = float(ui::textWidth(left, ui_.scale())), rightW = float(ui::textWidth(right, ui_.scale()));
        ui_.box({dividerX - leftW - 2.0f * margin, margin, leftW + margin, line + margin}, {0, 0, 0, 200});
        ui_.textAt({dividerX - leftW - 1.5f * margin, margin * 1.5f}, left, ui::palette::kHeading);
        ui_.box({dividerX + margin, margin, rightW + margin, line + margin}, {0, 0, 0, 200});
        ui_.textAt({dividerX + 1.5f * margin, margin * 1.5f}, right, ui::palette::kHeading);
    }

    struct StatsLine {
        std::string text;
        bool dim = false;
    };
    // The stats strip: frame time and GPU pass timers (on their own line when they do not fit beside it), the
    // renderer note and camera, and the passes of the last material edit (e.g. wang2020's quadtree, DPF
    // accumulation, prefilter; wall ms) while there are any.
    std::vector<StatsLine> statsText(float available) const {
        std::vector<StatsLine> lines;
        std::string frame = "frame " + formatMsShort(frameMs_) + " ms (" +
                            std::to_string(int(std::lround(1000.0 / std::max(frameMs_, 1e-3)))) + " fps) " +
                            resolution_->statsText();
        std::string timers = "GPU ms:";
        for (const PassTiming& t : renderer_->passTimings())   // NaN: no plausible result (render/frame/pass_timer.h)
            timers += " " + t.name + " " + (std::isnan(t.gpuMs) ? std::string("n/a") : formatMsShort(t.gpuMs));
        if (renderer_->passTimings().empty()) timers += " (pending)";
        if (float(ui::textWidth(frame + " | " + timers, ui_.scale())) <= available) {
            lines.push_back({frame + " | " + timers});
        } else {
            lines.push_back({frame});
            lines.push_back({timers});
        }
        const Camera& c = motion_->camera();
        char where[160];
        std::snprintf(where, sizeof where, "pos %.2f %.2f %.2f  speed %.2g m/s  vsync %s  ibl %s%s%s", c.position.x,
                      c.position.y, c.position.z, double(controls_.moveSpeed), controls_.vsync ? "on" : "off",
                      renderer_->settings().ibl.c_str(),
                      renderer_->accumulating() ? (" " + std::to_string(sampleIndex_ + 1) + " spp").c_str() : "",
                      captured_ ? "  mouse captured (C/Esc)" : "");
        std::string note = softwareRenderer_ ? "GPU timers unreliable on software renderers (llvmpipe)" : "";
        if (note.empty()) {
            lines.push_back({where, true});
        } else if (float(ui::textWidth(note + " | " + where, ui_.scale())) <= available) {
            lines.push_back({note + " | " + where, true});
        } else {
            lines.push_back({note, true});
            lines.push_back({where, true});
        }
        if (!renderer_->lastEditPasses().empty()) {
            std::string edits = "last edit:";
            for (const PassTiming& t : renderer_->lastEditPasses()) edits += " " + t.name + " " + formatMsShort(t.wallMs);
            lines.push_back({edits + " ms"});
        }
        return lines;
    }

    void drawStats(const std::vector<StatsLine>& stats, int width, int height, float statsHeight, float margin,
                   float line) {
        float top = float(height) - statsHeight;
        ui_.box({0.0f, top, float(width), statsHeight}, {0, 0, 0, 200});
        if (now_ < messageUntil_) {
            // Transient notices (screenshot written, shaders rebuilt, camera) in the top-right corner.
            float textW = float(ui::textWidth(message_, ui_.scale()));
            float boxW = std::min(textW + 2.0f * margin, float(width) * 0.6f);
            ui_.box({float(width) - boxW - margin, margin, boxW, line + margin}, {0, 0, 0, 200});
            ui_.textAt({float(width) - boxW, margin + margin * 0.5f}, message_, ui::palette::kHeading, boxW - margin);
        }
        for (size_t i = 0; i < stats.size(); ++i)
            ui_.textAt({margin, top + margin + float(i) * line}, stats[i].text,
                       stats[i].dim ? ui::palette::kDim : ui::palette::kText, float(width) - 2.0f * margin);
    }

    // ---- frame ----
    // Monte Carlo IBL modes average their estimates while camera, size, scene and settings stay as they were;
    // any change starts a new mean.
    void updateAccumulation(int width, int height) {
        glm::mat4 view = motion_->camera().view();
        bool still = view == accumulatedView_ && width == accumulatedWidth_ && height == accumulatedHeight_ &&
                     accumulatedSettingsVersion_ == settingsVersion_;
        sampleIndex_ = still && renderer_->accumulating() ? sampleIndex_ + 1 : 0;
        accumulatedView_ = view;
        accumulatedWidth_ = width;
        accumulatedHeight_ = height;
        accumulatedSettingsVersion_ = settingsVersion_;
    }

    void drawFrame(int width, int height) {
        int renderW = width, renderH = height;
        resolution_->internalSize(width, height, renderW, renderH);
        updateAccumulation(renderW, renderH);
        // aa=taa below scale 1 resolves to the window size (TAAU).
        View view{.camera = motion_->camera(), .width = renderW, .height = renderH, .outputWidth = width,
                  .outputHeight = height, .sampleIndex = sampleIndex_};
        renderer_->renderView(scene_, *gpuScene_, view);
        present_.resize(width, height);
        resolution_->present(*renderer_, present_.framebuffer(), width, height);
        if (split_) drawSplit(width, height);
        glBindFramebuffer(GL_FRAMEBUFFER, present_.framebuffer());
        uiRenderer_->draw(ui_.drawList(), width, height);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glBlitNamedFramebuffer(present_.framebuffer(), 0, 0, 0, width, height, 0, 0, width, height,
                               GL_COLOR_BUFFER_BIT, GL_NEAREST);
        if (!scriptScreenshot_.empty() && scriptScreenshotDelay_-- <= 0) {
            writeScreenshot(scriptScreenshot_);
            scriptScreenshot_.clear();
        }
        if (pendingScreenshot_) {
            writeScreenshot(nextScreenshotName(pendingScreenshot_ == 2 ? ".exr" : ".png"));
            pendingScreenshot_ = 0;
        }
    }

    // The right part of the split: a second renderer (same scene and camera, the left settings with the other
    // method) blitted over the columns right of the divider, then a 2-pixel divider line. Costs a second frame.
    void drawSplit(int width, int height) {
        RenderSettings settings = renderer_->settings();
        settings.method = splitMethodId();
        try {
            if (!splitRenderer_) {
                splitRenderer_ = std::make_unique<Renderer>(renderer_->shaderRoot(), settings);
                splitRenderer_->setAsyncGpuTimers(true);
            }
            splitRenderer_->setSettings(settings);
        } catch (const std::exception& e) {
            methodError_ = "split method " + settings.method + ": " + e.what();
            split_ = false;
            return;
        }
        int renderW = width, renderH = height;
        resolution_->internalSize(width, height, renderW, renderH);
        // The same view as the left side, accumulating in step with it.
        View view{.camera = motion_->camera(), .width = renderW, .height = renderH, .outputWidth = width,
                  .outputHeight = height, .sampleIndex = sampleIndex_};
        splitRenderer_->renderView(scene_, *gpuScene_, view);
        int x = std::clamp(int(std::lround(splitFraction_ * float(width))), 0, width);
        resolution_->present(*splitRenderer_, present_.framebuffer(), width, height, x);
        const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
        glEnable(GL_SCISSOR_TEST);
        glScissor(std::max(x - 1, 0), 0, 2, height);
        glClearNamedFramebufferfv(present_.framebuffer(), GL_COLOR, 0, white);
        glDisable(GL_SCISSOR_TEST);
    }

    std::string nextScreenshotName(const char* extension) {
        for (int i = 1;; ++i) {
            char name[256];
            std::snprintf(name, sizeof name, "glimmer-%s-%03d%s", baseScene_.name.c_str(), i, extension);
            if (!std::filesystem::exists(name)) return name;
        }
    }

    // PNG: the window image (with the UI when shown). EXR: the renderer's HDR radiance (or debug view), linear.
    void writeScreenshot(const std::string& path) {
        int width = renderer_->lastView().postWidth, height = renderer_->lastView().postHeight;
        if (imageFormatForPath(path, "--screenshot") == ImageFormat::Exr) {
            std::vector<float> hdr = renderer_->readHdr();
            writeExr(path, hdr.data(), width, height);
        } else {
            std::vector<uint8_t> pixels = present_.read();   // the window image, window size (render scale < 1)
            writePng(path, pixels.data(), present_.width(), present_.height());
        }
        if (options_.frameLimit > 0) std::printf("%s\n", path.c_str());
        log::info("view: wrote ", path);
        showMessage("wrote " + path);
    }

    ViewOptions options_;
    Scene baseScene_, scene_;
    GlfwWindow window_;
    std::unique_ptr<GpuScene> gpuScene_;
    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<Renderer> splitRenderer_;  // created on the first split frame
    std::unique_ptr<ui::UiRenderer> uiRenderer_;
    std::unique_ptr<FileWatcher> watcher_;
    std::map<std::filesystem::path, std::unique_ptr<FileWatcher>> methodWatchers_;   // user methods' folders
    std::map<std::filesystem::path, std::string> methodFileErrors_;   // header errors, file:line: message
    std::vector<std::filesystem::path> methodFileChoices_;            // what the panel's load buttons load
    std::vector<std::pair<GlintMethod, RenderSettings>> replacedMethods_;   // entries a reload replaced (undo)
    std::unique_ptr<WindowResolution> resolution_;
    PresentTarget present_;
    ui::Context ui_;
    ui::WindowControls controls_;
    std::unique_ptr<SceneCollision> collision_;  // null for a scene without triangles
    std::unique_ptr<ui::PlayerMotion> motion_;
    ui::MoveMode preferredMode_ = ui::MoveMode::Walk;  // what F chose; cameras that do not stand on a floor fly
    ui::KeyHolds keys_;
    std::unique_ptr<ui::ScriptPlayer> script_;
    std::string scriptScreenshot_;
    int scriptScreenshotDelay_ = 0;
    bool scriptQuit_ = false;
    double scriptOffset_ = -1.0;     // frame-clock time of script time 0 (the end of the first frame)
    ui::Input pendingScriptInput_;   // panel keys from the script, given to the panel next frame
    // Accumulation of Monte Carlo IBL modes (updateAccumulation).
    uint32_t sampleIndex_ = 0;
    uint64_t settingsVersion_ = 0, accumulatedSettingsVersion_ = ~uint64_t(0);
    glm::mat4 accumulatedView_{0.0f};
    int accumulatedWidth_ = 0, accumulatedHeight_ = 0;
    std::unique_ptr<ui::CameraPath> path_;
    ui::RecordedPath recorded_;
    std::filesystem::path pathFile_;
    double recordStart_ = 0.0;
    float walkthroughTime_ = 0.0f;
    bool uiHidden_ = false, captured_ = false, rightLook_ = false, lookStarted_ = false, softwareRenderer_ = false;
    glm::dvec2 lastCursor_{0.0};
    double frameMs_ = 0.0, now_ = 0.0, messageUntil_ = 0.0;
    std::string message_, uiError_, methodError_;
    int pendingScreenshot_ = 0;
    bool split_ = false, draggingDivider_ = false;
    std::string splitMethod_;      // "" = first method differing from the left one
    float splitFraction_ = 0.5f;
};

}  // namespace

int runWalkthroughWindow(const ViewOptions& options) {
    Walkthrough walkthrough(options);
    return walkthrough.run();
}

}  // namespace glimmer
