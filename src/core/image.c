/* image.c: RGBA8 images, PNG input and output (libpng), image comparison. */
#include <math.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <png.h>

#include "oit.h"

/* Larger images are surely a mistake (and 16384^2 * 4 bytes = 1 GiB). */
#define OIT_IMAGE_MAX_SIDE 16384

oit_status oit_image_alloc(oit_image *image, int width, int height, oit_error *err)
{
    image->width = image->height = 0;
    image->rgba = NULL;
    if (width <= 0 || height <= 0 || width > OIT_IMAGE_MAX_SIDE || height > OIT_IMAGE_MAX_SIDE)
        return oit_fail(err, OIT_E_INPUT, "image size %dx%d out of range (1..%d per side)", width,
                        height, OIT_IMAGE_MAX_SIDE);
    image->rgba = calloc((size_t)width * (size_t)height, 4);
    if (!image->rgba)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for a %dx%d image", width, height);
    image->width = width;
    image->height = height;
    return OIT_OK;
}

void oit_image_free(oit_image *image)
{
    if (!image)
        return;
    free(image->rgba);
    image->rgba = NULL;
    image->width = image->height = 0;
}

/* libpng reports errors through these; the message is kept for ours and
 * png_error longjmps back to the setjmp in the caller. */
typedef struct png_context {
    char message[256];
} png_context;

static void on_png_error(png_structp png, png_const_charp message)
{
    png_context *context = png_get_error_ptr(png);
    if (context)
        snprintf(context->message, sizeof context->message, "%s", message);
    png_longjmp(png, 1);
}

static void on_png_warning(png_structp png, png_const_charp message)
{
    (void)png;
    (void)message; /* warnings (e.g. bad ancillary chunks) are not errors */
}

/* Written through oit_atomic_file: a write that fails (a full disk) leaves
 * the previous file whole. */
oit_status oit_png_write(const char *path, const oit_image *image, oit_error *err)
{
    const char *volatile name = path; /* volatile: used after longjmp */
    if (!image || !image->rgba || image->width <= 0 || image->height <= 0)
        return oit_fail(err, OIT_E_INPUT, "%s: no image to write", name);
    oit_atomic_file *volatile output = NULL;
    oit_atomic_file *opened;
    oit_status status = oit_atomic_file_open(path, NULL, 0, &opened, err);
    if (status != OIT_OK)
        return status;
    output = opened;

    png_context context = {{0}};
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &context, on_png_error,
                                              on_png_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    /* Row pointers live outside the setjmp scope's locals that change after
     * setjmp, so they are freed on every path. */
    png_bytep *volatile rows = NULL;
    if (!png || !info) {
        png_destroy_write_struct(&png, &info);
        return oit_atomic_file_abort(output, OIT_E_RUNTIME, "out of memory", err);
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        free(rows);
        /* no half-written files; the previous one stays. The reason is the
         * failed write's errno where there was one, else libpng's. */
        return oit_atomic_file_abort(output, OIT_E_RUNTIME, context.message, err);
    }
    rows = malloc((size_t)image->height * sizeof *rows);
    if (!rows)
        png_error(png, "out of memory");
    for (int y = 0; y < image->height; ++y)
        rows[y] = image->rgba + (size_t)y * (size_t)image->width * 4;
    png_init_io(png, oit_atomic_file_stream(output));
    png_set_IHDR(png, info, (png_uint_32)image->width, (png_uint_32)image->height, 8,
                 PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, 6);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(rows);
    return oit_atomic_file_commit(output, err);
}

