/*
 * oit.h: the public interface of the oit-workbench core (C11).
 *
 * The core takes plain matrices and C structs. Every function that can fail
 * returns an oit_status and leaves a one-line message in an oit_error; the core
 * never prints and never exits.
 *
 * Conventions
 * - Matrices are double[16] in OpenGL's column-major order (m[col * 4 + row]),
 *   column-vector convention: clip = projection * modelview * v. A frame's
 *   modelview applies to the model's own (file) coordinates; the model keeps
 *   its positions relative to its centre (oit_model.origin), and
 *   oit_algorithm_render folds that translation into the modelview in double,
 *   so a part drawn in millimetres far from the origin reaches the GPU and
 *   the reference as the same well-conditioned numbers as one at the origin.
 * - Images are RGBA8, top row first (as PNG stores them).
 * - Fragments are ordered by (depth, triangle index). The depth is the
 *   canonical one (common/canonical_depth.glsl): where the fragment's coplanar
 *   plane (oit_model.planes) meets the pixel centre's eye-space ray, as the
 *   fraction s in [0, 1] of the ray from its near-plane point to its
 *   far-plane point. Faces in one plane tie exactly, whatever their
 *   triangulation, and then order by triangle index; s is linear in eye
 *   depth, so floats separate surfaces 1e-3 apart at 800 units even with
 *   the near plane at 0.01.
 * - Compositing is front to back in floating point; colour is quantized once.
 */
#ifndef OIT_H
#define OIT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h> /* FILE */

/* Defined in a build under AddressSanitizer, which reports crashes and limits
 * memory its own way: the command line's crash handler and the import
 * worker's address-space limit stand aside for it. */
#if defined(__SANITIZE_ADDRESS__)
#define OIT_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define OIT_ADDRESS_SANITIZER 1
#endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ status */

typedef enum oit_status {
    OIT_OK = 0,
    OIT_E_INPUT = 2,   /* bad usage or input (maps to exit status 2) */
    OIT_E_RUNTIME = 3, /* GL or runtime failure (maps to exit status 3) */
    OIT_CANCELLED = 4  /* not a failure: the frame's progress callback asked to stop
                          (oit_progress); the algorithm stays usable */
} oit_status;

#define OIT_ERROR_MESSAGE_SIZE 512

typedef struct oit_error {
    char message[OIT_ERROR_MESSAGE_SIZE]; /* one line, no trailing newline */
} oit_error;

