// session.cpp: see session.h.
#include "session.h"

#include <QDir>
#include <QFileInfo>

#include <algorithm>

#include <rapidjson/document.h>
#include <rapidjson/error/en.h>
#include <rapidjson/prettywriter.h>
#include <rapidjson/stringbuffer.h>
#include <rapidjson/writer.h>

using rapidjson::Value;

namespace {

// every double read back bit for bit (RapidJSON's default parse may be off by one unit in the last place)
constexpr unsigned kExact = rapidjson::kParseFullPrecisionFlag;

int line_at(const std::string &text, size_t offset)
{
    offset = std::min(offset, text.size());
    return 1 + int(std::count(text.begin(), text.begin() + long(offset), '\n'));
}

std::string to_text(const Value &v)
{
    rapidjson::StringBuffer buffer;
    rapidjson::Writer<rapidjson::StringBuffer> writer(buffer);
    v.Accept(writer);
    return buffer.GetString();
}

// The preset's "camera" object for this camera (preset_to_json's, one vocabulary).
Value camera_object(const Camera &camera, rapidjson::Document::AllocatorType &a)
{
    rapidjson::Document preset;
    preset.Parse<kExact>(preset_to_json(RenderSettings(), camera, nullptr).c_str());
    return Value(preset["camera"], a);
}

// 16 numbers row by row (the command line's --modelview order) from column-major.
Value matrix_rows(const double m[16], rapidjson::Document::AllocatorType &a)
{
    Value rows(rapidjson::kArrayType);
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col)
            rows.PushBack(Value(m[col * 4 + row]), a);
    return rows;
}

// The preset reader's "FILE:LINE: problem" without "FILE:LINE: " (its lines are
// the re-written object's, not the session file's).
std::string without_place(const std::string &file, const std::string &problem)
{
    size_t at = problem.find(": ", std::min(problem.size(), file.size()));
    return at == std::string::npos ? problem : problem.substr(at + 2);
}

} // namespace

std::string session_to_json(const std::string &session_path, const std::string &model_path,
                            const RenderSettings &settings, const Camera &camera, const oit_model *model,
                            const std::vector<SavedView> &views, const SessionExport &exported)
{
    rapidjson::Document d(rapidjson::kObjectType);
    auto &a = d.GetAllocator();
    d.AddMember("format", Value(kSessionFormat, a), a);
    d.AddMember("version", Value(kSessionVersion), a);
    // relative to the session's folder: the two travel together
    QDir folder = QFileInfo(QString::fromStdString(session_path)).absoluteDir();
    std::string relative = folder.relativeFilePath(QString::fromStdString(model_path)).toStdString();
    Value models(rapidjson::kArrayType);
    models.PushBack(Value(relative.c_str(), a), a);
    d.AddMember("models", std::move(models), a);
    rapidjson::Document render;
    render.Parse<kExact>(preset_to_json(settings, camera, model).c_str());
    d.AddMember("render", Value(render, a), a);
    Value list(rapidjson::kArrayType);
    for (const SavedView &view : views) {
        Value item(rapidjson::kObjectType);
        item.AddMember("name", Value(view.name.c_str(), a), a);
        item.AddMember("camera", camera_object(view.camera, a), a);
        list.PushBack(std::move(item), a);
    }
    d.AddMember("views", std::move(list), a);
    if (exported.width > 0 && exported.height > 0) {
        Value e(rapidjson::kObjectType), size(rapidjson::kArrayType);
        size.PushBack(exported.width, a).PushBack(exported.height, a);
        e.AddMember("size", std::move(size), a);
        e.AddMember("modelview", matrix_rows(exported.modelview, a), a);
        e.AddMember("projection", matrix_rows(exported.projection, a), a);
        e.AddMember("aids", Value(exported.aids), a);
        if (exported.samples > 0)
            e.AddMember("samples", Value(exported.samples), a);
        d.AddMember("export", std::move(e), a);
    }
    rapidjson::StringBuffer buffer;
    rapidjson::PrettyWriter<rapidjson::StringBuffer> writer(buffer);
    writer.SetIndent(' ', 2);
    writer.SetFormatOptions(rapidjson::kFormatSingleLineArray);
    d.Accept(writer);
    return std::string(buffer.GetString()) + "\n";
}

