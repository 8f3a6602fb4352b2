// The window loop of `glimmer view`: one frame = events, hot reload, input, the panel, camera motion, the renderer's
// frame (and the split's), the UI over it, and the swap. This file ties the parts together and carries out what
// the keys and the panel ask for; each part lives in its own file (walkthrough.h lists them).
#include <glad/gl.h>
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/walkthrough/camera_motion.h"
#include "app/walkthrough/frame_driver.h"
#include "app/walkthrough/input.h"
#include "app/walkthrough/loading_screen.h"
#include "app/walkthrough/method_files.h"
#include "app/walkthrough/overlay.h"
#include "app/walkthrough/present.h"
#include "app/walkthrough/split_view.h"
#include "app/walkthrough/walkthrough.h"
#include "app/walkthrough/window_resolution.h"
#include "app/walkthrough/window_settings.h"
#include "core/files.h"
#include "core/log.h"
#include "environment/ibl/ibl_modes.h"
#include "platform/glfw_window.h"
#include "render/aov.h"
#include "render/renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/scene_loader.h"
#include "ui/settings_panel.h"
#include "ui/ui.h"
#include "ui/ui_renderer.h"

namespace glimmer {
namespace {

// A headless run that writes images (--frames with --screenshot or --screenshot-at): its scale must not depend on
// the machine's speed. Runs without images (--frames N --stats) adapt like the window.
bool writesFrameScreenshots(const ViewOptions& options) {
    return options.frameLimit > 0 && (options.screenshot || !options.frameScreenshots.empty());
}

class Walkthrough final : public WindowActions, public MethodFilesHost {
public:
    explicit Walkthrough(const ViewOptions& options)
        : options_(options),
          baseScene_(loadScene(options.request.scene)),
          window_(options.request.width, options.request.height, "Glimmer - " + baseScene_.name,
                  options.frameLimit == 0),
          camera_(controls_, [this](const std::string& text) { showMessage(text); }),
          split_(options.splitMethod, options.splitPosition) {
        const Camera& start = baseScene_.camera(options.request.camera);
        startCamera_ = start.name;
        if (options.request.environment) baseScene_.environment = *options.request.environment;
        std::filesystem::path shaderRoot =
            options.request.shaderRoot.empty() ? defaultShaderDir() : options.request.shaderRoot;
        // The loading frame first (the UI renderer's one program), then every slow step behind it.
        loading_ = std::make_unique<LoadingScreen>(window_, baseScene_.name);   // the window opened just now
        uiRenderer_ = std::make_unique<ui::UiRenderer>(shaderRoot);
        loading_->show(LoadingScreen::Shaders, *uiRenderer_);
        scene_ = baseScene_;
        applySceneOverrides(options.request.settings, scene_);
        updateMappedMaterial();
        camera_.prebuildCollision(scene_);   // on another thread while the GPU upload and the shaders run here
        gpuScene_ = std::make_unique<GpuScene>(scene_);
        std::string rendererName = window_.rendererString();
        softwareRenderer_ = rendererName.find("llvmpipe") != std::string::npos ||
                            rendererName.find("softpipe") != std::string::npos;
        renderer_ = std::make_unique<Renderer>(
            shaderRoot, windowRenderSettings(options.request.settings, softwareRenderer_, options.likeRender));
        renderer_->setAsyncGpuTimers(true);
        methodFiles_ = std::make_unique<MethodFiles>(*this, controls_, shaderRoot, options.frameLimit == 0);
        loading_->show(LoadingScreen::Collision, *uiRenderer_);
        startScene(start);
        input_ = std::make_unique<WindowInput>(window_, controls_, camera_, *this, options.inputScript);
        controls_.moveSpeed = camera_.preferredMode() == ui::MoveMode::Walk
                                  ? kWalkingSpeed
                                  : std::clamp(glm::length(start.target - start.position) * 0.5f, 0.05f, 20.0f);

        controls_.vsync = options.vsync && options.frameLimit == 0;
        window_.setVsync(controls_.vsync);
        uiHidden_ = options.hideUi;
        log::info("view: ", rendererName, ", ", window_.versionString());
        resolution_ = std::make_unique<WindowResolution>(shaderRoot, softwareRenderer_, writesFrameScreenshots(options),
                                                         options.likeRender, options.renderScale,
                                                         options.targetFps);
        if (options.playWalkthrough) camera_.togglePathPlaying();
    }

