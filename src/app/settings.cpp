// settings.cpp: see settings.h.
#include "settings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cctype>
#include <cstring>
#include <memory>
#include <sstream>
#include <vector>

#include <rapidjson/document.h>
#include <rapidjson/error/en.h>
#include <rapidjson/prettywriter.h>
#include <rapidjson/stringbuffer.h>

RenderSettings::RenderSettings()
{
    oit_algorithm_config_defaults(&config);
}

void RenderSettings::reset_parts(const oit_model &model)
{
    part_alpha.assign(model.component_count, 1.0f);
    part_visible.assign(model.component_count, 1);
    section_parts.clear(); // every part: the flags were another model's
}

bool RenderSettings::parts_modified() const
{
    for (size_t i = 0; i < part_alpha.size(); ++i)
        if (part_alpha[i] != 1.0f || !part_visible[i])
            return true;
    return false;
}

oit_frame_settings make_frame(const RenderSettings &s, const oit_model &model, const Camera &camera, int width,
                              int height, std::vector<float> &storage)
{
    oit_frame_settings frame;
    std::memset(&frame, 0, sizeof frame);
    frame.width = width;
    frame.height = height;
    // side by side, each half shows what the whole view (twice as wide) frames
    double framed_aspect = s.split == SplitMode::SideBySide ? 2.0 * width / std::max(1, height) : 0.0;
    camera.matrices(width, height, frame.modelview, frame.projection, framed_aspect);
    frame.alpha = s.alpha;
    frame.shading = s.shading;
    frame.samples = view_samples(s); // the view's still frame (render_worker.h); exports raise it
    std::copy(s.background, s.background + 3, frame.background);
    frame.modulation = s.modulation;
    storage.clear();
    if (s.part_alpha.size() == model.component_count && s.parts_modified()) {
        for (size_t i = 0; i < s.part_alpha.size(); ++i)
            storage.push_back(s.part_visible[i] ? s.part_alpha[i] : 0.0f);
        frame.local.component_alpha = storage.data();
        frame.local.component_count = model.component_count;
    }
    frame.local.focus_shape = s.focus_shape;
    std::copy(s.focus, s.focus + 6, frame.local.focus);
    frame.local.contrast = s.contrast;
    frame.local.focus_default_region = model.radius / 4.0f; // as the command line
    apply_sections(s, model, frame.local);
    return frame;
}

void apply_sections(const RenderSettings &s, const oit_model &model, oit_local_modulation &local)
{
    local.section_count = 0;
    for (const SectionPlane &plane : s.sections) {
        if (!plane.enabled || local.section_count >= OIT_SECTION_PLANES_MAX)
            continue;
        double *out = local.sections[local.section_count++];
        std::copy(plane.normal, plane.normal + 3, out);
        out[3] = plane.d;
    }
    local.section_parts = nullptr;
    local.section_parts_count = 0;
    if (local.section_count > 0 && s.section_parts.size() == model.component_count) {
        local.section_parts = reinterpret_cast<const uint8_t *>(s.section_parts.data());
        local.section_parts_count = model.component_count;
    }
    local.no_caps = !s.caps;
}

namespace {

// The words are the core's (oit_setting_word); a preset also says "default"
// for the neighbour search it leaves to the core (0), as it always has.
const char *neighbour_word(oit_neighbour_search search)
{
    return search == OIT_NEIGHBOURS_DEFAULT ? "default" : oit_setting_word(OIT_SETTING_NEIGHBOURS, search);
}

// %.9g: every float survives text and back
std::string number(double value)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.9g", value);
    return buffer;
}

// Every double survives the round trip (matrices, coordinates).
std::string exact_number(double value)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.17g", value);
    return buffer;
}

// The shortest text that reads back as the same double ("0.1", not
// "0.10000000000000001"): sections and the explode factor are typed or slid.
std::string short_exact(double value)
{
    char buffer[64];
    for (int digits = 6; digits < 17; ++digits) {
        std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
        if (std::strtod(buffer, nullptr) == value)
            return buffer;
    }
    return exact_number(value);
}

std::string shell_quote(const std::string &text)
{
    bool plain = !text.empty();
    for (char c : text)
        plain = plain && (std::isalnum((unsigned char)c) || std::strchr("/._-+=,:@%", c));
    if (plain)
        return text;
    std::string out = "'";
    for (char c : text)
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string distance_name(const oit_modulation &m)
{
    if (m.distance == OIT_DISTANCE_FAR_END)
        return "far";
    if (m.distance == OIT_DISTANCE_SKIP)
        return "skip:" + std::to_string(m.distance_skip > 0 ? m.distance_skip : 2);
    return "adjacent";
}

std::string fields_name(int mask)
{
    std::string out;
    const char *names[] = {"alpha", "beta", "gamma"};
    for (int f = 0; f < 3; ++f)
        if (mask & (1 << f))
            out += (out.empty() ? "" : ",") + std::string(names[f]);
    return out;
}

} // namespace

const char *split_mode_name(SplitMode mode)
{
    return mode == SplitMode::Wipe ? "wipe" : mode == SplitMode::SideBySide ? "side-by-side" : "off";
}

bool parse_split_mode(const std::string &text, SplitMode &mode)
{
    for (SplitMode m : {SplitMode::Off, SplitMode::Wipe, SplitMode::SideBySide})
        if (text == split_mode_name(m)) {
            mode = m;
            return true;
        }
    return false;
}

std::string tessellation_name(const oit_import_options &import)
{
    return import.linear_deflection_mm > 0 ? exact_number(import.linear_deflection_mm)
                                           : oit_tessellation_level_word(import.tessellation);
}

std::string view_name(const oit_modulation &m)
{
    std::string word = oit_setting_word(OIT_SETTING_VIEW, m.view);
    if (word == "unknown")
        return "colour";
    // every view that takes a number is written with it, the ib views' 0 too
    return oit_view_parameter_rule(m.view) != 0 ? word + ":" + std::to_string(m.view_parameter) : word;
}

bool parse_view(const std::string &text, oit_modulation &m)
{
    size_t colon = text.find(':');
    std::string name = text.substr(0, colon);
    int parameter = 0;
    if (colon != std::string::npos) {
        char *end = nullptr;
        long value = std::strtol(text.c_str() + colon + 1, &end, 10);
        if (end == text.c_str() + colon + 1 || *end || value < 0 || value > 1000000)
            return false;
        parameter = int(value);
    }
    int view;
    if (!oit_setting_value(OIT_SETTING_VIEW, name.c_str(), name.size(), &view) ||
        (oit_view_parameter_rule(oit_view(view)) == 0 && colon != std::string::npos))
        return false;
    m.view = oit_view(view);
    m.view_parameter = parameter;
    return true;
}

const char *modulation_mode_name(oit_modulation_mode mode)
{
    const char *word = oit_setting_word(OIT_SETTING_MODULATION, mode);
    return std::string(word) == "unknown" ? "none" : word;
}

int view_samples(const RenderSettings &s)
{
    // Auto anti-aliases the colour view; the diagnostic views (heat map,
    // layers, fields...) and the error map show each pixel centre's own figures
    if (s.samples == 0)
        return s.modulation.view == OIT_VIEW_COLOUR && !s.error_view ? int(RenderSettings::kAutoSamples) : 1;
    return s.samples;
}

int export_samples(const RenderSettings &s)
{
    return std::max(view_samples(s), int(RenderSettings::kAutoSamples));
}