bool session_from_json(const std::string &file, const std::string &text, SessionData &out, std::string &error)
{
    out = SessionData();
    auto fail = [&](const std::string &problem) {
        error = file + ": " + problem;
        return false;
    };
    auto warn = [&](const std::string &problem) { out.warnings.push_back(file + ": " + problem); };
    rapidjson::Document d;
    d.Parse<kExact>(text.c_str(), text.size());
    if (d.HasParseError())
        return fail("line " + std::to_string(line_at(text, d.GetErrorOffset())) + ": not valid JSON: " +
                    rapidjson::GetParseError_En(d.GetParseError()));
    if (!d.IsObject())
        return fail("a session is a JSON object");
    if (!d.HasMember("format") || !d["format"].IsString() || d["format"].GetString() != std::string(kSessionFormat))
        return fail(std::string("not an oit session: \"format\" must be \"") + kSessionFormat + "\"" +
                    (d.HasMember("format") ? ", got " + to_text(d["format"]) : std::string(", and is missing")));
    int version = 1; // missing: version 1
    if (d.HasMember("version")) {
        if (!d["version"].IsInt() || d["version"].GetInt() < 1)
            return fail("\"version\" must be a whole number from 1, got " + to_text(d["version"]));
        version = d["version"].GetInt();
    }
    if (version > kSessionVersion)
        return fail("version " + std::to_string(version) + " is newer than this build reads (" +
                    std::to_string(kSessionVersion) + "): a newer oit-workbench wrote it");
    static const char *const known[] = {"format", "version", "models", "render", "views", "export"};
    for (auto it = d.MemberBegin(); it != d.MemberEnd(); ++it)
        if (std::find_if(std::begin(known), std::end(known), [&](const char *k) {
                return it->name.GetString() == std::string(k);
            }) == std::end(known))
            warn(std::string("unknown field \"") + it->name.GetString() + "\" ignored");

    if (!d.HasMember("models") || !d["models"].IsArray() || d["models"].Empty())
        return fail("\"models\" must be an array with the model's path (relative to the session's folder)");
    const Value &models = d["models"];
    for (const Value &m : models.GetArray())
        if (!m.IsString() || m.GetStringLength() == 0)
            return fail("\"models\" must hold paths (strings)");
    if (models.Size() > 1)
        warn("\"models\": the workbench opens one model; the first is used");
    QString model = QString::fromUtf8(models[0].GetString());
    QDir folder = QFileInfo(QString::fromStdString(file)).absoluteDir();
    QString resolved = QDir::cleanPath(folder.absoluteFilePath(model));
    if (!QFileInfo(resolved).isFile())
        return fail("model '" + model.toStdString() + "' not found (looked for " + resolved.toStdString() + ")");
    out.model_path = resolved.toStdString();

    if (d.HasMember("render")) {
        const Value &render = d["render"];
        if (!render.IsObject())
            return fail("\"render\" must be an object (a preset: the command line's flag names)");
        // unknown keys are said and dropped; each key is tried alone against
        // the preset reader, the one list of the keys it knows
        rapidjson::Document kept(rapidjson::kObjectType);
        for (auto it = render.MemberBegin(); it != render.MemberEnd(); ++it) {
            rapidjson::Document one(rapidjson::kObjectType);
            one.AddMember(Value(it->name, one.GetAllocator()), Value(it->value, one.GetAllocator()),
                          one.GetAllocator());
            RenderSettings s;
            Camera c;
            bool has_camera;
            std::string problem;
            if (!preset_from_json(file, to_text(one), s, c, has_camera, nullptr, problem) &&
                problem.find("unknown key") != std::string::npos) {
                warn(std::string("\"render\": unknown field \"") + it->name.GetString() + "\" ignored");
                continue;
            }
            kept.AddMember(Value(it->name, kept.GetAllocator()), Value(it->value, kept.GetAllocator()),
                           kept.GetAllocator());
        }
        out.render = to_text(kept);
        // the whole object checked now (ranges, names): a bad value is an error, not a surprise later
        RenderSettings s;
        Camera c;
        bool has_camera;
        std::string problem;
        if (!preset_from_json(file, out.render, s, c, has_camera, nullptr, problem))
            return fail("\"render\": " + without_place(file, problem));
    }
    if (d.HasMember("views")) {
        const Value &views = d["views"];
        if (!views.IsArray())
            return fail("\"views\" must be an array of {\"name\", \"camera\"}");
        for (const Value &view : views.GetArray()) {
            if (!view.IsObject() || !view.HasMember("name") || !view["name"].IsString() ||
                view["name"].GetStringLength() == 0 || !view.HasMember("camera"))
                return fail("\"views\": every view needs a \"name\" string and a \"camera\"");
            for (auto it = view.MemberBegin(); it != view.MemberEnd(); ++it)
                if (it->name.GetString() != std::string("name") && it->name.GetString() != std::string("camera"))
                    warn(std::string("\"views\": unknown field \"") + it->name.GetString() + "\" ignored");
            rapidjson::Document wrapper(rapidjson::kObjectType);
            wrapper.AddMember("camera", Value(view["camera"], wrapper.GetAllocator()), wrapper.GetAllocator());
            SavedView saved{view["name"].GetString(), Camera()};
            RenderSettings unused;
            bool has_camera;
            std::string problem;
            if (!preset_from_json(file, to_text(wrapper), unused, saved.camera, has_camera, nullptr, problem))
                return fail("\"views\": " + saved.name + ": " + without_place(file, problem));
            out.views.push_back(saved);
        }
    }
    if (d.HasMember("export")) {
        const Value &e = d["export"];
        if (!e.IsObject())
            return fail("\"export\" must be an object {\"size\", \"modelview\", \"projection\"}");
        for (auto it = e.MemberBegin(); it != e.MemberEnd(); ++it) {
            std::string key = it->name.GetString();
            if (key != "size" && key != "modelview" && key != "projection" && key != "aids" &&
                key != "samples")
                warn("\"export\": unknown field \"" + key + "\" ignored");
        }
        if (e.HasMember("size")) {
            const Value &size = e["size"];
            if (!size.IsArray() || size.Size() != 2 || !size[0].IsInt() || !size[1].IsInt() || size[0].GetInt() < 1 ||
                size[1].GetInt() < 1 || size[0].GetInt() > 16384 || size[1].GetInt() > 16384)
                return fail("\"export\": \"size\" must be [width, height], 1..16384 each");
            out.export_width = size[0].GetInt();
            out.export_height = size[1].GetInt();
        }
        if (e.HasMember("samples")) {
            const Value &n = e["samples"];
            if (!n.IsInt() || (n.GetInt() != 1 && n.GetInt() != 4 && n.GetInt() != 8 && n.GetInt() != 16))
                return fail("\"export\": \"samples\" must be 1, 4, 8 or 16");
        }
        if (e.HasMember("aids")) {
            if (!e["aids"].IsBool())
                return fail("\"export\": \"aids\" must be true or false");
            out.export_aids = e["aids"].GetBool() ? 1 : 0;
        }
        for (const char *key : {"modelview", "projection"})
            if (e.HasMember(key)) {
                const Value &m = e[key];
                bool ok = m.IsArray() && m.Size() == 16;
                for (rapidjson::SizeType i = 0; ok && i < 16; ++i)
                    ok = m[i].IsNumber();
                if (!ok)
                    return fail(std::string("\"export\": \"") + key + "\" must be 16 numbers, row by row");
            }
    }
    return true;
}
