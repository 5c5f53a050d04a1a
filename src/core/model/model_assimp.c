/* model_assimp.c: every format but OBJ read through Assimp: the scene's node
 * tree walked iteratively, each mesh a node instances one component, node
 * transforms applied, materials' colour and opacity; Assimp's log gathered as
 * warnings, and the files a model refers to read through a file system of
 * our own, so that a failing one is named. The model it makes is finished by
 * model_import.c. The only file of the core that includes Assimp's importer. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "model_internal.h"

/* ------------------------------------------------------------------ log */

/* Assimp's log lines are "Warn,  T0: text" and "Error, T0: text". Errors
 * that end the import come back as the import's error instead; the ones
 * logged on a successful import are repairs (e.g. OFF indices clamped). What
 * this renderer never reads (bones, animations, textures) is left out. */
static void assimp_log(const char *message, char *user)
{
    import_warnings *w = (import_warnings *)user;
    bool warn = strncmp(message, "Warn", 4) == 0, error = strncmp(message, "Error", 5) == 0;
    if (!warn && !error)
        return;
    const char *text = strstr(message, ": ");
    text = text ? text + 2 : message;
    static const char *const unread[] = {"bone", "Bone", "nimation", "exture",
                                         "No object detected to attach"};
    for (size_t i = 0; i < sizeof unread / sizeof unread[0]; ++i)
        if (strstr(text, unread[i]))
            return;
    char line[OIT_ERROR_MESSAGE_SIZE];
    snprintf(line, sizeof line, "%s", text);
    size_t length = strlen(line);
    while (length > 0 && (line[length - 1] == '\n' || line[length - 1] == '\r' || line[length - 1] == ' '))
        line[--length] = '\0';
    /* Assimp's OFF reader replaces an index past the end by the last vertex. */
    const char *repair = strstr(line, "OFF: Vertex index is out of range")
                             ? " (it drew the face with the last vertex instead)"
                             : "";
    oit_import_warn(w, "the importer reports: %s%s", line, repair);
}

/* -------------------------------------------------------------- loading */

typedef struct load_state {
    const struct aiScene *scene;
    oit_model *model;
    uint64_t vertex_count, triangle_count, component_count; /* counted, then filled */
    bool any_normals; /* some mesh has normals: keep them, compute only the missing */
    uint32_t *mesh_uses; /* per Assimp mesh: how many nodes instance it */
    uint32_t *vertex_owner; /* per vertex: the component that filled it */
    float *texture_coordinates; /* per vertex: the first UV(W) channel, or 0 */
    name_set *names;
    bool bad_index; /* first face index outside its mesh, for the message */
    uint32_t bad_mesh_face, bad_mesh_index;
    char bad_mesh_name[OIT_NAME_SIZE];
} load_state;

static bool mesh_has_triangles(const struct aiMesh *mesh)
{
    return mesh && (mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) && mesh->mNumVertices > 0 &&
           mesh->mNumFaces > 0 && mesh->mVertices;
}

static uint32_t mesh_triangle_count(const struct aiMesh *mesh)
{
    uint32_t count = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f)
        if (mesh->mFaces[f].mNumIndices == 3)
            ++count;
    return count;
}

/* Row-major Assimp matrices: a1..a4 is the first row, translation in a4/b4/c4. */
static void transform_point(const struct aiMatrix4x4 *m, const struct aiVector3D *v, float out[3])
{
    out[0] = (float)(m->a1 * v->x + m->a2 * v->y + m->a3 * v->z + m->a4);
    out[1] = (float)(m->b1 * v->x + m->b2 * v->y + m->b3 * v->z + m->b4);
    out[2] = (float)(m->c1 * v->x + m->c2 * v->y + m->c3 * v->z + m->c4);
}

static void multiply(const struct aiMatrix4x4 *a, const struct aiMatrix4x4 *b,
                     struct aiMatrix4x4 *out)
{
    const ai_real *pa = &a->a1, *pb = &b->a1;
    ai_real r[16];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            ai_real s = 0;
            for (int k = 0; k < 4; ++k)
                s += pa[i * 4 + k] * pb[k * 4 + j];
            r[i * 4 + j] = s;
        }
    memcpy(&out->a1, r, sizeof r);
}

