// camera.cpp: see camera.h.
#include "camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "oit.h"

namespace {

const glm::vec3 world_up(0.0f, 1.0f, 0.0f);

// A point in widget pixels on Shoemake's virtual trackball (unit sphere, the
// hyperbolic sheet outside it so dragging past the edge keeps turning).
glm::vec3 on_trackball(glm::vec2 p, int width, int height)
{
    float scale = 2.0f / float(std::max(1, std::min(width, height)));
    glm::vec3 v((p.x - 0.5f * width) * scale, (0.5f * height - p.y) * scale, 0.0f);
    float d2 = v.x * v.x + v.y * v.y;
    v.z = d2 <= 0.5f ? std::sqrt(1.0f - d2) : 0.5f / std::sqrt(d2);
    return glm::normalize(v);
}

} // namespace

void Camera::frame(const oit_model &model, int width, int height, float azimuth_degrees,
                   float elevation_degrees)
{
    scene_centre = glm::vec3(model.centre[0], model.centre[1], model.centre[2]);
    scene_radius = model.radius > 0.0f ? model.radius : 1.0f;
    fov_degrees = 40.0f;
    // as oit_default_camera: the sphere fits the narrower field of view with a 5% margin
    double fov_y = glm::radians(40.0);
    double aspect = width > 0 && height > 0 ? double(width) / height : 1.0;
    double fov_x = 2.0 * std::atan(std::tan(fov_y / 2.0) * aspect);
    double distance = 1.05 * scene_radius / std::sin(std::min(fov_y, fov_x) / 2.0);
    orientation = glm::angleAxis(glm::radians(azimuth_degrees), world_up) *
                  glm::angleAxis(glm::radians(-elevation_degrees), glm::vec3(1.0f, 0.0f, 0.0f));
    target = scene_centre;
    eye = target + orientation * glm::vec3(0.0f, 0.0f, float(distance));
}

// The distance at which a sphere of this radius fits the narrower field of
// view with a 5% margin (as oit_default_camera).
static double fitting_distance(float radius, float fov_degrees, int width, int height)
{
    double fov_y = glm::radians(double(fov_degrees));
    double aspect = width > 0 && height > 0 ? double(width) / height : 1.0;
    double fov_x = 2.0 * std::atan(std::tan(fov_y / 2.0) * aspect);
    return 1.05 * radius / std::sin(std::min(fov_y, fov_x) / 2.0);
}

void Camera::frame_box(const float box_min[3], const float box_max[3], int width, int height)
{
    glm::vec3 lo(box_min[0], box_min[1], box_min[2]), hi(box_max[0], box_max[1], box_max[2]);
    float radius = 0.5f * glm::length(hi - lo);
    if (!(radius > scene_radius * 1e-4f))
        radius = scene_radius * 1e-4f; // a point or a sliver: still a usable distance
    target = 0.5f * (lo + hi);
    eye = target + orientation * glm::vec3(0.0f, 0.0f, float(fitting_distance(radius, fov_degrees, width, height)));
    mode_ = Mode::Orbit;
}

void Camera::set_view_direction(float azimuth_degrees, float elevation_degrees)
{
    float distance = glm::length(eye - target);
    if (!(distance > 0.0f))
        distance = scene_radius;
    orientation = glm::angleAxis(glm::radians(azimuth_degrees), world_up) *
                  glm::angleAxis(glm::radians(-elevation_degrees), glm::vec3(1.0f, 0.0f, 0.0f));
    eye = target + orientation * glm::vec3(0.0f, 0.0f, distance);
    mode_ = Mode::Orbit;
}

void Camera::matrices(int width, int height, float modelview[16], float projection[16]) const
{
    glm::mat4 view = glm::mat4_cast(glm::conjugate(orientation)) * glm::translate(glm::mat4(1.0f), -eye);
    float aspect = width > 0 && height > 0 ? float(width) / float(height) : 1.0f;
    // near and far around the bounding sphere, as oit_default_camera
    float distance = glm::length(scene_centre - eye);
    float near_plane = std::max(distance - 1.1f * scene_radius, std::max(distance, scene_radius) * 1e-3f);
    float far_plane = distance + 1.1f * scene_radius;
    float fov = glm::radians(fov_degrees);
    glm::mat4 proj;
    if (orthographic) {
        // the same size at the target as the perspective view shows there
        float half_height = std::max(glm::length(target - eye), scene_radius * 1e-3f) * std::tan(fov / 2.0f);
        proj = glm::ortho(-half_height * aspect, half_height * aspect, -half_height, half_height, near_plane,
                          far_plane);
    } else {
        proj = glm::perspective(fov, aspect, near_plane, far_plane);
    }
    const float *v = glm::value_ptr(view), *p = glm::value_ptr(proj);
    std::copy(v, v + 16, modelview);
    std::copy(p, p + 16, projection);
}

void Camera::trackball(glm::vec2 from, glm::vec2 to, int width, int height)
{
    glm::vec3 a = on_trackball(from, width, height), b = on_trackball(to, width, height);
    float d = glm::clamp(glm::dot(a, b), -1.0f, 1.0f);
    glm::vec3 axis = glm::cross(a, b);
    if (glm::length(axis) < 1e-7f)
        return;
    // turning the model by r in eye space is turning the camera by r^-1
    glm::quat r = glm::angleAxis(std::acos(d) * 2.0f, glm::normalize(axis));
    float distance = glm::length(target - eye);
    orientation = glm::normalize(orientation * glm::conjugate(r));
    eye = target + orientation * glm::vec3(0.0f, 0.0f, distance);
}

void Camera::pan(glm::vec2 delta, int height)
{
    float distance = std::max(glm::length(target - eye), scene_radius * 1e-3f);
    float per_pixel = 2.0f * distance * std::tan(glm::radians(fov_degrees) / 2.0f) / float(std::max(1, height));
    glm::vec3 move = orientation * glm::vec3(-delta.x * per_pixel, delta.y * per_pixel, 0.0f);
    eye += move;
    target += move;
}

void Camera::zoom(float steps)
{
    if (mode_ == Mode::Walk) {
        walk(glm::vec3(0.0f, 0.0f, 2.0f * steps));
        return;
    }
    float distance = glm::length(target - eye) * std::pow(0.85f, steps);
    distance = std::max(distance, scene_radius * 1e-3f);
    eye = target + orientation * glm::vec3(0.0f, 0.0f, distance);
}

void Camera::walk(glm::vec3 direction)
{
    float step = 0.05f * scene_radius;
    glm::vec3 move = orientation * glm::vec3(direction.x, 0.0f, -direction.z) * step + world_up * direction.y * step;
    eye += move;
    target += move;
}

void Camera::look(glm::vec2 delta)
{
    const float radians_per_pixel = 0.005f;
    orientation = glm::normalize(glm::angleAxis(-delta.x * radians_per_pixel, world_up) * orientation *
                                 glm::angleAxis(-delta.y * radians_per_pixel, glm::vec3(1.0f, 0.0f, 0.0f)));
    target = eye + orientation * glm::vec3(0.0f, 0.0f, -glm::length(target - eye));
}

void Camera::set_mode(Mode mode)
{
    if (mode == mode_)
        return;
    // orbit about the point straight ahead, as far away as the model's centre
    float distance = std::max(glm::length(scene_centre - eye), scene_radius * 0.1f);
    target = eye + orientation * glm::vec3(0.0f, 0.0f, -distance);
    mode_ = mode;
}
