/*
 * model_obj.cpp: the OBJ (and MTL) reader, in place of Assimp's OBJ importer.
 *
 * Assimp's OBJ importer is quadratic in the parts of an assembly: every
 * `usemtl` and `g` looks its material up by a linear search of all materials
 * (ObjFileParser::getMaterialIndex), every `o` searches all objects, and each
 * material costs about 37 KB (a dozen 1 KB texture-name strings), so a
 * 100,000-part OBJ took 45 s and 3.7 GB (docs/cli.md, "Assemblies"). No import
 * setting avoids that, and tinyobjloader reads `nan`, `inf` and words that are
 * no number as 0, rounds coordinates differently (1 ulp on 3% of the gearbox's
 * numbers) and splits quads by their shorter diagonal, so models and images
 * would change. This reader keeps what Assimp 5.2 made of a file -- the same
 * meshes, names, materials, warnings and errors, and bit for bit the same
 * coordinates, read by Assimp's own number reader (its public fast_atof.h) --
 * with hash maps where Assimp searched lists. Polygons of more than four
 * corners are cut into ears by our own code (on Assimp's test files, the same
 * triangles). What it does not keep: texture and option statements of MTL
 * files are not read, and where Assimp read past the end of a malformed face
 * line (a fourth index in one corner), the face ends there.
 */
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include <assimp/fast_atof.h>

#include "model_obj.h"

namespace {

// What Assimp's number reader throws: its message, from the pieces it is given.
struct NumberError {
    std::string message;
    template <typename... Pieces> explicit NumberError(Pieces &&...pieces)
    {
        std::ostringstream text;
        (text << ... << pieces);
        message = text.str();
    }
};

// An import error, with Assimp's words.
struct ImportError {
    std::string message;
};

const char *const default_material = "DefaultMaterial"; // AI_DEFAULT_MATERIAL_NAME
const char *const default_object = "defaultobject";
const unsigned no_material = ~0u;
const size_t name_limit = 1023; // aiString keeps no longer name (it keeps none)

bool line_end(char c) { return c == '\r' || c == '\n' || c == '\0' || c == '\f'; }
bool space(char c) { return c == ' ' || c == '\t'; }
bool space_or_end(char c) { return space(c) || line_end(c); }

// The next word of a line (after spaces), moving p past it.
std::string next_word(const char *&p)
{
    while (space(*p))
        ++p;
    const char *start = p;
    while (!space_or_end(*p))
        ++p;
    return std::string(start, p);
}

float read_number(const std::string &word)
{
    ai_real value = 0;
    try {
        Assimp::fast_atoreal_move<ai_real, NumberError>(word.c_str(), value);
    } catch (const NumberError &e) {
        throw ImportError{e.message};
    }
    return (float)value;
}

std::string trim(const std::string &s)
{
    size_t a = 0, b = s.size();
    while (a < b && space(s[a]))
        ++a;
    while (b > a && space(s[b - 1]))
        --b;
    return s.substr(a, b - a);
}

struct Material {
    std::string name;
    float diffuse[3] = {0.6f, 0.6f, 0.6f}; // Assimp's OBJ defaults
    float alpha = 1.0f;
    int illumination = 1;
};

enum FaceType { face_polygon, face_line, face_point };

struct Face {
    FaceType type;
    uint32_t first_vertex, vertex_count, first_uv, uv_count, first_normal, normal_count;
};

struct Mesh {
    std::string name;
    unsigned material = no_material;
    size_t first_face = 0, face_count = 0;
    bool has_normals = false;
    size_t uv_count = 0;
};

struct Object {
    std::string name;
    std::vector<size_t> meshes;
};

class Reader {
public:
    Reader(const std::string &path, void (*warn)(void *, const char *), void *user)
        : path_(path), warn_(warn), user_(user)
    {
        add_material(default_material);
    }

    void read();
    void convert(obj_data *out);

private:
    std::string path_;
    void (*warn_)(void *, const char *);
    void *user_;