/* Normals go through the cofactor matrix (inverse transpose up to scale). */
static void normal_matrix(const struct aiMatrix4x4 *m, double n[9], double *determinant)
{
    double a = m->a1, b = m->a2, c = m->a3, d = m->b1, e = m->b2, f = m->b3, g = m->c1,
           h = m->c2, i = m->c3;
    n[0] = e * i - f * h; n[1] = f * g - d * i; n[2] = d * h - e * g;
    n[3] = c * h - b * i; n[4] = a * i - c * g; n[5] = b * g - a * h;
    n[6] = b * f - c * e; n[7] = c * d - a * f; n[8] = a * e - b * d;
    *determinant = a * n[0] + b * n[1] + c * n[2];
}

/* The node tree is walked depth first, children in order, with a stack of
 * its own: files nest nodes as deep as they like (a glTF chain of 5,000
 * nodes is valid), and a recursion would either cut them off or overflow
 * the C stack. Each entry carries its node's global transform. */
typedef struct node_entry {
    const struct aiNode *node;
    struct aiMatrix4x4 global;
} node_entry;

typedef struct node_walk {
    node_entry *entries;
    size_t count, capacity;
    bool out_of_memory;
} node_walk;

static void walk_push(node_walk *walk, const struct aiNode *node, const struct aiMatrix4x4 *global)
{
    if (!node || walk->out_of_memory)
        return;
    if (walk->count == walk->capacity) {
        size_t capacity = walk->capacity ? walk->capacity * 2 : 64;
        node_entry *grown = realloc(walk->entries, capacity * sizeof *grown);
        if (!grown) {
            walk->out_of_memory = true;
            return;
        }
        walk->entries = grown;
        walk->capacity = capacity;
    }
    walk->entries[walk->count].node = node;
    walk->entries[walk->count].global = *global;
    ++walk->count;
}

/* Pops the next node in depth-first order and pushes its children; false
 * when the walk is over (or out of memory: walk->out_of_memory). */
static bool walk_next(node_walk *walk, node_entry *out)
{
    if (walk->count == 0 || walk->out_of_memory)
        return false;
    *out = walk->entries[--walk->count];
    for (unsigned i = out->node->mNumChildren; i-- > 0;) {
        const struct aiNode *child = out->node->mChildren[i];
        if (!child)
            continue;
        struct aiMatrix4x4 global;
        multiply(&out->global, &child->mTransformation, &global);
        walk_push(walk, child, &global);
    }
    return true;
}

/* Pass 1: count what one node instantiates (a mesh used by two nodes
 * becomes two components). */
static void count_node(load_state *st, const struct aiNode *node)
{
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
        unsigned m = node->mMeshes[i];
        if (m >= st->scene->mNumMeshes)
            continue;
        const struct aiMesh *mesh = st->scene->mMeshes[m];
        if (!mesh_has_triangles(mesh))
            continue;
        uint32_t triangles = mesh_triangle_count(mesh);
        if (triangles == 0)
            continue;
        if (st->mesh_uses[m] < UINT32_MAX)
            ++st->mesh_uses[m];
        st->vertex_count += mesh->mNumVertices;
        st->triangle_count += triangles;
        st->component_count += 1;
        st->any_normals |= mesh->mNormals != NULL;
    }
}