    ~Walkthrough() override {
        window_.makeCurrent();  // GL objects die with the context current
    }

    int run() {
        prepareBehindLoadingFrame();
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
            // Frame 0 builds shaders and the environment; a still view holds its scale (window_resolution.h).
            if (frame >= 2) resolution_->addFrame(dt * 1e3, stillFrames_);
            int width = 0, height = 0;
            window_.framebufferSize(width, height);
            WindowEvents events = window_.takeEvents();
            input_->beginFrame(events, start, now);
            if (width <= 0 || height <= 0) {  // minimised: wait for events instead of spinning
                glfwWaitEventsTimeout(0.1);
                continue;
            }
            methodFiles_->poll();
            ui::Input uiInput = input_->panelInput(events, width, height);
            buildUi(uiInput, width, height);
            input_->moveCamera(events, previous, now, width, height);
            previous = now;
            // Eye adaptation: the metered exposure moves towards each frame's target with a 0.5 s time constant
            // (headless --frames runs converge at once, like offscreen renders).
            renderer_->setExposureAdaptation(options_.frameLimit == 0 && frame > 0 ? float(1.0 - std::exp(-dt / 0.5)) : 1.0f);
            drawFrame(width, height);
            for (const auto& [at, file] : options_.frameScreenshots)
                if (frame + 1 == at) writeScreenshot(file);
            if (options_.screenshot && frame + 1 == options_.frameLimit) writeScreenshot(*options_.screenshot);
            window_.swapBuffers();
            if (!loading_->finished()) finishLoading();
            if (input_->scriptQuit()) window_.requestClose();  // after a pending screenshot
            input_->startScriptClock(glfwGetTime() - start);
        }
        if (options_.printStats) printStats();
        return 0;
    }

private:
    // The environment before the first frame, and the frame's on-demand work (probes, glint data, the sky bake) in
    // it, each step named on the loading frame.
    void prepareBehindLoadingFrame() {
        // What only refines the image waits for the frames after the first picture, one a frame: the environment's
        // prefilter (1-3 s on llvmpipe when not in the disk cache; a preview until then), the probes' capture (1.5
        // s) and the environment glints (0.6 s). Warm caches supply the first two at once. Headless runs that write
        // screenshots of given frames are captures: their every frame is complete.
        pacedRefinements_ = !writesFrameScreenshots(options_);
        if (pacedRefinements_) renderer_->setRefinementPace(Renderer::RefinementPace::Deferred);
        loading_->show(LoadingScreen::Environment, *uiRenderer_);
        renderer_->prepareEnvironment(scene_);
        renderer_->setPrepareListener([this](const std::string& pass) {
            if (auto step = LoadingScreen::stepOfPass(pass)) loading_->show(*step, *uiRenderer_);
        });
    }
    void finishLoading() {
        if (pacedRefinements_) renderer_->setRefinementPace(Renderer::RefinementPace::OnePerFrame);
        renderer_->setPrepareListener({});
        loading_->finish();
    }

    void printStats() const {
        nlohmann::json stats = resolution_->statsJson();
        stats["scene"] = baseScene_.name;
        stats["camera"] = startCamera_;
        stats["method"] = renderer_->settings().method;
        stats["ibl"] = renderer_->settings().ibl;
        int w = 0, h = 0;
        window_.framebufferSize(w, h);
        stats["window"] = {w, h};
        stats["gl_renderer"] = window_.rendererString();
        stats["walkthrough"] = options_.playWalkthrough;
        stats["vsync"] = controls_.vsync;
        std::printf("%s\n", stats.dump().c_str());
    }

    // ---- what keys and the panel ask for (WindowActions, MethodFilesHost) ----
    void reloadAllShaders() override { methodFiles_->reloadShaders({}, true); }
    void requestScreenshot(bool hdr) override { pendingScreenshot_ = hdr ? 2 : 1; }
    void toggleUi() override { uiHidden_ = !uiHidden_; }
    void toggleRecording() override { camera_.toggleRecording(now_); }
    bool pointerOverUi() const override { return showUi() && ui_.mouseOverUi(); }
    void dragDivider(ui::Input& input, bool leftPressed, int width) override {
        split_.dragDivider(input, leftPressed, pointerOverUi(), width);
    }

