#include "app/walkthrough/method_files.h"

#include <algorithm>

#include "app/walkthrough/overlay.h"
#include "core/clock.h"
#include "core/files.h"
#include "core/log.h"
#include "glints/user/user_methods.h"

namespace glimmer {

MethodFiles::MethodFiles(MethodFilesHost& host, ui::WindowControls& controls, const std::filesystem::path& shaderRoot,
                         bool watch)
    : host_(host), controls_(controls) {
    if (watch) {
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
}

void MethodFiles::poll() {
    if (!watcher_) return;
    std::vector<std::filesystem::path> changed = watcher_->poll();
    // The folders of method files outside the shader root hold other files too (screenshots, notes): only the
    // files the programs read count as edits; anything else there may only add or remove a method file choice.
    auto canonical = [](const std::filesystem::path& f) {
        std::error_code ec;
        std::filesystem::path c = std::filesystem::weakly_canonical(f, ec);
        return ec ? f : c;
    };
    std::vector<std::filesystem::path> dependencies;
    for (const auto& f : watchedFiles()) dependencies.push_back(canonical(f));
    bool otherFiles = false;
    for (auto& [folder, watcher] : methodWatchers_)
        for (const auto& f : watcher->poll()) {
            if (std::find(dependencies.begin(), dependencies.end(), canonical(f)) == dependencies.end())
                otherFiles = true;
            else if (std::find(changed.begin(), changed.end(), f) == changed.end()) changed.push_back(f);
        }
    if (changed.empty()) {
        if (otherFiles) refreshMethodFileChoices();
        return;
    }
    for (const auto& f : changed) log::info("view: shader changed: ", f.string());
    replacedMethods_.clear();
    reloadMethodHeaders(changed);
    reloadShaders(changed, false);
    // A new header whose body does not compile: the last good program runs on, so its header (the parameter
    // block's layout) comes back too.
    for (const auto& [method, settings] : replacedMethods_) {
        bool failed = false;
        for (const auto& [program, error] : host_.renderer().shaderErrors()) failed |= program.find("lighting/") == 0;
        if (!failed) continue;
        registerGlintMethod(method);
        host_.applySettings(settings);
    }
    watchMethodFolders();
    refreshMethodFileChoices();
}

// User methods (--method-file, glints/user/user_methods.h) may live anywhere: their folders and the folders of the
// files they include from outside the shader root are watched too (without subfolders).
std::vector<std::filesystem::path> MethodFiles::watchedFiles() const {
    std::vector<std::filesystem::path> files = host_.renderer().shaderDependencies();
    if (Renderer* split = host_.splitRenderer())
        for (const auto& f : split->shaderDependencies()) files.push_back(f);
    for (const GlintMethod& m : glintMethods())
        if (m.isUserMethod()) files.push_back(m.sourceFile);
    return files;
}

void MethodFiles::watchMethodFolders() {
    if (!watcher_) return;
    for (const auto& file : watchedFiles()) {
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

// A changed user method file: its header is parsed again before the program is rebuilt. A header that does not
// parse keeps the last good method and program; a good one replaces the table entry, and the parameter values that
// still exist are kept (clamped).
void MethodFiles::reloadMethodHeaders(std::vector<std::filesystem::path>& changed) {
    for (auto it = changed.begin(); it != changed.end();) {
        const GlintMethod* old = userMethodForFile(*it);
        if (!old) {
            ++it;
            continue;
        }
        const std::filesystem::path file = *it;
        GlintMethod fresh;
        try {
            fresh = readUserMethodFile(file);
            replacedMethods_.push_back({*old, host_.renderer().settings()});
            std::string previous = registerGlintMethod(fresh);
            methodFileErrors_.erase(file);
            RenderSettings next = host_.renderer().settings();
            ParamValues values = carryParamValues(next.methodValues(previous), fresh);
            next.methods.erase(previous);
            next.methods[fresh.id] = values;
            if (next.method == previous) next.method = fresh.id;
            host_.renameMethod(previous, fresh.id);
            // Same method id: only values change (the program is rebuilt below); a renamed method rebuilds.
            host_.applySettings(next);
            std::string note =
                "method " + fresh.id + ": header read (" + std::to_string(fresh.params.size()) + " parameters)";
            log::info("view: ", note);
            host_.showMessage(note);
            ++it;
        } catch (const std::exception& e) {
            methodFileErrors_[file] = e.what();
            log::error("view: ", e.what());
            it = changed.erase(it);   // keep the last good program: do not rebuild from a broken header
        }
    }
}

// The panel's "load" buttons: method files of content/methods/ and of the folders of loaded methods.
void MethodFiles::refreshMethodFileChoices() {
    std::vector<std::filesystem::path> folders = {defaultContentDir() / "methods"};
    for (const GlintMethod& m : glintMethods())
        if (m.isUserMethod() &&
            std::find(folders.begin(), folders.end(), m.sourceFile.parent_path()) == folders.end())
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

void MethodFiles::loadChoice(int index) {
    if (index >= 0 && size_t(index) < methodFileChoices_.size()) loadMethodFile(methodFileChoices_[size_t(index)]);
}

void MethodFiles::loadMethodFile(const std::filesystem::path& file) {
    try {
        std::string id = loadUserMethodFile(file);
        methodFileErrors_.erase(file);
        RenderSettings next = host_.renderer().settings();
        next.method = id;
        host_.applySettings(next);
        host_.showMessage("method " + id + " from " + displayPath(file));
    } catch (const std::exception& e) {
        methodFileErrors_[file] = e.what();
        host_.showMessage(e.what());
    }
    watchMethodFolders();
    refreshMethodFileChoices();
}

void MethodFiles::reloadShaders(const std::vector<std::filesystem::path>& changed, bool all) {
    std::vector<std::filesystem::path> files = changed;
    if (all) {
        files = host_.renderer().shaderDependencies();
        const auto& ui = host_.uiRenderer().dependencies();
        files.insert(files.end(), ui.begin(), ui.end());
    }
    Stopwatch clock;
    std::vector<std::string> rebuilt = host_.renderer().reloadChangedPrograms(files);
    if (Renderer* split = host_.splitRenderer()) split->reloadChangedPrograms(files);
    host_.programsRebuilt();
    try {
        if (host_.uiRenderer().reloadIfChanged(files)) rebuilt.push_back("ui");
        uiError_.clear();
    } catch (const std::exception& e) {
        uiError_ = e.what();
    }
    if (!rebuilt.empty()) {
        std::string names;
        for (const auto& n : rebuilt) names += (names.empty() ? "" : ", ") + n;
        log::info("view: rebuilt ", names, " in ", twoDecimals(clock.elapsedMs()), " ms");
        host_.showMessage("rebuilt " + names);
    }
    for (const auto& [program, error] : host_.renderer().shaderErrors()) log::error("shader ", program, ": ", error);
    if (!uiError_.empty()) log::error("shader ui: ", uiError_);
}

}  // namespace glimmer
