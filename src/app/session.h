// session.h: the workbench's sessions (.oitsession, docs/sessions.md): the
// model, the render settings (a preset: the command line's flag names), the
// camera, the named saved views and what Export PNG renders (its size and
// matrices, which `oit render --session` uses). JSON through RapidJSON, as
// presets; the command line reads the same file with cJSON (src/cli/session_file.c).
#pragma once

#include <string>
#include <vector>

#include "settings.h"

constexpr const char *kSessionFormat = "oit-session";
constexpr int kSessionVersion = 1; // the newest this build writes and reads

// What a session holds once read. The render object is kept as JSON text
// (a preset, applied with preset_from_json once the model is loaded).
struct SessionData {
    std::string model_path;  // absolute: relative paths resolved against the session's folder
    std::string render;      // a preset's JSON object, "" if the session has none
    std::vector<SavedView> views;
    int export_width = 0, export_height = 0; // 0: not stored
    int export_aids = -1;                     // "export": "aids" (Include in exports): -1 not stored, 0, 1
    std::vector<std::string> warnings;      // unknown fields, ignored: "FILE: ..."
};

// The export's frame: what `oit render --session` renders (matrices column-major, as oit_frame_settings).
struct SessionExport {
    int width = 0, height = 0;
    double modelview[16] = {}, projection[16] = {};
    bool aids = false; // the orientation aids drawn on it (View > Orientation aids > Include in exports)
    int samples = 0;   // its samples per pixel (export_samples: exports always anti-alias); 0: not written
};

// The session file's text. model_path is written relative to the session's folder.
std::string session_to_json(const std::string &session_path, const std::string &model_path,
                            const RenderSettings &settings, const Camera &camera, const oit_model *model,
                            const std::vector<SavedView> &views, const SessionExport &exported);

// Reads a session; false with a one-line "FILE: problem" in error for
// malformed JSON, a wrong "format", a newer "version", a bad field or a model
// that does not exist. Unknown fields (top level, "render", "export", views)
// are dropped with a warning each; missing ones take their defaults.
bool session_from_json(const std::string &session_path, const std::string &text, SessionData &out,
                       std::string &error);