    void toggleSplit(bool nextMethod) override {
        if (nextMethod) split_.cycleMethod(renderer_->settings().method);
        else split_.toggle();
        if (split_.enabled())
            showMessage("split: " + renderer_->settings().method + " | " + split_.rightMethod(renderer_->settings().method));
    }

    void cycleMethod(int step) override {
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
        announceMethod();
    }

    // I / Shift+I: the next IBL mode that runs with the current method (modes made for one method, such as
    // glint-is for kemppinen2025, are skipped under the others, so every press moves on and the cycle wraps).
    void cycleIblMode(int step) override {
        const auto& modes = iblModes();
        const std::string& method = renderer_->settings().method;
        int n = int(modes.size()), current = 0;
        for (int i = 0; i < n; ++i)
            if (modes[size_t(i)].id == renderer_->settings().ibl) current = i;
        int chosen = current;
        for (int k = 1; k <= n; ++k) {
            int candidate = ((current + step * k) % n + n) % n;
            if (iblModeRunsWith(modes[size_t(candidate)], method)) {
                chosen = candidate;
                break;
            }
        }
        RenderSettings next = renderer_->settings();
        next.ibl = modes[size_t(chosen)].id;
        applySettings(next);
        log::info("view: ibl ", renderer_->settings().ibl);
        showMessage("ibl " + renderer_->settings().ibl);
    }

    void cycleDebugView(int step) override {
        RenderSettings next = renderer_->settings();
        const AovInfo& view = nextDebugView(next.debugView, step);
        next.debugView = view.viewId;
        applySettings(next);
        showMessage("debug view " + view.name + ": " + view.meaning);
    }

    // Live edits: renderer settings (method, parameters, view) and the scene's material/light overrides.
    void applySettings(const RenderSettings& requested) override {
        RenderSettings next = requested;
        edited_ = true;
        renderer_->forgetEditPasses();
        // An IBL mode made for another method (picked on the panel) is refused with a notice in the window's words,
        // not a red error box; the mode in use stays.
        if (const IblMode& mode = findIblMode(next.ibl); !iblModeRunsWith(mode, next.method)) {
            showMessage("IBL mode " + mode.id + " works only with method " + requiredMethodsText(mode) +
                        " (M changes the method)");
            next.ibl = iblModeRunsWith(findIblMode(renderer_->settings().ibl), next.method)
                           ? renderer_->settings().ibl
                           : defaultIblOf(findGlintMethod(next.method));
        }
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
            updateMappedMaterial();
            gpuScene_->updateMaterialsAndLights(scene_);
        }
    }

    Renderer& renderer() override { return *renderer_; }
    Renderer* splitRenderer() override { return split_.renderer(); }
    ui::UiRenderer& uiRenderer() override { return *uiRenderer_; }
    void renameMethod(const std::string& from, const std::string& to) override { split_.renameMethod(from, to); }
    void programsRebuilt() override {
        ++settingsVersion_;
        edited_ = true;
        renderer_->forgetEditPasses();
    }
    void showMessage(const std::string& text) override { overlay_.notify(text, now_); }

    // The whole description of the method in use (the panel may show only its citation) and, when the method maps
    // material values, whose values the "mat" sliders show.
    void announceMethod() {
        const GlintMethod& method = findGlintMethod(renderer_->settings().method);
        std::string text = "method " + method.id + ": " + method.title;
        if (!method.materialMapping.empty() && controls_.mappedMaterial)
            text += "; \"mat\" values: material " + controls_.mappedMaterial->name;
        showMessage(text);
    }

    // ---- scenes ----
    // The method sliders of mapped parameters start from the first glinty material's values (ui/settings_panel.h).
    void updateMappedMaterial() {
        controls_.mappedMaterial.reset();
        for (const Material& m : scene_.materials)
            if (m.glinty) {
                controls_.mappedMaterial = m;
                break;
            }
    }

    // The camera path P plays: --path FILE, else <scene>.path.json in the scene file's folder (the content folder
    // for scenes described there, the current folder for generated ones). R saves elsewhere when that exists.
    std::filesystem::path defaultPathFile() const {
        if (options_.pathFile) return *options_.pathFile;
        std::filesystem::path scene(options_.request.scene);
        std::error_code ec;
        if (std::filesystem::is_regular_file(scene, ec)) return scene.parent_path() / (scene.stem().string() + ".path.json");
        if (std::filesystem::is_regular_file(defaultContentDir() / (baseScene_.name + ".json"), ec))
            return defaultContentDir() / (baseScene_.name + ".path.json");
        return baseScene_.name + ".path.json";
    }

