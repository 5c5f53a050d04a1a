// settings.h: everything that decides a frame besides the model: the algorithm
// and its configuration, opacity, modulations, per-part opacity, the camera.
// Turns into oit_frame_settings, into the equivalent `oit render` command, and
// into / out of preset JSON (RapidJSON). Names follow the command line's flags.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "camera.h"
#include "oit.h"

// The split view (split_view.h): off, two algorithms either side of a wipe
// line over the whole view, or side by side at half the view's width each.
enum class SplitMode { Off = 0, Wipe = 1, SideBySide = 2 };
const char *split_mode_name(SplitMode mode); // "off", "wipe", "side-by-side"
bool parse_split_mode(const std::string &text, SplitMode &mode);

// A section plane (--section NX,NY,NZ,D; docs/sections.md): keeps the points p
// with dot(normal, p) <= d, model (file) coordinates of the model as drawn
// (exploded where it is). A disabled plane stays in the list (the Sections
// tab) but cuts nothing and is not in the command.
struct SectionPlane {
    double normal[3] = {1.0, 0.0, 0.0}; // never zero
    double d = 0.0;
    bool enabled = true;
    bool operator==(const SectionPlane &o) const
    {
        return normal[0] == o.normal[0] && normal[1] == o.normal[1] && normal[2] == o.normal[2] && d == o.d &&
               enabled == o.enabled;
    }
};

struct RenderSettings {
    std::string algorithm = "ll";
    oit_algorithm_config config{}; // shader_dir is set by the view
    float alpha = 0.5f;
    oit_shading_mode shading = OIT_SHADE_HEADLIGHT;
    float background[3] = {1.0f, 1.0f, 1.0f};
    oit_modulation modulation{};
    oit_focus_shape focus_shape = OIT_FOCUS_NONE;
    double focus[6] = {0, 0, 0, 0, 0, 0}; // model (file) coordinates
    float contrast = 1.0f;
    // per component of the loaded model; opacity used = visible ? part_alpha : 0
    std::vector<float> part_alpha;
    std::vector<char> part_visible;
    // the workbench's comparisons (preset keys "error-vs-reference", "split",
    // "split-algorithm", "wipe"; the command line has the first only)
    bool error_view = false;           // show the error map against the CPU reference
    SplitMode split = SplitMode::Off;
    std::string split_algorithm = "blend"; // side B; side A is `algorithm`
    float wipe = 0.5f;                 // the wipe line, 0..1 of the view's width
    // "Preview algorithm while moving" (preset key "preview-algorithm"): the
    // stand-in that renders while the camera or a slider moves and full frames
    // are slow: "auto" (ll at a coarse scale, or wboit where ll's fill is too
    // slow), "same" (the chosen algorithm, coarse) or an algorithm's name;
    // render_worker.h has the rules
    std::string preview_algorithm = "auto";
    // how STEP and IGES files are tessellated (--tessellation; applies when a
    // model is loaded)
    oit_import_options import{};
    // issue 28: sections and the exploded view (the Sections tab; preset keys
    // "section", "section-parts", "caps", "explode", the command line's flags)
    std::vector<SectionPlane> sections; // at most OIT_SECTION_PLANES_MAX
    // per component of the loaded model, nonzero where the sections cut it;
    // empty: every part (presets say "all", or the parts' names)
    std::vector<char> section_parts;
    bool caps = true;    // --caps on|off
    double explode = 0.0; // --explode F, 0..OIT_EXPLODE_MAX
    // issue 29: the orientation aids (View menu; preset keys "axes": a corner
    // or "off", "scale-bar", the command line's flags). The view shows what
    // these say; exports and Copy as command carry them when aids_in_export is
    // on (View > Include aids in exports, or Export PNG's box; not in presets)
    bool axes = true; // the triad, shown by default
    oit_corner axes_corner = OIT_CORNER_BOTTOM_LEFT;
    bool scale_bar = false;
    bool aids_in_export = false;
    // Anti-aliasing (issue 29; --samples, preset key "samples": "auto", 1, 4, 8
    // or 16): 0 is Auto, the view's frames at 1 sample while the view moves and
    // again at kAutoSamples once it is still (render_worker.h has the rule);
    // 1 is off; 4, 8, 16 every full frame. Exports use export_samples().
    int samples = 0;
    static constexpr int kAutoSamples = 4;

    RenderSettings();
    void reset_parts(const oit_model &model);
    bool parts_modified() const;
};