static void material_properties(const struct aiScene *scene, unsigned index, oit_component *comp)
{
    memcpy(comp->colour, oit_model_default_colour, sizeof comp->colour);
    comp->opacity = 1.0f;
    if (index >= scene->mNumMaterials)
        return;
    const struct aiMaterial *mat = scene->mMaterials[index];
    struct aiString name;
    /* For files without materials Assimp invents one: "DefaultMaterial"
     * (STL, OBJ), or an unnamed one (PLY white, OFF grey 0.6). Our default
     * applies to those. (A glTF base colour is always the file's own.) */
    bool invented = aiGetMaterialString(mat, AI_MATKEY_NAME, &name) != aiReturn_SUCCESS ||
                    strcmp(name.data, AI_DEFAULT_MATERIAL_NAME) == 0;
    struct aiColor4D colour;
    bool have_base = false;
    /* glTF (metallic-roughness) base colour wins; its alpha is the opacity. */
    if (aiGetMaterialColor(mat, AI_MATKEY_BASE_COLOR, &colour) == aiReturn_SUCCESS) {
        have_base = true;
        comp->colour[0] = colour.r;
        comp->colour[1] = colour.g;
        comp->colour[2] = colour.b;
        comp->opacity = colour.a;
    } else if (invented) {
        return;
    } else if (aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &colour) == aiReturn_SUCCESS) {
        comp->colour[0] = colour.r;
        comp->colour[1] = colour.g;
        comp->colour[2] = colour.b;
    }
    /* MTL d / Tr and most formats: the opacity property. glTF importers set
     * it to the base alpha as well; take the smaller where both exist. */
    ai_real opacity;
    unsigned max = 1;
    if (aiGetMaterialFloatArray(mat, AI_MATKEY_OPACITY, &opacity, &max) == aiReturn_SUCCESS)
        comp->opacity = have_base ? fminf(comp->opacity, (float)opacity) : (float)opacity;
    oit_clamp_material(comp);
}

/* Pass 2: copy one node's vertices (transformed to model space), triangles,
 * components. */
static void fill_node(load_state *st, const struct aiNode *node, const struct aiMatrix4x4 *node_global)
{
    struct aiMatrix4x4 global = *node_global;
    double nm[9], determinant;
    normal_matrix(&global, nm, &determinant);
    oit_model *model = st->model;
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
        unsigned m = node->mMeshes[i];
        if (m >= st->scene->mNumMeshes)
            continue;
        const struct aiMesh *mesh = st->scene->mMeshes[m];
        if (!mesh_has_triangles(mesh) || mesh_triangle_count(mesh) == 0)
            continue;
        uint32_t c = model->component_count++;
        oit_component *comp = &model->components[c];
        oit_component_name(model, st->names, c, mesh->mName.length > 0 ? mesh->mName.data : "",
                       node->mName.length > 0 ? node->mName.data : "", st->mesh_uses[m] > 1);
        material_properties(st->scene, mesh->mMaterialIndex, comp);
        comp->first_triangle = model->triangle_count;

        uint32_t base = model->vertex_count;
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            float *p = model->positions + ((size_t)base + v) * 3;
            transform_point(&global, &mesh->mVertices[v], p);
            float *n = model->normals + ((size_t)base + v) * 3;
            if (mesh->mNormals) {
                const struct aiVector3D *in = &mesh->mNormals[v];
                for (int k = 0; k < 3; ++k)
                    n[k] = (float)(nm[k * 3] * in->x + nm[k * 3 + 1] * in->y + nm[k * 3 + 2] * in->z);
            } else {
                n[0] = n[1] = n[2] = 0.0f; /* recomputed by oit_model_finish */
            }
        }
        model->vertex_count += mesh->mNumVertices;

        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const struct aiFace *face = &mesh->mFaces[f];
            if (face->mNumIndices != 3)
                continue; /* a stray point or line SortByPType left behind */
            uint32_t *tri = model->indices + (size_t)model->triangle_count * 3;
            for (int k = 0; k < 3; ++k) {
                /* Out-of-range indices stay out of range (finish reports them). */
                if (face->mIndices[k] >= mesh->mNumVertices && !st->bad_index) {
                    st->bad_index = true;
                    st->bad_mesh_face = f;
                    st->bad_mesh_index = face->mIndices[k];
                    snprintf(st->bad_mesh_name, sizeof st->bad_mesh_name, "%s", comp->name);
                }
                uint64_t index = (uint64_t)base + face->mIndices[k];
                tri[k] = index >= model->vertex_count ? UINT32_MAX : (uint32_t)index;
            }
            if (determinant < 0.0) { /* a mirroring transform flips the winding back */
                uint32_t t = tri[1];
                tri[1] = tri[2];
                tri[2] = t;
            }
            ++model->triangle_count;
        }
        comp->triangle_count = model->triangle_count - comp->first_triangle;
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            st->vertex_owner[base + v] = c;
            float *uv = st->texture_coordinates + ((size_t)base + v) * 3;
            const struct aiVector3D *in = mesh->mTextureCoords[0] ? &mesh->mTextureCoords[0][v] : NULL;
            uv[0] = in ? (float)in->x : 0.0f;
            uv[1] = in ? (float)in->y : 0.0f;
            uv[2] = in ? (float)in->z : 0.0f;
        }
    }
}