    // Camera, collision and camera path of the current scene, starting at `start`, and the panel's scene list.
    void startScene(const Camera& start) {
        camera_.startScene(scene_, options_.request.scene, start, defaultPathFile(), options_.pathFile.has_value(),
                           options_.inputScript.has_value());
        controls_.sceneNames = builtinSceneNames();
        auto it = std::find(controls_.sceneNames.begin(), controls_.sceneNames.end(), options_.request.scene);
        if (it == controls_.sceneNames.end()) {
            controls_.sceneNames.push_back(options_.request.scene);
            it = controls_.sceneNames.end() - 1;
        }
        controls_.sceneIndex = int(it - controls_.sceneNames.begin());
        controls_.lightNames = ui::lightSelectorNames(baseScene_.lights);
        controls_.lightIndex = 0;
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
        camera_.stopPathPlaying();
        if (controls_.recording) camera_.toggleRecording(now_);
        baseScene_ = std::move(loaded);
        if (options_.request.environment) baseScene_.environment = *options_.request.environment;
        // A light's own edits name the old scene's lights by number: they do not carry over.
        RenderSettings withoutLightEdits = renderer_->settings();
        clearLightEdits(withoutLightEdits);
        if (withoutLightEdits.common != renderer_->settings().common) renderer_->setSettings(withoutLightEdits);
        scene_ = baseScene_;
        applySceneOverrides(renderer_->settings(), scene_);
        updateMappedMaterial();
        gpuScene_ = std::make_unique<GpuScene>(scene_);
        options_.request.scene = name;
        options_.pathFile.reset();
        startScene(baseScene_.cameras.front());
        ++settingsVersion_;
        glfwSetWindowTitle(window_.glfwHandle(), ("Glimmer - " + baseScene_.name).c_str());
        showMessage("scene " + baseScene_.name);
    }

    // ---- UI ----
    bool showUi() const { return !uiHidden_; }

    std::vector<std::string> errors() const {
        // Only compile and link errors are called shader errors; a refused setting or a bad method file is not one.
        std::vector<std::string> all;
        for (const auto& [program, error] : renderer_->shaderErrors())
            all.push_back("SHADER ERROR " + error + "  [" + program + "]");
        if (!methodFiles_->uiError().empty()) all.push_back("SHADER ERROR " + methodFiles_->uiError() + "  [ui]");
        if (!methodError_.empty()) all.push_back("ERROR " + methodError_);
        for (const auto& [file, error] : methodFiles_->fileErrors()) all.push_back("ERROR " + error + "  [method file]");
        return all;
    }

    void buildUi(const ui::Input& input, int width, int height) {
        int scale = ui::panelLayout(width, height, 0).scale;
        ui_.begin(input, width, height, scale);
        float line = ui_.lineHeight();
        float margin = overlayMargin(ui_);
        std::vector<StatsLine> stats;
        if (showUi()) {
            WindowStatus status;
            status.frameMs = frameMs_;
            status.resolution = resolution_->statsText();
            status.position = camera_.camera().position;
            status.moveSpeed = controls_.moveSpeed;
            status.vsync = controls_.vsync;
            status.sampleIndex = frames_.sampleIndex();
            status.mouseCaptured = input_->mouseCaptured();
            status.softwareRenderer = softwareRenderer_;
            status.edited = edited_;
            stats = Overlay::statsLines(*renderer_, status, float(width) - 2.0f * margin, ui_.scale());
        }
        float statsHeight = showUi() ? float(stats.size()) * line + 2.0f * margin : 0.0f;
        Overlay::drawErrors(ui_, errors(), width, height, statsHeight);
        if (showUi()) {
            RenderSettings edited = renderer_->settings();
            ui::PanelResult result =
                ui::settingsPanel(ui_, edited, controls_, margin, margin, float(height) - statsHeight - 2.0f * margin);
            if (result.settingsChanged) {
                std::string before = renderer_->settings().method;
                applySettings(edited);
                if (renderer_->settings().method != before) announceMethod();
            }
            if (result.vsyncChanged) window_.setVsync(controls_.vsync);
            if (result.cameraRequested >= 0) camera_.jumpToCamera(result.cameraRequested);
            if (result.toggleWalkthrough) camera_.togglePathPlaying();
            if (result.toggleWalking) camera_.toggleWalking();
            if (result.toggleRecording) camera_.toggleRecording(now_);
            if (result.sceneRequested >= 0 && result.sceneRequested != controls_.sceneIndex)
                switchScene(controls_.sceneNames[size_t(result.sceneRequested)]);
            if (result.reloadShaders) methodFiles_->reloadShaders({}, true);
            if (result.loadMethodFile >= 0) methodFiles_->loadChoice(result.loadMethodFile);
            if (result.screenshot) pendingScreenshot_ = 1;
            overlay_.drawStats(ui_, stats, width, height, statsHeight, now_);
            if (split_.enabled()) split_.drawLabels(ui_, renderer_->settings().method, width, margin, line);
        }
        ui_.end();
    }

