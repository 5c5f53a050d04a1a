/* model_occt.cpp: STEP (AP203, AP214, AP242) and IGES through OpenCASCADE, the
 * only file that includes OCCT's headers (tests/core_layers.sh keeps it so).
 *
 * The file is read into an XCAF document (names, colours and layers on), whose
 * length unit is set to millimetres so OCCT converts the file's unit. The free
 * shapes are walked: assemblies and instances become assembly nodes, with
 * their placements composed, so a part used N times appears N times; each
 * part (prototype) is tessellated once with BRepMesh_IncrementalMesh and its
 * faces' triangles are placed once per instance. A part whose faces have
 * different colours (KiCad puts a package's body and pins in one solid) gives
 * one component per colour, "NAME (colour K)" in the order the colours first
 * appear. Colours: the face's, else that of the shell, solid or compound
 * holding it, else the nearest instance's, else the part's, else the default;
 * surface colour first, generic next; the alpha, when the file has one, is the
 * opacity. Names are UTF-8 (OCCT's conversion of the file's). */
#include "model_internal.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <new>
#include <set>
#include <string>
#include <strings.h>
#include <vector>

#include <BRepBndLib.hxx>
#include <BRepGProp_Face.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESCAFControl_Reader.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Poly_Triangulation.hxx>
#include <Quantity_ColorRGBA.hxx>
#include <STEPCAFControl_ExternFile.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TDF_Label.hxx>
#include <TDF_LabelSequence.hxx>
#include <TDF_Tool.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_ColorTool.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>