    std::vector<float> vertices_, normals_, uvs_; // 3 each
    unsigned uv_dimensions_ = 0;                  // the most numbers a vt line gave
    size_t colours_ = 0;                          // vertices given with a colour
    std::vector<Material> materials_;             // Assimp's material list, "DefaultMaterial" first
    std::unordered_map<std::string, unsigned> material_index_;
    std::vector<Object> objects_;
    std::unordered_map<std::string, size_t> object_index_; // the first object of a name
    std::vector<Mesh> meshes_;
    std::vector<Face> faces_;
    std::vector<int64_t> face_vertices_, face_uvs_, face_normals_;
    long current_object_ = -1, current_mesh_ = -1, current_material_ = -1;
    std::string active_group_;

    std::string last_said_;
    // Assimp's log dropped a message that repeated the one before it
    void say(const std::string &text)
    {
        if (text != last_said_)
            warn_(user_, text.c_str());
        last_said_ = text;
    }
    unsigned add_material(const std::string &name)
    {
        Material m;
        m.name = name;
        materials_.push_back(m);
        return material_index_[name] = unsigned(materials_.size() - 1);
    }
    int material_of(const std::string &name) const
    {
        auto it = material_index_.find(name);
        return it == material_index_.end() ? -1 : int(it->second);
    }