    // ---- frame ----
    void drawFrame(int width, int height) {
        int renderW = width, renderH = height;
        resolution_->internalSize(width, height, renderW, renderH);
        const Camera& camera = camera_.camera();
        bool still = camera.position == stillCamera_.position && camera.target == stillCamera_.target &&
                     camera.up == stillCamera_.up && camera.verticalFovDegrees == stillCamera_.verticalFovDegrees &&
                     settingsVersion_ == stillVersion_;
        stillFrames_ = still ? stillFrames_ + 1 : 0;
        stillCamera_ = camera;
        stillVersion_ = settingsVersion_;
        frames_.render(*renderer_, scene_, *gpuScene_, camera, width, height, renderW, renderH, settingsVersion_);
        present_.resize(width, height);
        resolution_->present(*renderer_, present_.framebuffer(), width, height);
        if (split_.enabled())
            if (auto error = split_.render(*renderer_, frames_, *resolution_, present_.framebuffer(), scene_,
                                           *gpuScene_, camera_.camera(), width, height))
                methodError_ = *error;
        glBindFramebuffer(GL_FRAMEBUFFER, present_.framebuffer());
        uiRenderer_->draw(ui_.drawList(), width, height);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glBlitNamedFramebuffer(present_.framebuffer(), 0, 0, 0, width, height, 0, 0, width, height,
                               GL_COLOR_BUFFER_BIT, GL_NEAREST);
        for (const std::string& path : input_->dueScriptScreenshots()) writeScreenshot(path);
        if (pendingScreenshot_) {
            writeScreenshot(nextScreenshotName(baseScene_.name, pendingScreenshot_ == 2 ? ".exr" : ".png"));
            pendingScreenshot_ = 0;
        }
    }

    void writeScreenshot(const std::string& path) {
        writeWindowScreenshot(path, *renderer_, present_);
        if (options_.frameLimit > 0) std::printf("%s\n", path.c_str());
        log::info("view: wrote ", path);
        showMessage("wrote " + path);
    }

    ViewOptions options_;
    Scene baseScene_, scene_;
    GlfwWindow window_;
    ui::WindowControls controls_;
    CameraMotion camera_;
    SplitView split_;
    FrameDriver frames_;
    Overlay overlay_;
    std::unique_ptr<GpuScene> gpuScene_;
    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<ui::UiRenderer> uiRenderer_;
    std::unique_ptr<LoadingScreen> loading_;
    std::unique_ptr<MethodFiles> methodFiles_;
    std::unique_ptr<WindowInput> input_;
    std::unique_ptr<WindowResolution> resolution_;
    PresentTarget present_;
    ui::Context ui_;
    bool uiHidden_ = false, softwareRenderer_ = false;
    bool pacedRefinements_ = false;   // Renderer::RefinementPace: Deferred, then OnePerFrame (else AllAtOnce)
    bool edited_ = false;            // an edit happened (the strip's "last edit" line is about it)
    double frameMs_ = 0.0, now_ = 0.0;
    uint64_t settingsVersion_ = 0;   // every edit that restarts the accumulation changes it
    std::string methodError_;
    std::string startCamera_;        // the camera the window opened at (the scene's first unless --camera)
    int pendingScreenshot_ = 0;      // 1 PNG, 2 EXR, at the end of this frame
    // Consecutive frames drawn with the same camera and settings (window_resolution.h holds the scale then).
    unsigned stillFrames_ = 0;
    Camera stillCamera_;
    uint64_t stillVersion_ = ~uint64_t(0);
};

}  // namespace

int runWalkthroughWindow(const ViewOptions& options) {
    Walkthrough walkthrough(options);
    return walkthrough.run();
}

}  // namespace glimmer