std::string render_command(const std::string &oit_program, const std::string &model_path,
                           const RenderSettings &s, const oit_frame_settings &frame, const std::string &out_path)
{
    std::ostringstream c;
    c << shell_quote(oit_program) << " render --model " << shell_quote(model_path) << " --algorithm "
      << s.algorithm << " --size " << frame.width << "x" << frame.height;
    for (int which = 0; which < 2; ++which) {
        const double *m = which == 0 ? frame.modelview : frame.projection;
        c << (which == 0 ? " --modelview " : " --projection ");
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col)
                c << (row || col ? "," : "") << exact_number(m[col * 4 + row]);
    }
    c << " --alpha " << number(s.alpha) << " --shading " << oit_setting_word(OIT_SETTING_SHADING, s.shading);
    c << " --background " << number(s.background[0]) << "," << number(s.background[1]) << ","
      << number(s.background[2]);
    if (frame.samples > 1) // the frame's own count: an export's is at least 4
        c << " --samples " << frame.samples;
    oit_algorithm_config defaults;
    oit_algorithm_config_defaults(&defaults);
    if (s.config.max_memory_bytes != defaults.max_memory_bytes)
        c << " --max-memory " << s.config.max_memory_bytes / (1024 * 1024);
    if (s.config.ll_sort != defaults.ll_sort)
        c << " --sort " << oit_setting_word(OIT_SETTING_SORT, s.config.ll_sort);
    if (s.config.max_layers != defaults.max_layers)
        c << " --max-layers " << s.config.max_layers;
    // the approximations' parameters, only for the algorithms that read them (as oit render takes them)
    const oit_algorithm_ops *ops = oit_algorithm_find(s.algorithm.c_str());
    if (ops && oit_algorithm_reads(ops, OIT_OPTION_LAYERS) && s.config.layers != 0)
        c << " --layers " << s.config.layers;
    if (ops && oit_algorithm_reads(ops, OIT_OPTION_MOMENTS) && s.config.moments != OIT_MOMENTS_DEFAULT)
        c << " --moments " << oit_setting_word(OIT_SETTING_MOMENTS, s.config.moments);
    if (ops && oit_algorithm_reads(ops, OIT_OPTION_WAVELET_RANK) && s.config.wavelet_rank != 0)
        c << " --wavelet-rank " << s.config.wavelet_rank;
    if (ops && oit_algorithm_reads(ops, OIT_OPTION_SEED) && s.config.seed != 0)
        c << " --seed " << s.config.seed;
    if (ops && oit_algorithm_reads(ops, OIT_OPTION_SEED) && s.config.stochastic_masks == OIT_STOCHASTIC_INDEPENDENT)
        c << " --stochastic-masks independent";
    const oit_modulation &m = s.modulation;
    if (m.view != OIT_VIEW_COLOUR)
        c << " --view " << view_name(m);
    if (m.mode != OIT_MODULATE_NONE)
        c << " --modulation " << modulation_mode_name(m.mode);
    if (m.neighbours != OIT_NEIGHBOURS_DEFAULT)
        c << " --neighbours " << oit_setting_word(OIT_SETTING_NEIGHBOURS, m.neighbours);
    if (m.epsilon_max > 0.0f)
        c << " --epsilon-max " << number(m.epsilon_max);
    if (m.curvature_effect > 0.0f)
        c << " --curvature-effect " << number(m.curvature_effect);
    if (m.curvature_neighbours == 8)
        c << " --curvature-neighbours 8";
    if (m.distance != OIT_DISTANCE_ADJACENT)
        c << " --distance " << distance_name(m);
    if (m.focus_region > 0.0f)
        c << " --focus-region " << number(m.focus_region);
    if (m.fields != 0)
        c << " --fields " << fields_name(m.fields);
    if (m.diffusion_iterations != 0)
        c << " --diffusion-iterations " << std::max(0, m.diffusion_iterations);
    if (m.blur_iterations != 0)
        c << " --blur-iterations " << std::max(0, m.blur_iterations);
    if (m.lambda_alpha > 0.0f)
        c << " --lambda-alpha " << number(m.lambda_alpha);
    if (m.lambda_beta > 0.0f)
        c << " --lambda-beta " << number(m.lambda_beta);
    if (m.lambda_gamma > 0.0f)
        c << " --lambda-gamma " << number(m.lambda_gamma);
    if (m.has_halo_colour)
        c << " --halo-colour " << number(m.halo_colour[0]) << "," << number(m.halo_colour[1]) << ","
          << number(m.halo_colour[2]);
    if (m.last_layer_opaque)
        c << " --last-layer-opaque";
    // local modulation (issue 4's flags): parts by index, which is unambiguous
    if (frame.local.component_alpha)
        for (uint32_t i = 0; i < frame.local.component_count; ++i)
            if (frame.local.component_alpha[i] != 1.0f)
                c << " --component-alpha " << i << "=" << number(frame.local.component_alpha[i]);
    const int focus_values = s.focus_shape == OIT_FOCUS_POINT   ? 3
                             : s.focus_shape == OIT_FOCUS_PLANE ? 4
                             : s.focus_shape == OIT_FOCUS_BOX   ? 6
                                                                : 0;
    if (focus_values > 0) {
        c << (s.focus_shape == OIT_FOCUS_POINT   ? " --focus-point "
              : s.focus_shape == OIT_FOCUS_PLANE ? " --focus-plane "
                                                 : " --focus-box ");
        for (int i = 0; i < focus_values; ++i)
            c << (i ? "," : "") << exact_number(s.focus[i]);
    }
    if (s.contrast != 0.0f && s.contrast != 1.0f)
        c << " --contrast " << number(s.contrast);
    // the selection highlight, when the view shows one: parts by index
    if (frame.local.component_highlight) {
        const char *separator = " --highlight ";
        for (uint32_t i = 0; i < frame.local.component_highlight_count; ++i)
            if (frame.local.component_highlight[i] > 0.0f) {
                c << separator << i;
                separator = ",";
            }
        if (frame.local.has_highlight_colour)
            c << " --highlight-colour " << number(frame.local.highlight_colour[0]) << ","
              << number(frame.local.highlight_colour[1]) << "," << number(frame.local.highlight_colour[2]);
    }
    if (s.import.tessellation != OIT_TESSELLATION_NORMAL || s.import.linear_deflection_mm > 0)
        c << " --tessellation " << tessellation_name(s.import);
    // sections and the exploded view (issue 28): the enabled planes, the
    // parts they cut by index (as --highlight), caps only when off
    const oit_local_modulation &l = frame.local;
    bool cuts_some = l.section_count > 0;
    if (cuts_some && l.section_parts) {
        cuts_some = false;
        for (uint32_t i = 0; i < l.section_parts_count; ++i)
            cuts_some = cuts_some || l.section_parts[i];
    }
    if (cuts_some) { // planes that cut no part change nothing and are left out
        for (uint32_t i = 0; i < l.section_count; ++i)
            c << " --section " << short_exact(l.sections[i][0]) << "," << short_exact(l.sections[i][1]) << ","
              << short_exact(l.sections[i][2]) << "," << short_exact(l.sections[i][3]);
        if (l.section_parts) {
            const char *separator = " --section-parts ";
            for (uint32_t i = 0; i < l.section_parts_count; ++i)
                if (l.section_parts[i]) {
                    c << separator << i;
                    separator = ",";
                }
        }
        if (l.no_caps)
            c << " --caps off";
    }
    if (s.explode > 0.0)
        c << " --explode " << short_exact(s.explode);
    // the orientation aids, when exports carry them (issue 29)
    const oit_overlay_options aids = export_aids(s);
    if (aids.axes)
        c << " --axes=" << oit_corner_name(aids.axes_corner);
    if (aids.scale_bar)
        c << " --scale-bar";
    if (s.error_view) {
        // the same frame with the CPU reference: the figures, and the map beside the image
        std::string map = out_path.empty() ? "error.png" : out_path;
        size_t dot = map.rfind('.'), slash = map.rfind('/');
        if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
            dot = map.size();
        map = map.substr(0, dot) + "-error" + (dot < map.size() ? map.substr(dot) : std::string(".png"));
        c << " --error-vs-reference --error-map " << shell_quote(map);
    }
    if (!out_path.empty())
        c << " --out " << shell_quote(out_path);
    return c.str();
}