/* Runs visit on every node of the scene, depth first; false when out of memory. */
static bool walk_scene(load_state *st, void (*visit)(load_state *, const struct aiNode *,
                                                     const struct aiMatrix4x4 *))
{
    /* The root node's transform is applied too: importers put axis
     * conversions (e.g. Z-up to Y-up) there. */
    node_walk walk = {0};
    walk_push(&walk, st->scene->mRootNode, &st->scene->mRootNode->mTransformation);
    node_entry entry;
    while (walk_next(&walk, &entry))
        visit(st, entry.node, &entry.global);
    bool ok = !walk.out_of_memory;
    free(walk.entries);
    return ok;
}

static void count_visit(load_state *st, const struct aiNode *node, const struct aiMatrix4x4 *global)
{
    (void)global;
    count_node(st, node);
}

/* ------------------------------------------------- files the model refers to */

/* Assimp reads through this file system so that the files a model refers to
 * (an OBJ's material libraries, a glTF's buffers) are known: when an import
 * fails, it is tried once more with those files refused, and if the error
 * goes away (or changes) the message names the referred file, not the
 * model. */
typedef struct import_files {
    const char *model_path;
    bool refuse_others;
    char first_other[4096]; /* the first other file opened, "" if none */
    char not_regular[OIT_ERROR_MESSAGE_SIZE]; /* "NAME: not a regular file (a FIFO)" for the first such, or "" */
} import_files;

static FILE *io_stream(struct aiFile *file) { return (FILE *)(void *)file->UserData; }

static size_t io_read(struct aiFile *file, char *buffer, size_t size, size_t count)
{
    return fread(buffer, size, count, io_stream(file));
}

static size_t io_write(struct aiFile *file, const char *buffer, size_t size, size_t count)
{
    (void)file, (void)buffer, (void)size, (void)count;
    return 0; /* import only */
}

static size_t io_tell(struct aiFile *file)
{
    long position = ftell(io_stream(file));
    return position < 0 ? 0 : (size_t)position;
}

static size_t io_size(struct aiFile *file)
{
    FILE *stream = io_stream(file);
    long position = ftell(stream), end = -1;
    if (position >= 0 && fseek(stream, 0, SEEK_END) == 0)
        end = ftell(stream);
    if (position >= 0)
        fseek(stream, position, SEEK_SET);
    return end < 0 ? 0 : (size_t)end;
}

static void io_flush(struct aiFile *file) { fflush(io_stream(file)); }

static enum aiReturn io_seek(struct aiFile *file, size_t offset, enum aiOrigin origin)
{
    int whence = origin == aiOrigin_SET ? SEEK_SET : origin == aiOrigin_CUR ? SEEK_CUR : SEEK_END;
    /* aiOrigin_CUR moves backwards by a wrapped-around size_t */
    return fseek(io_stream(file), (long)offset, whence) == 0 ? aiReturn_SUCCESS : aiReturn_FAILURE;
}