namespace {

/* Linear deflection as a share of the model's bounding-box diagonal, and
 * angular deflection (radians), per oit_tessellation_level. */
const double level_relative_deflection[OIT_TESSELLATION_LEVEL_COUNT] = {1e-3, 4e-3, 2.5e-4};
const double level_angular_deflection[OIT_TESSELLATION_LEVEL_COUNT] = {0.35, 0.6, 0.17};

struct colour {
    float rgba[4];
    bool operator<(const colour &o) const { return std::lexicographical_compare(rgba, rgba + 4, o.rgba, o.rgba + 4); }
    bool operator==(const colour &o) const { return std::equal(rgba, rgba + 4, o.rgba); }
};

/* One face of a part, tessellated in the part's coordinates. */
struct face_mesh {
    std::vector<double> positions, normals; /* 3 per node */
    std::vector<uint32_t> indices;          /* 3 per triangle, wound counter-clockwise seen from outside */
    int colour_group;                       /* index into part_mesh::colours */
};

struct part_mesh {
    std::vector<face_mesh> faces;
    std::vector<colour> colours; /* the distinct face colours, in order of first appearance */
    std::vector<bool> coloured;  /* per colour: from the file (false: the default) */
};

struct walker {
    Handle(XCAFDoc_ShapeTool) shapes;
    Handle(XCAFDoc_ColorTool) colours;
    double linear, angular;
    std::map<std::string, part_mesh> meshes; /* by the part label's entry */
    /* what becomes the model */
    std::vector<oit_model_node> nodes;
    std::vector<std::set<std::string>> sibling_names; /* per node: its children's names */
    std::set<std::string> top_names, component_names;  /* the top's; every component's */
    struct component {
        std::string name;
        uint32_t node;
        colour rgba;
        uint32_t first_triangle, triangle_count;
    };
    std::vector<component> components;
    std::vector<float> positions, normals;
    std::vector<uint32_t> indices;
    unsigned long untessellated_faces = 0; /* of the parts (each once, not per instance) */
};

std::string label_name(const TDF_Label &label)
{
    Handle(TDataStd_Name) name;
    if (label.IsNull() || !label.FindAttribute(TDataStd_Name::GetID(), name))
        return "";
    TCollection_AsciiString text(name->Get());
    std::string out(text.ToCString());
    for (char &c : out)
        if ((unsigned char)c < 0x20 || c == '/')
            c = '_'; /* one line, and '/' separates a path's names */
    return out;
}

/* base, else base#2, base#3...: not yet in taken (nor in also, when given). */
std::string unique_name(const std::string &base_in, const std::set<std::string> &taken,
                        const std::set<std::string> *also = nullptr)
{
    std::string base = base_in.substr(0, OIT_NAME_SIZE - 8);
    auto free_name = [&](const std::string &n) { return !taken.count(n) && !(also && also->count(n)); };
    if (free_name(base))
        return base;
    for (unsigned k = 2;; ++k) {
        std::string candidate = base + "#" + std::to_string(k);
        if (free_name(candidate))
            return candidate;
    }
}

bool label_colour(walker &w, const TDF_Label &label, colour &out)
{
    Quantity_ColorRGBA c;
    if (label.IsNull() ||
        !(w.colours->GetColor(label, XCAFDoc_ColorSurf, c) || w.colours->GetColor(label, XCAFDoc_ColorGen, c)))
        return false;
    /* OCCT keeps colours linear and converts the file's (sRGB) values on
     * reading; asking for sRGB gives the numbers the file holds */
    Standard_Real r, g, b;
    c.GetRGB().Values(r, g, b, Quantity_TOC_sRGB);
    out = colour{{(float)r, (float)g, (float)b, c.Alpha()}};
    return true;
}

std::set<std::string> &siblings_of(walker &w, uint32_t node)
{
    return node == OIT_NO_NODE ? w.top_names : w.sibling_names[node];
}

uint32_t add_node(walker &w, const std::string &name, uint32_t parent)
{
    oit_model_node node{};
    std::string unique = unique_name(name.empty() ? "assembly" : name, siblings_of(w, parent));
    siblings_of(w, parent).insert(unique);
    snprintf(node.name, sizeof node.name, "%s", unique.c_str());
    node.parent = parent;
    w.nodes.push_back(node);
    w.sibling_names.emplace_back();
    return (uint32_t)(w.nodes.size() - 1);
}

/* The part's faces, tessellated once (in the part's own coordinates). */
part_mesh &mesh_part(walker &w, const TDF_Label &part)
{
    TCollection_AsciiString entry;
    TDF_Tool::Entry(part, entry);
    auto found = w.meshes.find(entry.ToCString());
    if (found != w.meshes.end())
        return found->second;
    part_mesh &mesh = w.meshes[entry.ToCString()];
    TopoDS_Shape shape = XCAFDoc_ShapeTool::GetShape(part);
    if (shape.IsNull())
        return mesh;
    BRepMesh_IncrementalMesh(shape, w.linear, Standard_False, w.angular, Standard_False);
    /* the colours of the part's sub-shapes (faces, and the shells, solids and
     * compounds holding faces), the most specific winning: a face's own colour
     * over its shell's over its solid's */
    TopTools_IndexedMapOfShape face_index;
    TopExp::MapShapes(shape, TopAbs_FACE, face_index);
    std::vector<colour> face_colours((size_t)face_index.Extent());
    std::vector<int> face_colour_rank((size_t)face_index.Extent(), -1);
    TDF_LabelSequence subs;
    XCAFDoc_ShapeTool::GetSubShapes(part, subs);
    for (int i = 1; i <= subs.Length(); ++i) {
        colour c;
        TopoDS_Shape sub = XCAFDoc_ShapeTool::GetShape(subs.Value(i));
        if (sub.IsNull() || !label_colour(w, subs.Value(i), c))
            continue;
        const int rank = (int)sub.ShapeType(); /* TopAbs_COMPOUND 0 .. TopAbs_FACE 4 */
        for (TopExp_Explorer in(sub, TopAbs_FACE); in.More(); in.Next()) {
            const int at = face_index.FindIndex(in.Current());
            if (at > 0 && rank > face_colour_rank[(size_t)at - 1]) {
                face_colours[(size_t)at - 1] = c;
                face_colour_rank[(size_t)at - 1] = rank;
            }
        }
    }
    for (TopExp_Explorer faces(shape, TopAbs_FACE); faces.More(); faces.Next()) {
        const TopoDS_Face &face = TopoDS::Face(faces.Current());
        TopLoc_Location location;
        Handle(Poly_Triangulation) tris = BRep_Tool::Triangulation(face, location);
        if (tris.IsNull() || tris->NbTriangles() == 0) {
            ++w.untessellated_faces; /* said in a warning: the model is not silently incomplete */
            continue;
        }
        face_mesh fm;
        colour c{{-1, -1, -1, -1}};
        const int index = face_index.FindIndex(face);
        const bool has = index > 0 && face_colour_rank[(size_t)index - 1] >= 0;
        if (has)
            c = face_colours[(size_t)index - 1];
        /* faces without a colour form their own group ({-1...}): the
         * instance's or part's colour fills it in later */
        auto at = std::find(mesh.colours.begin(), mesh.colours.end(), c);
        fm.colour_group = (int)(at - mesh.colours.begin());
        if (at == mesh.colours.end()) {
            mesh.colours.push_back(c);
            mesh.coloured.push_back(has);
        }
        const gp_Trsf &trsf = location.Transformation();
        const bool reversed = face.Orientation() == TopAbs_REVERSED;
        BRepGProp_Face surface(face); /* its normal takes the face's orientation into account */
        const int n = tris->NbNodes();
        fm.positions.resize((size_t)n * 3);
        fm.normals.resize((size_t)n * 3);
        for (int i = 1; i <= n; ++i) {
            gp_Pnt p = tris->Node(i).Transformed(trsf);
            gp_Vec normal(0, 0, 0);
            if (tris->HasUVNodes()) {
                gp_Pnt2d uv = tris->UVNode(i);
                gp_Pnt on;
                surface.Normal(uv.X(), uv.Y(), on, normal);
                if (normal.SquareMagnitude() > 1e-300)
                    normal.Transform(trsf);
            }
            for (int k = 0; k < 3; ++k) {
                fm.positions[(size_t)(i - 1) * 3 + k] = p.Coord(k + 1);
                fm.normals[(size_t)(i - 1) * 3 + k] = normal.Coord(k + 1);
            }
        }
        const int t = tris->NbTriangles();
        fm.indices.reserve((size_t)t * 3);
        for (int i = 1; i <= t; ++i) {
            int a, b, cc;
            tris->Triangle(i).Get(a, b, cc);
            if (reversed)
                std::swap(b, cc);
            if (a < 1 || b < 1 || cc < 1 || a > n || b > n || cc > n)
                continue;
            fm.indices.push_back((uint32_t)(a - 1));
            fm.indices.push_back((uint32_t)(b - 1));
            fm.indices.push_back((uint32_t)(cc - 1));
        }
        mesh.faces.push_back(std::move(fm));
    }
    return mesh;
}

/* A part placed at location: one component per colour group under node parent. */
void place_part(walker &w, const TDF_Label &part, const std::string &name, const gp_Trsf &placement,
                uint32_t parent, const colour *instance_colour)
{
    part_mesh &mesh = mesh_part(w, part);
    colour part_colour{{oit_model_default_colour[0], oit_model_default_colour[1], oit_model_default_colour[2], 1}};
    if (instance_colour)
        part_colour = *instance_colour;
    else
        label_colour(w, part, part_colour);
    const bool mirrored = placement.IsNegative();
    for (size_t group = 0; group < mesh.colours.size(); ++group) {
        walker::component comp;
        std::string base = name;
        if (mesh.colours.size() > 1)
            base += " (colour " + std::to_string(group + 1) + ")";
        comp.name = unique_name(base, w.component_names, &siblings_of(w, parent));
        w.component_names.insert(comp.name);
        siblings_of(w, parent).insert(comp.name);
        comp.node = parent;
        comp.rgba = mesh.coloured[group] ? mesh.colours[group] : part_colour;
        comp.first_triangle = (uint32_t)(w.indices.size() / 3);
        for (const face_mesh &fm : mesh.faces) {
            if (fm.colour_group != (int)group)
                continue;
            const size_t first_vertex = w.positions.size() / 3;
            for (size_t v = 0; v < fm.positions.size() / 3; ++v) {
                gp_Pnt p(fm.positions[v * 3], fm.positions[v * 3 + 1], fm.positions[v * 3 + 2]);
                gp_Vec normal(fm.normals[v * 3], fm.normals[v * 3 + 1], fm.normals[v * 3 + 2]);
                p.Transform(placement);
                if (normal.SquareMagnitude() > 1e-300)
                    normal.Transform(placement);
                for (int k = 0; k < 3; ++k) {
                    w.positions.push_back((float)p.Coord(k + 1));
                    w.normals.push_back((float)normal.Coord(k + 1));
                }
            }
            for (size_t i = 0; i < fm.indices.size(); i += 3) {
                /* a mirroring placement turns the winding over */
                w.indices.push_back((uint32_t)first_vertex + fm.indices[i]);
                w.indices.push_back((uint32_t)first_vertex + fm.indices[i + (mirrored ? 2 : 1)]);
                w.indices.push_back((uint32_t)first_vertex + fm.indices[i + (mirrored ? 1 : 2)]);
            }
        }
        comp.triangle_count = (uint32_t)(w.indices.size() / 3) - comp.first_triangle;
        if (comp.triangle_count > 0)
            w.components.push_back(comp);
    }
}

/* label: a free shape, an assembly's component (an instance, a reference
 * label) or a simple shape; placement: where its parent puts it. */
void walk(walker &w, const TDF_Label &label, const gp_Trsf &placement_in, uint32_t parent,
          const colour *inherited, int depth)
{
    if (depth > 64)
        throw Standard_Failure("the assembly is nested more than 64 deep (a cycle?)");
    gp_Trsf placement = placement_in;
    TDF_Label shape = label;
    std::string name = label_name(label);
    colour own;
    const colour *instance_colour = inherited;
    if (XCAFDoc_ShapeTool::IsReference(label)) {
        XCAFDoc_ShapeTool::GetReferredShape(label, shape);
        placement = placement * XCAFDoc_ShapeTool::GetLocation(label).Transformation();
        if (label_colour(w, label, own))
            instance_colour = &own;
        if (name.empty() || name.compare(0, 2, "=>") == 0)
            name = label_name(shape);
    }
    if (XCAFDoc_ShapeTool::IsAssembly(shape)) {
        uint32_t node = add_node(w, name, parent);
        TDF_LabelSequence components;
        XCAFDoc_ShapeTool::GetComponents(shape, components);
        for (int i = 1; i <= components.Length(); ++i)
            walk(w, components.Value(i), placement, node, instance_colour, depth + 1);
        return;
    }
    place_part(w, shape, name.empty() ? "part" : name, placement, parent, instance_colour);
}

/* The file's length unit, and millimetres per unit. */
void file_unit(STEPCAFControl_Reader &step, IGESCAFControl_Reader &iges, occt_format format,
               std::string &unit, double &to_mm)
{
    unit.clear();
    to_mm = 0;
    if (format == OCCT_FORMAT_STEP) {
        TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
        step.ChangeReader().FileUnits(lengths, angles, solid_angles);
        if (lengths.IsEmpty())
            return;
        std::string name = lengths.First().ToCString();
        for (char &c : name)
            c = (char)tolower((unsigned char)c);
        static const struct { const char *name; double mm; } known[] = {
            {"millimetre", 1}, {"millimeter", 1}, {"metre", 1000}, {"meter", 1000}, {"centimetre", 10},
            {"centimeter", 10}, {"micrometre", 1e-3}, {"micrometer", 1e-3}, {"kilometre", 1e6},
            {"kilometer", 1e6}, {"inch", 25.4}, {"foot", 304.8}, {"mile", 1609344}, {"mil", 0.0254}};
        for (const auto &k : known)
            if (name == k.name) {
                unit = name;
                to_mm = k.mm;
            }
        if (unit.empty())
            unit = name;
    } else {
        Handle(IGESData_IGESModel) model = iges.IGESModel();
        if (model.IsNull())
            return;
        const IGESData_GlobalSection &global = model->GlobalSection();
        /* the unit flag (IGES 5.3, 2.2.4.3), and millimetres per unit */
        static const struct { const char *name; double mm; } flags[] = {
            {"", 0}, {"inch", 25.4}, {"millimetre", 1}, {"", 0}, {"foot", 304.8}, {"mile", 1609344},
            {"metre", 1000}, {"kilometre", 1e6}, {"mil", 0.0254}, {"micrometre", 1e-3}, {"centimetre", 10},
            {"microinch", 2.54e-5}};
        int flag = global.UnitFlag();
        if (flag >= 1 && flag <= 11 && flags[flag].name[0]) {
            unit = flags[flag].name;
            to_mm = flags[flag].mm;
        } else if (!global.UnitName().IsNull()) {
            unit = global.UnitName()->ToCString(); /* flag 3: a unit by name only */
        }
    }
}

oit_status to_model(walker &w, const char *name, oit_model *out, oit_error *err)
{
    const uint64_t v = w.positions.size() / 3, t = w.indices.size() / 3, c = w.components.size();
    if (t == 0)
        return oit_fail(err, OIT_E_INPUT, "%s: no triangles (the file holds no surfaces OpenCASCADE could "
                        "tessellate)", name);
    if (v >= OIT_MODEL_LIMIT || t >= OIT_MODEL_LIMIT || w.nodes.size() >= OIT_MODEL_LIMIT)
        return oit_fail(err, OIT_E_INPUT, "%s: too large: %llu vertices, %llu triangles (limit 2^31)", name,
                        (unsigned long long)v, (unsigned long long)t);
    out->positions = (float *)oit_model_alloc_array(v * 3, sizeof(float));
    out->normals = (float *)oit_model_alloc_array(v * 3, sizeof(float));
    out->indices = (uint32_t *)oit_model_alloc_array(t * 3, sizeof(uint32_t));
    out->components = (oit_component *)oit_model_calloc_array(c, sizeof(oit_component));
    out->component_node = (uint32_t *)oit_model_alloc_array(c, sizeof(uint32_t));
    if (!w.nodes.empty())
        out->nodes = (oit_model_node *)oit_model_alloc_array(w.nodes.size(), sizeof(oit_model_node));
    if (!out->positions || !out->normals || !out->indices || !out->components || !out->component_node ||
        (!w.nodes.empty() && !out->nodes))
        return oit_fail(err, OIT_E_RUNTIME, "%s: out of memory for %llu triangles", name, (unsigned long long)t);
    memcpy(out->positions, w.positions.data(), v * 3 * sizeof(float));
    memcpy(out->normals, w.normals.data(), v * 3 * sizeof(float));
    memcpy(out->indices, w.indices.data(), t * 3 * sizeof(uint32_t));
    if (!w.nodes.empty())
        memcpy(out->nodes, w.nodes.data(), w.nodes.size() * sizeof(oit_model_node));
    for (uint64_t k = 0; k < c; ++k) {
        const walker::component &from = w.components[k];
        oit_component *comp = &out->components[k];
        snprintf(comp->name, sizeof comp->name, "%s", from.name.c_str());
        memcpy(comp->colour, from.rgba.rgba, sizeof comp->colour);
        comp->opacity = from.rgba.rgba[3];
        oit_clamp_material(comp);
        comp->first_triangle = from.first_triangle;
        comp->triangle_count = from.triangle_count;
        out->component_node[k] = from.node;
    }
    out->vertex_count = (uint32_t)v;
    out->triangle_count = (uint32_t)t;
    out->component_count = (uint32_t)c;
    out->node_count = (uint32_t)w.nodes.size();
    return OIT_OK;
}

/* OCCT's messages go to stdout, which in the import worker is the model's
 * stream: no printers. */
void silence_messages()
{
    Message::DefaultMessenger()->ChangePrinters().Clear();
}

} // namespace