// ------------------------------------------------------------------ presets

namespace {

// JSON with comments and trailing commas; a syntax error becomes "FILE:LINE: what".
bool parse_json(const std::string &file, const std::string &text, rapidjson::Document &d, std::string &error)
{
    d.Parse<rapidjson::kParseCommentsFlag | rapidjson::kParseTrailingCommasFlag | rapidjson::kParseFullPrecisionFlag>(
        text.c_str(), text.size()); // full precision: every double comes back bit for bit (sessions, saved views)
    if (!d.HasParseError())
        return true;
    size_t offset = std::min(d.GetErrorOffset(), text.size());
    int line = 1 + int(std::count(text.begin(), text.begin() + long(offset), '\n'));
    error = file + ":" + std::to_string(line) + ": " + rapidjson::GetParseError_En(d.GetParseError());
    return false;
}

using rapidjson::Value;

void add(Value &object, const char *key, Value value, rapidjson::Document::AllocatorType &a)
{
    object.AddMember(Value(key, a), value, a);
}

Value string_value(const std::string &text, rapidjson::Document::AllocatorType &a)
{
    return Value(text.c_str(), rapidjson::SizeType(text.size()), a);
}

template <typename Number>
Value array_value(const Number *values, int count, rapidjson::Document::AllocatorType &a)
{
    Value array(rapidjson::kArrayType);
    for (int i = 0; i < count; ++i)
        array.PushBack(Value(double(values[i])), a);
    return array;
}

// 1-based line of the first occurrence of "key" in the text (for messages
// about a value the parser accepted but the workbench does not)
int line_of_key(const std::string &text, const char *key)
{
    size_t at = text.find("\"" + std::string(key) + "\"");
    if (at == std::string::npos)
        return 1;
    return 1 + int(std::count(text.begin(), text.begin() + long(at), '\n'));
}

struct PresetReader {
    const std::string &file, &text;
    std::string &error;

