/* matrix.c: column-major 4x4 helpers, the default camera and the shared shading formula. */
#include <math.h>
#include <string.h>

#include "oit.h"
#include "oit_shared.h"

void oit_mat4_identity(double m[16])
{
    memset(m, 0, 16 * sizeof m[0]);
    m[0] = m[5] = m[10] = m[15] = 1.0;
}

void oit_mat4_multiply(const double a[16], const double b[16], double out[16])
{
    double result[16];
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) {
            double sum = 0.0;
            for (int k = 0; k < 4; ++k)
                sum += a[k * 4 + row] * b[col * 4 + k];
            result[col * 4 + row] = sum;
        }
    memcpy(out, result, sizeof result);
}

void oit_model_modelview(const oit_model *model, const double modelview[16], double out[16])
{
    /* modelview x translate(origin): only the translation column changes */
    double result[16];
    memcpy(result, modelview, sizeof result);
    for (int row = 0; row < 4; ++row)
        result[12 + row] = modelview[row] * model->origin[0] + modelview[4 + row] * model->origin[1] +
                           modelview[8 + row] * model->origin[2] + modelview[12 + row];
    memcpy(out, result, sizeof result);
}

/* Upper 3x3 of a column-major 4x4, as a[row][col]. */
static void upper3x3(const double m[16], double a[3][3])
{
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col)
            a[row][col] = m[col * 4 + row];
}

static double det3(double a[3][3])
{
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

bool oit_mat4_normal_matrix(const double m[16], double out[9])
{
    double a[3][3];
    upper3x3(m, a);
    double det = det3(a);
    double scale = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            scale = fmax(scale, fabs(a[i][j]));
    if (!isfinite(det) || scale == 0.0 || fabs(det) <= 1e-12 * scale * scale * scale)
        return false;
    /* inverse transpose = cofactor matrix / det; stored column-major */
    double cof[3][3];
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) {
            int r0 = (row + 1) % 3, r1 = (row + 2) % 3;
            int c0 = (col + 1) % 3, c1 = (col + 2) % 3;
            cof[row][col] = a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0];
        }
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col)
            out[col * 3 + row] = cof[row][col] / det;
    return true;
}

/* Determinant of a[4][4] (row-major, double) by cofactor expansion. */
static double det4(double a[4][4])
{
    double det = 0.0;
    for (int col = 0; col < 4; ++col) {
        double minor[3][3];
        for (int row = 1; row < 4; ++row)
            for (int c = 0, mc = 0; c < 4; ++c)
                if (c != col)
                    minor[row - 1][mc++] = a[row][c];
        det += ((col % 2) ? -1.0 : 1.0) * a[0][col] * det3(minor);
    }
    return det;
}

double oit_mat4_regularity(const double m[16])
{
    /* Units make a plain determinant useless as a test: a projection's
     * translation column carries lengths (2fn/(n-f)) while its other columns
     * are ratios, so scaling the scene by s scales one column by s and the
     * determinant with it. Equilibrating first (each column, then each row,
     * scaled to a largest element of 1, twice over) removes every such
     * scaling; then |det| / (product of the row lengths) (Hadamard's ratio) is
     * 1 for orthogonal rows and 0 for a singular matrix, whatever the units. */
    double a[4][4];
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col)
            a[row][col] = m[col * 4 + row];
    for (int round = 0; round < 2; ++round) {
        for (int col = 0; col < 4; ++col) {
            double largest = 0.0;
            for (int row = 0; row < 4; ++row)
                largest = fmax(largest, fabs(a[row][col]));
            if (largest == 0.0 || !isfinite(largest))
                return 0.0;
            for (int row = 0; row < 4; ++row)
                a[row][col] /= largest;
        }
        for (int row = 0; row < 4; ++row) {
            double largest = 0.0;
            for (int col = 0; col < 4; ++col)
                largest = fmax(largest, fabs(a[row][col]));
            if (largest == 0.0)
                return 0.0;
            for (int col = 0; col < 4; ++col)
                a[row][col] /= largest;
        }
    }
    double lengths = 1.0;
    for (int row = 0; row < 4; ++row)
        lengths *= sqrt(a[row][0] * a[row][0] + a[row][1] * a[row][1] + a[row][2] * a[row][2] +
                        a[row][3] * a[row][3]);
    double ratio = fabs(det4(a)) / lengths;
    return isfinite(ratio) ? fmin(ratio, 1.0) : 0.0;
}

