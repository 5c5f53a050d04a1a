// camera.h: the workbench camera (GLM): a pose (eye position + orientation
// quaternion) that orbit mode turns about a target (turntable about the up
// axis, the default, or a virtual trackball) and walk mode moves with W/A/S/D,
// Q/E and mouse look; perspective or orthographic; Y or Z up.
// In double, in the model's file coordinates: a part far from the origin keeps
// its matrices exact (the core moves them to the model's centre in double).
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

struct oit_model;

class Camera {
public:
    enum class Mode { Orbit, Walk };
    // Turntable: horizontal drags turn about the up axis, vertical drags change
    // the elevation (short of the poles), never a roll, as CAD viewers do.
    // Trackball: Shoemake's virtual trackball, free (rolls too).
    enum class Orbit { Turntable, Trackball };
    // The model's up axis: azimuths turn about it, elevations rise towards it
    // (frame, standard views, turntable, walk).
    enum class Up { Y, Z };

    // Frame the model's bounding sphere like oit_default_camera(azimuth, elevation)
    // does for this aspect ratio (the same matrices for a perspective camera).
    void frame(const oit_model &model, int width, int height, float azimuth_degrees = 30.0f,
               float elevation_degrees = 20.0f);

    // Keep the direction of view, look at the box's centre from where its
    // bounding sphere fits the view (frame selected parts).
    void frame_box(const double box_min[3], const double box_max[3], int width, int height);
    // A standard view of the whole model: azimuth about the up axis, elevation
    // above the horizon (front 0,0; top 0,90; ...), looking at the model's
    // centre from where its bounding sphere fits a width x height view (the
    // pivot returns to the centre, whatever was framed before).
    void set_view_direction(float azimuth_degrees, float elevation_degrees, int width, int height);

    // Column-major matrices for a view of width x height pixels. framed_aspect:
    // the aspect of the view the camera frames (side by side: the whole view,
    // while each half renders at half its width; 0: this one's); the image
    // then shows at least what that view shows along its narrower axis, so a
    // model framed in the whole view stays whole in each half.
    void matrices(int width, int height, double modelview[16], double projection[16],
                  double framed_aspect = 0.0) const;

    // Orbit: a left drag between two points in widget pixels, as orbit_style says.
    void orbit(glm::vec2 from, glm::vec2 to, int width, int height);
    // Virtual trackball between two points in widget pixels.
    void trackball(glm::vec2 from, glm::vec2 to, int width, int height);
    // Turntable by a drag between two points: azimuth from x, elevation from y
    // (half a turn per view height), the up axis kept up (no roll).
    void turntable(glm::vec2 from, glm::vec2 to, int width, int height);
    // The world's up axis as a vector.
    glm::dvec3 up_vector() const;
    // Pan by a pixel delta (both modes) in an image of width x height (framed_aspect
    // as matrices'): the point under the mouse follows it.
    void pan(glm::vec2 delta_pixels, int width, int height, double framed_aspect = 0.0);
    // How much matrices() widens tan(fov / 2) for an image of this aspect framing
    // a view of framed_aspect (1 unless the image's narrower axis is narrower).
    static double widening(double aspect, double framed_aspect);
    // Wheel: orbit moves towards the target, walk moves forwards. steps > 0 is closer.
    void zoom(float steps);
    // Walk: move in the camera's frame (x right, y world up, z forwards) by model radii.
    void walk(glm::vec3 direction);
    // Walk: mouse look by a pixel delta.
    void look(glm::vec2 delta_pixels);

    void set_mode(Mode mode);
    Mode mode() const { return mode_; }
    bool orthographic = false;
    float fov_degrees = 40.0f;
    Orbit orbit_style = Orbit::Turntable;
    Up up = Up::Y;

    // The pose, for presets and saved views.
    glm::dvec3 eye{0.0, 0.0, 1.0};
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0}; // camera to world
    glm::dvec3 target{0.0};                     // orbit centre
    glm::dvec3 scene_centre{0.0};
    double scene_radius = 1.0;

private:
    Mode mode_ = Mode::Orbit;
};