oit_status oit_png_read(const char *path, oit_image *image, oit_error *err)
{
    const char *volatile name = path; /* volatile: used after longjmp */
    image->width = image->height = 0;
    image->rgba = NULL;
    /* a FIFO or a device would block or never end */
    FILE *file;
    oit_status status = oit_open_regular_file(path, NULL, &file, err);
    if (status != OIT_OK)
        return status;
    png_byte signature[8];
    if (fread(signature, 1, sizeof signature, file) != sizeof signature ||
        png_sig_cmp(signature, 0, sizeof signature) != 0) {
        fclose(file);
        return oit_fail(err, OIT_E_INPUT, "%s: not a PNG file", name);
    }

    png_context context = {{0}};
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &context, on_png_error,
                                             on_png_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    /* Everything allocated after setjmp is volatile so the error path sees it. */
    png_bytep *volatile rows = NULL;
    uint8_t *volatile pixels = NULL;
    if (!png || !info) {
        png_destroy_read_struct(&png, &info, NULL);
        fclose(file);
        return oit_fail(err, OIT_E_RUNTIME, "%s: out of memory", name);
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        free(rows);
        free(pixels);
        fclose(file);
        return oit_fail(err, OIT_E_INPUT, "%s: broken PNG file: %s", name, context.message);
    }
    png_init_io(png, file);
    png_set_sig_bytes(png, sizeof signature);
    png_set_user_limits(png, OIT_IMAGE_MAX_SIDE, OIT_IMAGE_MAX_SIDE);
    png_read_info(png, info);

    png_uint_32 width = 0, height = 0;
    int bit_depth = 0, colour_type = 0;
    png_get_IHDR(png, info, &width, &height, &bit_depth, &colour_type, NULL, NULL, NULL);
    /* Whatever the PNG holds, end with 8-bit RGBA. */
    if (colour_type == PNG_COLOR_TYPE_PALETTE)
        png_set_palette_to_rgb(png);
    if (colour_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8)
        png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS))
        png_set_tRNS_to_alpha(png);
    if (bit_depth == 16)
        png_set_scale_16(png);
    if (colour_type == PNG_COLOR_TYPE_GRAY || colour_type == PNG_COLOR_TYPE_GRAY_ALPHA)
        png_set_gray_to_rgb(png);
    if (!(colour_type & PNG_COLOR_MASK_ALPHA) && !png_get_valid(png, info, PNG_INFO_tRNS))
        png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != (size_t)width * 4)
        png_error(png, "unexpected row layout after conversion to RGBA8");

    pixels = malloc((size_t)width * (size_t)height * 4);
    rows = malloc((size_t)height * sizeof *rows);
    if (!pixels || !rows)
        png_error(png, "out of memory");
    for (png_uint_32 y = 0; y < height; ++y)
        rows[y] = pixels + (size_t)y * width * 4;
    png_read_image(png, rows);
    png_read_end(png, NULL);

    png_destroy_read_struct(&png, &info, NULL);
    free(rows);
    fclose(file);
    image->width = (int)width;
    image->height = (int)height;
    image->rgba = pixels;
    return OIT_OK;
}

oit_status oit_image_compare(const oit_image *a, const oit_image *b, int tolerance,
                             oit_image_diff *out, oit_error *err)
{
    memset(out, 0, sizeof *out);
    if (!a->rgba || !b->rgba)
        return oit_fail(err, OIT_E_INPUT, "no image to compare");
    if (a->width != b->width || a->height != b->height)
        return oit_fail(err, OIT_E_INPUT, "image sizes differ: %dx%d and %dx%d", a->width,
                        a->height, b->width, b->height);
    size_t pixels = (size_t)a->width * (size_t)a->height;
    uint64_t sum = 0, sum_squares = 0;
    int max_diff = 0;
    long over = 0;
    for (size_t i = 0; i < pixels; ++i) {
        const uint8_t *pa = a->rgba + i * 4, *pb = b->rgba + i * 4;
        int pixel_max = 0;
        for (int c = 0; c < 3; ++c) { /* alpha is ignored */
            int d = abs((int)pa[c] - (int)pb[c]);
            sum += (uint64_t)d;
            sum_squares += (uint64_t)(d * d);
            if (d > pixel_max)
                pixel_max = d;
        }
        if (pixel_max > max_diff)
            max_diff = pixel_max;
        if (pixel_max > tolerance)
            ++over;
    }
    double samples = (double)pixels * 3.0;
    double mse = (double)sum_squares / samples;
    out->max_channel_diff = max_diff;
    out->mean_diff = (double)sum / samples;
    out->rmse = sqrt(mse);
    out->psnr_db = sum_squares == 0 ? INFINITY : 10.0 * log10(255.0 * 255.0 / mse);
    out->pixels_over_tolerance = over;
    out->share_over_tolerance = (double)over / (double)pixels;
    return OIT_OK;
}
