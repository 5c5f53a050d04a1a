// camera.cpp: see camera.h.
#include "camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "oit.h"

namespace {

const glm::dvec3 world_up(0.0, 1.0, 0.0);

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
    orientation = glm::angleAxis(glm::radians(double(azimuth_degrees)), world_up) *
                  glm::angleAxis(glm::radians(-double(elevation_degrees)), glm::dvec3(1.0, 0.0, 0.0));
    target = scene_centre;
    eye = target + orientation * glm::dvec3(0.0, 0.0, distance);
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

void Camera::set_view_direction(float azimuth_degrees, float elevation_degrees)
{
    double distance = glm::length(eye - target);
    if (!(distance > 0.0))
        distance = scene_radius;
    orientation = glm::angleAxis(glm::radians(double(azimuth_degrees)), world_up) *
                  glm::angleAxis(glm::radians(-double(elevation_degrees)), glm::dvec3(1.0, 0.0, 0.0));
    eye = target + orientation * glm::dvec3(0.0, 0.0, distance);
    mode_ = Mode::Orbit;
}

void Camera::matrices(int width, int height, double modelview[16], double projection[16]) const
{
    glm::dmat4 view = glm::mat4_cast(glm::conjugate(orientation)) * glm::translate(glm::dmat4(1.0), -eye);
    double aspect = width > 0 && height > 0 ? double(width) / double(height) : 1.0;
    // near and far around the bounding sphere, as oit_default_camera
    double distance = glm::length(scene_centre - eye);
    double near_plane = std::max(distance - 1.1 * scene_radius, std::max(distance, scene_radius) * 1e-3);
    double far_plane = distance + 1.1 * scene_radius;
    double fov = glm::radians(double(fov_degrees));
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

void Camera::pan(glm::vec2 delta, int height)
{
    double distance = std::max(glm::length(target - eye), scene_radius * 1e-3);
    double per_pixel = 2.0 * distance * std::tan(glm::radians(double(fov_degrees)) / 2.0) / double(std::max(1, height));
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
    glm::dvec3 move = orientation * glm::dvec3(direction.x, 0.0, -direction.z) * step + world_up * double(direction.y) * step;
    eye += move;
    target += move;
}

void Camera::look(glm::vec2 delta)
{
    const double radians_per_pixel = 0.005;
    orientation = glm::normalize(glm::angleAxis(-delta.x * radians_per_pixel, world_up) * orientation *
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
