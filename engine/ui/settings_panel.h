// The walkthrough window's control panel, generated from the tables: a method selector, one slider per
// parameter of the current method (ParamSpec ranges, integer, logScale, choices), the common parameters grouped
// by prefix (image, light, env, material overrides), the debug-view selector and the window's own controls.
// A method added to glintMethods() or a parameter added to commonParams() gets its widgets with no UI code.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "glints/methods.h"
#include "render/settings.h"
#include "scene/scene.h"
#include "ui/ui.h"

namespace glimmer::ui {

// Window state shown and edited by the panel.
struct WindowControls {
    bool vsync = true;
    float moveSpeed = 1.0f;                 // metres per second
    std::vector<std::string> sceneNames;    // scenes the panel can switch to
    int sceneIndex = 0;
    std::vector<std::string> cameraNames;   // scene cameras, jumped to with keys 1..9
    int cameraIndex = 0;                    // the camera last jumped to
    bool walkthroughPlaying = false;
    bool walking = false;                   // walking (collision) or flying
    bool recording = false;                 // a camera path is being recorded (R)
    bool hasRecordedPath = false;           // P plays the recorded (or loaded) path instead of the cameras
    // User glint method files the panel offers to load (content/methods/ and the folders of loaded ones), as
    // shown; glints/user/user_methods.h.
    std::vector<std::string> methodFileChoices;
    // The material whose mapped values the method sliders start from while a mapped parameter is not set (the
    // scene's first glinty material, with the material overrides applied); none: they start from the default.
    // Without it one arrow press set log_density to default + 1 = 17 on every material and wiped the glints.
    std::optional<Material> mappedMaterial;
    // The scene's lights as the "edit light" selector names them ("1 sun", "2 sphere", ...: lightNames), and the
    // one whose own edits (lightEditParams, settings key light.<N>.<field>) the Lights section shows.
    std::vector<std::string> lightNames;
    int lightIndex = 0;
};

// The selector's names of a scene's lights: number (as in --set light.<N>.<field>), kind, and where it is.
std::vector<std::string> lightSelectorNames(const std::vector<Light>& lights);

struct PanelResult {
    bool settingsChanged = false;   // anything in RenderSettings (method, parameters, debug view)
    bool methodChanged = false;
    int cameraRequested = -1;       // index into cameraNames
    int sceneRequested = -1;        // index into sceneNames
    bool toggleRecording = false;
    bool toggleWalkthrough = false;
    bool toggleWalking = false;
    bool reloadShaders = false;
    bool vsyncChanged = false;
    bool screenshot = false;
    int loadMethodFile = -1;        // index into methodFileChoices
};

constexpr int kPanelWidthChars = 34;
constexpr const char* kPanelId = "settings";

// Where the window puts the panel: an integer text scale chosen by window height, the margin, and the height
// left above a stats strip of `statsLines` lines (kMaxStatsLines at most).
struct PanelLayout {
    int scale = 1;
    float margin = 4.0f;
    float x = 4.0f, y = 4.0f, maxHeight = 0.0f;
};
constexpr int kMaxStatsLines = 4;
PanelLayout panelLayout(int width, int height, int statsLines);

// What a method parameter's row shows instead of its number: "material" for a parameter that each glint material
// maps (deliot2023's log_density, kemppinen2025's alpha*, ...) while no override is set, since the materials'
// mapped values are then in effect, not the spec's default; nullptr (show the number) otherwise.
const char* methodParameterValueText(const GlintMethod& method, const RenderSettings& settings,
                                     const std::string& name);

// What the panel shows of a method's description: all of it where it fits the panel's width, else the citation
// before " (" (the window's notice shows the whole description when the method is selected).
std::string panelMethodTitle(const std::string& title, int uiScale);

// The speed slider's range (also used by the wheel).
ParamSpec moveSpeedSpec();

PanelResult settingsPanel(Context& ui, RenderSettings& settings, WindowControls& window, float x, float y,
                          float maxHeight, const std::vector<GlintMethod>& methods = glintMethods());

// Heading for a common parameter group ("" -> "Image", "light" -> "Lights", ...); unknown prefixes as is.
std::string commonGroupTitle(const std::string& prefix);
// Common parameters set only with --set or a scene file (bake and sampling settings), not in the panel.
bool panelHidesParameter(const std::string& name);

}  // namespace glimmer::ui
