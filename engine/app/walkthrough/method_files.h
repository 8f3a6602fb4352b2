// Shader hot reload and user glint method files in the window: shaders/ and the folders of user methods (and of
// the files they include) are watched; a changed file rebuilds the programs that use it, a changed method file
// has its header read again first (a broken header or body keeps the last good method and program, and its error
// stays on screen until fixed). The panel's "load" buttons load method files.
#pragma once
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/file_watcher.h"
#include "glints/methods.h"
#include "render/renderer.h"
#include "render/settings.h"
#include "ui/settings_panel.h"
#include "ui/ui_renderer.h"

namespace glimmer {

// What reloading needs from the window.
class MethodFilesHost {
public:
    virtual ~MethodFilesHost() = default;
    virtual Renderer& renderer() = 0;
    virtual Renderer* splitRenderer() = 0;       // null while the split has not been shown
    virtual ui::UiRenderer& uiRenderer() = 0;
    virtual void applySettings(const RenderSettings& next) = 0;
    virtual void renameMethod(const std::string& from, const std::string& to) = 0;   // a header renamed a method
    virtual void programsRebuilt() = 0;          // a rebuilt shader starts a new accumulation
    virtual void showMessage(const std::string& text) = 0;
};

class MethodFiles {
public:
    // `watch`: interactive windows watch files; headless --frames runs build once and fail on any error.
    // `controls`: the panel's list of method files to load is kept there.
    MethodFiles(MethodFilesHost& host, ui::WindowControls& controls, const std::filesystem::path& shaderRoot,
                bool watch);

    // Reloads what changed on disk since the last call.
    void poll();
    // Rebuilds the programs using `changed`, or every program (F5). Errors stay in the overlay until fixed.
    void reloadShaders(const std::vector<std::filesystem::path>& changed, bool all);
    // The panel's load button `index` (into ui::WindowControls::methodFileChoices).
    void loadChoice(int index);

    const std::string& uiError() const { return uiError_; }
    // Header errors of method files, "file:line: message".
    const std::map<std::filesystem::path, std::string>& fileErrors() const { return methodFileErrors_; }

private:
    // Every file the programs read (both renderers) and every user method file.
    std::vector<std::filesystem::path> watchedFiles() const;
    void watchMethodFolders();
    void reloadMethodHeaders(std::vector<std::filesystem::path>& changed);
    void refreshMethodFileChoices();
    void loadMethodFile(const std::filesystem::path& file);

    MethodFilesHost& host_;
    ui::WindowControls& controls_;
    std::unique_ptr<FileWatcher> watcher_;
    std::map<std::filesystem::path, std::unique_ptr<FileWatcher>> methodWatchers_;   // user methods' folders
    std::map<std::filesystem::path, std::string> methodFileErrors_;
    std::vector<std::filesystem::path> methodFileChoices_;            // what the panel's load buttons load
    std::vector<std::pair<GlintMethod, RenderSettings>> replacedMethods_;   // entries a reload replaced (undo)
    std::string uiError_;
};

}  // namespace glimmer