    void line(const char *p);
    void vertex(const char *p);
    void face(const char *p, FaceType type);
    void use_material(const char *p);
    void material_library(const char *p);
    void group(const char *p);
    void object(const char *p);
    void create_object(const std::string &name);
    void create_mesh(const std::string &name);
    bool needs_new_mesh(const std::string &material);
    void read_materials(const std::string &text);
};

// A regular file only (a FIFO would block the import until the wall limit):
// false if it cannot be read; refused says why when it exists but is no file.
bool read_file(const std::string &path, std::string &text, std::string *refused = nullptr)
{
    FILE *file = nullptr;
    oit_error err;
    if (oit_open_regular_file(path.c_str(), nullptr, &file, &err) != OIT_OK) {
        const char *kind = strstr(err.message, "not a regular file");
        if (kind && refused)
            *refused = kind;
        return false;
    }
    char buffer[1 << 16];
    size_t got;
    while ((got = fread(buffer, 1, sizeof buffer, file)) > 0)
        text.append(buffer, got);
    fclose(file);
    return true;
}

void Reader::read()
{
    std::string text;
    if (!read_file(path_, text))
        throw ImportError{"Failed to open file " + path_ + "."};
    if (text.size() < 16)
        throw ImportError{"OBJ-file is too small."};
    // Lines end at \n, \r, \0 or \f, each line end one character. A backslash
    // before a line end skips to the next \n and takes the character after it
    // whatever it is, as Assimp's line reader did.
    std::string line_text;
    bool in_cstype = false;
    size_t i = 0;
    const size_t size = text.size();
    while (i < size) {
        line_text.clear();
        for (;;) {
            if (text[i] == '\\' && (i + 1 >= size || line_end(text[i + 1]))) {
                ++i;
                while (i < size && text[i] != '\n')
                    ++i;
                ++i;
                if (i >= size)
                    break;
            } else if (line_end(text[i])) {
                break;
            }
            line_text += text[i];
            if (++i >= size)
                break;
        }
        ++i;
        line_text += '\n';
        const char *p = line_text.c_str();
        if (in_cstype) { // a free-form curve section, up to "end"
            const char *q = p;
            in_cstype = next_word(q) != "end";
            continue;
        }
        if (*p == 'c') {
            const char *q = p;
            in_cstype = next_word(q) == "cstype";
            continue;
        }
        line(p);
    }
}

void Reader::line(const char *p)
{
    switch (*p) {
    case 'v':
        vertex(p + 1);
        break;
    case 'f':
        face(p + 1, face_polygon);
        break;
    case 'l':
        face(p + 1, face_line);
        break;
    case 'p':
        face(p + 1, face_point);
        break;
    case 'u': {
        const char *q = p;
        if (next_word(q) == "usemtl")
            use_material(q);
        break;
    }
    case 'm': {
        const char *q = p;
        if (next_word(q) == "mtllib")
            material_library(q);
        break;
    }
    case 'g':
        group(p + 1);
        break;
    case 'o':
        object(p + 1);
        break;
    default: // comments, s, mg and what is not OBJ
        break;
    }
}

bool numeric_start(const char *p)
{
    return (*p >= '0' && *p <= '9') || *p == '-' || *p == '+' ||
           ((p[0] == 'n' || p[0] == 'N') && strncasecmp(p, "nan", 3) == 0) ||
           ((p[0] == 'i' || p[0] == 'I') && strncasecmp(p, "inf", 3) == 0);
}

void Reader::vertex(const char *p)
{
    char kind = *p;
    if (kind == 't' || kind == 'n')
        ++p;
    else if (!space(kind))
        return;
    // how many of the words start like numbers
    size_t numbers = 0;
    for (const char *q = p;;) {
        while (space(*q))
            ++q;
        if (line_end(*q))
            break;
        numbers += numeric_start(q);
        while (!space_or_end(*q))
            ++q;
    }
    float v[4];
    if (kind == 't') {
        if (numbers != 2 && numbers != 3)
            throw ImportError{"OBJ: Invalid number of components"};
        for (size_t k = 0; k < numbers; ++k)
            v[k] = read_number(next_word(p));
        if (numbers == 2)
            v[2] = 0.0f;
        for (int k = 0; k < 3; ++k) // nan and inf become 0, OBJ's default
            if (!std::isfinite(v[k]))
                v[k] = 0.0f;
        uvs_.insert(uvs_.end(), v, v + 3);
        uv_dimensions_ = std::max(uv_dimensions_, unsigned(numbers));
    } else if (kind == 'n') {
        for (int k = 0; k < 3; ++k)
            v[k] = read_number(next_word(p));
        normals_.insert(normals_.end(), v, v + 3);
    } else if (numbers == 3 || numbers == 6) { // x y z (r g b: colours, not read)
        for (int k = 0; k < 3; ++k)
            v[k] = read_number(next_word(p));
        if (numbers == 6) {
            for (int k = 0; k < 3; ++k)
                read_number(next_word(p));
            ++colours_;
        }
        vertices_.insert(vertices_.end(), v, v + 3);
    } else if (numbers == 4) { // homogeneous
        for (int k = 0; k < 4; ++k)
            v[k] = read_number(next_word(p));
        if (v[3] == 0.0f)
            throw ImportError{"OBJ: Invalid component in homogeneous vector (Division by zero)"};
        for (int k = 0; k < 3; ++k)
            v[k] /= v[3];
        vertices_.insert(vertices_.end(), v, v + 3);
    }
    // any other count: Assimp keeps no vertex
}

void Reader::face(const char *p, FaceType type)
{
    while (!space_or_end(*p)) // the rest of the keyword
        ++p;
    while (space(*p))
        ++p;
    if (*p == '\0')
        return;
    Face f{type, uint32_t(face_vertices_.size()), 0, uint32_t(face_uvs_.size()), 0,
           uint32_t(face_normals_.size()), 0};
    const int64_t vertex_count = int64_t(vertices_.size() / 3), uv_count = int64_t(uvs_.size() / 3),
                  normal_count = int64_t(normals_.size() / 3);
    const bool any_uv = uv_count > 0, any_normal = normal_count > 0;
    bool has_normal = false;
    int slot = 0; // 0 vertex, 1 texture coordinate, 2 normal
    while (!line_end(*p)) {
        int step = 1;
        if (*p == '/') {
            if (type == face_point)
                say("Obj: Separator unexpected in point statement");
            ++slot;
        } else if (space(*p)) {
            slot = 0;
        } else {
            // Assimp reads the number with atoi and steps over as many
            // characters as its digits (and sign) take
            const int value = atoi(p);
            for (int rest = value; (rest /= 10) != 0;)
                ++step;
            if (value < 0)
                ++step;
            if (slot == 1 && !any_uv && any_normal)
                slot = 2; // "f 1//1" written as "f 1/1" when there are no texture coordinates
            if (value == 0)
                throw ImportError{"OBJ: Invalid face index."};
            int64_t base = slot == 0 ? vertex_count : slot == 1 ? uv_count : normal_count;
            int64_t index = value > 0 ? int64_t(value) - 1 : base + value;
            if (slot == 0) {
                face_vertices_.push_back(index);
                ++f.vertex_count;
            } else if (slot == 1) {
                face_uvs_.push_back(index);
                ++f.uv_count;
            } else if (slot == 2) {
                face_normals_.push_back(index);
                ++f.normal_count;
                has_normal = true;
            } else {
                // (Assimp went on reading past the end of the line here, with
                // results that depend on what was there before: we end the face)
                say("OBJ: Not supported token in face description detected");
                break;
            }
        }
        p += step;
    }
    if (f.vertex_count == 0) {
        say("Obj: Ignoring empty face");
        face_uvs_.resize(f.first_uv);
        face_normals_.resize(f.first_normal);
        return;
    }
    if (current_object_ < 0)
        create_object(default_object);
    if (current_mesh_ < 0)
        create_mesh(default_object);
    Mesh &mesh = meshes_[size_t(current_mesh_)];
    if (mesh.face_count == 0)
        mesh.first_face = faces_.size();
    faces_.push_back(f);
    ++mesh.face_count;
    mesh.uv_count += f.uv_count;
    mesh.has_normals |= has_normal;
}

void Reader::use_material(const char *p)
{
    std::string name = trim(std::string(p, strcspn(p, "\r\n\f")));
    if (name.empty())
        return;
    if (current_material_ >= 0 && materials_[size_t(current_material_)].name == name)
        return;
    int found = material_of(name);
    if (found < 0) {
        say("OBJ: failed to locate material " + name + ", creating new material");
        found = int(add_material(name));
    }
    current_material_ = found;
    if (needs_new_mesh(name))
        create_mesh(name);
    meshes_[size_t(current_mesh_)].material = unsigned(found);
}

bool Reader::needs_new_mesh(const std::string &material)
{
    if (current_mesh_ < 0)
        return true;
    const Mesh &mesh = meshes_[size_t(current_mesh_)];
    return mesh.material != no_material && int(mesh.material) != material_of(material) && mesh.face_count > 0;
}

void Reader::create_object(const std::string &name)
{
    objects_.push_back(Object{name, {}});
    current_object_ = long(objects_.size() - 1);
    object_index_.emplace(name, objects_.size() - 1);
    create_mesh(name);
    if (current_material_ >= 0)
        meshes_[size_t(current_mesh_)].material = unsigned(current_material_);
}

void Reader::create_mesh(const std::string &name)
{
    Mesh mesh;
    mesh.name = name;
    meshes_.push_back(mesh);
    current_mesh_ = long(meshes_.size() - 1);
    if (current_object_ >= 0)
        objects_[size_t(current_object_)].meshes.push_back(meshes_.size() - 1);
}

void Reader::group(const char *p)
{
    while (!space_or_end(*p)) // "g" may be followed by more letters
        ++p;
    while (space(*p))
        ++p;
    // the rest of the line (spaces before its end are kept, as Assimp did)
    std::string name(p, strcspn(p, "\r\n\f"));
    if (active_group_ != name) {
        create_object(name);
        active_group_ = name;
    }
}

void Reader::object(const char *p)
{
    while (!space_or_end(*p))
        ++p;
    std::string name = next_word(p);
    if (name.empty())
        return;
    auto it = object_index_.find(name);
    if (it != object_index_.end())
        current_object_ = long(it->second); // the current mesh stays as it is
    else
        create_object(name);
}

void Reader::material_library(const char *p)
{
    while (space(*p))
        ++p;
    std::string name(p, strcspn(p, "\r\n\f"));
    if (name.empty()) {
        say("OBJ: no name for material library specified.");
        return;
    }
    size_t slash = path_.find_last_of('/');
    std::string full = slash != std::string::npos && slash > 0 ? path_.substr(0, slash + 1) + name : name;
    std::string text, refused;
    if (!read_file(full, text, &refused)) {
        if (!refused.empty())
            throw ImportError{"material library " + name + ": " + refused};
        say("OBJ: Unable to locate material file " + name);
        std::string fallback = path_.substr(0, path_.size() - 3) + "mtl";
        if (!read_file(fallback, text)) {
            say("OBJ: Unable to locate fallback material file " + fallback);
            return;
        }
        name = fallback.substr(fallback.find_last_of('/') == std::string::npos ? 0 : fallback.find_last_of('/') + 1);
    }
    try {
        read_materials(text);
    } catch (const ImportError &e) {
        std::string base = name.substr(name.find_last_of('/') == std::string::npos ? 0 : name.find_last_of('/') + 1);
        throw ImportError{"material library " + base + ": " + e.message};
    }
}

// The MTL statements that matter here: newmtl, Kd, d, Tr, illum; the other
// colours and numbers are read only for their errors.
void Reader::read_materials(const std::string &text)
{
    long current = -1;
    std::string line_text;
    size_t i = 0;
    while (i < text.size()) {
        size_t end = i;
        while (end < text.size() && !line_end(text[end]))
            ++end;
        line_text.assign(text, i, end - i);
        line_text += '\n';
        i = end;
        while (i < text.size() && line_end(text[i]))
            ++i;
        const char *p = line_text.c_str();
        while (space(*p)) // Assimp skips the spaces that start a line
            ++p;
        Material *m = current >= 0 ? &materials_[size_t(current)] : nullptr;
        auto colour = [&p](float out[3]) {
            // r, then g and b unless the line ends after r
            out[0] = read_number(next_word(p));
            out[1] = out[2] = 0.0f;
            if (!line_end(*p)) {
                out[1] = read_number(next_word(p));
                out[2] = read_number(next_word(p));
            }
        };
        auto number = [&p]() {
            std::string word = next_word(p);
            return word.empty() ? 0.0f : read_number(word);
        };
        float scratch[3];
        switch (*p) {
        case 'k':
        case 'K':
            ++p;
            if (*p == 'd') {
                ++p;
                if (m)
                    colour(m->diffuse);
            } else if ((*p == 'a' || *p == 's' || *p == 'e') && m) {
                ++p;
                colour(scratch);
            }
            break;
        case 'T':
            ++p;
            if (*p == 'f') {
                ++p;
                if (m)
                    colour(scratch);
            } else if (*p == 'r') {
                ++p;
                float tr = number();
                if (m)
                    m->alpha = 1.0f - tr;
            }
            break;
        case 'd':
            if (strncmp(p, "disp", 4) != 0) {
                ++p;
                if (m)
                    m->alpha = number();
            }
            break;
        case 'n':
        case 'N':
            ++p;
            if ((*p == 's' || *p == 'i') && m) {
                ++p;
                number();
            } else if (*p == 'e') { // newmtl: the rest of the line, trimmed
                std::string name;
                const char *q = p;
                while (!space_or_end(*q))
                    ++q;
                if (line_end(*q) || line_end(*(q + strspn(q, " \t"))))
                    name = default_material;
                else
                    name = trim(std::string(q, strcspn(q, "\r\n\f")));
                int found = material_of(name);
                if (found < 0) {
                    found = int(add_material(name));
                    if (current_mesh_ >= 0)
                        meshes_[size_t(current_mesh_)].material = unsigned(found);
                }
                current = found;
                current_material_ = found; // Assimp's MTL reader left its last material current
            }
            break;
        case 'P':
            ++p;
            if (m && (*p == 'r' || *p == 'm' || *p == 'c')) {
                ++p;
                if (*p == 'r')
                    ++p;
                number();
            } else if (m && *p == 's') {
                ++p;
                colour(scratch);
            }
            break;
        case 'a': // anisotropy
            if (m) {
                ++p;
                number();
            }
            break;
        case 'i':
            if (m) {
                next_word(p);
                m->illumination = atoi(next_word(p).c_str());
            }
            break;
        default: // textures, comments
            break;
        }
    }
}

// A polygon of n > 4 corners (vertices first .. first + n - 1) cut into n - 2
// triangles by ear clipping in the plane its Newell normal is most nearly
// perpendicular to, so that concave ones stay inside their outline. Writes
// from triangle t on; returns the next triangle.
uint64_t cut_ears(const float *positions, uint64_t first, uint32_t n, uint32_t *indices, uint64_t t,
                  bool *not_simple)
{
    double normal[3] = {0, 0, 0};
    for (uint32_t i = 0; i < n; ++i) {
        const float *a = positions + (first + i) * 3, *b = positions + (first + (i + 1) % n) * 3;
        normal[0] += (double(a[1]) - b[1]) * (double(a[2]) + b[2]);
        normal[1] += (double(a[2]) - b[2]) * (double(a[0]) + b[0]);
        normal[2] += (double(a[0]) - b[0]) * (double(a[1]) + b[1]);
    }
    int drop = 2;
    if (std::fabs(normal[0]) > std::fabs(normal[1]) && std::fabs(normal[0]) > std::fabs(normal[2]))
        drop = 0;
    else if (std::fabs(normal[1]) > std::fabs(normal[2]))
        drop = 1;
    int u = (drop + 1) % 3, v = (drop + 2) % 3;
    if (normal[drop] < 0.0)
        std::swap(u, v); // counter-clockwise in (u, v)
    std::vector<uint32_t> left(n);
    for (uint32_t i = 0; i < n; ++i)
        left[i] = i;
    auto at = [&](uint32_t i, int axis) { return double(positions[(first + i) * 3 + axis]); };
    auto cross = [&](uint32_t a, uint32_t b, uint32_t c) {
        return (at(b, u) - at(a, u)) * (at(c, v) - at(a, v)) - (at(b, v) - at(a, v)) * (at(c, u) - at(a, u));
    };
    auto emit = [&](uint32_t a, uint32_t b, uint32_t c) {
        uint32_t *tri = indices + t++ * 3;
        tri[0] = uint32_t(first + a);
        tri[1] = uint32_t(first + b);
        tri[2] = uint32_t(first + c);
    };
    while (left.size() > 3) {
        size_t m = left.size(), ear = m;
        for (size_t i = 0; i < m && ear == m; ++i) {
            uint32_t a = left[(i + m - 1) % m], b = left[i], c = left[(i + 1) % m];
            if (cross(a, b, c) < 0.0)
                continue; // reflex (a flat corner may go: it leaves no gap)
            bool empty = true;
            for (size_t k = 0; k < m && empty; ++k) {
                uint32_t p = left[k];
                if (p == a || p == b || p == c)
                    continue;
                // a corner repeated at the same place does not block the ear
                auto same = [&](uint32_t q) { return at(p, u) == at(q, u) && at(p, v) == at(q, v); };
                if (same(a) || same(b) || same(c))
                    continue;
                empty = !(cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0);
            }
            if (empty)
                ear = i;
        }
        if (ear == m) { // nothing is an ear (a degenerate outline): fan the rest
            *not_simple = true;
            for (size_t k = 1; k + 1 < m; ++k)
                emit(left[0], left[k], left[k + 1]);
            return t;
        }
        emit(left[(ear + m - 1) % m], left[ear], left[(ear + 1) % m]);
        left.erase(left.begin() + long(ear));
    }
    emit(left[0], left[1], left[2]);
    return t;
}

void Reader::convert(obj_data *out)
{
    // what Assimp's validation and SortByPType make of the meshes: faces of 1
    // or 2 corners given as "f" are refused unless the mesh also has points or
    // lines, and points and lines are dropped
    size_t scene_meshes = 0, triangle_meshes = 0;
    uint64_t vertex_total = 0, triangle_total = 0;
    const int64_t vertex_count = int64_t(vertices_.size() / 3);
    for (const Object &object : objects_) // Assimp's conversion, before its validation
        for (size_t m : object.meshes)
            for (size_t f = meshes_[m].first_face; f < meshes_[m].first_face + meshes_[m].face_count; ++f)
                for (uint32_t k = 0; k < faces_[f].vertex_count; ++k) {
                    const int64_t index = face_vertices_[faces_[f].first_vertex + k];
                    if (index < 0 || index >= vertex_count)
                        throw ImportError{"OBJ: vertex index out of range"};
                }
    for (const Object &object : objects_)
        for (size_t m : object.meshes) {
            const Mesh &mesh = meshes_[m];
            if (mesh.face_count == 0)
                continue;
            ++scene_meshes;
            bool points = false, lines = false;
            for (size_t f = mesh.first_face; f < mesh.first_face + mesh.face_count; ++f) {
                points |= faces_[f].type == face_point;
                lines |= faces_[f].type == face_line;
            }
            uint64_t index = 0;
            uint64_t triangles = 0, corners = 0;
            for (size_t f = mesh.first_face; f < mesh.first_face + mesh.face_count; ++f) {
                const Face &face = faces_[f];
                if (face.type == face_polygon && face.vertex_count < 3 && !(face.vertex_count == 1 ? points : lines)) {
                    const char *kind = face.vertex_count == 1 ? "POINT" : "LINE";
                    char text[160];
                    snprintf(text, sizeof text,
                             "Validation failed: aiMesh::mFaces[%llu] is a %s but aiMesh::mPrimitiveTypes does not "
                             "report the %s flag",
                             (unsigned long long)index, kind, kind);
                    throw ImportError{text};
                }
                index += face.type == face_line ? face.vertex_count - 1 : face.type == face_point ? face.vertex_count : 1;
                if (face.type == face_polygon && face.vertex_count >= 3) {
                    triangles += face.vertex_count - 2;
                    corners += face.vertex_count;
                }
            }
            if (triangles > 0)
                ++triangle_meshes;
            vertex_total += corners;
            triangle_total += triangles;
        }
    // without faces, Assimp made one mesh of all the points (and then found no faces in it)
    if (objects_.empty() && !vertices_.empty() && !normals_.empty() && normals_.size() < vertices_.size())
        throw ImportError{"OBJ: vertex normal index out of range"};
    if (objects_.empty() && colours_ > 0 && colours_ < vertices_.size() / 3)
        throw ImportError{"OBJ: vertex color index out of range"};
    if (objects_.empty() || scene_meshes == 0)
        throw ImportError{!objects_.empty() || vertices_.empty()
                              ? "Validation failed: aiScene::mNumMeshes is 0. At least one mesh must be there"
                              : "Validation failed: Mesh  contains no faces"};
    if (triangle_meshes == 0)
        throw ImportError{"No meshes remaining"};
    if (vertex_total >= (uint64_t(1) << 31) || triangle_total >= (uint64_t(1) << 31))
        throw ImportError{"too large: more than 2^31 vertices or triangles"};

    out->positions = static_cast<float *>(malloc(vertex_total * 3 * sizeof(float)));
    out->normals = static_cast<float *>(calloc(vertex_total * 3, sizeof(float)));
    out->texture_coordinates = static_cast<float *>(calloc(vertex_total * 3, sizeof(float)));
    out->indices = static_cast<uint32_t *>(malloc(triangle_total * 3 * sizeof(uint32_t)));
    out->meshes = static_cast<obj_mesh *>(calloc(triangle_meshes, sizeof(obj_mesh)));
    if (!out->positions || !out->normals || !out->texture_coordinates || !out->indices || !out->meshes)
        throw std::bad_alloc();

    for (const Object &object : objects_)
        for (size_t m : object.meshes) {
            const Mesh &mesh = meshes_[m];
            obj_mesh o = {}; // kept only if it has triangles
            o.first_vertex = uint32_t(out->vertex_count);
            o.first_triangle = uint32_t(out->triangle_count);
            bool normals_ok = !normals_.empty() && mesh.has_normals;
            bool uvs_ok = !uvs_.empty() && mesh.uv_count > 0;
            uint64_t v = out->vertex_count, t = out->triangle_count;
            for (size_t f = mesh.first_face; f < mesh.first_face + mesh.face_count; ++f) {
                const Face &face = faces_[f];
                if (face.type != face_polygon || face.vertex_count < 3)
                    continue;
                const uint64_t first = v;
                for (uint32_t k = 0; k < face.vertex_count; ++k, ++v) {
                    memcpy(out->positions + v * 3, &vertices_[size_t(face_vertices_[face.first_vertex + k]) * 3],
                           3 * sizeof(float));
                    if (normals_ok && k < face.normal_count) {
                        int64_t n = face_normals_[face.first_normal + k];
                        if (n < 0 || n >= int64_t(normals_.size() / 3))
                            normals_ok = false;
                        else
                            memcpy(out->normals + v * 3, &normals_[size_t(n) * 3], 3 * sizeof(float));
                    }
                    if (uvs_ok && k < face.uv_count) {
                        int64_t u = face_uvs_[face.first_uv + k];
                        if (u < 0 || u >= int64_t(uvs_.size() / 3))
                            uvs_ok = false;
                        else
                            memcpy(out->texture_coordinates + v * 3, &uvs_[size_t(u) * 3], 3 * sizeof(float));
                    }
                }
                // triangles: a quad is cut from its concave corner if it has one
                // (its angle is over 180 degrees), else from corner 0, as Assimp did
                uint32_t start = 0, n = face.vertex_count;
                if (n == 4) {
                    for (uint32_t i = 0; i < 4; ++i) {
                        const float *c = out->positions + (first + i) * 3;
                        float d[3][3];
                        for (int e = 0; e < 3; ++e) { // to the previous, opposite and next corner
                            const float *q = out->positions + (first + (i + 3 - e) % 4) * 3;
                            float length = std::sqrt((q[0] - c[0]) * (q[0] - c[0]) + (q[1] - c[1]) * (q[1] - c[1]) +
                                                     (q[2] - c[2]) * (q[2] - c[2]));
                            for (int k = 0; k < 3; ++k)
                                d[e][k] = (q[k] - c[k]) / length;
                        }
                        float angle = std::acos(d[0][0] * d[1][0] + d[0][1] * d[1][1] + d[0][2] * d[1][2]) +
                                      std::acos(d[2][0] * d[1][0] + d[2][1] * d[1][1] + d[2][2] * d[1][2]);
                        if (angle > float(M_PI)) {
                            start = i;
                            break;
                        }
                    }
                }
                if (n > 4) {
                    bool not_simple = false;
                    t = cut_ears(out->positions, first, n, out->indices, t, &not_simple);
                    if (not_simple) // Assimp's words when its ear cutting gave up
                        say("Failed to triangulate polygon (no ear found). Probably not a simple polygon?");
                    continue;
                }
                for (uint32_t k = 1; k + 1 < n; ++k, ++t) {
                    uint32_t *tri = out->indices + t * 3;
                    tri[0] = uint32_t(first + start);
                    tri[1] = uint32_t(first + (start + k) % n);
                    tri[2] = uint32_t(first + (start + k + 1) % n);
                }
            }
            if (t == out->triangle_count)
                continue; // no triangles: no part
            if (!normals_ok) // Assimp dropped the mesh's normals
                memset(out->normals + out->vertex_count * 3, 0, (v - out->vertex_count) * 3 * sizeof(float));
            if (!uvs_ok)
                memset(out->texture_coordinates + out->vertex_count * 3, 0,
                       (v - out->vertex_count) * 3 * sizeof(float));
            // Assimp's scene check: 3D texture coordinates whose third is 0 everywhere
            if (uvs_ok && uv_dimensions_ == 3) {
                bool flat = true;
                for (uint64_t k = out->vertex_count; k < v && flat; ++k)
                    flat = out->texture_coordinates[k * 3 + 2] == 0.0f;
                if (flat)
                    say("ScenePreprocessor: UVs are declared to be 3D but they're obviously not. Reverting to 2D.");
            }
            o.has_normals = normals_ok;
            o.vertex_count = uint32_t(v - out->vertex_count);
            o.triangle_count = uint32_t(t - out->triangle_count);
            out->vertex_count = v;
            out->triangle_count = t;
            if (mesh.name.size() <= name_limit)
                snprintf(o.name, sizeof o.name, "%s", mesh.name.c_str());
            if (object.name.size() <= name_limit)
                snprintf(o.object_name, sizeof o.object_name, "%s", object.name.c_str());
            const Material &material = materials_[mesh.material == no_material ? 0 : mesh.material];
            // Assimp's "DefaultMaterial" is one it invented: the renderer's default applies
            o.invented_material = material.name == default_material;
            memcpy(o.colour, material.diffuse, sizeof o.colour);
            o.opacity = material.alpha;
            out->meshes[out->mesh_count++] = o;
        }
    for (const Material &material : materials_)
        if (material.name != default_material && (material.illumination < 0 || material.illumination > 2))
            say("OBJ: unexpected illumination model (0-2 recognized)");
}

} // namespace

extern "C" bool obj_read(const char *path, obj_data *out, void (*warn)(void *, const char *), void *user, char *why,
                         size_t why_size)
{
    memset(out, 0, sizeof *out);
    try {
        Reader reader(path, warn, user);
        reader.read();
        reader.convert(out);
        return true;
    } catch (const ImportError &e) {
        snprintf(why, why_size, "%s", e.message.c_str());
    } catch (const std::bad_alloc &) {
        snprintf(why, why_size, "std::bad_alloc");
    } catch (const std::exception &e) {
        snprintf(why, why_size, "%s", e.what());
    }
    obj_free(out);
    return false;
}

extern "C" void obj_free(obj_data *data)
{
    free(data->positions);
    free(data->normals);
    free(data->texture_coordinates);
    free(data->indices);
    free(data->meshes);
    memset(data, 0, sizeof *data);
}