// The frame for width x height with the camera's matrices; component_alpha
// points into storage, which must outlive the frame; local.section_parts into
// settings.section_parts (the settings must outlive it too). The enabled
// sections, in order, are local.sections (apply_sections).
oit_frame_settings make_frame(const RenderSettings &settings, const oit_model &model, const Camera &camera,
                              int width, int height, std::vector<float> &storage);

// The enabled section planes (the first OIT_SECTION_PLANES_MAX), which parts
// they cut and the caps into local; section_parts points into settings.
void apply_sections(const RenderSettings &settings, const oit_model &model, oit_local_modulation &local);

// The orientation aids the view shows (settings.axes, scale_bar), and those an
// export and Copy as command carry (none unless settings.aids_in_export).
oit_overlay_options view_aids(const RenderSettings &settings);
oit_overlay_options export_aids(const RenderSettings &settings);
// The samples of the frame the view settles on (Auto: kAutoSamples in the
// colour view without the error map, else 1) and of an export (at least
// kAutoSamples: exports always anti-alias).
int view_samples(const RenderSettings &settings);
int export_samples(const RenderSettings &settings);

// --tessellation's value: "normal", "coarse", "fine" or the millimetres.
std::string tessellation_name(const oit_import_options &import);

// --view value ("heatmap", "peel-limit:4", ...) and back.
std::string view_name(const oit_modulation &modulation);
bool parse_view(const std::string &text, oit_modulation &modulation);
const char *modulation_mode_name(oit_modulation_mode mode);

// The Algorithm tab's summary: the core's one line and whether the algorithm
// is exact, "(exact)" or "(approximate)", unless the line already says so
// (mboit's ends in "approximate": never "approximate (approximate)").
std::string algorithm_summary(const oit_algorithm_ops &ops);

// The `oit render` command that reproduces a frame (matrices row by row, with
// enough digits that every double survives the round trip). With the error
// view, --error-vs-reference and --error-map (out_path's name with "-error").
// The command line has no split view: the command is side A's.
std::string render_command(const std::string &oit_program, const std::string &model_path,
                           const RenderSettings &settings, const oit_frame_settings &frame,
                           const std::string &out_path);

// Presets: a JSON object whose keys are the command line's flag names.
std::string preset_to_json(const RenderSettings &settings, const Camera &camera, const oit_model *model);
// The settings a preset lacking every key gives: RenderSettings' defaults, with
// current's parts (without a model they cannot be matched) and what presets
// do not hold (the shader folder, the tests' configuration). The one place
// the reader's defaults are resolved.
RenderSettings preset_defaults(const RenderSettings &current);
// On failure returns false with "FILE:LINE: problem" in error. Every setting
// the preset lacks takes its default (preset_defaults), so a preset gives the
// same state whatever came before. The camera is changed only if the preset
// has one (its fov, mode and projection default too; the pose is kept if the
// preset lacks it); parts are matched by name against model.
bool preset_from_json(const std::string &file_name, const std::string &text, RenderSettings &settings,
                      Camera &camera, bool &has_camera, const oit_model *model, std::string &error);

// The workbench's saved state (saved_state.h) as JSON: {"settings": a preset
// (the last settings), "last-model": a file name, "recent": [file names],
// "geometry" and "window": base64 (QMainWindow's saveGeometry, saveState)},
// every key optional. Reading checks every value, the settings as a preset
// (ranges, names; parts once a model is loaded), and fails with
// "FILE:LINE: problem" on the first bad one.
// A camera pose the user saved and named (the Camera tab's saved views).
struct SavedView {
    std::string name;
    Camera camera;
};
struct SavedStateText {
    std::string settings; // preset JSON, "" for none
    std::string last_model;
    std::vector<std::string> recent;
    std::string geometry, window; // base64
    // "views": {model file: [{"name", "camera": a preset's camera}]}, kept
    // across model loads and restarts
    std::map<std::string, std::vector<SavedView>> views;
    // "export-folder", "export-size": [w, h]: Export PNG's last folder and
    // chosen size (0 x 0: the view's size)
    std::string export_folder;
    int export_width = 0, export_height = 0;
    // "recent-sessions": File > Open recent session, newest first (docs/sessions.md)
    std::vector<std::string> recent_sessions;
};
bool saved_state_from_json(const std::string &file_name, const std::string &text, SavedStateText &out,
                           std::string &error);
std::string saved_state_to_json(const SavedStateText &state);

// config/models.json: [{"name", "path"}]; relative paths are taken from base_dir.
struct ModelEntry {
    std::string name, path;
};
bool read_model_list(const std::string &file_name, const std::string &text, const std::string &base_dir,
                     std::vector<ModelEntry> &out, std::string &error);
