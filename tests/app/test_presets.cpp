// test_presets.cpp: a preset restores the whole state (issue 27, item 5). Every
// field of RenderSettings and the camera set away from its default survives
// save -> reset -> load; a preset with fewer keys gives the defaults, not what
// was there before; older presets still load; the saved state keeps saved
// views and the export's choices. No window and no GL.
#include <QtTest/QtTest>

#include <cstring>
#include <string>

#include <rapidjson/document.h>

#include "parts_test_model.h"
#include "settings.h"

// A field added to these structs without preset support must fail here: add
// it to the preset (settings.cpp), to every_field_changed() and to
// differences() below, then update the size. Sizes on x86-64 (LP64).
static_assert(sizeof(oit_modulation) == 84, "oit_modulation changed: presets (settings.cpp) and this test");
static_assert(sizeof(oit_algorithm_config) == 72, "oit_algorithm_config changed: presets (settings.cpp) and this test");
static_assert(sizeof(oit_import_options) == 16, "oit_import_options changed: presets (settings.cpp) and this test");
static_assert(sizeof(RenderSettings) == 496, "RenderSettings changed: presets (settings.cpp) and this test");
static_assert(sizeof(Camera) == 136, "Camera changed: presets (settings.cpp) and this test");

namespace {

// Every field a preset holds, each away from its default.
void every_field_changed(RenderSettings &s, Camera &c)
{
    s.algorithm = "dp";
    s.config.max_memory_bytes = uint64_t(300) * 1024 * 1024;
    s.config.ll_sort = OIT_LL_SORT_LOCAL_ARRAY;
    s.config.max_layers = 5;
    s.config.layers = 4;
    s.config.moments = OIT_MOMENTS_POWER6;
    s.config.wavelet_rank = 2;
    s.config.seed = 7;
    s.config.stochastic_masks = OIT_STOCHASTIC_INDEPENDENT;
    s.alpha = 0.3f;
    s.shading = OIT_SHADE_FLAT;
    s.background[0] = 0.1f;
    s.background[1] = 0.2f;
    s.background[2] = 0.3f;
    oit_modulation &m = s.modulation;
    m.view = OIT_VIEW_LAYER;
    m.view_parameter = 2;
    m.mode = OIT_MODULATE_FIELDS;
    m.neighbours = OIT_NEIGHBOURS_EPSILON;
    m.curvature_neighbours = 8;
    m.curvature_effect = 3.5f;
    m.focus_region = 2.5f;
    m.distance = OIT_DISTANCE_SKIP;
    m.distance_skip = 3;
    m.fields = OIT_FIELD_ALPHA | OIT_FIELD_GAMMA;
    m.diffusion_iterations = 7;
    m.blur_iterations = 2;
    m.lambda_alpha = 0.7f;
    m.lambda_beta = 0.06f;
    m.lambda_gamma = 0.3f;
    m.has_halo_colour = true;
    m.halo_colour[0] = 0.9f;
    m.halo_colour[1] = 0.1f;
    m.halo_colour[2] = 0.4f;
    m.last_layer_opaque = true;
    m.epsilon_max = 0.02f;
    s.focus_shape = OIT_FOCUS_BOX;
    const double box[6] = {-1.5, -0.25, 0.125, 2.5, 0.75, 1.0625};
    std::copy(box, box + 6, s.focus);
    s.contrast = 2.5f;
    s.part_alpha = {0.25f, 1.0f, 0.5f};
    s.part_visible = {1, 0, 1};
    s.error_view = true;
    s.split = SplitMode::SideBySide;
    s.split_algorithm = "wboit";
    s.wipe = 0.3f;
    s.preview_algorithm = "wboit";
    // the tessellation is a level or a deflection in mm (one setting; the level
    // round trip is app_workbench's tessellation test)
    s.import.linear_deflection_mm = 0.25;
    // sections and the exploded view (issue 28): a disabled plane is kept too
    SectionPlane a, b;
    a.normal[0] = 0.0;
    a.normal[2] = -1.0;
    a.d = 0.375;
    b.normal[1] = 2.0;
    b.d = -0.1;
    b.enabled = false;
    s.sections = {a, b};
    s.section_parts = {0, 1, 1};
    s.caps = false;
    s.explode = 1.5;
    // the orientation aids (issue 29): "axes" holds the corner or "off" (the
    // triad on, its default, in another corner); aids_in_export is the
    // workbench's choice, not a preset's
    s.axes_corner = OIT_CORNER_TOP_RIGHT;
    s.scale_bar = true;
    s.samples = 8; // issue 29 (default 0: auto)
    c.set_mode(Camera::Mode::Walk);
    c.orthographic = true;
    c.fov_degrees = 55.0f;
    c.orbit_style = Camera::Orbit::Trackball;
    c.up = Camera::Up::Z;
    c.eye = glm::dvec3(1.25, -2.5, 3.75);
    c.orientation = glm::normalize(glm::dquat(0.9, 0.1, -0.2, 0.3));
    c.target = glm::dvec3(0.5, 0.25, -0.125);
}

#define SAME(field)                                                                                                    \
    if (!(a.field == b.field))                                                                                         \
        out << #field;
#define SAME_ARRAY(field, n)                                                                                           \
    for (int i = 0; i < (n); ++i)                                                                                      \
        if (!(a.field[i] == b.field[i]))                                                                               \
            out << QString(#field "[%1]").arg(i);

// The fields a preset holds that differ (config: only the preset's options).
QStringList differences(const RenderSettings &a, const RenderSettings &b)
{
    QStringList out;
    SAME(algorithm) SAME(config.max_memory_bytes) SAME(config.ll_sort) SAME(config.max_layers) SAME(config.layers)
    SAME(config.moments) SAME(config.wavelet_rank) SAME(config.seed) SAME(config.stochastic_masks) SAME(alpha) SAME(shading) SAME_ARRAY(background, 3)
    SAME(modulation.view) SAME(modulation.view_parameter) SAME(modulation.mode) SAME(modulation.neighbours)
    SAME(modulation.curvature_neighbours) SAME(modulation.curvature_effect) SAME(modulation.focus_region)
    SAME(modulation.distance) SAME(modulation.distance_skip) SAME(modulation.fields)
    SAME(modulation.diffusion_iterations) SAME(modulation.blur_iterations) SAME(modulation.lambda_alpha)
    SAME(modulation.lambda_beta) SAME(modulation.lambda_gamma) SAME(modulation.has_halo_colour)
    SAME_ARRAY(modulation.halo_colour, 3) SAME(modulation.last_layer_opaque) SAME(modulation.epsilon_max)
    SAME(focus_shape) SAME_ARRAY(focus, 6) SAME(contrast) SAME(part_alpha) SAME(part_visible) SAME(error_view)
    SAME(split) SAME(split_algorithm) SAME(wipe) SAME(preview_algorithm) SAME(import.tessellation) SAME(import.linear_deflection_mm)
    SAME(sections) SAME(section_parts) SAME(caps) SAME(explode) SAME(axes) SAME(axes_corner) SAME(scale_bar)
    SAME(samples)
    return out;
}

QStringList camera_differences(const Camera &a, const Camera &b)
{
    QStringList out;
    SAME(mode()) SAME(orthographic) SAME(fov_degrees) SAME(orbit_style) SAME(up) SAME(eye) SAME(orientation)
    SAME(target)
    return out;
}
#undef SAME
#undef SAME_ARRAY

} // namespace

class PresetsTest : public QObject {
    Q_OBJECT
    parts_test::Model model_;

private slots:
    void initTestCase()
    {
        QString message;
        QVERIFY2(parts_test::build(model_,
                                   {parts_test::square("housing", 0, 0, 0, 1), parts_test::square("gear", 0, 0, 0.5f, 0.5f),
                                    parts_test::square("shaft", 0.5f, 0, 1, 0.25f)},
                                   &message),
                 qPrintable(message));
    }

