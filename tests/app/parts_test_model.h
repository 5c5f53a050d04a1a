// parts_test_model.h: models built in memory for the Parts tab's tests
// (test_parts_panel.cpp, test_parts_tree.cpp): parts from plain arrays, and
// optionally an assembly tree, finished by oit_model_finish.
#pragma once

#include <QString>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "oit.h"

namespace parts_test {

// A model freed on destruction.
struct Model {
    oit_model m{};
    Model() = default;
    Model(const Model &) = delete;
    Model &operator=(const Model &) = delete;
    ~Model() { oit_model_free(&m); }
};

struct Part {
    std::string name;
    float colour[3];
    std::vector<float> positions;    // 3 per vertex
    std::vector<uint32_t> triangles; // 3 per triangle, indices into this part's vertices
    uint32_t node = OIT_NO_NODE;     // the assembly node it hangs under (with a tree)
};

struct Node {
    std::string name;
    uint32_t parent; // an earlier node, or OIT_NO_NODE
};

// false (and the message) if oit_model_finish refuses it; nodes empty: no tree
inline bool build(Model &out, const std::vector<Part> &parts, QString *message, const std::vector<Node> &nodes = {})
{
    size_t vertices = 0, triangles = 0;
    for (const Part &p : parts) {
        vertices += p.positions.size() / 3;
        triangles += p.triangles.size() / 3;
    }
    oit_model &m = out.m;
    m.vertex_count = uint32_t(vertices);
    m.triangle_count = uint32_t(triangles);
    m.component_count = uint32_t(parts.size());
    m.positions = static_cast<float *>(malloc(vertices * 3 * sizeof(float)));
    m.indices = static_cast<uint32_t *>(malloc(std::max<size_t>(triangles, 1) * 3 * sizeof(uint32_t)));
    m.components = static_cast<oit_component *>(calloc(std::max<size_t>(parts.size(), 1), sizeof(oit_component)));
    if (!nodes.empty()) {
        m.node_count = uint32_t(nodes.size());
        m.nodes = static_cast<oit_model_node *>(calloc(nodes.size(), sizeof(oit_model_node)));
        m.component_node = static_cast<uint32_t *>(malloc(std::max<size_t>(parts.size(), 1) * sizeof(uint32_t)));
        for (size_t n = 0; n < nodes.size(); ++n) {
            snprintf(m.nodes[n].name, sizeof m.nodes[n].name, "%s", nodes[n].name.c_str());
            m.nodes[n].parent = nodes[n].parent;
        }
    }
    size_t v = 0, t = 0;
    for (size_t c = 0; c < parts.size(); ++c) {
        const Part &p = parts[c];
        oit_component &comp = m.components[c];
        snprintf(comp.name, sizeof comp.name, "%s", p.name.c_str());
        std::copy(p.colour, p.colour + 3, comp.colour);
        comp.opacity = 1.0f;
        comp.first_triangle = uint32_t(t);
        comp.triangle_count = uint32_t(p.triangles.size() / 3);
        std::copy(p.positions.begin(), p.positions.end(), m.positions + v * 3);
        for (size_t k = 0; k < p.triangles.size(); ++k)
            m.indices[t * 3 + k] = uint32_t(v) + p.triangles[k];
        if (m.component_node)
            m.component_node[c] = p.node;
        v += p.positions.size() / 3;
        t += p.triangles.size() / 3;
    }
    oit_error err{};
    if (oit_model_finish(&m, true, &err) != OIT_OK) {
        *message = QString::fromUtf8(err.message);
        return false;
    }
    return true;
}

// An axis-aligned square facing +z (counter-clockwise seen from +z): two triangles.
inline Part square(const std::string &name, float cx, float cy, float z, float half, uint32_t node = OIT_NO_NODE)
{
    Part p{name, {0.2f, 0.5f, 0.8f}, {}, {0, 1, 2, 0, 2, 3}, node};
    p.positions = {cx - half, cy - half, z, cx + half, cy - half, z, cx + half, cy + half, z, cx - half, cy + half, z};
    return p;
}

} // namespace parts_test