/* Format a one-line message into err (may be NULL) and return status. */
oit_status oit_fail(oit_error *err, oit_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* ------------------------------------------------------------------- model */

#define OIT_NAME_SIZE 128

typedef struct oit_component {
    char name[OIT_NAME_SIZE]; /* group / mesh name, unique within the model */
    float colour[3];          /* material diffuse colour (MTL Kd, glTF base colour) */
    float opacity;            /* material opacity (MTL d, glTF base alpha), 1 if none */
    uint32_t first_triangle;  /* the component's triangles are contiguous */
    uint32_t triangle_count;
    float longest_edge;       /* its longest triangle edge (model space; computed) */
    /* Whether it encloses a volume (oit_model_finish): every edge, by welded
     * vertex ids, is used by an even number of its triangles. Only closed parts
     * get section caps (docs/sections.md); a sheet or a tray missing a face is open. */
    bool closed;
} oit_component;

/* An assembly node (a STEP/IGES (sub)assembly or instance, a glTF, FBX or COLLADA
 * node): the tree the parts panel shows and the paths --hide and --component-alpha
 * accept. Components hang under nodes; a model without a tree has none. */
#define OIT_NO_NODE UINT32_MAX
typedef struct oit_model_node {
    char name[OIT_NAME_SIZE]; /* unique among its siblings (nodes and components) */
    uint32_t parent;          /* an earlier node's index, or OIT_NO_NODE at the top */
} oit_model_node;

typedef struct oit_model {
    /* The centre of the bounding box in the file's coordinates, a float value
     * (so most positions subtract from it exactly). Every coordinate below
     * (positions, bounds, planes) is relative to it: file coordinates =
     * origin + relative ones. oit_model_finish sets it. */
    double origin[3];
    uint32_t vertex_count;
    float *positions;           /* 3 per vertex, relative to origin */
    float *normals;             /* 3 per vertex, unit length (computed if the file has none) */
    uint32_t *vertex_component; /* per vertex: index of its component */
    uint32_t *welded_ids;       /* per vertex: vertices at the same position share an id */
    uint32_t welded_count;      /* number of distinct welded ids */

    uint32_t triangle_count;
    uint32_t *indices; /* 3 per triangle; triangle index == gl_PrimitiveID */

    uint32_t component_count;
    oit_component *components;
    /* The assembly tree (NULL and 0 when the file has none): nodes, parents
     * before children, and each component's node (OIT_NO_NODE: at the top). */
    uint32_t node_count;
    oit_model_node *nodes;
    uint32_t *component_node; /* per component, or NULL */

    float bounds_min[3], bounds_max[3]; /* relative to origin */
    float radius; /* bounding sphere about origin: every vertex lies within it */
    float longest_edge; /* the longest triangle edge (model space), the largest of the
                           components' */
    /* Coplanar clusters (oit_model_finish): triangles that lie within
     * OIT_COPLANAR_ULPS float ulps of the largest file coordinate of one
     * plane and touch (directly or through others in it) share it, and every exact algorithm
     * and the reference take a fragment's sort depth from its triangle's
     * plane at the pixel centre, so coincident faces tie bit for bit and then
     * order by triangle index. */
    uint32_t plane_count;
    float *planes;            /* 4 per plane: unit normal xyz, d (n . p + d = 0), relative
                                 to origin */
    uint32_t *triangle_plane; /* per triangle: its plane */
    /* What the import skipped, repaired or could not check, one line each
     * ("FILE: what"): a model that loads is never silently incomplete. At most
     * OIT_MODEL_WARNING_LIMIT; repeats are counted in their line, and the last
     * line says how many other warnings were left out. */
    uint32_t warning_count;
    char (*warnings)[OIT_ERROR_MESSAGE_SIZE];
    float *triangle_reach; /* per triangle: the longest edge of any triangle that shares a
                              (welded) vertex with it, itself included. A fragment of a
                              triangle sharing a vertex with t lies within 2 x reach[t] of
                              any fragment of t: ib's neighbour search stops there */
    /* B-rep files (STEP, IGES; model_occt.cpp): the file's length unit ("inch",
     * "millimetre") and millimetres per unit; the positions are in millimetres.
     * "" and 0 for formats that declare no unit. */
    char unit_name[24];
    double unit_to_mm;
    /* Their tessellation: linear deflection (mm) and angular deflection
     * (radians) used, and the milliseconds it took; 0 when not tessellated. */
    double tessellation_linear_mm, tessellation_angular_rad, tessellation_ms;
    /* Section caps (oit_model_derive): per vertex 0, or 1 + the section whose
     * cap the vertex's triangles are; NULL in a model with no caps. A cap
     * fragment lies on its own plane, so that section never removes it (the
     * rule in docs/sections.md); the GPU gets it in the component attribute's
     * high bits (OIT_COMPONENT_CAP_SHIFT). */
    uint8_t *vertex_section_cap;
} oit_model;

/* How B-rep files (STEP, IGES) are tessellated. Zeroed: normal detail. */
typedef enum oit_tessellation_level {
    OIT_TESSELLATION_NORMAL = 0,
    OIT_TESSELLATION_COARSE,
    OIT_TESSELLATION_FINE,
    OIT_TESSELLATION_LEVEL_COUNT
} oit_tessellation_level;
typedef struct oit_import_options {
    oit_tessellation_level tessellation; /* linear deflection a fraction of the model's
                                            bounding-box diagonal (docs/cli.md) */
    double linear_deflection_mm;         /* > 0: this linear deflection instead */
} oit_import_options;
/* "coarse", "normal", "fine" or a linear deflection in millimetres (a number
 * > 0 and finite) into options; anything else is OIT_E_INPUT naming it. */
oit_status oit_import_options_parse_tessellation(const char *text, oit_import_options *options,
                                                 oit_error *err);
/* The words of the levels, indexed by oit_tessellation_level. */
const char *oit_tessellation_level_word(oit_tessellation_level level);

#define OIT_MODEL_WARNING_LIMIT 16
/* Coplanar tolerance, in ulps of the model's largest file coordinate (the
 * import's own rounding: half an ulp per coordinate, under one off a plane),
 * so faces that are coplanar in the file and rounded to float on import still
 * tie, while faces 1e-3 apart in a model 1,600 units across stay apart
 * (docs/algorithms.md, "Ties and precision"). */
#define OIT_COPLANAR_ULPS 2

/* Import any format Assimp reads, and STEP and IGES through OpenCASCADE. Bad
 * files give OIT_E_INPUT and a message naming the file and the problem. */
oit_status oit_model_load(const char *path, oit_model *out, oit_error *err);
/* The same with import options (NULL: the defaults). */
oit_status oit_model_load_with(const char *path, const oit_import_options *options, oit_model *out,
                               oit_error *err);
/* Validate indices and coordinates, move the positions to be relative to
 * the model's centre (origin), compute missing normals, welded ids, bounds,
 * bounding sphere and coplanar planes. Called by oit_model_load; usable for
 * models built in memory (tests, generators), once per model: the positions
 * given are file coordinates. */
oit_status oit_model_finish(oit_model *model, bool compute_normals, oit_error *err);
void oit_model_free(oit_model *model);
/* A component's path: its nodes' names and its own, joined by '/'
 * ("gearbox/input_shaft/bearing_1"); its name alone when it has no node.
 * Returns the path's length (snprintf's rule: >= size means cut short). */
int oit_model_component_path(const oit_model *model, uint32_t component, char *out, size_t size);
/* The parts a name or path names (--hide, --component-alpha, the workbench's
 * filter): selected[c] (one per component) is set for each and cleared for
 * the others; returns how many. In this order: a component's exact name; else
 * an index ("3"); else an assembly path as oit_model_component_path writes
 * it: a node's path selects every part under it (a subassembly), a part's
 * path that part. 0: none. */
uint32_t oit_model_match_parts(const oit_model *model, const char *name_or_path, bool *selected);

/* Import in a contained child process (model_contained.c): the program runs
 * itself (/proc/self/exe) with OIT_IMPORT_WORKER_FLAG as an import worker
 * under CPU-time and memory limits, and receives the finished model through
 * a pipe. A crash, abort, limit or hang of the importer is OIT_E_INPUT with
 * one line ("FILE: the importer crashed (signal 11, Segmentation fault)",
 * "... timed out ..."). Every program that calls it must start with
 *     if (oit_import_worker_requested(argc, argv))
 *         return oit_import_worker_main(argc, argv);
 * OIT_IMPORT=in-process imports in the calling process instead (to measure
 * the overhead); OIT_IMPORT_WORKER_STDERR=1 lets the worker's stderr through. */
#define OIT_IMPORT_WORKER_FLAG "--oit-import-worker"
/* OIT_IMPORT_CPU_SECONDS may set the CPU limit up to this (a value that is not
 * a number of seconds in (0, max], "inf" or 1e30, fails the import: OIT_E_INPUT
 * naming the variable). The worker dies with its caller (PR_SET_PDEATHSIG) and
 * ends itself a few seconds past the wall limit. */
#define OIT_IMPORT_CPU_SECONDS_MAX 1e6
typedef struct oit_import_limits {
    double cpu_seconds;    /* CPU time of the worker */
    uint64_t memory_bytes; /* its address space (not under AddressSanitizer) */
    double wall_seconds;   /* no result by then: the worker is killed */
} oit_import_limits;
/* The limits for a file of this size: they grow with it, so that real large
 * models load and a parser spinning on a small file is stopped. */
void oit_import_limits_for_file(long long file_bytes, oit_import_limits *limits);
/* limits NULL: oit_import_limits_for_file of the file's size. */
oit_status oit_model_load_contained(const char *path, const oit_import_limits *limits, oit_model *out,
                                    oit_error *err);
/* The same with import options (NULL: the defaults); they reach the worker. */
oit_status oit_model_load_contained_with(const char *path, const oit_import_limits *limits,
                                         const oit_import_options *options, oit_model *out,
                                         oit_error *err);
bool oit_import_worker_requested(int argc, char **argv);
int oit_import_worker_main(int argc, char **argv);

/* ------------------------------------------------------------------- image */

typedef struct oit_image {
    int width, height;
    uint8_t *rgba; /* width * height * 4, top row first */
} oit_image;

oit_status oit_image_alloc(oit_image *image, int width, int height, oit_error *err);
void oit_image_free(oit_image *image);
oit_status oit_png_write(const char *path, const oit_image *image, oit_error *err);
oit_status oit_png_read(const char *path, oit_image *image, oit_error *err);

typedef struct oit_image_diff {
    int max_channel_diff;        /* largest |a - b| over RGB channels, 0..255 */
    double mean_diff;            /* mean |a - b| over RGB channels */
    double rmse;                 /* root mean square of a - b over RGB channels */
    double psnr_db;              /* INFINITY when identical */
    double share_over_tolerance; /* share of pixels with any channel diff > tolerance, 0..1 */
    long pixels_over_tolerance;
} oit_image_diff;

/* Images of different sizes are OIT_E_INPUT. Alpha is ignored. */
oit_status oit_image_compare(const oit_image *a, const oit_image *b, int tolerance,
                             oit_image_diff *out, oit_error *err);

/* How far an image is from a reference (image_error.c; docs/cli.md), RGB only:
 * rmse and max on the 0..255 scale, psnr in dB (INFINITY when identical),
 * ssim (Wang et al. 2004: 11x11 Gaussian window, sigma 1.5, K1 0.01, K2 0.03,
 * mean over windows and channels), share_over_2 in percent of the pixels,
 * flip the mean of the per-pixel LDR FLIP (oit_image_flip) at
 * OIT_FLIP_PPD_DEFAULT, 0 (identical) .. 1. */
typedef struct oit_image_error {
    double rmse;
    double psnr_db;
    double ssim;
    int max;
    double share_over_2;
    double flip;
} oit_image_error;

/* FLIP (Andersson et al., HPG 2020), the LDR version (flip.c): the perceived
 * difference of two sRGB images seen at ppd pixels per degree of visual
 * angle, per pixel in [0, 1] (0 where nothing differs). The default ppd is
 * the paper's: a 0.7 m wide 3840-pixel monitor seen from 0.7 m,
 * 3840 * (0.7 / 0.7) * pi / 180. map (w * h floats, may be NULL) receives
 * the per-pixel values, *mean their mean. Images of different sizes, or ppd
 * outside (0, 1000], are OIT_E_INPUT. The result is symmetric in the two
 * images. */
#define OIT_FLIP_PPD_DEFAULT 67.02064327658225
oit_status oit_image_flip(const oit_image *image, const oit_image *reference, double ppd, float *map,
                          double *mean, oit_error *err);

oit_status oit_image_error_compute(const oit_image *image, const oit_image *reference, oit_image_error *out,
                                   oit_error *err);
/* A per-pixel heat map of the largest channel difference (black where exact,
 * then blue, green, yellow, red on a logarithmic scale up to
 * OIT_ERROR_MAP_SATURATION), the image's size; with legend, a bar with
 * labelled ticks OIT_ERROR_MAP_LEGEND_HEIGHT rows high below it. */
#define OIT_ERROR_MAP_SATURATION 64
#define OIT_ERROR_MAP_LEGEND_HEIGHT 18
oit_status oit_image_error_map(const oit_image *image, const oit_image *reference, bool legend, oit_image *out,
                               oit_error *err);
/* The map's scale: where a difference lies on the bar (0..1), and its colour. */
double oit_error_map_position(int difference);
void oit_error_map_colour(int difference, uint8_t rgb[3]);
/* What --error-map draws: the largest channel difference (abs, above) or
 * the per-pixel FLIP at OIT_FLIP_PPD_DEFAULT (flip: 0..1 through the magma
 * colour map, black at 0, light yellow at 1; with legend, ticks at 0, .25,
 * .5, .75 and 1). */
typedef enum oit_error_metric { OIT_ERROR_METRIC_ABS = 0, OIT_ERROR_METRIC_FLIP = 1 } oit_error_metric;
oit_status oit_error_metric_parse(const char *word, oit_error_metric *out, oit_error *err);
oit_status oit_image_error_map_metric(const oit_image *image, const oit_image *reference, oit_error_metric metric,
                                      bool legend, oit_image *out, oit_error *err);
/* The flip map's colour of a value in [0, 1] (clamped): magma at round(255 value). */
void oit_flip_map_colour(double value, uint8_t rgb[3]);
/* The buffer views' heatmap (view "heatmap", ll and ib): the colour of a pixel
 * whose list holds length fragments when the frame's longest list
 * (oit_stats.max_list) is longest, as their compose shaders compute it:
 * heat(length / max(longest, 1)), blue -> green -> yellow -> red (the error
 * map's scale). Pixels without fragments show the background. */
void oit_heatmap_colour(int64_t length, int64_t longest, uint8_t rgb[3]);

/* ------------------------------------------------------- orientation aids */

/* issue 29 (overlay.c; docs/cli.md, --axes and --scale-bar): drawn on the
 * CPU onto a finished RGBA8 frame, so the command line and the workbench's
 * export give the same bytes whatever rendered it. */
typedef enum oit_corner {
    OIT_CORNER_BOTTOM_LEFT = 0,
    OIT_CORNER_BOTTOM_RIGHT = 1,
    OIT_CORNER_TOP_LEFT = 2,
    OIT_CORNER_TOP_RIGHT = 3
} oit_corner;
/* "bottom-left", "bottom-right", "top-left", "top-right" */
const char *oit_corner_name(oit_corner corner);
oit_status oit_corner_parse(const char *text, oit_corner *out, oit_error *err);

typedef struct oit_overlay_options {
    bool axes;              /* the triad: X red, Y green, Z blue, turned by the modelview */
    oit_corner axes_corner; /* default bottom-left */
    bool scale_bar;         /* bottom right (bottom left when the triad is there) */
} oit_overlay_options;
void oit_overlay_options_defaults(oit_overlay_options *options); /* both off, bottom-left */

/* What was drawn (pixels in image coordinates: x right, y down, the pixel
 * (x, y) covering [x, x + 1) x [y, y + 1)). */
typedef struct oit_overlay_info {
    bool axes;
    double axes_origin[2];        /* where the three arrows start */
    double axes_length;           /* an arrow's length when it lies in the image plane */
    double axes_directions[3][2]; /* X, Y, Z: each arrow's tip is origin + length * direction */
    bool scale_bar;               /* false with options->scale_bar: scale_problem says why */
    double scale_value;           /* 1, 2 or 5 x 10^k model units */
    char scale_units[8];          /* "mm" (STEP, IGES) or "" (the model's own units) */
    char scale_label[48];         /* "20 mm" */
    double scale_pixels;          /* scale_value x scale_pixels_per_unit: the bar's length */
    double scale_pixels_per_unit; /* along x, at the depth of the model's centre */
    double scale_start[2];        /* the bar's top-left corner */
    double scale_thickness;
    bool scale_exact;             /* orthographic: true everywhere; perspective: only at the centre's depth */
    char scale_problem[96];
} oit_overlay_info;

/* Draws the aids options asks for onto image, for the frame's matrices
 * (file coordinates, as oit_frame_settings). The triad shows the model's axes
 * as the modelview's rotation turns them, the ones pointing away under those
 * pointing at the eye. The scale bar is measured at the depth of the model's
 * centre (model->origin; the default camera orbits it), exact there (and
 * everywhere for an orthographic projection); its units are millimetres for
 * B-rep imports, the model's own otherwise. The sizes grow with the image's
 * shorter side. info (may be NULL) receives what was drawn. */
oit_status oit_overlay_draw(oit_image *image, const oit_overlay_options *options, const double modelview[16],
                            const double projection[16], const oit_model *model, oit_overlay_info *info,
                            oit_error *err);

/* ------------------------------------------------------------------- files */
/* atomic_file.c. WHAT names the file in the user's words (a flag such as
 * "--model"); it may be NULL or "". */

/* Inputs must be regular files: a FIFO, a device (/dev/zero), a directory or
 * a socket is OIT_E_INPUT "WHAT PATH: not a regular file (a FIFO)", as is a
 * file that does not exist or cannot be opened ("WHAT PATH: cannot open:
 * <strerror>"; without WHAT "PATH: ...").
 * Nothing blocks: the file is opened with O_NONBLOCK and checked with fstat. */
oit_status oit_check_regular_file(const char *path, const char *what, oit_error *err);
/* The same check, and the open file for reading ("rb", blocking again) in *out. */
oit_status oit_open_regular_file(const char *path, const char *what, FILE **out, oit_error *err);

/* Outputs must be regular files or new names, and are checked before any
 * work (oit_check_output_file) as well as when opened:
 * - a symbolic link stays a link: its target is written (also a dangling
 *   link's: the file it names is created), beside it;
 * - a directory, a FIFO (which would block the open), a device or a socket
 *   is OIT_E_INPUT "WHAT PATH: not a regular file or a new name (a FIFO)",
 *   except two files that have nothing to replace and are written in place:
 *   /dev/null (the output is dropped; to time a run without keeping it) and
 *   the process's own standard output or error (/dev/stdout, /dev/stderr,
 *   /proc/self/fd/1, or a path to the same file), written through that
 *   stream where it stands (a pipe, a terminal, the shell's file);
 * - a name longer than NAME_MAX, a path of PATH_MAX or more, a missing or
 *   read-only directory, a read-only file: OIT_E_INPUT.
 * oit_check_output_file says it at length: "WHAT PATH: File name too long: a
 * name has at most 255 bytes, this one 300", "WHAT PATH: the directory D does
 * not exist", "WHAT PATH: cannot write in D: <strerror>", "WHAT PATH: not a
 * regular file or a new name (a FIFO)" (without WHAT "PATH: ..."); a refusal
 * by oit_atomic_file_open itself keeps the form of a failed write below, with
 * the short reason: "WHAT: cannot write PATH: Permission denied".
 * A replaced file is written to a temporary (oit_temporary_create), flushed,
 * fsync'ed, closed and renamed over the target, so a failed write (a full
 * disk) leaves the previous file byte for byte and no temporary file. The
 * file keeps the previous file's permissions, else 0666 less the umask.
 * Failing to create is OIT_E_INPUT, failing to write OIT_E_RUNTIME; both
 * say "WHAT: cannot write PATH: <strerror of the first failed write>"
 * (without WHAT "PATH: cannot write: ..."; with OIT_ATOMIC_APPEND "cannot
 * append to PATH").
 * OIT_ATOMIC_APPEND appends in place, safely across processes: the file
 * (created if new) is locked with flock(LOCK_EX) (other appenders wait),
 * the stream's bytes are written with one write() at finish, fsync'ed, and
 * on any failure (or a signal, see oit_temporaries_remove_all) the file is
 * cut back to its size before, so it is the old file or the old file plus
 * the whole new lines; a new file that could not be written is removed. */
typedef struct oit_atomic_file oit_atomic_file;
#define OIT_ATOMIC_APPEND 1 /* append in place under an exclusive lock */
oit_status oit_check_output_file(const char *path, const char *what, oit_error *err);
/* A folder an output replaces whole (bench --bundle, render --turntable): a
 * new name (*replaces false), an empty folder, or a previous one of its KIND,
 * which holds MARKER and nothing but regular files; *mode is then its
 * permissions. Else OIT_E_INPUT "WHAT GIVEN: the directory is not empty and
 * not a KIND (no MARKER)" or "WHAT GIVEN: holds 'NAME', which is not a regular
 * file: not a KIND". PATH is the folder's resolved path (oit_output_target). */
oit_status oit_output_folder_check(const char *path, const char *what, const char *given, const char *kind,
                                   const char *marker, bool *replaces, unsigned *mode, oit_error *err);
/* The check for an output that is a folder (oit bench --bundle): a new name
 * or a directory (which is replaced: it must be readable and writable); a
 * regular file is "WHAT PATH: not a directory", anything else refused as
 * above. The target, its links followed, goes to *target (free it). */
oit_status oit_output_target(const char *path, const char *what, char **target, oit_error *err);
/* 1 or 2 when path is the very file of the standard output or error, else 0. */
int oit_output_standard_stream(const char *path);
oit_status oit_atomic_file_open(const char *path, const char *what, int flags, oit_atomic_file **out,
                                oit_error *err);
/* Where to write; every write's error is kept (the first errno is reported). */
FILE *oit_atomic_file_stream(oit_atomic_file *file);
/* OIT_ATOMIC_APPEND: the file's size when it was locked (0 for a new file). */
long long oit_atomic_file_kept_bytes(const oit_atomic_file *file);
/* True once a write failed. */
bool oit_atomic_file_failed(const oit_atomic_file *file);
/* Flush, fsync and close without renaming yet (to commit several files
 * together: finish them all, then commit). On failure, abort the file. */
oit_status oit_atomic_file_finish(oit_atomic_file *file, oit_error *err);
/* Finish (if not done) and rename over the target; frees file, which is
 * aborted on failure. */
oit_status oit_atomic_file_commit(oit_atomic_file *file, oit_error *err);
/* Give up: remove the temporary file (PATH stays as it was) and free file
 * (NULL is allowed). Returns status. With err and reason, err gets "cannot
 * write" with the first failed write's strerror, else reason; with reason
 * NULL, err is left as it is. */
oit_status oit_atomic_file_abort(oit_atomic_file *file, oit_status status, const char *reason,
                                 oit_error *err);

/* Temporaries (temporaries.c): TARGET.tmp.XXXXXX beside TARGET (for a name
 * longer than NAME_MAX - 11 bytes, .oit.tmp.XXXXXX), a file (0666) or a
 * folder (0777, less the umask), created and locked with flock(LOCK_EX) for
 * as long as it is open. Creating one first removes the orphans of TARGET's
 * name: temporaries nobody holds a lock on, left by a run that was killed
 * (SIGKILL); a live run's are kept. Each live temporary is listed in a
 * fixed table until released, for oit_temporaries_remove_all. */
typedef struct oit_temporary {
    char *path; /* NULL when released */
    int fd;     /* the file, open for writing, or the folder; holds the lock */
    int watch;  /* its entry in the table, -1 if the table was full */
} oit_temporary;
oit_status oit_temporary_create(const char *target, bool directory, oit_temporary *out, oit_error *err);
/* Closes it (and its lock) and takes it off the table; with remove, removes
 * it first (a folder with its regular files). After a rename, remove false. */
void oit_temporary_release(oit_temporary *temporary, bool remove);
/* The length the path of a temporary of target has. */
size_t oit_temporary_path_length(const char *target);
/* Removes every live temporary (folders with their regular files) and cuts
 * every unfinished OIT_ATOMIC_APPEND back to its size before. Async-signal-
 * safe: for a program's SIGINT, SIGTERM and SIGHUP handlers, before the
 * signal is raised again. */
void oit_temporaries_remove_all(void);
/* The table, for those who manage a temporary themselves: an append to cut
 * back to size on a signal; -1 if the table is full. Unwatch takes it off. */
int oit_temporaries_watch_append(int fd, long long size);
void oit_temporaries_unwatch(int watch);

/* ---------------------------------------------------------- frame settings */

typedef enum oit_shading_mode {
    OIT_SHADE_FLAT = 0,     /* unlit material colour; used for comparisons */
    OIT_SHADE_HEADLIGHT = 1 /* colour * (0.25 + 0.75 |n . v|), v towards the eye point */
} oit_shading_mode;

/* Buffer views (what the compose pass shows instead of the colour image). */
typedef enum oit_view {
    OIT_VIEW_COLOUR = 0,    /* the composited image */
    OIT_VIEW_HEATMAP = 1,   /* list length / longest list, blue -> green -> yellow -> red */
    OIT_VIEW_PEEL_LIMIT = 2, /* composite only the first view_parameter fragments */
    OIT_VIEW_LAYER = 3,     /* only fragment number view_parameter (0 = nearest) */
    OIT_VIEW_NEIGHBOURS = 4, /* ib: colour each fragment by its neighbour count */
    OIT_VIEW_CURVATURE = 5, /* ib: grey = curvature * curvature_effect of fragment view_parameter */
    OIT_VIEW_DISTANCE = 6,  /* ib: grey = normalised distance of fragment view_parameter */
    OIT_VIEW_FIELDS = 7     /* ib: rgb = (alpha, beta, gamma) fields of fragment view_parameter */
} oit_view;

/* The largest view_parameter (peel limit, layer) a view takes. */
#define OIT_VIEW_PARAMETER_MAX 1000000
/* Whether a view's word takes ":N", its view_parameter: 1 it must (peel-limit,
 * layer), 0 it must not (colour, heatmap, neighbours), -1 it may (the ib
 * views: the fragment shown, default 0, the nearest). */
int oit_view_parameter_rule(oit_view view);


/* Opacity modulation of the Illustration Buffer (ib; docs/illustration-buffer.md).
 * Every field's zero value means its default, so a zeroed struct is "no modulation". */
typedef enum oit_modulation_mode {
    OIT_MODULATE_NONE = 0,      /* the material opacity, as ll */
    OIT_MODULATE_CURVATURE = 1, /* alpha = saturate(curvature * curvature_effect) */
    OIT_MODULATE_DISTANCE = 2,  /* alpha = saturate(distance along the ray / focus) */
    OIT_MODULATE_DIST_CURV = 3, /* the larger of the two */
    OIT_MODULATE_FIELDS = 4,    /* transparency fields alpha, beta, gamma */
    OIT_MODULATE_EDGES = 5      /* opaque where a fragment has fewer than four neighbours */
} oit_modulation_mode;


typedef enum oit_neighbour_search {
    OIT_NEIGHBOURS_DEFAULT = 0, /* the best by the measurements (welded) */
    OIT_NEIGHBOURS_INDEX = 1,   /* shares a vertex index (the thesis) */
    OIT_NEIGHBOURS_WELDED = 2,  /* shares a position-welded vertex id */
    OIT_NEIGHBOURS_EPSILON = 3  /* Carnecky's depth/normal heuristic, mutual check */
} oit_neighbour_search;

typedef enum oit_distance_mode {
    OIT_DISTANCE_ADJACENT = 0, /* to the next fragment on the ray */
    OIT_DISTANCE_SKIP = 1,     /* to the fragment distance_skip places on (or the last) */
    OIT_DISTANCE_FAR_END = 2   /* to the last fragment on the ray */
} oit_distance_mode;

#define OIT_VIEW_COUNT 8       /* oit_view's values: 0 .. OIT_VIEW_COUNT - 1 */
#define OIT_MODULATION_COUNT 6 /* oit_modulation_mode's */
#define OIT_DISTANCE_COUNT 3   /* oit_distance_mode's */


#define OIT_FIELD_ALPHA 1
#define OIT_FIELD_BETA 2
#define OIT_FIELD_GAMMA 4

typedef struct oit_modulation {
    oit_view view;
    int view_parameter;

    oit_modulation_mode mode;
    oit_neighbour_search neighbours;
    int curvature_neighbours;  /* 4 or 8; 0: 4 */
    float curvature_effect;    /* delta_c; 0: 8 */
    float focus_region;        /* eye-space distance that is opaque; 0: the frame's largest */
    oit_distance_mode distance;
    int distance_skip;         /* k for OIT_DISTANCE_SKIP; 0: 2 */
    int fields;                /* OIT_FIELD_* mask; 0: all three */
    int diffusion_iterations;  /* 0: 15; negative: none */
    int blur_iterations;       /* 0: 1; negative: none */
    float lambda_alpha, lambda_beta, lambda_gamma; /* 0: auto (1, 0.95 / iterations, 0.45) */
    bool has_halo_colour;
    float halo_colour[3];      /* default white */
    bool last_layer_opaque;
    float epsilon_max;         /* epsilon search: largest accepted epsilon; 0: 0.05 */
} oit_modulation;

/* The modulation with every field left at zero ("the default") given the
 * value it stands for, the one place these defaults live: neighbours welded,
 * curvature over 4 neighbours with effect 8, distance skip 2, all three
 * fields, 15 diffusion and 1 blur iterations (-1 where the input asks for
 * none), lambdas 1, 0.95 / iterations (0.95 without diffusion) and 0.45, a
 * white halo, epsilon 0.05, view parameter at least 0. focus_region stays 0
 * for "the frame's largest" (it depends on the frame). Resolving twice
 * changes nothing. */
oit_modulation oit_modulation_defaults(const oit_modulation *modulation);

/* Local opacity modulation, expressible in every algorithm (issue "Opacity
 * modulation in every algorithm"; extended there). */
typedef enum oit_focus_shape {
    OIT_FOCUS_NONE = 0,
    OIT_FOCUS_POINT = 1, /* alpha *= saturate(|p - f| / focus_region) */
    OIT_FOCUS_PLANE = 2,
    OIT_FOCUS_BOX = 3
} oit_focus_shape;

/* The most section planes at once, for programs that must not include the
 * shaders' header; equal to oit_shared.h's OIT_SECTIONS_MAX (sections.c asserts it). */
#define OIT_SECTION_PLANES_MAX 6

typedef struct oit_local_modulation {
    /* per-component opacity multipliers in [0, 1], component_count of them, or
     * NULL for all 1; 0 hides the part: its fragments are never stored.
     * Parts at or past component_count keep 1. Any number of parts: the GPU
     * algorithms read them from a buffer (oit_scene.part_alpha_buffer). */
    const float *component_alpha;
    uint32_t component_count;
    oit_focus_shape focus_shape;
    double focus[6]; /* point xyz | plane abcd | box min xyz, max xyz; model (file)
                        coordinates */
    float contrast;  /* 0 or 1: unchanged */
    /* The fall-off length of the focus shapes (model units) when
     * modulation.focus_region is 0; 0 here too: 1 (the CLI sets a quarter of
     * the model's bounding radius). docs/modulation.md */
    float focus_default_region;
    /* Selection highlight (docs/modulation.md): part i's material colour
     * becomes mix(colour, highlight_colour, highlight_strength *
     * component_highlight[i]) before shading, in every algorithm and the
     * reference alike, so images with a highlight stay exact. component_highlight
     * holds component_highlight_count weights in [0, 1] (1: highlighted), or
     * NULL: no highlight. Zeroed colour and strength mean the defaults
     * (oit_local_highlight resolves them: OIT_HIGHLIGHT_* in oit_shared.h). */
    const float *component_highlight;
    uint32_t component_highlight_count;
    bool has_highlight_colour;
    float highlight_colour[3];
    float highlight_strength; /* in (0, 1]; 0: the default */
    /* Section planes (--section; docs/sections.md): section i keeps the points
     * p with dot(sections[i].xyz, p) <= sections[i][3] (model (file)
     * coordinates, of the model as drawn: exploded where it is) and removes the
     * rest, in every algorithm, the reference and the pick alike. The normal
     * need not be unit length; a zero normal is refused. */
    uint32_t section_count; /* 0..OIT_SECTION_PLANES_MAX */
    double sections[OIT_SECTION_PLANES_MAX][4];
    /* Which parts the sections cut (--section-parts): section_parts_count
     * flags, nonzero where part i is cut; NULL: every part. Parts at or past
     * the count are not cut. */
    const uint8_t *section_parts;
    uint32_t section_parts_count;
    /* Caps (--caps): false (the default) draws a cap where a section cuts a
     * closed part (oit_model_derive makes them); true: none. */
    bool no_caps;
} oit_local_modulation;

/* Part component's highlight: its weight (highlight_strength times the
 * part's component_highlight, 0 when not highlighted) and the highlight
 * colour in rgb, defaults resolved; the one place they are. */
float oit_local_highlight(const oit_local_modulation *local, uint32_t component, float rgb[3]);

/* Whether section i removes model (file coordinates) point p of part
 * component, by the one rule (sections.c): the part is cut (section_parts)
 * and dot(n, p) > d. The reference and the pick have their own code for it in
 * the frame's relative coordinates; this is for the shells (measurement, tests). */
bool oit_section_removes(const oit_local_modulation *local, uint32_t component, const double p[3]);

/* Progress of one frame, for shells that render off their GUI thread (the
 * workbench). report is called after every stage (every peel of dp and ddp,
 * every fill, sort, compose...; the reference: after counting and after
 * rasterizing) with the
 * stage's name and the number of stages done so far; returning false
 * abandons the frame at that point, and render() returns OIT_CANCELLED.
 * Called on the rendering thread; a zeroed struct means no callback. */
typedef struct oit_progress {
    bool (*report)(void *user, const char *stage, int stages_done);
    void *user;
} oit_progress;

typedef struct oit_frame_settings {
    int width, height;
    double modelview[16];  /* column-major; model (file) coordinates to eye */
    double projection[16]; /* column-major */
    float alpha;          /* uniform opacity multiplier in [0, 1] */
    oit_shading_mode shading;
    float background[3];
    oit_modulation modulation;
    oit_local_modulation local;
    oit_progress progress;
    /* Anti-aliasing (--samples; docs/algorithms.md, "Anti-aliasing"): 0 or 1
     * renders one sample at each pixel centre, as always; 4, 8 or 16 render
     * the frame that many times, each with the projection moved by one of
     * the standard sample positions (oit_sample_positions), and average the
     * RGBA8 images. oit_frame_check refuses any other value. Done once for
     * every algorithm, the reference included, by oit_algorithm_render, but
     * those that read it themselves (OIT_OPTION_SAMPLES: stochastic's
     * samples per pixel, 0 its default), which render once. */
    int samples;
} oit_frame_settings;

/* The sample counts --samples takes besides 1, and the largest. */
#define OIT_SAMPLES_MAX 16
/* The sample positions of a frame of `samples` samples (0 or 1: the pixel
 * centre; 4, 8, 16: the standard multisample positions of Direct3D 11
 * (D3D11_STANDARD_MULTISAMPLE_PATTERN) and Vulkan (standard sample
 * locations), which are the same), as offsets from the pixel centre in
 * 1/16 pixel, x to the right and y down the image, two per sample; their
 * count, or 0 for a count --samples does not take. */
int oit_sample_positions(int samples, const signed char **offsets);
/* The positions' name for reports ("centre", "d3d11-standard-4", ...);
 * "unknown" for a count --samples does not take. */
const char *oit_sample_positions_name(int samples);

/* Matrix helpers (matrix.c), column-major double[16]. */
void oit_mat4_identity(double m[16]);
void oit_mat4_multiply(const double a[16], const double b[16], double out[16]);
/* normal matrix: inverse transpose of the upper 3x3 of m, column-major 3x3 */
bool oit_mat4_normal_matrix(const double m[16], double out[9]);
/* How far m is from singular, independent of units and scale: |det| over the
 * product of the row lengths after equilibrating rows and columns, in [0, 1]
 * (1: orthogonal rows; 0: singular). */
double oit_mat4_regularity(const double m[16]);
/* Below this a projection counts as singular: float rounding of an exactly
 * singular matrix leaves about 1e-7. */
#define OIT_MATRIX_REGULARITY_MIN 1e-5
/* Reject NaN/inf, a singular modelview (its 3x3 part) and singular
 * projections (oit_mat4_regularity) with OIT_E_INPUT. */
oit_status oit_matrices_validate(const double modelview[16], const double projection[16],
                                 oit_error *err);
/* The inverse of a column-major 4x4 in double; false (and zeros) if singular. */
bool oit_mat4_inverse_double(const double m[16], double out[16]);
/* The modelview that applies to model->positions (relative to model->origin):
 * modelview x translate(origin), in double. */
void oit_model_modelview(const oit_model *model, const double modelview[16], double out[16]);
/* A camera that frames the model's bounding sphere: perspective with a 40
 * degree vertical field of view, near/far around the sphere. With azimuth and
 * elevation 0 it looks down -z from +z; azimuth turns the model about the
 * vertical axis (degrees, positive shows its right side), elevation tilts the
 * camera up (positive looks down on it). The modelview applies to file
 * coordinates, like every frame's. */
#define OIT_MODEL_RADIUS_MIN 1e-12f
#define OIT_MODEL_RADIUS_MAX 1e15f
/* Fails (OIT_E_INPUT) for a bounding radius outside [OIT_MODEL_RADIUS_MIN,
 * OIT_MODEL_RADIUS_MAX]; a radius of 0 (a single point) is framed as 1. */
oit_status oit_default_camera(const oit_model *model, int width, int height, double azimuth_degrees,
                              double elevation_degrees, double modelview[16], double projection[16],
                              oit_error *err);
/* The matrix that takes a plane (a, b, c, d) of the frame's modelview's
 * space to eye space: transpose(inverse(modelview)), computed in double,
 * column-major; the identity if the modelview is singular (canonical depth,
 * common/canonical_depth.glsl). */
void oit_plane_to_eye_double(const oit_frame_settings *frame, double out[16]);

/* Local modulation set-up for the GPU (local_modulation.c; the per-fragment
 * formulas are in shaders/common/local_modulation.glsl, the reference has its
 * own). The focus shapes' fall-off length, in model units. */
float oit_local_focus_region(const oit_frame_settings *frame);

/* ----------------------------------------------- exploded view, section caps */

/* The exploded view's offsets (explode.c; docs/sections.md, "Exploded view"),
 * 3 floats per component (model units) into offsets: factor 0 gives all
 * zeros. Without an assembly tree, part p moves by factor * (centre(p) -
 * centre(model)); with one, every node and part moves away from its parent's
 * centre by factor * (centre(child) - centre(parent)), and a part's offset is
 * the sum along its path from the top. Centres are bounding-box centres of
 * the geometry under a node. OIT_E_INPUT for a factor outside
 * [0, OIT_EXPLODE_MAX] or not finite. */
#define OIT_EXPLODE_MAX 10.0
oit_status oit_explode_offsets(const oit_model *model, double factor, float *offsets, oit_error *err);

/* The model as drawn (model_derive.c): the parts moved by part_offsets (3
 * floats per part, part_offset_count parts; NULL: none), then, unless
 * local->no_caps, a cap appended to each closed part every section of local
 * cuts (section_caps.c): triangles on the section's plane, filling the part's
 * cross-section, with the part's component (contiguous with its own
 * triangles), its colour and opacity, the section's plane as their coplanar
 * cluster (so caps of nested parts tie bit for bit and order by triangle
 * index) and vertex_section_cap set. The origin stays; bounds, radius, planes,
 * welded ids and reach are the moved model's. out is a new model
 * (oit_model_free); the input is not changed. open_cut, when not NULL,
 * receives per part 1 where a section cuts an open part (no cap: the shells
 * name them). */
oit_status oit_model_derive(const oit_model *model, const float *part_offsets, uint32_t part_offset_count,
                            const oit_local_modulation *local, oit_model *out, uint8_t *open_cut,
                            oit_error *err);
/* Whether oit_model_derive would change anything (an offset not zero, or a
 * cap to make): shells draw the model itself otherwise. */
bool oit_model_derive_needed(const oit_model *model, const float *part_offsets,
                             uint32_t part_offset_count, const oit_local_modulation *local);

/* -------------------------------------------------------------- statistics */

#define OIT_STAGE_NAME_SIZE 32
#define OIT_MAX_STAGES 264 /* room for OIT_MAX_PEEL_LAYERS peels plus fixed stages; further
                              stages are summed as "(remaining stages)" */
#define OIT_PEEL_LAYER_CAP_MAX 1000000 /* the largest explicit --max-layers */
#define OIT_HISTOGRAM_BINS 65 /* list lengths 0..63, and 64 or more */

typedef struct oit_stage_time {
    char name[OIT_STAGE_NAME_SIZE];
    double gpu_ms; /* GL_TIME_ELAPSED on a GPU; on llvmpipe (whose timer queries do not
                      measure the work) glFinish-bracketed wall time; for the reference,
                      CPU time of the stage */
} oit_stage_time;

typedef struct oit_stats {
    double cpu_ms; /* wall time of the whole frame, including waiting for the GPU */
    int stage_count;
    oit_stage_time stages[OIT_MAX_STAGES];
    /* Memory figures come from the allocations, never from a formula: GPU
     * algorithms record every buffer and texture they allocate in one tracker
     * (gl_util.h, oit_gl_memory), the reference sums its arrays' sizes.
     * tests/memory_figures.sh checks memory_bytes against the GL objects
     * counted without the tracker (oit render --json, "gl_allocated_bytes"). */
    uint64_t memory_bytes;    /* what the algorithm holds after the frame: GPU buffers and
                                 textures (CPU arrays for the reference), the RGBA8 output,
                                 fragment pools at their capacity (headroom included),
                                 counters, parameters, per-triangle tables; not the scene's
                                 buffers (oit_scene.gpu_bytes) */
    int64_t fragments;        /* fragments stored; -1 where not applicable */
    int64_t max_list;         /* longest per-pixel list; -1 where not applicable */
    int64_t layers;           /* layers peeled; -1 where not applicable */
    int64_t overflow_retries; /* frames rendered again with a larger pool; -1 n/a */
    int64_t bands;            /* ll, ib: bands of rows the frame was rendered in (1: whole;
                                 more when its fragments exceed what one buffer binding
                                 addresses, ib: or the memory budget holds; docs/algorithms.md,
                                 Limits); -1 n/a */
    bool truncated;           /* fragments were left out (dp, ddp: the --max-layers cap was
                                 reached with fragments left); false: the frame is whole */

    /* list statistics (ll, ib, reference); negative where not applicable */
    double mean_list; /* mean list length over non-empty pixels */
    double psi;       /* share of non-empty pixels whose list is longer than 2/3 of the longest */
    int histogram_bins; /* 0 when no histogram: bin i counts pixels with list length i, the last bin the rest */
    uint64_t list_histogram[OIT_HISTOGRAM_BINS];
    double bytes_per_fragment; /* ll, ib, reference: the bytes of the buffers sized by the fragment
                                  pool (every per-fragment buffer, ping-pong copies included) /
                                  the pool's capacity in fragments; capacity x it is the pool's
                                  share of memory_bytes. -1 where there is no pool */
    double bytes_per_pixel;    /* the bytes of the allocations sized by the image (output
                                  included) / width x height; the reference's offset array has
                                  one entry more than pixels, hence a fraction. -1: n/a */
    double neighbours_four_share;           /* ib: fragments with all four neighbours */
    double neighbours_symmetric_share;      /* ib: links whose partner links back */
    double neighbours_same_component_share; /* ib: links that stay on the same component */
} oit_stats;

void oit_stats_reset(oit_stats *stats); /* zeroes, and marks the optional figures n/a (-1) */
/* Adds ms to the stage named `name`, appending it when there is none (a
 * frame's last slot sums the stages past OIT_MAX_STAGES, as the timer does). */
void oit_stats_add_stage(oit_stats *stats, const char *name, double ms);

/* ------------------------------------------------------ the algorithm table */

typedef enum oit_ll_sort {
    OIT_LL_SORT_INSERTION = 0, /* in-place insertion sort on the lists, second next buffer */
    OIT_LL_SORT_LOCAL_ARRAY = 1, /* copy into a fixed local array and sort there */
    OIT_LL_SORT_BMA = 2,  /* Knowles et al.: arrays sized by list length, register blocks,
                             a merge sort in the lists past the largest array */
    OIT_LL_SORT_MERGE = 3 /* bma without the arrays: register blocks merged in the lists (the default) */
} oit_ll_sort;

/* stochastic: how a fragment of opacity a picks the samples it covers */
typedef enum oit_stochastic_masks {
    OIT_STOCHASTIC_DEFAULT = 0,     /* stratified */
    OIT_STOCHASTIC_STRATIFIED = 1,  /* exactly round(a S) distinct samples (Laine & Karras 2011 style) */
    OIT_STOCHASTIC_INDEPENDENT = 2  /* each sample with probability a */
} oit_stochastic_masks;
/* stochastic: the samples per pixel when the frame's samples is 0 (not given) */
#define OIT_STOCHASTIC_SAMPLES_DEFAULT 8

/* wavelet: the rank R of its Haar basis (oit_algorithm_config.wavelet_rank,
 * --wavelet-rank): 2^(R+1) coefficients per pixel; 0 in the config means the
 * default. The most equals shaders/common/oit_shared.h's OIT_WAVELET_RANK_MAX
 * (alg_wavelet.c asserts it). */
#define OIT_WAVELET_RANK_DEFAULT 3
#define OIT_WAVELET_RANK_MAX 3

/* mboit: which moments of the optical depth it keeps (Muenstermann et al. 2018) */
typedef enum oit_moments {
    OIT_MOMENTS_DEFAULT = 0, /* power 4 */
    OIT_MOMENTS_POWER4 = 1,  /* b0 and 4 power moments of warped depth: 5 floats per pixel */
    OIT_MOMENTS_POWER6 = 2,  /* b0 and 6 power moments: 7 floats per pixel */
    OIT_MOMENTS_TRIG3 = 3    /* b0 and 3 trigonometric moments (complex): 7 floats per pixel */
} oit_moments;


/* kbuffer, hybrid, mlab: the layers kept per pixel (oit_algorithm_config.layers, --layers)
 * by default and at most, for programs that must not include the shaders' header; equal
 * to shaders/common/oit_shared.h's OIT_APPROX_LAYERS_DEFAULT and _MAX (closest_layers.c
 * asserts it). */
#define OIT_LAYERS_DEFAULT 8
#define OIT_LAYERS_MAX 64

typedef struct oit_algorithm_config {
    const char *shader_dir;     /* root of the shader tree (contains common/) */
    uint64_t max_memory_bytes;  /* budget for buffers that grow (fragment pools; ib draws a
                                   frame past it in bands of rows) */
    oit_ll_sort ll_sort;
    int max_layers;             /* dp, ddp: 0 (default) peels until no fragment is left;
                                   N in 1..OIT_PEEL_LAYER_CAP_MAX is an explicit cap, and
                                   a frame it cuts short is marked truncated */
    uint64_t initial_fragment_capacity; /* 0: automatic; small values force pool growth (tests) */
    bool debug;                 /* check GL errors after every stage */
    bool neighbour_quality;     /* ib: measure the neighbour links every frame (a pass of its
                                   own; the neighbours_* stats are n/a without it) */
    /* tests only (0 normally): ll's and ib's fill start their fragment counter
     * here, as if that many fragments had come before the frame's, so the
     * 32-bit counter's limits (OIT_MAX_FRAME_FRAGMENTS) are reached without
     * 2^32 fragments; such a frame fails or needs that much more pool */
    uint32_t fragment_counter_start;
    /* tests only (0 normally): ll and ib address at most this many fragments in
     * one buffer, as if the GL's limit (GL_MAX_SHADER_STORAGE_BLOCK_SIZE) were
     * that low, so frames are drawn in bands of rows without 8M fragments */
    uint64_t buffer_fragment_limit;
    /* kbuffer, hybrid, mlab: the layers kept per pixel (k), 1..OIT_LAYERS_MAX;
       0: OIT_LAYERS_DEFAULT. Others ignore it. */
    int layers;
    oit_moments moments; /* mboit; others ignore it */
    /* stochastic: the seed of its coverage masks and how they are drawn */
    uint32_t seed;
    oit_stochastic_masks stochastic_masks;
    int wavelet_rank; /* wavelet: 1..OIT_WAVELET_RANK_MAX, 0: OIT_WAVELET_RANK_DEFAULT; others ignore it */
    /* tests only (false normally): mlab's clear leaves every pixel's lock taken,
     * as if a fragment outside the frame held it, so every fragment spins to its
     * cap (OIT_MLAB_LOCK_TRIES) and gives up, and the frame must fail naming them */
    bool locks_held;
} oit_algorithm_config;

void oit_algorithm_config_defaults(oit_algorithm_config *config);

/* A model ready to draw: the CPU model and, when a GL context exists, its buffers. */
typedef struct oit_scene {
    const oit_model *model;
    bool has_gpu;
    unsigned vertex_array;      /* GLuint */
    unsigned vertex_buffers[4]; /* position, normal, component, welded id */
    unsigned index_buffer;
    unsigned component_buffer;  /* SSBO at OIT_SSBO_COMPONENTS */
    /* per-part opacity: part_count floats (the model's components, at least 1),
     * rewritten every frame from oit_local_modulation.component_alpha by
     * oit_gl_bind_part_alpha, read through the buffer texture at
     * OIT_TEXUNIT_LOCAL_PART_ALPHA (common/local_modulation.glsl) */
    unsigned part_alpha_buffer, part_alpha_texture;
    /* selection highlight: part_count vec4s (highlight rgb, weight; weight 0
     * for a part not highlighted), rewritten every frame from
     * oit_local_modulation.component_highlight by oit_gl_bind_part_alpha, read
     * through the buffer texture at OIT_TEXUNIT_LOCAL_PART_TINT */
    unsigned part_tint_buffer, part_tint_texture;
    /* which parts the section planes cut: part_count bytes (1: cut),
     * rewritten by oit_gl_bind_part_alpha when a frame names parts
     * (oit_local_modulation.section_parts), read through the buffer texture at
     * OIT_TEXUNIT_LOCAL_PART_SECTION */
    unsigned part_section_buffer, part_section_texture;
    uint32_t part_count;
    unsigned triangle_reach_buffer; /* oit_model.triangle_reach, one float per triangle */
    /* oit_model.planes and .triangle_plane, and buffer textures over them
     * (OIT_TEXUNIT_PLANES, OIT_TEXUNIT_TRIANGLE_PLANES: common/canonical_depth.glsl) */
    unsigned plane_buffer, triangle_plane_buffer;
    unsigned plane_texture, triangle_plane_texture;
    uint32_t index_count;
    uint64_t gpu_bytes;
} oit_scene;

/* Upload the model (needs a current GL context). */
oit_status oit_scene_upload(oit_scene *scene, const oit_model *model, oit_error *err);
/* A scene without GPU buffers, for the reference renderer. */
void oit_scene_cpu(oit_scene *scene, const oit_model *model);
void oit_scene_release(oit_scene *scene);

typedef struct oit_algorithm oit_algorithm; /* each algorithm's own state */

/* ------------------------------------------------------------ capabilities */
/* What an algorithm renders, as data on its operations table (issue "One
 * shape for every algorithm"): for every view, modulation and distance mode,
 * NULL where it renders it, else why it cannot, one clause in which "%s"
 * stands for the value's name. oit_frame_check refuses the rest, once, for
 * every algorithm, before any work; render() keeps only the limits that
 * depend on the frame's contents (fragments, memory). The command line's
 * help, `oit algorithms --json`, the workbench's greyed-out entries and the
 * generated capability page all read this table. */
typedef struct oit_capabilities {
    const char *views[OIT_VIEW_COUNT];
    const char *modulations[OIT_MODULATION_COUNT];
    const char *distances[OIT_DISTANCE_COUNT]; /* with a modulation that measures distance */
    unsigned options;                          /* OIT_OPTION_*: the render options it reads */
} oit_capabilities;

/* The render options an algorithm reads beyond every algorithm's own (size,
 * camera, alpha, shading, background, the local modulations), by their
 * command-line flags (oit_option_flags). */
enum {
    OIT_OPTION_SORT = 1u << 0,           /* --sort: oit_algorithm_config.ll_sort */
    OIT_OPTION_MAX_LAYERS = 1u << 1,     /* --max-layers */
    OIT_OPTION_LAYERS = 1u << 2,         /* --layers */
    OIT_OPTION_MOMENTS = 1u << 3,        /* --moments */
    OIT_OPTION_FRAGMENT_POOL = 1u << 4,  /* --fragment-pool, --fragment-counter-start,
                                            --buffer-fragment-limit */
    OIT_OPTION_MAX_MEMORY = 1u << 5,     /* --max-memory */
    OIT_OPTION_LOCKS_HELD = 1u << 6,     /* --locks-held (tests) */
    OIT_OPTION_WAVELET_RANK = 1u << 7,   /* --wavelet-rank */
    OIT_OPTION_SEED = 1u << 8,           /* --seed, --stochastic-masks */
    /* --samples read by the algorithm itself as its samples per pixel, in one
     * render (0: its own default), instead of the central supersampling */
    OIT_OPTION_SAMPLES = 1u << 9,
    OIT_OPTION_COUNT = 10
};
/* The flags of one OIT_OPTION_* bit, space-separated ("--sort"); NULL for a bit outside them. */
const char *oit_option_flags(unsigned option);

typedef struct oit_algorithm_ops {
    const char *name;    /* as on the command line */
    const char *summary; /* one line for `oit algorithms` */
    bool uses_gl;        /* false only for the CPU reference */
    bool exact;          /* true if it composites every fragment in depth order */
    const oit_capabilities *capabilities; /* what it renders, and why not the rest */
    oit_status (*create)(const oit_algorithm_config *config, oit_algorithm **out, oit_error *err);
    oit_status (*resize)(oit_algorithm *alg, int width, int height, oit_error *err);
    /* Render one frame into the algorithm's RGBA8 output; fills the stage
     * times and per-frame figures returned by stats(). */
    oit_status (*render)(oit_algorithm *alg, const oit_scene *scene,
                         const oit_frame_settings *frame, oit_error *err);
    oit_status (*read_image)(oit_algorithm *alg, oit_image *out, oit_error *err);
    void (*stats)(const oit_algorithm *alg, oit_stats *out);
    /* Anti-aliasing, for oit_algorithm_render only (every algorithm has the
     * same one, its kind's: oit_gpu_accumulate, the reference's own): after
     * sample `sample` (0-based) of `samples` (2..OIT_SAMPLES_MAX) rendered,
     * adds the output to the accumulation target (sample 0 stores it), adds
     * the step's time to *frame as the stage "samples_accumulate" and the
     * memory held to it; after the last, writes the rounded average (sum +
     * samples / 2) / samples per channel into the output, which read_image
     * then returns, and takes *frame as its statistics. samples 1: releases
     * the target (a frame of one sample holds none). */
    oit_status (*accumulate)(oit_algorithm *alg, int sample, int samples, oit_stats *frame, oit_error *err);
    void (*destroy)(oit_algorithm *alg);
} oit_algorithm_ops;

/* Whether the algorithm renders what the frame asks (its capabilities):
 * OIT_E_INPUT "NAME: reason" for the first thing it does not (the
 * modulation, then its distance mode, then the view), or for a value outside
 * its enum. oit_algorithm_render calls it; shells may ask before rendering. */
oit_status oit_frame_check(const oit_algorithm_ops *ops, const oit_frame_settings *frame, oit_error *err);
/* Whether it reads that OIT_OPTION_* (the option is ignored otherwise). */
bool oit_algorithm_reads(const oit_algorithm_ops *ops, unsigned option);

/* The one way to create an algorithm (shells call it, never ops->create): the
 * configuration's fields the algorithm reads (its capabilities' options) are
 * checked here, once for every algorithm, each refusal naming the field:
 * max_layers 0..OIT_PEEL_LAYER_CAP_MAX, layers 0..OIT_LAYERS_MAX, moments and
 * ll_sort within their enums; then ops->create. */
oit_status oit_algorithm_create(const oit_algorithm_ops *ops, const oit_algorithm_config *config,
                                oit_algorithm **out, oit_error *err);
/* The one way to size an algorithm's output ahead of a frame (shells call it,
 * never ops->resize): a size under 1x1 is refused here, for every algorithm. */
oit_status oit_algorithm_resize(const oit_algorithm_ops *ops, oit_algorithm *alg, int width, int height,
                                oit_error *err);
/* The one way to render a frame (every shell calls it, never ops->render):
 * checks the frame against the algorithm's capabilities (oit_frame_check)
 * and validates the matrices, then hands the algorithm the frame as its GPU
 * passes must see it: the modelview folded onto the model's relative
 * positions (oit_model_modelview) and the focus shapes moved with them, both
 * matrices and the focus rounded to float, as the GL takes them. The
 * reference gets the same frame, so the oracle sees the numbers the GL sees. */
oit_status oit_algorithm_render(const oit_algorithm_ops *ops, oit_algorithm *alg, const oit_scene *scene,
                                const oit_frame_settings *frame, oit_error *err);

/* The frame as oit_algorithm_render hands it to the algorithms: the
 * modelview folded onto the model's relative positions, the focus shapes
 * moved with them, matrices and focus rounded to float. OIT_E_INPUT where an
 * element leaves float's range. */
oit_status oit_frame_relative(const oit_model *model, const oit_frame_settings *frame,
                              oit_frame_settings *relative, oit_error *err);

/* ------------------------------------------------------------------- pick */

/* What one pixel shows, part by part (pick.c; docs/algorithms.md, "Pick"):
 * every fragment at the pixel centre, as the reference keeps them (its
 * coverage rule, canonical depth and tie order), each with its opacity after
 * the material, --alpha, the per-part opacity and the focus shapes; a
 * fragment's weight is alpha * T, T the transmittance in front of it, so the
 * weights are what each adds to the pixel's colour. The view and the
 * non-local modulations (distance, curvature...) are not applied. */
typedef struct oit_pick_part {
    uint32_t component;  /* index into model->components */
    double contribution; /* the sum of its fragments' weights at the pixel */
    double depth;        /* canonical depth of its nearest fragment there, 0..1 from near to far */
    double point[3];     /* that fragment's position, file coordinates (origin added back) */
    uint32_t triangle;   /* that fragment's triangle */
} oit_pick_part;

typedef struct oit_pick {
    /* every part with a fragment at the pixel, largest contribution first;
     * equal ones (behind something opaque: 0) nearest first, then by index */
    oit_pick_part *parts;
    uint32_t part_count;
    uint32_t fragment_count;
    double background; /* the transmittance left for the background */
} oit_pick;

/* Picks pixel (x, y) of the frame, x from the left and y from the top row
 * (as in the PNG), with the reference's maths (no GL). OIT_E_INPUT for a
 * pixel outside the frame (naming it), bad matrices or model. *out is empty
 * on failure; release it with oit_pick_release. */
oit_status oit_pick_pixel(const oit_model *model, const oit_frame_settings *frame, int x, int y,
                          oit_pick *out, oit_error *err);
void oit_pick_release(oit_pick *pick);

/* The registry, in the order `oit algorithms` lists them. */
const oit_algorithm_ops *const *oit_algorithm_list(size_t *count);
const oit_algorithm_ops *oit_algorithm_find(const char *name);

/* The oracle, which shells name to compare against (the rest by oit_algorithm_find). */
extern const oit_algorithm_ops oit_algorithm_reference;

/* ------------------------------------------------------------- GL context */

typedef enum oit_backend { OIT_BACKEND_EGL = 0, OIT_BACKEND_OSMESA = 1 } oit_backend;

typedef struct oit_gl_context oit_gl_context;

/* Create a headless OpenGL 4.3+ core-profile context and make it current.
 * debug: request a debug context and route KHR_debug output into
 * oit_gl_debug_messages (errors are also reported by oit_gl_check). */
oit_status oit_gl_context_create(oit_backend backend, bool debug, oit_gl_context **out,
                                 oit_error *err);
void oit_gl_context_destroy(oit_gl_context *context);
const char *oit_gl_renderer_string(void); /* GL_RENDERER of the current context */
/* GL_VERSION and GL_VENDOR of the current context, as oit_gl_renderer_string
 * gives GL_RENDERER: "(no GL context)" without one, "(unknown)" if GL has none. */
const char *oit_gl_version_string(void);
const char *oit_gl_vendor_string(void);
/* The independent count of what GL holds, for tests only (oit render --json,
 * "gl_allocated_bytes"; the algorithms' own count is oit_stats.memory_bytes,
 * from gl_util.h's oit_gl_memory): enumerates GL object names 1, 2, ... (until
 * 4096 names in a row are not objects) and sums GL_BUFFER_SIZE of every buffer
 * and the size of every level of every texture other than buffer textures
 * (whose storage is their buffer's), bytes per texel from the component sizes
 * GL reports (GL_TEXTURE_RED_SIZE ... GL_TEXTURE_STENCIL_SIZE), times samples;
 * renderbuffers likewise. Knows nothing of oit_gl_memory. -1 if this GL lacks
 * the direct state access queries it needs (GL 4.5). Needs a current context. */
int64_t oit_gl_enumerate_allocated_bytes(void);

/* ---------------------------------------------------------------- shaders */

/* Find the shader tree: $OIT_SHADER_DIR, next to the executable
 * (../share/oit-workbench/shaders, then ./shaders), then the source tree.
 * On failure the message lists every place it looked. */
oit_status oit_find_shader_dir(const char *argv0, char *out, size_t out_size, oit_error *err);

/* ------------------------------------------------------------------ words */

/* The words of the settings that take one of a few values (the command
 * line's --shading flat, the presets' "shading": "flat", the messages), in
 * one table for every shell. A setting whose zero value means "the default"
 * writes that default's word for it. */
typedef enum oit_setting {
    OIT_SETTING_SHADING,    /* oit_shading_mode: flat, headlight */
    OIT_SETTING_SORT,       /* oit_ll_sort: insertion, array, bma, merge */
    OIT_SETTING_MOMENTS,    /* oit_moments: power4, power6, trig3 (0: power4) */
    OIT_SETTING_VIEW,       /* oit_view: colour, heatmap, peel-limit, layer, ... */
    OIT_SETTING_MODULATION, /* oit_modulation_mode: none, curvature, distance, ... */
    OIT_SETTING_DISTANCE,   /* oit_distance_mode: adjacent, skip, far */
    OIT_SETTING_NEIGHBOURS, /* oit_neighbour_search: index, welded, epsilon (0: welded) */
    OIT_SETTING_BACKEND,    /* oit_backend: egl, osmesa */
    OIT_SETTING_COUNT
} oit_setting;

/* Its flag, "--shading" ("" outside the enum). */
const char *oit_setting_flag(oit_setting setting);
/* The word for one of its values; "unknown" outside them. */
const char *oit_setting_word(oit_setting setting, int value);
/* Its words in the order of their values, and how many (0 outside the enum). */
int oit_setting_words(oit_setting setting, const char *const **words);
/* The value the first `length` bytes of `word` name; false if none. */
bool oit_setting_value(oit_setting setting, const char *word, size_t length, int *value);
/* The value `word` names, or OIT_E_INPUT "FLAG must be A, B or C, got 'WORD'". */
oit_status oit_setting_parse(oit_setting setting, const char *word, int *value, oit_error *err);

/* -------------------------------------------------------------- generators */

/* Procedural scenes written as OBJ + MTL (the MTL next to the OBJ). */
typedef struct oit_scene_generator {
    const char *name;
    const char *summary;
    int default_complexity; /* scene-specific: layers, grid size, subdivisions... */
} oit_scene_generator;

const oit_scene_generator *oit_scene_generator_list(size_t *count);
/* complexity <= 0 uses the default */
oit_status oit_scene_generate(const char *name, int complexity, const char *obj_path,
                              oit_error *err);

/* ------------------------------------------------------ turntables, video */

/* A turntable (turntable.c; docs/cli.md, "Turntables"): n frames of a full
 * orbit of the camera about an up axis through a centre. Frame i's modelview
 * is base * translate(centre) * rotate(axis, -360 * i / n degrees) *
 * translate(-centre), in double (frame 0 is base bit for bit): the camera
 * turns by +360 i / n about the axis (as --orbit's azimuth grows, for the
 * default camera and the y axis), the centre keeps its eye-space position,
 * the axis keeps its direction in the image. The axis is a model (file)
 * space unit vector: x, y or z, or "view", the direction base shows pointing
 * up the image (base^-1 applied to eye +y); oit_turntable_axis takes that
 * modelview, which may be NULL for x, y and z. */
typedef enum oit_turntable_up {
    OIT_TURNTABLE_UP_Y = 0, /* the default: the CLI's default camera and the workbench's Y up */
    OIT_TURNTABLE_UP_Z = 1,
    OIT_TURNTABLE_UP_X = 2,
    OIT_TURNTABLE_UP_VIEW = 3
} oit_turntable_up;
#define OIT_TURNTABLE_FRAMES_MAX 10000
#define OIT_TURNTABLE_VIDEO_NAME "turntable.mp4"
oit_status oit_turntable_axis(const double modelview[16], oit_turntable_up up, double axis[3], oit_error *err);
void oit_turntable_modelview(const double base[16], const double centre[3], const double axis[3], int frame,
                             int count, double out[16]);

/* An MP4 video, H.264 (libx264, crf 18, preset medium, one thread) in
 * yuv420p at fps frames per second, written with FFmpeg's libraries
 * (video.c). yuv420p halves the colour resolution, so the width and height
 * must be even (odd sizes are refused, not padded: OIT_E_INPUT). The file is
 * written to a temporary beside path; oit_video_close(keep = true) finishes
 * it and renames it over path, keep = false (or any failure) removes it.
 * The libraries' own logging is turned off (av_log_set_level, process-wide). */
#define OIT_VIDEO_FPS_MAX 240
typedef struct oit_video oit_video;
oit_status oit_video_check_size(int width, int height, oit_error *err);
oit_status oit_video_open(const char *path, int width, int height, int fps, oit_video **out, oit_error *err);
oit_status oit_video_write(oit_video *video, const oit_image *frame, oit_error *err);
/* Frees video (NULL is allowed) in every case. */
oit_status oit_video_close(oit_video *video, bool keep, oit_error *err);

/* A turntable's folder: FOLDER/frame_0000.png ... (four digits, from 0) and,
 * with fps > 0, FOLDER/turntable.mp4. FOLDER is a new name, an empty
 * directory or a previous turntable (it holds frame_0000.png and only
 * regular files), replaced whole: everything is written into a temporary
 * folder beside it (oit_temporary_create), which commit renames over it in
 * one step; abort (or a signal) removes it and FOLDER stays as it was.
 * WHAT names the folder in messages (a flag, "--out"). Check runs open's
 * checks (and makes and removes the temporary) without writing anything. */
typedef struct oit_turntable_output oit_turntable_output;
oit_status oit_turntable_output_check(const char *folder, const char *what, int frames, oit_error *err);
oit_status oit_turntable_output_open(const char *folder, const char *what, int width, int height, int frames,
                                     int fps, oit_turntable_output **out, oit_error *err);
/* The next frame: its PNG, and its video frame. */
oit_status oit_turntable_output_add(oit_turntable_output *output, const oit_image *image, oit_error *err);
/* Milliseconds spent so far writing the PNGs and encoding the video. */
void oit_turntable_output_times(const oit_turntable_output *output, double *png_ms, double *video_ms);
/* Finishes the video and puts the folder in place; frees output (aborted on failure). */
oit_status oit_turntable_output_commit(oit_turntable_output *output, oit_error *err);
/* Removes the temporary folder and frees output (NULL is allowed). */
void oit_turntable_output_abort(oit_turntable_output *output);

#ifdef __cplusplus
}
#endif
#endif