    // Every field away from its default, saved, reset to the defaults, loaded:
    // the same settings and camera, and the same preset written again.
    void every_field_survives_save_reset_load()
    {
        RenderSettings changed;
        Camera camera;
        every_field_changed(changed, camera);
        RenderSettings defaults;
        defaults.reset_parts(model_.m);
        Camera default_camera;
        // every field really is away from its default (else the test proves nothing for it)
        QStringList changed_fields = differences(changed, defaults);
        // 58 comparisons (arrays element by element), all but import.tessellation
        // (the deflection stands for it) and axes (on by default; the corner stands for it)
        QVERIFY2(changed_fields.size() == 58 && !changed_fields.contains("import.tessellation"),
                 qPrintable(changed_fields.join(", ")));
        QCOMPARE(camera_differences(camera, default_camera).size(), 8);

        const std::string text = preset_to_json(changed, camera, &model_.m);
        RenderSettings loaded = defaults;
        Camera loaded_camera = default_camera;
        bool has_camera = false;
        std::string error;
        QVERIFY2(preset_from_json("p.json", text, loaded, loaded_camera, has_camera, &model_.m, error), error.c_str());
        QVERIFY(has_camera);
        QVERIFY2(differences(loaded, changed).isEmpty(), qPrintable(differences(loaded, changed).join(", ")));
        QVERIFY2(camera_differences(loaded_camera, camera).isEmpty(), qPrintable(camera_differences(loaded_camera, camera).join(", ")));
        QCOMPARE(preset_to_json(loaded, loaded_camera, &model_.m), text);

        // every key the writer writes is changed by some field: a key added to
        // the preset must be given a non-default value above
        rapidjson::Document all, plain;
        all.Parse(text.c_str());
        const std::string plain_text = preset_to_json(defaults, default_camera, &model_.m);
        plain.Parse(plain_text.c_str());
        QVERIFY(all.IsObject() && plain.IsObject());
        QCOMPARE(all.MemberCount(), plain.MemberCount() - 1 + 1); // focus-box in place of focus: none
        for (auto it = all.MemberBegin(); it != all.MemberEnd(); ++it) {
            const char *key = it->name.GetString();
            QVERIFY2(!plain.HasMember(key) || !(plain[key] == it->value), key);
        }
    }

