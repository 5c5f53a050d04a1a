// camera.cpp: see camera.h.
#include "camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "oit.h"

namespace {

// Turntable elevations stop this short of the poles (degrees): at a pole the
// azimuth would turn the view about the line of sight.
const double kPoleMarginDegrees = 1.0;

// The orientation (camera to world) that looks from azimuth, elevation (radians)
// towards the target with the up axis up. Y up: front (0, 0) looks along -z,
// top along -y; Z up: front looks along +y, top along -z.
glm::dquat pose(double azimuth, double elevation, Camera::Up up)
{
    // the Y-up pose, then Y-up to Z-up (+90 degrees about x: y -> z, z -> -y)
    glm::dquat y_up = glm::angleAxis(azimuth, glm::dvec3(0.0, 1.0, 0.0)) *
                      glm::angleAxis(-elevation, glm::dvec3(1.0, 0.0, 0.0));
    if (up == Camera::Up::Y)
        return y_up;
    return glm::angleAxis(glm::half_pi<double>(), glm::dvec3(1.0, 0.0, 0.0)) * y_up;
}

// A point in widget pixels on Shoemake's virtual trackball (unit sphere, the
// hyperbolic sheet outside it so dragging past the edge keeps turning).
glm::dvec3 on_trackball(glm::vec2 p, int width, int height)
{
    double scale = 2.0 / double(std::max(1, std::min(width, height)));
    glm::dvec3 v((p.x - 0.5 * width) * scale, (0.5 * height - p.y) * scale, 0.0);
    double d2 = v.x * v.x + v.y * v.y;
    v.z = d2 <= 0.5 ? std::sqrt(1.0 - d2) : 0.5 / std::sqrt(d2);
    return glm::normalize(v);
}

} // namespace

void Camera::frame(const oit_model &model, int width, int height, float azimuth_degrees,
                   float elevation_degrees)
{
    scene_centre = glm::dvec3(model.origin[0], model.origin[1], model.origin[2]);
    scene_radius = model.radius > 0.0f ? double(model.radius) : 1.0;
    fov_degrees = 40.0f;
    // as oit_default_camera: the sphere fits the narrower field of view with a 5% margin
    double fov_y = glm::radians(40.0);
    double aspect = width > 0 && height > 0 ? double(width) / height : 1.0;
    double fov_x = 2.0 * std::atan(std::tan(fov_y / 2.0) * aspect);
    double distance = 1.05 * scene_radius / std::sin(std::min(fov_y, fov_x) / 2.0);
    orientation = pose(glm::radians(double(azimuth_degrees)), glm::radians(double(elevation_degrees)), up);
    target = scene_centre;
    eye = target + orientation * glm::dvec3(0.0, 0.0, distance);
}

glm::dvec3 Camera::up_vector() const
{
    return up == Up::Y ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(0.0, 0.0, 1.0);
}

// The distance at which a sphere of this radius fits the narrower field of
// view with a 5% margin (as oit_default_camera).
static double fitting_distance(double radius, float fov_degrees, int width, int height)
{
    double fov_y = glm::radians(double(fov_degrees));
    double aspect = width > 0 && height > 0 ? double(width) / height : 1.0;
    double fov_x = 2.0 * std::atan(std::tan(fov_y / 2.0) * aspect);
    return 1.05 * radius / std::sin(std::min(fov_y, fov_x) / 2.0);
}

void Camera::frame_box(const double box_min[3], const double box_max[3], int width, int height)
{
    glm::dvec3 lo(box_min[0], box_min[1], box_min[2]), hi(box_max[0], box_max[1], box_max[2]);
    double radius = 0.5 * glm::length(hi - lo);
    if (!(radius > scene_radius * 1e-4))
        radius = scene_radius * 1e-4; // a point or a sliver: still a usable distance
    target = 0.5 * (lo + hi);
    eye = target + orientation * glm::dvec3(0.0, 0.0, fitting_distance(radius, fov_degrees, width, height));
    mode_ = Mode::Orbit;
}

void Camera::set_view_direction(float azimuth_degrees, float elevation_degrees, int width, int height)
{
    orientation = pose(glm::radians(double(azimuth_degrees)), glm::radians(double(elevation_degrees)), up);
    target = scene_centre;
    eye = target + orientation * glm::dvec3(0.0, 0.0, fitting_distance(scene_radius, fov_degrees, width, height));
    mode_ = Mode::Orbit;
}

void Camera::matrices(int width, int height, double modelview[16], double projection[16],
                      double framed_aspect) const
{
    glm::dmat4 view = glm::mat4_cast(glm::conjugate(orientation)) * glm::translate(glm::dmat4(1.0), -eye);
    double aspect = width > 0 && height > 0 ? double(width) / double(height) : 1.0;
    // near and far around the bounding sphere, as oit_default_camera
    double distance = glm::length(scene_centre - eye);
    double near_plane = std::max(distance - 1.1 * scene_radius, std::max(distance, scene_radius) * 1e-3);
    double far_plane = distance + 1.1 * scene_radius;
    double fov = glm::radians(double(fov_degrees));
    // a narrower image than the framed view: widen the field of view until its
    // narrower axis shows what the framed view's narrower axis shows
    double widen = widening(aspect, framed_aspect);
    if (widen != 1.0)
        fov = 2.0 * std::atan(std::tan(fov / 2.0) * widen);
    glm::dmat4 proj;
    if (orthographic) {
        // the same size at the target as the perspective view shows there
        double half_height = std::max(glm::length(target - eye), scene_radius * 1e-3) * std::tan(fov / 2.0);
        proj = glm::ortho(-half_height * aspect, half_height * aspect, -half_height, half_height, near_plane,
                          far_plane);
    } else {
        proj = glm::perspective(fov, aspect, near_plane, far_plane);
    }
    const double *v = glm::value_ptr(view), *p = glm::value_ptr(proj);
    std::copy(v, v + 16, modelview);
    std::copy(p, p + 16, projection);
}

