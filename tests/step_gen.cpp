// step_gen OUTDIR: writes a small gearbox assembly with OpenCASCADE's own API
// as STEP (AP214 in millimetres and in inches, AP242, AP203) and IGES; the same with
// the cover and bolts lifted 1 mm off the housing (gearbox_apart.step); as an
// assembly whose parts are files of their own (external/gearbox.step); and
// OUTDIR/expected.json saying what was written (parts, paths, colours, bounds
// in millimetres, unit), which tests/step_import.py checks the import against.
//
// The gearbox (millimetres):
//   gearbox
//     housing       box 0..100 x 0..60 x 0..40, grey; its top face red
//     cover         box 0..100 x 0..60 x 40..45, blue, 50% opaque: its bottom
//                   face lies on the housing's top face (mating faces)
//     input_shaft   a subassembly placed at (0, 30, 20)
//       shaft       cylinder r 5 along x from -10 to 110, green
//       gear        cylinder r 20, 10 long, modelled along z, turned onto x
//                   (a rotation in the placement) at x 45..55, orange
//       bearing_1   a bearing (cylinder r 8, 5 long, along x) at x 0..5
//       bearing_2   the same part at x 95..100
//     bolt_1..4     one bolt part (cylinder r 3, 10 high, yellow) placed four
//                   times on the cover, z 45..55
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESCAFControl_Writer.hxx>
#include <IGESControl_Controller.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Quantity_ColorRGBA.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <STEPControl_Controller.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopoDS_Face.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_ColorTool.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <gp_Ax2.hxx>
#include <gp_Trsf.hxx>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace {

struct part_record {
    std::string path;
    float rgba[4];
};

Quantity_ColorRGBA rgba(double r, double g, double b, float a = 1.0f)
{
    return Quantity_ColorRGBA(Quantity_Color(r, g, b, Quantity_TOC_sRGB), a);
}

TDF_Label named(const TDF_Label &label, const char *name)
{
    TDataStd_Name::Set(label, name);
    return label;
}

gp_Trsf translation(double x, double y, double z)
{
    gp_Trsf t;
    t.SetTranslation(gp_Vec(x, y, z));
    return t;
}