extern "C" occt_format oit_occt_format(const char *path, const char *name)
{
    const char *extension = strrchr(name, '.');
    if (extension && (strcasecmp(extension, ".step") == 0 || strcasecmp(extension, ".stp") == 0))
        return OCCT_FORMAT_STEP;
    if (extension && (strcasecmp(extension, ".iges") == 0 || strcasecmp(extension, ".igs") == 0))
        return OCCT_FORMAT_IGES;
    /* IFC is written in STEP's file format too: Assimp reads it */
    if (extension && (strcasecmp(extension, ".ifc") == 0 || strcasecmp(extension, ".ifczip") == 0))
        return OCCT_FORMAT_NONE;
    FILE *file = fopen(path, "rb");
    if (!file)
        return OCCT_FORMAT_NONE;
    char head[4096];
    size_t got = fread(head, 1, sizeof head - 1, file);
    fclose(file);
    head[got] = '\0';
    const char *p = head;
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n')
        ++p;
    if (strncmp(p, "ISO-10303-21", 12) != 0)
        return OCCT_FORMAT_NONE;
    const char *schema = strstr(head, "FILE_SCHEMA");
    return schema && strstr(schema, "IFC") ? OCCT_FORMAT_NONE : OCCT_FORMAT_STEP;
}

extern "C" oit_status oit_model_read_occt(const char *path, const char *name, occt_format format,
                                          const oit_import_options *options_in, import_warnings *warnings,
                                          oit_model *out, oit_error *err)
{
    oit_import_options options{};
    if (options_in)
        options = *options_in;
    if ((int)options.tessellation < 0 || options.tessellation >= OIT_TESSELLATION_LEVEL_COUNT)
        options.tessellation = OIT_TESSELLATION_NORMAL;
    const char *kind = format == OCCT_FORMAT_STEP ? "STEP" : "IGES";
    /* OCCT finds an assembly's part files beside the file only when given an
     * absolute path ("dir/a.step" looks for "dir/dir/part.stp"... and fails) */
    char *absolute = realpath(path, nullptr);
    std::string full = absolute ? absolute : path;
    free(absolute);
    path = full.c_str();
    try {
        silence_messages();
        Handle(XCAFApp_Application) application = XCAFApp_Application::GetApplication();
        Handle(TDocStd_Document) document;
        application->NewDocument("MDTV-XCAF", document);
        /* the application keeps its documents: close this one on every way out */
        struct closer {
            Handle(XCAFApp_Application) application;
            Handle(TDocStd_Document) document;
            ~closer()
            {
                if (application->CanClose(document) == CDM_CCS_OK)
                    application->Close(document);
            }
        } close_document{application, document};
        /* the document in millimetres: OCCT scales the file's unit to it */
        XCAFDoc_DocumentTool::SetLengthUnit(document, 1.0, UnitsMethods_LengthUnit_Millimeter);
        Interface_Static::SetCVal("xstep.cascade.unit", "MM");
        STEPCAFControl_Reader step;
        IGESCAFControl_Reader iges;
        IFSelect_ReturnStatus read;
        bool transferred;
        if (format == OCCT_FORMAT_STEP) {
            step.SetColorMode(true);
            step.SetNameMode(true);
            step.SetLayerMode(true);
            read = step.ReadFile(path);
            transferred = read == IFSelect_RetDone && step.Transfer(document);
        } else {
            iges.SetColorMode(true);
            iges.SetNameMode(true);
            iges.SetLayerMode(true);
            read = iges.ReadFile(path);
            transferred = read == IFSelect_RetDone && iges.Transfer(document);
        }
        if (read != IFSelect_RetDone)
            return oit_fail(err, OIT_E_INPUT, "%s: cannot import: not a readable %s file (OpenCASCADE's reader "
                            "stopped: %s)", name, kind,
                            read == IFSelect_RetVoid ? "nothing to read" : read == IFSelect_RetFail ? "read failed"
                                                                                                    : "syntax errors");
        if (!transferred)
            return oit_fail(err, OIT_E_INPUT, "%s: cannot import: OpenCASCADE read the %s file but could not "
                            "transfer its shapes (a corrupt file?)", name, kind);
        /* an assembly whose parts are files of their own: OCCT leaves a part
         * it cannot read out, and the model would be silently incomplete */
        if (format == OCCT_FORMAT_STEP)
            for (NCollection_DataMap<TCollection_AsciiString, Handle(STEPCAFControl_ExternFile)>::Iterator
                     file(step.ExternFiles());
                 file.More(); file.Next())
                if (file.Value().IsNull() || file.Value()->GetLoadStatus() != IFSelect_RetDone)
                    return oit_fail(err, OIT_E_INPUT, "%s: cannot import: it refers to the file '%.200s', which "
                                    "cannot be read (missing or broken)", name, file.Key().ToCString());
        walker w;
        w.shapes = XCAFDoc_DocumentTool::ShapeTool(document->Main());
        w.colours = XCAFDoc_DocumentTool::ColorTool(document->Main());
        TDF_LabelSequence roots;
        w.shapes->GetFreeShapes(roots);
        Bnd_Box box;
        for (int i = 1; i <= roots.Length(); ++i)
            BRepBndLib::Add(XCAFDoc_ShapeTool::GetShape(roots.Value(i)), box);
        if (box.IsVoid())
            return oit_fail(err, OIT_E_INPUT, "%s: no triangles (the %s file holds no shapes OpenCASCADE could "
                            "read: a corrupt file, or an assembly whose part files are missing?)", name, kind);
        const double diagonal = std::sqrt(box.SquareExtent());
        w.linear = options.linear_deflection_mm > 0 ? options.linear_deflection_mm
                                                    : diagonal * level_relative_deflection[options.tessellation];
        if (!(w.linear > 0) || !std::isfinite(w.linear))
            w.linear = 0.01; /* a model of one point: any deflection */
        w.angular = level_angular_deflection[options.tessellation];
        auto start = std::chrono::steady_clock::now();
        for (int i = 1; i <= roots.Length(); ++i)
            walk(w, roots.Value(i), gp_Trsf(), OIT_NO_NODE, nullptr, 0);
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        oit_status status = to_model(w, name, out, err);
        if (status != OIT_OK)
            return status;
        std::string unit;
        double to_mm = 0;
        file_unit(step, iges, format, unit, to_mm);
        snprintf(out->unit_name, sizeof out->unit_name, "%s", unit.c_str());
        out->unit_to_mm = to_mm;
        if (unit.empty())
            oit_import_warn(warnings, "the file names no length unit: read as millimetres");
        if (w.untessellated_faces)
            oit_import_warn(warnings, "%lu faces could not be tessellated and are left out",
                            w.untessellated_faces);
        out->tessellation_linear_mm = w.linear;
        out->tessellation_angular_rad = w.angular;
        out->tessellation_ms = ms;
        return OIT_OK;
    } catch (const Standard_Failure &failure) {
        return oit_fail(err, OIT_E_INPUT, "%s: cannot import: OpenCASCADE failed on this %s file (%s: %s)", name,
                        kind, failure.DynamicType()->Name(), failure.GetMessageString());
    } catch (const std::bad_alloc &) {
        return oit_fail(err, OIT_E_RUNTIME, "%s: not enough memory to import this %s file", name, kind);
    } catch (const std::exception &failure) {
        return oit_fail(err, OIT_E_INPUT, "%s: cannot import: %s", name, failure.what());
    }
}