void Camera::trackball(glm::vec2 from, glm::vec2 to, int width, int height)
{
    glm::dvec3 a = on_trackball(from, width, height), b = on_trackball(to, width, height);
    double d = glm::clamp(glm::dot(a, b), -1.0, 1.0);
    glm::dvec3 axis = glm::cross(a, b);
    if (glm::length(axis) < 1e-7)
        return;
    // turning the model by r in eye space is turning the camera by r^-1
    glm::dquat r = glm::angleAxis(std::acos(d) * 2.0, glm::normalize(axis));
    double distance = glm::length(target - eye);
    orientation = glm::normalize(orientation * glm::conjugate(r));
    eye = target + orientation * glm::dvec3(0.0, 0.0, distance);
}

void Camera::orbit(glm::vec2 from, glm::vec2 to, int width, int height)
{
    if (orbit_style == Orbit::Trackball)
        trackball(from, to, width, height);
    else
        turntable(from, to, width, height);
}

void Camera::turntable(glm::vec2 from, glm::vec2 to, int width, int height)
{
    // the pose's azimuth and elevation in the Y-up frame (pose() without the
    // Y-up to Z-up turn); a rolled pose (a trackball's, a saved view's) loses its roll
    glm::dquat to_y_up = up == Up::Y ? glm::dquat(1.0, 0.0, 0.0, 0.0)
                                     : glm::angleAxis(-glm::half_pi<double>(), glm::dvec3(1.0, 0.0, 0.0));
    glm::dvec3 back = to_y_up * (orientation * glm::dvec3(0.0, 0.0, 1.0));
    glm::dvec3 right = to_y_up * (orientation * glm::dvec3(1.0, 0.0, 0.0));
    double elevation = std::asin(glm::clamp(back.y, -1.0, 1.0));
    // the right vector stays horizontal in a pose without roll, also at the poles
    double azimuth = std::hypot(right.x, right.z) > 1e-3 ? std::atan2(-right.z, right.x) : std::atan2(back.x, back.z);
    // half a turn per view height; dragging right turns the model right (the camera left)
    double radians_per_pixel = glm::pi<double>() / double(std::max(1, std::min(width, height)));
    azimuth -= double(to.x - from.x) * radians_per_pixel;
    double limit = glm::radians(90.0 - kPoleMarginDegrees);
    elevation = glm::clamp(elevation + double(to.y - from.y) * radians_per_pixel, -limit, limit);
    double distance = glm::length(target - eye);
    orientation = pose(azimuth, elevation, up);
    eye = target + orientation * glm::dvec3(0.0, 0.0, distance);
}

double Camera::widening(double aspect, double framed_aspect)
{
    if (framed_aspect > 0.0 && std::min(1.0, aspect) < std::min(1.0, framed_aspect))
        return std::min(1.0, framed_aspect) / std::min(1.0, aspect);
    return 1.0;
}

void Camera::pan(glm::vec2 delta, int width, int height, double framed_aspect)
{
    double distance = std::max(glm::length(target - eye), scene_radius * 1e-3);
    double aspect = width > 0 && height > 0 ? double(width) / double(height) : 1.0;
    double per_pixel = 2.0 * distance * std::tan(glm::radians(double(fov_degrees)) / 2.0) *
                       widening(aspect, framed_aspect) / double(std::max(1, height));
    glm::dvec3 move = orientation * glm::dvec3(-delta.x * per_pixel, delta.y * per_pixel, 0.0);
    eye += move;
    target += move;
}

void Camera::zoom(float steps)
{
    if (mode_ == Mode::Walk) {
        walk(glm::vec3(0.0f, 0.0f, 2.0f * steps));
        return;
    }
    double distance = glm::length(target - eye) * std::pow(0.85, double(steps));
    distance = std::max(distance, scene_radius * 1e-3);
    eye = target + orientation * glm::dvec3(0.0, 0.0, distance);
}

void Camera::walk(glm::vec3 direction)
{
    double step = 0.05 * scene_radius;
    glm::dvec3 move = orientation * glm::dvec3(direction.x, 0.0, -direction.z) * step + up_vector() * double(direction.y) * step;
    eye += move;
    target += move;
}

void Camera::look(glm::vec2 delta)
{
    const double radians_per_pixel = 0.005;
    orientation = glm::normalize(glm::angleAxis(-delta.x * radians_per_pixel, up_vector()) * orientation *
                                 glm::angleAxis(-delta.y * radians_per_pixel, glm::dvec3(1.0, 0.0, 0.0)));
    target = eye + orientation * glm::dvec3(0.0, 0.0, -glm::length(target - eye));
}

void Camera::set_mode(Mode mode)
{
    if (mode == mode_)
        return;
    // orbit about the point straight ahead, as far away as the model's centre
    double distance = std::max(glm::length(scene_centre - eye), scene_radius * 0.1);
    target = eye + orientation * glm::dvec3(0.0, 0.0, -distance);
    mode_ = mode;
}