Handle(TDocStd_Document) build(double cover_lift)
{
    Handle(XCAFApp_Application) app = XCAFApp_Application::GetApplication();
    Handle(TDocStd_Document) doc;
    app->NewDocument("MDTV-XCAF", doc);
    XCAFDoc_DocumentTool::SetLengthUnit(doc, 1.0, UnitsMethods_LengthUnit_Millimeter);
    Handle(XCAFDoc_ShapeTool) shapes = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
    Handle(XCAFDoc_ColorTool) colours = XCAFDoc_DocumentTool::ColorTool(doc->Main());

    TDF_Label gearbox = named(shapes->NewShape(), "gearbox");
    TDF_Label input_shaft = named(shapes->NewShape(), "input_shaft");

    BRepPrimAPI_MakeBox housing_box(gp_Pnt(0, 0, 0), gp_Pnt(100, 60, 40));
    TDF_Label housing = named(shapes->AddShape(housing_box.Shape(), false), "housing");
    colours->SetColor(housing, rgba(0.6, 0.6, 0.6), XCAFDoc_ColorSurf);
    TDF_Label top = shapes->AddSubShape(housing, housing_box.TopFace());
    colours->SetColor(top, rgba(0.9, 0.2, 0.1), XCAFDoc_ColorSurf);

    TDF_Label cover = named(shapes->AddShape(BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 40 + cover_lift), gp_Pnt(100, 60, 45 + cover_lift)).Shape(), false),
                            "cover");
    colours->SetColor(cover, rgba(0.2, 0.4, 0.9, 0.5f), XCAFDoc_ColorSurf);

    TDF_Label shaft = named(
        shapes->AddShape(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-10, 0, 0), gp_Dir(1, 0, 0)), 5, 120).Shape(), false),
        "shaft");
    colours->SetColor(shaft, rgba(0.2, 0.7, 0.3), XCAFDoc_ColorSurf);
    TDF_Label gear = named(shapes->AddShape(BRepPrimAPI_MakeCylinder(20, 10).Shape(), false), "gear");
    colours->SetColor(gear, rgba(0.9, 0.6, 0.1), XCAFDoc_ColorSurf);
    TDF_Label bearing = named(
        shapes->AddShape(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)), 8, 5).Shape(), false),
        "bearing");
    colours->SetColor(bearing, rgba(0.5, 0.5, 0.7), XCAFDoc_ColorSurf);
    TDF_Label bolt = named(shapes->AddShape(BRepPrimAPI_MakeCylinder(3, 10).Shape(), false), "bolt");
    colours->SetColor(bolt, rgba(0.9, 0.85, 0.2), XCAFDoc_ColorSurf);

    named(shapes->AddComponent(input_shaft, shaft, TopLoc_Location()), "shaft");
    gp_Trsf onto_x; /* z onto x: a quarter turn about y */
    onto_x.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 1, 0)), M_PI / 2);
    named(shapes->AddComponent(input_shaft, gear, TopLoc_Location(translation(45, 0, 0) * onto_x)), "gear");
    named(shapes->AddComponent(input_shaft, bearing, TopLoc_Location(translation(0, 0, 0))), "bearing_1");
    named(shapes->AddComponent(input_shaft, bearing, TopLoc_Location(translation(95, 0, 0))), "bearing_2");

    named(shapes->AddComponent(gearbox, housing, TopLoc_Location()), "housing");
    named(shapes->AddComponent(gearbox, cover, TopLoc_Location()), "cover");
    named(shapes->AddComponent(gearbox, input_shaft, TopLoc_Location(translation(0, 30, 20))), "input_shaft");
    const double corners[4][2] = {{10, 10}, {90, 10}, {10, 50}, {90, 50}};
    for (int b = 0; b < 4; ++b) {
        char name[16];
        snprintf(name, sizeof name, "bolt_%d", b + 1);
        named(shapes->AddComponent(gearbox, bolt, TopLoc_Location(translation(corners[b][0], corners[b][1], 45 + cover_lift))),
              name);
    }
    shapes->UpdateAssemblies();
    return doc;
}

const std::vector<part_record> parts = {
    {"gearbox/housing (colour 1)", {0.6f, 0.6f, 0.6f, 1}},
    {"gearbox/housing (colour 2)", {0.9f, 0.2f, 0.1f, 1}},
    {"gearbox/cover", {0.2f, 0.4f, 0.9f, 0.5f}},
    {"gearbox/input_shaft/shaft", {0.2f, 0.7f, 0.3f, 1}},
    {"gearbox/input_shaft/gear", {0.9f, 0.6f, 0.1f, 1}},
    {"gearbox/input_shaft/bearing_1", {0.5f, 0.5f, 0.7f, 1}},
    {"gearbox/input_shaft/bearing_2", {0.5f, 0.5f, 0.7f, 1}},
    {"gearbox/bolt_1", {0.9f, 0.85f, 0.2f, 1}},
    {"gearbox/bolt_2", {0.9f, 0.85f, 0.2f, 1}},
    {"gearbox/bolt_3", {0.9f, 0.85f, 0.2f, 1}},
    {"gearbox/bolt_4", {0.9f, 0.85f, 0.2f, 1}},
};

bool write_step(const Handle(TDocStd_Document) &doc, const std::string &path, const char *unit,
                const char *schema = "AP214IS")
{
    STEPControl_Controller::Init();
    Interface_Static::SetCVal("write.step.schema", schema);
    Interface_Static::SetCVal("write.step.unit", unit);
    STEPCAFControl_Writer writer;
    writer.SetColorMode(true);
    writer.SetNameMode(true);
    return writer.Transfer(doc, STEPControl_AsIs) && writer.Write(path.c_str()) == IFSelect_RetDone;
}