    bool fail(const char *key, const std::string &problem)
    {
        error = file + ":" + std::to_string(line_of_key(text, key)) + ": \"" + key + "\": " + problem;
        return false;
    }
    bool number(const Value &object, const char *key, double low, double high, float &out, bool &present)
    {
        present = object.HasMember(key);
        if (!present)
            return true;
        const Value &v = object[key];
        if (!v.IsNumber() || !(v.GetDouble() >= low && v.GetDouble() <= high))
            return fail(key, "must be a number in [" + ::number(low) + ", " + ::number(high) + "]");
        out = float(v.GetDouble());
        return true;
    }
    bool number(const Value &object, const char *key, double low, double high, float &out)
    {
        bool present;
        return number(object, key, low, high, out, present);
    }
    bool whole(const Value &object, const char *key, int low, int high, int &out)
    {
        if (!object.HasMember(key))
            return true;
        const Value &v = object[key];
        if (!v.IsInt() || v.GetInt() < low || v.GetInt() > high)
            return fail(key, "must be a whole number in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
        out = v.GetInt();
        return true;
    }
    template <typename Number>
    bool numbers(const Value &object, const char *key, int count, Number *out, bool &present)
    {
        present = object.HasMember(key);
        if (!present)
            return true;
        const Value &v = object[key];
        if (!v.IsArray() || int(v.Size()) != count)
            return fail(key, "must be an array of " + std::to_string(count) + " numbers");
        for (int i = 0; i < count; ++i) {
            if (!v[i].IsNumber() || !std::isfinite(v[i].GetDouble()))
                return fail(key, "element " + std::to_string(i) + " is not a finite number");
            out[i] = Number(v[i].GetDouble());
        }
        return true;
    }
    // one of names[0..count); returns the index through out
    bool choice(const Value &object, const char *key, const char *const *names, int count, int &out)
    {
        if (!object.HasMember(key))
            return true;
        const Value &v = object[key];
        std::string all;
        for (int i = 0; i < count; ++i) {
            if (v.IsString() && v.GetString() == std::string(names[i])) {
                out = i;
                return true;
            }
            all += (i ? ", " : "") + std::string(names[i]);
        }
        return fail(key, "must be one of " + all);
    }
    // a number or "auto" (0)
    bool number_or_auto(const Value &object, const char *key, double low, double high, float &out)
    {
        if (object.HasMember(key) && object[key].IsString() && object[key].GetString() == std::string("auto")) {
            out = 0.0f;
            return true;
        }
        if (object.HasMember(key) && !object[key].IsNumber())
            return fail(key, "must be \"auto\" or a number");
        return number(object, key, low, high, out);
    }
};

} // namespace

namespace {

Value camera_value(const Camera &camera, rapidjson::Document::AllocatorType &a)
{
    Value cam(rapidjson::kObjectType);
    add(cam, "mode", Value(rapidjson::StringRef(camera.mode() == Camera::Mode::Walk ? "walk" : "orbit")), a);
    add(cam, "projection", Value(rapidjson::StringRef(camera.orthographic ? "orthographic" : "perspective")), a);
    add(cam, "fov", Value(double(camera.fov_degrees)), a);
    add(cam, "orbit", Value(rapidjson::StringRef(camera.orbit_style == Camera::Orbit::Trackball ? "trackball" : "turntable")), a);
    add(cam, "up", Value(rapidjson::StringRef(camera.up == Camera::Up::Z ? "z" : "y")), a);
    add(cam, "eye", array_value(&camera.eye.x, 3, a), a);
    const double q[4] = {camera.orientation.w, camera.orientation.x, camera.orientation.y, camera.orientation.z};
    add(cam, "orientation", array_value(q, 4, a), a);
    add(cam, "target", array_value(&camera.target.x, 3, a), a);
    return cam;
}

} // namespace

std::string preset_to_json(const RenderSettings &s, const Camera &camera, const oit_model *model)
{
    rapidjson::Document d(rapidjson::kObjectType);
    auto &a = d.GetAllocator();
    add(d, "algorithm", string_value(s.algorithm, a), a);
    add(d, "sort", Value(rapidjson::StringRef(oit_setting_word(OIT_SETTING_SORT, s.config.ll_sort))), a);
    add(d, "max-memory", Value(uint64_t(s.config.max_memory_bytes / (1024 * 1024))), a);
    add(d, "max-layers", Value(s.config.max_layers), a);
    add(d, "layers", Value(s.config.layers == 0 ? OIT_LAYERS_DEFAULT : s.config.layers), a);
    add(d, "moments", Value(rapidjson::StringRef(oit_setting_word(OIT_SETTING_MOMENTS, s.config.moments))), a);
    add(d, "wavelet-rank", Value(s.config.wavelet_rank == 0 ? OIT_WAVELET_RANK_DEFAULT : s.config.wavelet_rank), a);
    add(d, "seed", Value(s.config.seed), a);
    add(d, "stochastic-masks",
        Value(rapidjson::StringRef(s.config.stochastic_masks == OIT_STOCHASTIC_INDEPENDENT ? "independent" : "stratified")), a);
    add(d, "alpha", Value(double(s.alpha)), a);
    add(d, "shading", Value(rapidjson::StringRef(oit_setting_word(OIT_SETTING_SHADING, s.shading))), a);
    if (s.samples == 0)
        add(d, "samples", Value(rapidjson::StringRef("auto")), a);
    else
        add(d, "samples", Value(s.samples), a);
    add(d, "background", array_value(s.background, 3, a), a);
    const oit_modulation &m = s.modulation;
    add(d, "view", string_value(view_name(m), a), a);
    add(d, "modulation", Value(rapidjson::StringRef(modulation_mode_name(m.mode))), a);
    add(d, "neighbours", Value(rapidjson::StringRef(neighbour_word(m.neighbours))), a);
    const oit_modulation resolved = oit_modulation_defaults(&m);
    add(d, "curvature-neighbours", Value(resolved.curvature_neighbours), a);
    add(d, "curvature-effect", Value(double(resolved.curvature_effect)), a);
    add(d, "epsilon-max", Value(double(resolved.epsilon_max)), a);
    add(d, "distance", string_value(distance_name(m), a), a);
    add(d, "focus-region", m.focus_region > 0 ? Value(double(m.focus_region)) : Value(rapidjson::StringRef("auto")), a);
    add(d, "fields", string_value(fields_name(resolved.fields), a), a);
    add(d, "diffusion-iterations", Value(std::max(0, resolved.diffusion_iterations)), a);
    add(d, "blur-iterations", Value(std::max(0, resolved.blur_iterations)), a);
    add(d, "lambda-alpha", m.lambda_alpha > 0 ? Value(double(m.lambda_alpha)) : Value(rapidjson::StringRef("auto")), a);
    add(d, "lambda-beta", m.lambda_beta > 0 ? Value(double(m.lambda_beta)) : Value(rapidjson::StringRef("auto")), a);
    add(d, "lambda-gamma", m.lambda_gamma > 0 ? Value(double(m.lambda_gamma)) : Value(rapidjson::StringRef("auto")), a);
    // "auto" (the core's white) is written too: a preset says every setting
    add(d, "halo-colour", m.has_halo_colour ? array_value(m.halo_colour, 3, a) : Value(rapidjson::StringRef("auto")), a);
    add(d, "last-layer-opaque", Value(m.last_layer_opaque), a);
    if (s.focus_shape == OIT_FOCUS_POINT)
        add(d, "focus-point", array_value(s.focus, 3, a), a);
    else if (s.focus_shape == OIT_FOCUS_PLANE)
        add(d, "focus-plane", array_value(s.focus, 4, a), a);
    else if (s.focus_shape == OIT_FOCUS_BOX)
        add(d, "focus-box", array_value(s.focus, 6, a), a);
    else
        add(d, "focus", Value(rapidjson::StringRef("none")), a); // the reader's default, said explicitly
    add(d, "contrast", Value(double(s.contrast == 0.0f ? 1.0f : s.contrast)), a);
    add(d, "error-vs-reference", Value(s.error_view), a);
    add(d, "split", Value(rapidjson::StringRef(split_mode_name(s.split))), a);
    add(d, "split-algorithm", string_value(s.split_algorithm, a), a);
    add(d, "wipe", Value(double(s.wipe)), a);
    add(d, "preview-algorithm", string_value(s.preview_algorithm, a), a);
    if (s.import.linear_deflection_mm > 0)
        add(d, "tessellation", Value(s.import.linear_deflection_mm), a);
    else
        add(d, "tessellation", Value(rapidjson::StringRef(oit_tessellation_level_word(s.import.tessellation))), a);
    if (model && s.part_alpha.size() == model->component_count) {
        Value alphas(rapidjson::kObjectType), hidden(rapidjson::kArrayType);
        for (uint32_t i = 0; i < model->component_count; ++i) {
            if (s.part_alpha[i] != 1.0f)
                alphas.AddMember(Value(model->components[i].name, a), Value(double(s.part_alpha[i])), a);
            if (!s.part_visible[i])
                hidden.PushBack(Value(model->components[i].name, a), a);
        }
        add(d, "component-alpha", std::move(alphas), a);
        add(d, "hide", std::move(hidden), a);
    }
    // sections and the exploded view (issue 28)
    Value sections(rapidjson::kArrayType);
    for (const SectionPlane &plane : s.sections) {
        Value item(rapidjson::kObjectType);
        const double values[4] = {plane.normal[0], plane.normal[1], plane.normal[2], plane.d};
        add(item, "plane", array_value(values, 4, a), a);
        add(item, "enabled", Value(plane.enabled), a);
        sections.PushBack(std::move(item), a);
    }
    add(d, "section", std::move(sections), a);
    if (model && !s.section_parts.empty() && s.section_parts.size() == model->component_count) {
        Value parts(rapidjson::kArrayType); // by path: names repeat across assemblies
        char path[1024];
        for (uint32_t i = 0; i < model->component_count; ++i)
            if (s.section_parts[i]) {
                oit_model_component_path(model, i, path, sizeof path);
                parts.PushBack(Value(path, a), a);
            }
        add(d, "section-parts", std::move(parts), a);
    } else {
        add(d, "section-parts", Value(rapidjson::StringRef("all")), a);
    }
    add(d, "caps", Value(rapidjson::StringRef(s.caps ? "on" : "off")), a);
    add(d, "explode", Value(s.explode), a);
    // the orientation aids (issue 29)
    add(d, "axes", Value(rapidjson::StringRef(s.axes ? oit_corner_name(s.axes_corner) : "off")), a);
    add(d, "scale-bar", Value(s.scale_bar), a);
    add(d, "camera", camera_value(camera, a), a);

    rapidjson::StringBuffer buffer;
    rapidjson::PrettyWriter<rapidjson::StringBuffer> writer(buffer);
    writer.SetIndent(' ', 2);
    d.Accept(writer);
    return std::string(buffer.GetString()) + "\n";
}

RenderSettings preset_defaults(const RenderSettings &current)
{
    RenderSettings s; // every setting a preset holds at its default
    // what no preset holds is kept: the shader folder (set by the view) and the
    // tests' configuration (fragment counters, debug, neighbour quality, ...)
    oit_algorithm_config preset_config = s.config;
    s.config = current.config;
    s.config.max_memory_bytes = preset_config.max_memory_bytes;
    s.config.ll_sort = preset_config.ll_sort;
    s.config.max_layers = preset_config.max_layers;
    s.config.layers = preset_config.layers;
    s.config.moments = preset_config.moments;
    s.config.wavelet_rank = preset_config.wavelet_rank;
    s.config.seed = preset_config.seed;
    s.config.stochastic_masks = preset_config.stochastic_masks;
    // the parts are matched by name against a model; without one they stay
    s.part_alpha = current.part_alpha;
    s.part_visible = current.part_visible;
    s.section_parts = current.section_parts;
    s.aids_in_export = current.aids_in_export; // the workbench's choice, not the preset's
    return s;
}

namespace {

// A preset's object d, parsed from text (whose lines the messages name).
bool preset_from_object(const std::string &file, const std::string &text, const Value &d, RenderSettings &out,
                        Camera &camera, bool &has_camera, const oit_model *model, std::string &error)
{
    has_camera = false;
    PresetReader r{file, text, error};
    // applied only if the whole file is good; every key it lacks takes its default
    RenderSettings s = preset_defaults(out);
    static const char *const known[] = {
        "algorithm", "sort", "max-memory", "max-layers", "layers", "moments", "wavelet-rank", "seed", "stochastic-masks", "alpha", "shading", "background", "view", "modulation",
        "neighbours", "curvature-neighbours", "curvature-effect", "epsilon-max", "distance", "focus-region",
        "fields", "diffusion-iterations", "blur-iterations", "lambda-alpha", "lambda-beta", "lambda-gamma",
        "halo-colour", "last-layer-opaque", "focus", "focus-point", "focus-plane", "focus-box", "contrast",
        "component-alpha", "hide", "camera", "tessellation",
        // the workbench's comparisons (the first is `oit render`'s flag too)
        "error-vs-reference", "split", "split-algorithm", "wipe",
        // the workbench's interaction: what renders while moving
        "preview-algorithm",
        // sections and the exploded view (issue 28)
        "section", "section-parts", "caps", "explode",
        // the orientation aids (issue 29)
        "axes", "scale-bar",
        // anti-aliasing (issue 29): "auto" or --samples' count
        "samples"};
    for (auto it = d.MemberBegin(); it != d.MemberEnd(); ++it) {
        std::string key = it->name.GetString();
        if (std::find(std::begin(known), std::end(known), key) == std::end(known))
            return r.fail(key.c_str(), "unknown key (the keys are `oit render`'s flag names)");
    }
    if (d.HasMember("algorithm")) {
        if (!d["algorithm"].IsString() || !oit_algorithm_find(d["algorithm"].GetString()))
            return r.fail("algorithm", "unknown algorithm (oit algorithms lists them)");
        s.algorithm = d["algorithm"].GetString();
    }
    const char *const *words;
    int sort = s.config.ll_sort; // the words' order is the values' (oit_setting_words)
    if (!r.choice(d, "sort", words, oit_setting_words(OIT_SETTING_SORT, &words), sort))
        return false;
    s.config.ll_sort = oit_ll_sort(sort);
    int megabytes = int(s.config.max_memory_bytes / (1024 * 1024));
    if (!r.whole(d, "max-memory", 1, 1 << 22, megabytes) || !r.whole(d, "max-layers", 0, OIT_PEEL_LAYER_CAP_MAX, s.config.max_layers))
        return false;
    s.config.max_memory_bytes = uint64_t(megabytes) * 1024 * 1024;
    if (d.HasMember("layers") && !r.whole(d, "layers", 1, OIT_LAYERS_MAX, s.config.layers))
        return false;
    int moments = s.config.moments == OIT_MOMENTS_DEFAULT ? 0 : int(s.config.moments) - OIT_MOMENTS_POWER4;
    if (!r.choice(d, "moments", words, oit_setting_words(OIT_SETTING_MOMENTS, &words), moments))
        return false;
    if (d.HasMember("moments")) // absent: the default itself, not the value it stands for
        s.config.moments = oit_moments(moments + OIT_MOMENTS_POWER4);
    if (d.HasMember("wavelet-rank") && !r.whole(d, "wavelet-rank", 1, OIT_WAVELET_RANK_MAX, s.config.wavelet_rank))
        return false;
    int seed = int(s.config.seed & 0x7fffffffu);
    if (!r.whole(d, "seed", 0, 0x7fffffff, seed)) // presets: the seeds up to 2^31 - 1
        return false;
    s.config.seed = uint32_t(seed);
    static const char *const mask_words[] = {"stratified", "independent"};
    int masks = s.config.stochastic_masks == OIT_STOCHASTIC_INDEPENDENT ? 1 : 0;
    if (!r.choice(d, "stochastic-masks", mask_words, 2, masks))
        return false;
    if (d.HasMember("stochastic-masks"))
        s.config.stochastic_masks = masks == 1 ? OIT_STOCHASTIC_INDEPENDENT : OIT_STOCHASTIC_STRATIFIED;
    if (!r.number(d, "alpha", 0.0, 1.0, s.alpha))
        return false;
    int shading = s.shading;
    if (!r.choice(d, "shading", words, oit_setting_words(OIT_SETTING_SHADING, &words), shading))
        return false;
    s.shading = oit_shading_mode(shading);
    if (d.HasMember("samples")) {
        const Value &v = d["samples"];
        if (v.IsString() && std::string(v.GetString()) == "auto")
            s.samples = 0;
        else if (v.IsInt() && v.GetInt() >= 1 && oit_sample_positions(v.GetInt(), nullptr) != 0)
            s.samples = v.GetInt();
        else
            return r.fail("samples", "must be \"auto\", 1, 4, 8 or 16");
    }
    bool present;
    if (!r.numbers(d, "background", 3, s.background, present))
        return false;
    for (float c : s.background)
        if (!(c >= 0.0f && c <= 1.0f))
            return r.fail("background", "each component must be in [0, 1]");
    oit_modulation &m = s.modulation;
    if (d.HasMember("view") && (!d["view"].IsString() || !parse_view(d["view"].GetString(), m)))
        return r.fail("view", "must be colour, heatmap, peel-limit:N, layer:L, neighbours, curvature[:L], "
                              "distance[:L] or fields[:L]");
    int mode = m.mode, neighbours = m.neighbours;
    const char *const *search_words;
    int search_count = oit_setting_words(OIT_SETTING_NEIGHBOURS, &search_words);
    std::vector<const char *> neighbour_words{neighbour_word(OIT_NEIGHBOURS_DEFAULT)}; // its values from 0
    neighbour_words.insert(neighbour_words.end(), search_words, search_words + search_count);
    if (!r.choice(d, "modulation", words, oit_setting_words(OIT_SETTING_MODULATION, &words), mode) ||
        !r.choice(d, "neighbours", neighbour_words.data(), int(neighbour_words.size()), neighbours))
        return false;
    m.mode = oit_modulation_mode(mode);
    m.neighbours = oit_neighbour_search(neighbours);
    if (!r.whole(d, "curvature-neighbours", 4, 8, m.curvature_neighbours) ||
        !r.number(d, "curvature-effect", 1e-6, 1e6, m.curvature_effect) ||
        !r.number(d, "epsilon-max", 1e-6, 1e6, m.epsilon_max) ||
        !r.number_or_auto(d, "focus-region", 1e-9, 1e9, m.focus_region))
        return false;
    if (m.curvature_neighbours != 4 && m.curvature_neighbours != 8 && m.curvature_neighbours != 0)
        return r.fail("curvature-neighbours", "must be 4 or 8");
    if (d.HasMember("distance")) {
        std::string v = d["distance"].IsString() ? d["distance"].GetString() : "";
        if (v == "adjacent")
            m.distance = OIT_DISTANCE_ADJACENT;
        else if (v == "far")
            m.distance = OIT_DISTANCE_FAR_END;
        else if (v.rfind("skip:", 0) == 0 && std::atoi(v.c_str() + 5) >= 1) {
            m.distance = OIT_DISTANCE_SKIP;
            m.distance_skip = std::atoi(v.c_str() + 5);
        } else
            return r.fail("distance", "must be adjacent, far or skip:K (K >= 1)");
    }
    if (d.HasMember("fields")) {
        std::string v = d["fields"].IsString() ? d["fields"].GetString() : "";
        int mask = 0;
        std::stringstream items(v);
        std::string item;
        while (std::getline(items, item, ','))
            mask |= item == "alpha" ? OIT_FIELD_ALPHA : item == "beta" ? OIT_FIELD_BETA : item == "gamma" ? OIT_FIELD_GAMMA : 64;
        if (mask == 0 || mask >= 64)
            return r.fail("fields", "must be a comma-separated list of alpha, beta, gamma");
        m.fields = mask == 7 ? 0 : mask;
    }
    const oit_modulation resolved = oit_modulation_defaults(&m);
    int diffusion = std::max(0, resolved.diffusion_iterations), blur = std::max(0, resolved.blur_iterations);
    if (!r.whole(d, "diffusion-iterations", 0, 1000, diffusion) || !r.whole(d, "blur-iterations", 0, 1000, blur))
        return false;
    if (d.HasMember("diffusion-iterations"))
        m.diffusion_iterations = diffusion == 0 ? -1 : diffusion;
    if (d.HasMember("blur-iterations"))
        m.blur_iterations = blur == 0 ? -1 : blur;
    if (!r.number_or_auto(d, "lambda-alpha", 1e-6, 100, m.lambda_alpha) ||
        !r.number_or_auto(d, "lambda-beta", 1e-6, 100, m.lambda_beta) ||
        !r.number_or_auto(d, "lambda-gamma", 1e-6, 100, m.lambda_gamma))
        return false;
    if (d.HasMember("halo-colour") && d["halo-colour"].IsString()) {
        if (d["halo-colour"].GetString() != std::string("auto"))
            return r.fail("halo-colour", "must be \"auto\" or an array of 3 numbers");
    } else {
        if (!r.numbers(d, "halo-colour", 3, m.halo_colour, present))
            return false;
        m.has_halo_colour = present;
    }
    if (d.HasMember("last-layer-opaque")) {
        if (!d["last-layer-opaque"].IsBool())
            return r.fail("last-layer-opaque", "must be true or false");
        m.last_layer_opaque = d["last-layer-opaque"].GetBool();
    }
    const struct {
        const char *key;
        oit_focus_shape shape;
        int count;
    } shapes[] = {{"focus-point", OIT_FOCUS_POINT, 3}, {"focus-plane", OIT_FOCUS_PLANE, 4}, {"focus-box", OIT_FOCUS_BOX, 6}};
    if (d.HasMember("focus") && !(d["focus"].IsString() && d["focus"].GetString() == std::string("none")))
        return r.fail("focus", "must be \"none\" (a focus is given by focus-point, focus-plane or focus-box)");
    for (const auto &shape : shapes) {
        double values[6] = {0, 0, 0, 0, 0, 0};
        if (!r.numbers(d, shape.key, shape.count, values, present))
            return false;
        if (present) {
            s.focus_shape = shape.shape;
            std::copy(values, values + 6, s.focus);
        }
    }
    if (!r.number(d, "contrast", 0.1, 10.0, s.contrast))
        return false;
    if (d.HasMember("error-vs-reference")) {
        if (!d["error-vs-reference"].IsBool())
            return r.fail("error-vs-reference", "must be true or false");
        s.error_view = d["error-vs-reference"].GetBool();
    }
    if (d.HasMember("split") &&
        (!d["split"].IsString() || !parse_split_mode(d["split"].GetString(), s.split)))
        return r.fail("split", "must be off, wipe or side-by-side");
    if (d.HasMember("split-algorithm")) {
        if (!d["split-algorithm"].IsString() || !oit_algorithm_find(d["split-algorithm"].GetString()))
            return r.fail("split-algorithm", "unknown algorithm (oit algorithms lists them)");
        s.split_algorithm = d["split-algorithm"].GetString();
    }
    if (!r.number(d, "wipe", 0.0, 1.0, s.wipe))
        return false;
    if (d.HasMember("preview-algorithm")) {
        const Value &p = d["preview-algorithm"];
        if (!p.IsString() || !(std::strcmp(p.GetString(), "auto") == 0 || std::strcmp(p.GetString(), "same") == 0 ||
                               oit_algorithm_find(p.GetString())))
            return r.fail("preview-algorithm", "must be auto, same or an algorithm (oit algorithms lists them)");
        s.preview_algorithm = p.GetString();
    }
    if (d.HasMember("tessellation")) {
        const Value &t = d["tessellation"];
        std::string text = t.IsString() ? t.GetString() : t.IsNumber() ? exact_number(t.GetDouble()) : "";
        oit_error err{};
        if (text.empty() || oit_import_options_parse_tessellation(text.c_str(), &s.import, &err) != OIT_OK)
            return r.fail("tessellation", "must be coarse, normal, fine or a linear deflection in millimetres "
                                          "greater than 0");
    }
    if (d.HasMember("section")) {
        const Value &list = d["section"];
        const char *shape = "must be an array of planes, each {\"plane\": [nx, ny, nz, d], \"enabled\": "
                            "true|false} or [nx, ny, nz, d]";
        if (!list.IsArray())
            return r.fail("section", shape);
        if (list.Size() > OIT_SECTION_PLANES_MAX)
            return r.fail("section", "at most " + std::to_string(OIT_SECTION_PLANES_MAX) + " planes");
        for (const Value &item : list.GetArray()) {
            SectionPlane plane;
            const Value *values = &item;
            if (item.IsObject()) {
                for (auto it = item.MemberBegin(); it != item.MemberEnd(); ++it)
                    if (std::strcmp(it->name.GetString(), "plane") != 0 &&
                        std::strcmp(it->name.GetString(), "enabled") != 0)
                        return r.fail("section", shape);
                if (!item.HasMember("plane"))
                    return r.fail("section", shape);
                values = &item["plane"];
                if (item.HasMember("enabled")) {
                    if (!item["enabled"].IsBool())
                        return r.fail("section", shape);
                    plane.enabled = item["enabled"].GetBool();
                }
            }
            if (!values->IsArray() || values->Size() != 4)
                return r.fail("section", shape);
            double v[4];
            for (int k = 0; k < 4; ++k) {
                if (!(*values)[k].IsNumber() || !std::isfinite((*values)[k].GetDouble()))
                    return r.fail("section", "a plane's element " + std::to_string(k) + " is not a finite number");
                v[k] = (*values)[k].GetDouble();
            }
            if (v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0)
                return r.fail("section", "a plane's normal is zero");
            std::copy(v, v + 3, plane.normal);
            plane.d = v[3];
            s.sections.push_back(plane);
        }
    }
    if (d.HasMember("caps")) {
        const Value &caps = d["caps"];
        if (!caps.IsString() || (caps.GetString() != std::string("on") && caps.GetString() != std::string("off")))
            return r.fail("caps", "must be \"on\" or \"off\"");
        s.caps = caps.GetString() == std::string("on");
    }
    if (d.HasMember("axes")) {
        const Value &axes = d["axes"];
        oit_corner corner = OIT_CORNER_BOTTOM_LEFT;
        bool off = axes.IsString() && axes.GetString() == std::string("off");
        if (!axes.IsString() || (!off && oit_corner_parse(axes.GetString(), &corner, nullptr) != OIT_OK))
            return r.fail("axes", "must be \"off\", \"bottom-left\", \"bottom-right\", \"top-left\" or \"top-right\"");
        s.axes = !off;
        s.axes_corner = corner;
    }
    if (d.HasMember("scale-bar")) {
        if (!d["scale-bar"].IsBool())
            return r.fail("scale-bar", "must be true or false");
        s.scale_bar = d["scale-bar"].GetBool();
    }
    if (d.HasMember("explode")) {
        const Value &explode = d["explode"];
        if (!explode.IsNumber() || !(explode.GetDouble() >= 0.0 && explode.GetDouble() <= OIT_EXPLODE_MAX))
            return r.fail("explode", "must be a number in [0, " + ::number(OIT_EXPLODE_MAX) + "]");
        s.explode = explode.GetDouble();
    }
    if (d.HasMember("section-parts")) {
        const Value &parts = d["section-parts"];
        bool all = parts.IsString() && parts.GetString() == std::string("all");
        if (!all && !parts.IsArray())
            return r.fail("section-parts", "must be \"all\" or an array of part names or assembly paths");
        if (parts.IsArray())
            for (const Value &name : parts.GetArray())
                if (!name.IsString())
                    return r.fail("section-parts", "must be \"all\" or an array of part names or assembly paths");
    }
    if (model) {
        s.reset_parts(*model);
        // the parts the sections cut, by name or path (oit_model_match_parts,
        // as the command line matches them); unknown ones are ignored, as for "hide"
        if (d.HasMember("section-parts") && d["section-parts"].IsArray()) {
            s.section_parts.assign(model->component_count, 0);
            std::unique_ptr<bool[]> flags(new bool[model->component_count ? model->component_count : 1]);
            for (const Value &name : d["section-parts"].GetArray()) {
                std::fill(flags.get(), flags.get() + model->component_count, false);
                oit_model_match_parts(model, name.GetString(), flags.get());
                for (uint32_t i = 0; i < model->component_count; ++i)
                    if (flags[i])
                        s.section_parts[i] = 1;
            }
        }
        auto find_part = [&](const char *name) -> int {
            for (uint32_t i = 0; i < model->component_count; ++i)
                if (std::strcmp(model->components[i].name, name) == 0)
                    return int(i);
            return -1;
        };
        if (d.HasMember("component-alpha")) {
            const Value &parts = d["component-alpha"];
            if (!parts.IsObject())
                return r.fail("component-alpha", "must be an object {\"part name\": opacity}");
            for (auto it = parts.MemberBegin(); it != parts.MemberEnd(); ++it) {
                int index = find_part(it->name.GetString());
                if (!it->value.IsNumber() || !(it->value.GetDouble() >= 0.0 && it->value.GetDouble() <= 1.0))
                    return r.fail("component-alpha", std::string("\"") + it->name.GetString() + "\" needs an opacity in [0, 1]");
                if (index >= 0) // parts the model does not have are ignored: presets travel between models
                    s.part_alpha[size_t(index)] = float(it->value.GetDouble());
            }
        }
        if (d.HasMember("hide")) {
            const Value &hide = d["hide"];
            if (!hide.IsArray())
                return r.fail("hide", "must be an array of part names");
            for (const Value &name : hide.GetArray()) {
                if (!name.IsString())
                    return r.fail("hide", "must be an array of part names");
                int index = find_part(name.GetString());
                if (index >= 0)
                    s.part_visible[size_t(index)] = 0;
            }
        }
    }
    Camera c = camera;
    if (d.HasMember("camera")) {
        const Value &cam = d["camera"];
        if (!cam.IsObject())
            return r.fail("camera", "must be an object");
        static const char *const modes[] = {"orbit", "walk"};
        static const char *const projections[] = {"perspective", "orthographic"};
        // a camera without a mode, projection or fov gets the defaults, as settings do
        static const char *const orbits[] = {"turntable", "trackball"};
        static const char *const ups[] = {"y", "z"};
        c.fov_degrees = Camera().fov_degrees;
        int cam_mode = 0, projection = 0, orbit = 0, up = 0;
        double q[4] = {c.orientation.w, c.orientation.x, c.orientation.y, c.orientation.z};
        if (!r.choice(cam, "mode", modes, 2, cam_mode) || !r.choice(cam, "projection", projections, 2, projection) ||
            !r.choice(cam, "orbit", orbits, 2, orbit) || !r.choice(cam, "up", ups, 2, up) ||
            !r.number(cam, "fov", 1.0, 170.0, c.fov_degrees) || !r.numbers(cam, "eye", 3, &c.eye.x, present) ||
            !r.numbers(cam, "orientation", 4, q, present) || !r.numbers(cam, "target", 3, &c.target.x, present))
            return false;
        glm::dquat orientation(q[0], q[1], q[2], q[3]);
        if (!(glm::length(orientation) > 1e-6))
            return r.fail("orientation", "must be a non-zero quaternion w, x, y, z");
        // renormalised only if needed, so a saved view comes back bit for bit
        c.orientation = std::fabs(glm::length(orientation) - 1.0) > 1e-5 ? glm::normalize(orientation) : orientation;
        c.orthographic = projection == 1;
        c.orbit_style = orbit == 1 ? Camera::Orbit::Trackball : Camera::Orbit::Turntable;
        c.up = up == 1 ? Camera::Up::Z : Camera::Up::Y;
        // set_mode moves an orbit's target to the point ahead when the mode
        // changes: the preset's (or the kept) target is put back after it
        const glm::dvec3 target = c.target;
        c.set_mode(cam_mode ? Camera::Mode::Walk : Camera::Mode::Orbit);
        c.target = target;
        has_camera = true;
    }
    out = s;
    camera = c;
    return true;
}

} // namespace

bool preset_from_json(const std::string &file, const std::string &text, RenderSettings &out, Camera &camera,
                      bool &has_camera, const oit_model *model, std::string &error)
{
    has_camera = false;
    rapidjson::Document d;
    if (!parse_json(file, text, d, error))
        return false;
    if (!d.IsObject()) {
        error = file + ":1: a preset is a JSON object";
        return false;
    }
    return preset_from_object(file, text, d, out, camera, has_camera, model, error);
}

// ------------------------------------------------------------- saved state

namespace {

bool is_base64(const std::string &text)
{
    if (text.empty())
        return true;
    size_t last = text.find_last_not_of('=');
    if (text.size() % 4 != 0 || last == std::string::npos || text.size() - last - 1 > 2)
        return false;
    for (size_t i = 0; i <= last; ++i)
        if (!std::isalnum(static_cast<unsigned char>(text[i])) && text[i] != '+' && text[i] != '/')
            return false;
    return true;
}

} // namespace

bool saved_state_from_json(const std::string &file, const std::string &text, SavedStateText &out,
                           std::string &error)
{
    rapidjson::Document d;
    if (!parse_json(file, text, d, error))
        return false;
    if (!d.IsObject()) {
        error = file + ":1: the saved state is a JSON object";
        return false;
    }
    PresetReader r{file, text, error};
    SavedStateText state;
    static const char *const known[] = {"settings", "last-model", "recent",        "geometry",
                                        "window",   "views",      "export-folder", "export-size",
                                        "recent-sessions"};
    for (auto it = d.MemberBegin(); it != d.MemberEnd(); ++it) {
        std::string key = it->name.GetString();
        if (std::find(std::begin(known), std::end(known), key) == std::end(known))
            return r.fail(key.c_str(), "unknown key (the keys are settings, last-model, recent, geometry, window, "
                                       "views, export-folder, export-size, recent-sessions)");
    }
    if (d.HasMember("views")) {
        const Value &views = d["views"];
        if (!views.IsObject())
            return r.fail("views", "must be an object {\"model file\": [{\"name\", \"camera\"}]}");
        for (auto it = views.MemberBegin(); it != views.MemberEnd(); ++it) {
            if (!it->value.IsArray())
                return r.fail("views", "each model's views must be an array");
            std::vector<SavedView> &list = state.views[it->name.GetString()];
            for (const Value &view : it->value.GetArray()) {
                if (!view.IsObject() || !view.HasMember("name") || !view["name"].IsString() ||
                    !view.HasMember("camera"))
                    return r.fail("views", "every view needs a \"name\" string and a \"camera\"");
                // the camera is checked as a preset's
                rapidjson::Document wrapper(rapidjson::kObjectType);
                wrapper.AddMember("camera", Value(view["camera"], wrapper.GetAllocator()), wrapper.GetAllocator());
                RenderSettings unused;
                SavedView saved{view["name"].GetString(), Camera()};
                bool has_camera;
                if (!preset_from_object(file, text, wrapper, unused, saved.camera, has_camera, nullptr, error))
                    return false;
                list.push_back(saved);
            }
        }
    }
    if (d.HasMember("export-folder")) {
        if (!d["export-folder"].IsString())
            return r.fail("export-folder", "must be a folder name");
        state.export_folder = d["export-folder"].GetString();
    }
    if (d.HasMember("export-size")) {
        const Value &size = d["export-size"];
        if (!size.IsArray() || size.Size() != 2 || !size[0].IsInt() || !size[1].IsInt() || size[0].GetInt() < 1 ||
            size[1].GetInt() < 1 || size[0].GetInt() > 16384 || size[1].GetInt() > 16384)
            return r.fail("export-size", "must be [width, height] in pixels, 1..16384");
        state.export_width = size[0].GetInt();
        state.export_height = size[1].GetInt();
    }
    if (d.HasMember("settings")) {
        // the settings are checked as a preset would be (ranges, names); parts
        // are checked against the model once it is loaded
        const Value &settings = d["settings"];
        if (!settings.IsObject())
            return r.fail("settings", "must be an object (a preset)");
        RenderSettings checked;
        Camera camera;
        bool has_camera;
        if (!preset_from_object(file, text, settings, checked, camera, has_camera, nullptr, error))
            return false;
        rapidjson::StringBuffer buffer;
        rapidjson::PrettyWriter<rapidjson::StringBuffer> writer(buffer);
        writer.SetIndent(' ', 2);
        settings.Accept(writer);
        state.settings = std::string(buffer.GetString()) + "\n";
    }
    if (d.HasMember("last-model")) {
        if (!d["last-model"].IsString())
            return r.fail("last-model", "must be a file name");
        state.last_model = d["last-model"].GetString();
    }
    if (d.HasMember("recent")) {
        const Value &recent = d["recent"];
        if (!recent.IsArray())
            return r.fail("recent", "must be an array of file names");
        for (const Value &name : recent.GetArray()) {
            if (!name.IsString())
                return r.fail("recent", "must be an array of file names");
            state.recent.push_back(name.GetString());
        }
    }
    if (d.HasMember("recent-sessions")) { // File > Open recent session (docs/sessions.md)
        const Value &recent = d["recent-sessions"];
        if (!recent.IsArray())
            return r.fail("recent-sessions", "must be an array of file names");
        for (const Value &name : recent.GetArray()) {
            if (!name.IsString())
                return r.fail("recent-sessions", "must be an array of file names");
            state.recent_sessions.push_back(name.GetString());
        }
    }
    for (const char *key : {"geometry", "window"}) {
        if (!d.HasMember(key))
            continue;
        if (!d[key].IsString() || !is_base64(d[key].GetString()))
            return r.fail(key, "must be a base64 string");
        (std::strcmp(key, "geometry") == 0 ? state.geometry : state.window) = d[key].GetString();
    }
    out = state;
    return true;
}

std::string saved_state_to_json(const SavedStateText &state)
{
    rapidjson::Document d(rapidjson::kObjectType);
    auto &a = d.GetAllocator();
    if (!state.settings.empty()) {
        rapidjson::Document settings(&a);
        settings.Parse<rapidjson::kParseFullPrecisionFlag>(state.settings.c_str(), state.settings.size());
        if (!settings.HasParseError() && settings.IsObject())
            add(d, "settings", Value(settings, a), a);
    }
    if (!state.last_model.empty())
        add(d, "last-model", string_value(state.last_model, a), a);
    Value recent(rapidjson::kArrayType);
    for (const std::string &name : state.recent)
        recent.PushBack(string_value(name, a), a);
    add(d, "recent", std::move(recent), a);
    if (!state.recent_sessions.empty()) {
        Value sessions(rapidjson::kArrayType);
        for (const std::string &name : state.recent_sessions)
            sessions.PushBack(string_value(name, a), a);
        add(d, "recent-sessions", std::move(sessions), a);
    }
    if (!state.geometry.empty())
        add(d, "geometry", string_value(state.geometry, a), a);
    if (!state.window.empty())
        add(d, "window", string_value(state.window, a), a);
    Value views(rapidjson::kObjectType);
    for (const auto &entry : state.views) {
        if (entry.second.empty())
            continue;
        Value list(rapidjson::kArrayType);
        for (const SavedView &view : entry.second) {
            Value item(rapidjson::kObjectType);
            add(item, "name", string_value(view.name, a), a);
            add(item, "camera", camera_value(view.camera, a), a);
            list.PushBack(std::move(item), a);
        }
        views.AddMember(string_value(entry.first, a), std::move(list), a);
    }
    if (views.MemberCount() > 0)
        add(d, "views", std::move(views), a);
    if (!state.export_folder.empty())
        add(d, "export-folder", string_value(state.export_folder, a), a);
    if (state.export_width > 0 && state.export_height > 0) {
        Value size(rapidjson::kArrayType);
        size.PushBack(state.export_width, a).PushBack(state.export_height, a);
        add(d, "export-size", std::move(size), a);
    }
    rapidjson::StringBuffer buffer;
    rapidjson::PrettyWriter<rapidjson::StringBuffer> writer(buffer);
    writer.SetIndent(' ', 2);
    d.Accept(writer);
    return std::string(buffer.GetString()) + "\n";
}

bool read_model_list(const std::string &file, const std::string &text, const std::string &base_dir,
                     std::vector<ModelEntry> &out, std::string &error)
{
    rapidjson::Document d;
    if (!parse_json(file, text, d, error))
        return false;
    if (!d.IsObject() || !d.HasMember("models") || !d["models"].IsArray()) {
        error = file + ":1: expected an object with a \"models\" array";
        return false;
    }
    PresetReader r{file, text, error};
    for (const Value &entry : d["models"].GetArray()) {
        if (!entry.IsObject() || !entry.HasMember("name") || !entry["name"].IsString() || !entry.HasMember("path") ||
            !entry["path"].IsString())
            return r.fail("models", "every entry needs \"name\" and \"path\" strings");
        std::string path = entry["path"].GetString();
        if (!path.empty() && path[0] != '/')
            path = base_dir + "/" + path;
        out.push_back({entry["name"].GetString(), path});
    }
    return true;
}

std::string algorithm_summary(const oit_algorithm_ops &ops)
{
    const std::string line = ops.summary ? ops.summary : "";
    const std::string word = ops.exact ? "exact" : "approximate";
    // the word on its own (case aside), not inside another ("inexact")
    std::string lower = line;
    for (char &c : lower)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    for (size_t at = lower.find(word); at != std::string::npos; at = lower.find(word, at + 1)) {
        bool starts = at == 0 || !std::isalpha(static_cast<unsigned char>(lower[at - 1]));
        bool ends = at + word.size() == lower.size() || !std::isalpha(static_cast<unsigned char>(lower[at + word.size()]));
        if (starts && ends)
            return line;
    }
    return line + " (" + word + ")";
}

oit_overlay_options view_aids(const RenderSettings &settings)
{
    oit_overlay_options o;
    oit_overlay_options_defaults(&o);
    o.axes = settings.axes;
    o.axes_corner = settings.axes_corner;
    o.scale_bar = settings.scale_bar;
    return o;
}

oit_overlay_options export_aids(const RenderSettings &settings)
{
    oit_overlay_options o = view_aids(settings);
    if (!settings.aids_in_export)
        o.axes = o.scale_bar = false;
    return o;
}