    // A preset with fewer keys gives the defaults for the rest, whatever was
    // there before: focus "none" clears a focus box, no halo colour clears one.
    void missing_keys_give_defaults_not_leftovers()
    {
        RenderSettings before;
        Camera camera;
        every_field_changed(before, camera);
        const Camera before_camera = camera;
        RenderSettings loaded = before;
        bool has_camera = true;
        std::string error;
        QVERIFY2(preset_from_json("p.json", "{\"algorithm\": \"wboit\"}", loaded, camera, has_camera, &model_.m, error),
                 error.c_str());
        RenderSettings expected;
        expected.reset_parts(model_.m);
        expected.algorithm = "wboit";
        QVERIFY2(differences(loaded, expected).isEmpty(), qPrintable(differences(loaded, expected).join(", ")));
        QVERIFY(!has_camera);
        QCOMPARE(camera_differences(camera, before_camera), QStringList()); // no camera: the view stays

        // a preset of the default settings (focus none, no halo colour) over a focus box
        RenderSettings defaults;
        defaults.reset_parts(model_.m);
        const std::string saved = preset_to_json(defaults, Camera(), &model_.m);
        QVERIFY(saved.find("\"focus\": \"none\"") != std::string::npos);
        QVERIFY(saved.find("\"halo-colour\": \"auto\"") != std::string::npos);
        loaded = before;
        QVERIFY2(preset_from_json("p.json", saved, loaded, camera, has_camera, &model_.m, error), error.c_str());
        QCOMPARE(loaded.focus_shape, OIT_FOCUS_NONE);
        QVERIFY(!loaded.modulation.has_halo_colour);
        QCOMPARE(preset_to_json(loaded, Camera(), &model_.m), saved);

        // a camera with a pose only: mode, projection and fov default
        camera = before_camera;
        QVERIFY2(preset_from_json("p.json", "{\"camera\": {\"eye\": [0, 0, 5]}}", loaded, camera, has_camera, &model_.m, error),
                 error.c_str());
        QVERIFY(has_camera);
        QCOMPARE(camera.mode(), Camera::Mode::Orbit);
        QVERIFY(!camera.orthographic);
        QCOMPARE(camera.fov_degrees, Camera().fov_degrees);
        QCOMPARE(camera.orbit_style, Camera::Orbit::Turntable);
        QCOMPARE(camera.up, Camera::Up::Y);
        QCOMPARE(camera.eye, glm::dvec3(0, 0, 5));
        QCOMPARE(camera.target, before_camera.target); // the pose it lacks is kept
    }