// An assembly whose parts are in files of their own (external references):
// DIR/external/gearbox.step refers to the parts' files beside it.
bool write_step_external(const Handle(TDocStd_Document) &doc, const std::string &dir)
{
    std::error_code ignored;
    std::filesystem::create_directories(dir, ignored);
    STEPControl_Controller::Init();
    Interface_Static::SetCVal("write.step.schema", "AP214IS");
    Interface_Static::SetCVal("write.step.unit", "MM");
    STEPCAFControl_Writer writer;
    writer.SetColorMode(true);
    writer.SetNameMode(true);
    return writer.Transfer(doc, STEPControl_AsIs, "") && writer.Write((dir + "/gearbox.step").c_str()) == IFSelect_RetDone;
}

bool write_iges(const Handle(TDocStd_Document) &doc, const std::string &path)
{
    IGESControl_Controller::Init();
    Interface_Static::SetCVal("write.iges.unit", "MM");
    IGESCAFControl_Writer writer;
    writer.SetColorMode(true);
    writer.SetNameMode(true);
    return writer.Transfer(doc) && writer.Write(path.c_str());
}

} // namespace

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: step_gen OUTDIR\n");
        return 2;
    }
    Message::DefaultMessenger()->ChangePrinters().Clear();
    const std::string dir = argv[1];
    std::error_code ignored; /* (a failure shows as the write's) */
    std::filesystem::create_directories(dir, ignored);
    Handle(TDocStd_Document) doc = build(0.0);
    /* the cover and its bolts 1 mm up, off the housing: one coplanar plane more */
    if (!write_step(build(1.0), dir + "/gearbox_apart.step", "MM")) {
        fprintf(stderr, "step_gen: cannot write %s/gearbox_apart.step\n", argv[1]);
        return 1;
    }
    // tree: the file keeps the assembly tree and names (IGES: OCCT writes it
    // flattened); colours: each part's, or only present on some part (IGES;
    // OCCT writes AP203 with colours too, through SHAPE_APPEARANCE_LAYER_MIM)
    struct file {
        const char *name, *unit;
        double to_mm;
        const char *tree, *colours;
        bool ok;
    } files[] = {
        {"gearbox.step", "millimetre", 1.0, "true", "\"parts\"", write_step(doc, dir + "/gearbox.step", "MM")},
        {"gearbox_inch.stp", "inch", 25.4, "true", "\"parts\"", write_step(doc, dir + "/gearbox_inch.stp", "INCH")},
        {"gearbox_ap242.step", "millimetre", 1.0, "true", "\"parts\"",
         write_step(doc, dir + "/gearbox_ap242.step", "MM", "AP242DIS")},
        {"gearbox_ap203.step", "millimetre", 1.0, "true", "\"parts\"",
         write_step(doc, dir + "/gearbox_ap203.step", "MM", "AP203")},
        {"gearbox.igs", "millimetre", 1.0, "false", "\"some part\"", write_iges(doc, dir + "/gearbox.igs")}};
    if (!write_step_external(doc, dir + "/external")) {
        fprintf(stderr, "step_gen: cannot write %s/external/gearbox.step\n", argv[1]);
        return 1;
    }
    for (const file &f : files)
        if (!f.ok) {
            fprintf(stderr, "step_gen: cannot write %s/%s\n", argv[1], f.name);
            return 1;
        }
    FILE *out = fopen((dir + "/expected.json").c_str(), "w");
    if (!out)
        return 1;
    fprintf(out, "{\"bounds_min\": [-10, 0, 0], \"bounds_max\": [110, 60, 55], \"nodes\": 2,\n \"files\": [");
    for (size_t f = 0; f < sizeof files / sizeof files[0]; ++f)
        fprintf(out, "%s\n  {\"name\": \"%s\", \"unit\": \"%s\", \"unit_to_mm\": %g, \"tree\": %s, \"colours\": %s}",
                f ? "," : "", files[f].name, files[f].unit, files[f].to_mm, files[f].tree, files[f].colours);
    fprintf(out, "],\n \"parts\": [");
    for (size_t p = 0; p < parts.size(); ++p)
        fprintf(out, "%s\n  {\"path\": \"%s\", \"colour\": [%g, %g, %g], \"opacity\": %g}", p ? "," : "",
                parts[p].path.c_str(), parts[p].rgba[0], parts[p].rgba[1], parts[p].rgba[2], parts[p].rgba[3]);
    fprintf(out, "]}\n");
    return fclose(out) == 0 ? 0 : 1;
}