static struct aiFile *io_open(struct aiFileIO *io, const char *path, const char *mode)
{
    import_files *files = (import_files *)(void *)io->UserData;
    if (strcmp(path, files->model_path) != 0) {
        if (!files->first_other[0])
            snprintf(files->first_other, sizeof files->first_other, "%s", path);
        if (files->refuse_others)
            return NULL;
    }
    struct aiFile *file = calloc(1, sizeof *file);
    /* a file the model refers to (a glTF's .bin) must be a regular file too:
     * a FIFO would block the import until the wall limit */
    FILE *stream = NULL;
    oit_error refused;
    if (file && mode[0] == 'r' && oit_open_regular_file(path, NULL, &stream, &refused) != OIT_OK) {
        const char *kind = strstr(refused.message, "not a regular file");
        if (kind && !files->not_regular[0])
            snprintf(files->not_regular, sizeof files->not_regular, "%.200s: %s", oit_path_basename(path), kind);
    } else if (file && mode[0] != 'r') {
        stream = fopen(path, mode);
    }
    if (!stream) {
        free(file);
        return NULL;
    }
    file->ReadProc = io_read;
    file->WriteProc = io_write;
    file->TellProc = io_tell;
    file->FileSizeProc = io_size;
    file->SeekProc = io_seek;
    file->FlushProc = io_flush;
    file->UserData = (aiUserData)(void *)stream;
    return file;
}

static void io_close(struct aiFileIO *io, struct aiFile *file)
{
    (void)io;
    if (file) {
        fclose(io_stream(file));
        free(file);
    }
}

static const struct aiScene *import_with(const char *path, unsigned flags,
                                         const struct aiPropertyStore *props, import_files *files)
{
    struct aiFileIO io = {io_open, io_close, (aiUserData)(void *)files};
    return aiImportFileExWithProperties(path, flags, &io, props);
}

/* After a failed import that opened other files: was it one of those? */
static void name_failing_file(const char *path, unsigned flags,
                              const struct aiPropertyStore *props, import_files *files,
                              char *why, size_t why_size)
{
    if (!files->first_other[0])
        return;
    char other[4096];
    snprintf(other, sizeof other, "%s", files->first_other);
    files->refuse_others = true;
    const struct aiScene *again = import_with(path, flags, props, files);
    const char *again_why = again ? "" : aiGetErrorString();
    bool theirs = again || !again_why || strcmp(again_why, why) != 0;
    if (again)
        aiReleaseImport(again);
    if (!theirs)
        return;
    const char *other_name = oit_path_basename(other);
    const char *dot = strrchr(other_name, '.');
    char reason[OIT_ERROR_MESSAGE_SIZE];
    snprintf(reason, sizeof reason, "%s", why);
    snprintf(why, why_size, "%s %.200s: %.280s",
             dot && strcasecmp(dot, ".mtl") == 0 ? "material library" : "the file it refers to,",
             other_name, reason);
}

