// compose.vert: the full-screen triangle of common/fullscreen.vert, plus the
// outputs common/shade.glsl declares as inputs (unused by the compose pass,
// which shades from the buffer, but the stages must link).
out vec3 v_eye_position;
out vec3 v_eye_normal;
flat out uint v_component;
flat out uint v_section_cap;

void main()
{
    vec2 corner = vec2(float((gl_VertexID & 1) << 2), float((gl_VertexID & 2) << 1)) - 1.0;
    gl_Position = vec4(corner, 0.0, 1.0);
    v_eye_position = vec3(0.0);
    v_eye_normal = vec3(0.0);
    v_component = 0u;
    v_section_cap = 0u;
}