    // What presets do not hold is kept: the shader folder and the tests' options.
    void what_presets_do_not_hold_is_kept()
    {
        RenderSettings before;
        before.config.shader_dir = "/somewhere/shaders";
        before.config.initial_fragment_capacity = 17;
        before.config.debug = true;
        RenderSettings loaded = before;
        Camera camera;
        bool has_camera;
        std::string error;
        QVERIFY2(preset_from_json("p.json", "{}", loaded, camera, has_camera, nullptr, error), error.c_str());
        QCOMPARE(loaded.config.shader_dir, before.config.shader_dir);
        QCOMPARE(loaded.config.initial_fragment_capacity, uint64_t(17));
        QVERIFY(loaded.config.debug);
    }

    // Presets written before every key was written still load, and the new
    // keys' bad values are named.
    void older_presets_load_and_new_keys_are_checked()
    {
        const char *older = "{\n  \"algorithm\": \"ll\",\n  \"alpha\": 0.4,\n  \"halo-colour\": [1, 0, 0],\n"
                            "  \"focus-point\": [0, 0, 0.5]\n}\n";
        RenderSettings loaded;
        Camera camera;
        bool has_camera;
        std::string error;
        QVERIFY2(preset_from_json("old.json", older, loaded, camera, has_camera, &model_.m, error), error.c_str());
        QVERIFY(loaded.modulation.has_halo_colour);
        QCOMPARE(loaded.modulation.halo_colour[0], 1.0f);
        QCOMPARE(loaded.focus_shape, OIT_FOCUS_POINT);
        QCOMPARE(loaded.alpha, 0.4f);
        QVERIFY(!preset_from_json("bad.json", "{\n\"focus\": \"box\"}", loaded, camera, has_camera, nullptr, error));
        QVERIFY2(QString::fromStdString(error).startsWith("bad.json:2:") && error.find("focus") != std::string::npos,
                 error.c_str());
        QVERIFY(!preset_from_json("bad.json", "{\"halo-colour\": \"red\"}", loaded, camera, has_camera, nullptr, error));
        QVERIFY2(error.find("halo-colour") != std::string::npos, error.c_str());
    }

    // The saved state keeps each model's views and the export's folder and
    // size; bad ones are named.
    void saved_state_keeps_views_and_export_choices()
    {
        SavedStateText state;
        RenderSettings unused;
        Camera c;
        every_field_changed(unused, c);
        state.views["/models/a.obj"] = {{"inside", c}, {"top", Camera()}};
        state.export_folder = "/home/someone/Pictures/renders";
        state.export_width = 3840;
        state.export_height = 2160;
        const std::string text = saved_state_to_json(state);
        SavedStateText read;
        std::string error;
        QVERIFY2(saved_state_from_json("settings.json", text, read, error), error.c_str());
        QCOMPARE(int(read.views.size()), 1);
        const std::vector<SavedView> &views = read.views["/models/a.obj"];
        QCOMPARE(int(views.size()), 2);
        QCOMPARE(QString::fromStdString(views[0].name), QString("inside"));
        QCOMPARE(camera_differences(views[0].camera, c), QStringList());
        QCOMPARE(QString::fromStdString(views[1].name), QString("top"));
        QCOMPARE(QString::fromStdString(read.export_folder), QString("/home/someone/Pictures/renders"));
        QCOMPARE(read.export_width, 3840);
        QCOMPARE(read.export_height, 2160);
        QCOMPARE(saved_state_to_json(read), text);

        const char *bad[][2] = {
            {"{\"views\": []}", "views"},
            {"{\"views\": {\"a.obj\": [{\"camera\": {}}]}}", "name"},
            {"{\"views\": {\"a.obj\": [{\"name\": \"x\", \"camera\": {\"fov\": 500}}]}}", "fov"},
            {"{\"export-size\": [0, 10]}", "export-size"},
            {"{\"export-folder\": 3}", "export-folder"},
        };
        for (const auto &b : bad) {
            QVERIFY2(!saved_state_from_json("settings.json", b[0], read, error), b[0]);
            QVERIFY2(error.find(b[1]) != std::string::npos, error.c_str());
        }
    }
};

QTEST_GUILESS_MAIN(PresetsTest)
#include "test_presets.moc"