oit_status oit_model_read_assimp(const char *path, const char *name, long long file_size,
                                 import_warnings *warnings, oit_model *out, bool *any_normals,
                                 oit_error *err)
{
    /* Post-processing, and why:
     * - Triangulate: polygons become triangles (the renderer draws triangles).
     * - SortByPType + SBP_REMOVE(points, lines): a mesh mixing primitive types
     *   is split and the point and line meshes dropped, so OBJ line/point
     *   elements never reach us and a file with nothing else has no triangles.
     * - ValidateDataStructure: Assimp rejects broken index data itself.
     * Not used: JoinIdenticalVertices (OBJ and STL give one vertex per face
     *   corner; oit_model_join_identical_vertices shares them exactly, where Assimp's
     *   join uses tolerances that depend on the model's units),
     *   PreTransformVertices (it merges meshes sharing a material and
     *   loses their names; the node tree is walked here instead, applying
     *   node transforms), FindDegenerates (it would turn zero-area triangles
     *   into lines or points and change the triangle count; they are harmless),
     *   GenNormals (missing normals are computed in oit_model_finish). */
    unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure;
    struct aiPropertyStore *props = aiCreatePropertyStore();
    if (!props)
        return oit_fail(err, OIT_E_RUNTIME, "%s: out of memory", name);
    aiSetImportPropertyInteger(props, AI_CONFIG_PP_SBP_REMOVE,
                               aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    /* Assimp's log is process-wide: one import at a time listens to it (and
     * nothing of it reaches stderr). */
    static pthread_mutex_t import_lock = PTHREAD_MUTEX_INITIALIZER;
    pthread_mutex_lock(&import_lock);
    struct aiLogStream log = {assimp_log, (char *)warnings};
    aiAttachLogStream(&log);
    import_files files = {.model_path = path};
    const struct aiScene *scene = import_with(path, flags, props, &files);
    char why_text[OIT_ERROR_MESSAGE_SIZE] = "";
    if (!scene) {
        const char *assimp_why = aiGetErrorString();
        snprintf(why_text, sizeof why_text, "%s", assimp_why ? assimp_why : "");
        if (files.not_regular[0])
            snprintf(why_text, sizeof why_text, "the file it refers to, %.480s", files.not_regular);
        else if (why_text[0])
            name_failing_file(path, flags, props, &files, why_text, sizeof why_text);
    }
    aiDetachLogStream(&log);
    pthread_mutex_unlock(&import_lock);
    aiReleasePropertyStore(props);
    if (!scene)
        return oit_import_failure(name, why_text, file_size, err);
    if (!scene->mRootNode) {
        aiReleaseImport(scene);
        return oit_fail(err, OIT_E_INPUT, "%s: no triangles (the file has no scene nodes)", name);
    }

    oit_status status = OIT_OK;
    load_state st = {.scene = scene, .model = out};
    name_set names = {0};
    st.names = &names;
    st.mesh_uses = oit_model_calloc_array(scene->mNumMeshes, sizeof *st.mesh_uses);
    if (!st.mesh_uses) {
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory", name);
        goto done;
    }
    if (!walk_scene(&st, count_visit)) {
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory walking the node tree", name);
        goto done;
    }
    if (st.triangle_count == 0) {
        status = oit_fail(err, OIT_E_INPUT, "%s: no triangles", name);
        goto done;
    }
    if (st.vertex_count > OIT_MODEL_LIMIT || st.triangle_count > OIT_MODEL_LIMIT ||
        st.component_count > OIT_MODEL_LIMIT) {
        status = oit_fail(err, OIT_E_INPUT,
                          "%s: too large: %llu vertices, %llu triangles, %llu components "
                          "(limit 2^31)",
                          name, (unsigned long long)st.vertex_count,
                          (unsigned long long)st.triangle_count,
                          (unsigned long long)st.component_count);
        goto done;
    }
    out->positions = oit_model_alloc_array(st.vertex_count * 3, sizeof *out->positions);
    out->normals = oit_model_alloc_array(st.vertex_count * 3, sizeof *out->normals);
    out->indices = oit_model_alloc_array(st.triangle_count * 3, sizeof *out->indices);
    out->components = oit_model_calloc_array(st.component_count, sizeof *out->components);
    st.vertex_owner = oit_model_alloc_array(st.vertex_count, sizeof *st.vertex_owner);
    st.texture_coordinates = oit_model_alloc_array(st.vertex_count * 3, sizeof *st.texture_coordinates);
    if (!out->positions || !out->normals || !out->indices || !out->components || !st.vertex_owner ||
        !st.texture_coordinates ||
        !oit_name_set_init(&names, st.component_count)) {
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory for %llu vertices", name,
                          (unsigned long long)st.vertex_count);
        goto done;
    }
    if (!walk_scene(&st, fill_node))
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory walking the node tree", name);
    else if (st.bad_index)
        status = oit_fail(err, OIT_E_INPUT,
                          "%s: face %u of mesh '%s' refers to vertex %u, outside the mesh", name,
                          st.bad_mesh_face, st.bad_mesh_name, st.bad_mesh_index);
    else
        status = oit_model_join_identical_vertices(out, st.texture_coordinates, st.vertex_owner, err);

done:
    aiReleaseImport(scene);
    free(st.mesh_uses);
    free(st.vertex_owner);
    free(st.texture_coordinates);
    oit_name_set_free(&names);
    *any_normals = st.any_normals;
    return status;
}