oit_status oit_matrices_validate(const double modelview[16], const double projection[16],
                                 oit_error *err)
{
    for (int i = 0; i < 16; ++i) {
        if (!isfinite(modelview[i]))
            return oit_fail(err, OIT_E_INPUT, "modelview element %d (row %d, column %d) is not finite",
                            i, i % 4, i / 4);
        if (!isfinite(projection[i]))
            return oit_fail(err, OIT_E_INPUT, "projection element %d (row %d, column %d) is not finite",
                            i, i % 4, i / 4);
    }
    double normal_matrix[9];
    if (!oit_mat4_normal_matrix(modelview, normal_matrix))
        return oit_fail(err, OIT_E_INPUT, "modelview is singular (its 3x3 part has no inverse)");
    double regularity = oit_mat4_regularity(projection);
    if (regularity < OIT_MATRIX_REGULARITY_MIN)
        return oit_fail(err, OIT_E_INPUT,
                        "projection is singular (regularity %.3g after scaling rows and columns, "
                        "below %g: it maps a direction to nothing)",
                        regularity, OIT_MATRIX_REGULARITY_MIN);
    return OIT_OK;
}

oit_status oit_default_camera(const oit_model *model, int width, int height, double azimuth_degrees,
                              double elevation_degrees, double modelview[16], double projection[16],
                              oit_error *err)
{
    /* Eye space keeps the model's units (focus regions and distances along the
     * ray are lengths the user gives in them), so the model's size must leave
     * room for squared eye-space lengths in single precision. */
    if (model->radius > 0.0f &&
        (model->radius < OIT_MODEL_RADIUS_MIN || model->radius > OIT_MODEL_RADIUS_MAX))
        return oit_fail(err, OIT_E_INPUT,
                        "the model's bounding radius %g is outside the %g to %g units the default "
                        "camera frames in single precision; give --modelview and --projection",
                        model->radius, OIT_MODEL_RADIUS_MIN, OIT_MODEL_RADIUS_MAX);
    const double degrees = 3.14159265358979323846 / 180.0;
    const double fov_y = 40.0 * degrees;
    double aspect = (width > 0 && height > 0) ? (double)width / height : 1.0;
    double fov_x = 2.0 * atan(tan(fov_y / 2.0) * aspect);
    double radius = model->radius > 0.0f ? model->radius : 1.0;
    /* Distance at which the sphere fits the narrower field of view, with a small margin. */
    double distance = 1.05 * radius / sin(fmin(fov_y, fov_x) / 2.0);
    double near_plane = fmax(distance - 1.1 * radius, distance * 1e-3);
    double far_plane = distance + 1.1 * radius;

    /* modelview = translate(0, 0, -distance) * rotate_x(elevation) * rotate_y(-azimuth) * translate(-origin),
     * the origin being the sphere's centre in file coordinates */
    double ca = cos(-azimuth_degrees * degrees), sa = sin(-azimuth_degrees * degrees);
    double ce = cos(elevation_degrees * degrees), se = sin(elevation_degrees * degrees);
    double rotation[3][3] = {/* rows of rotate_x(e) * rotate_y(a) */
                             {ca, 0.0, sa},
                             {se * sa, ce, -se * ca},
                             {-ce * sa, se, ce * ca}};
    oit_mat4_identity(modelview);
    for (int row = 0; row < 3; ++row) {
        double moved = 0.0;
        for (int col = 0; col < 3; ++col) {
            modelview[col * 4 + row] = rotation[row][col];
            moved -= rotation[row][col] * model->origin[col];
        }
        modelview[12 + row] = moved - (row == 2 ? distance : 0.0);
    }

    double f = 1.0 / tan(fov_y / 2.0);
    memset(projection, 0, 16 * sizeof projection[0]);
    projection[0] = f / aspect;
    projection[5] = f;
    projection[10] = (far_plane + near_plane) / (near_plane - far_plane);
    projection[11] = -1.0;
    projection[14] = 2.0 * far_plane * near_plane / (near_plane - far_plane);
    return OIT_OK;
}

void oit_plane_to_eye_double(const oit_frame_settings *frame, double out[16])
{
    /* planes transform with the inverse transpose: for eye = M p, a plane
     * with q . (p, 1) = 0 becomes (M^-T q) . (eye, 1) = 0 */
    double inverse[16];
    if (!oit_mat4_inverse_double(frame->modelview, inverse)) {
        for (int i = 0; i < 16; ++i)
            out[i] = (i % 5 == 0) ? 1.0 : 0.0;
        return;
    }
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row)
            out[col * 4 + row] = inverse[row * 4 + col];
}


