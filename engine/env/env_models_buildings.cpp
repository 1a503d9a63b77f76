// Built structures: the facade unit (the Montmartre scene's building block) and the fountain.
#include "env/env_model_makers.h"

namespace ug::envmodels {
using envparts::addBox;
using envparts::addCylinder;
using envparts::addLathe;
using envparts::MeshBuilder;

namespace {

// Facade layout (env_models.h): the wall spans x in [-2, 2], y in [-0.2, 0.2], z in [0, 6].
constexpr float kHalfWidth = 2.0f, kBack = -0.2f, kFront = 0.2f, kHeight = 6.0f, kRecess = 0.2f;
constexpr float kWindowHalfWidth = 0.45f, kWindowHeight = 1.4f;
constexpr float kWindowX[2] = {-1.0f, 1.0f}, kWindowBottom[2] = {1.0f, 3.9f};

// The balcony on the upper floor: a slab in front of both upper windows and a railing of balusters.
void addBalcony(MeshBuilder* b) {
    const float half = 1.7f, depth = 0.7f, top = 3.0f, rail = 3.9f;
    addBox(b, {-half, kFront, top - 0.12f}, {half, kFront + depth, top}, {12, 3, 1});
    const float y_out = kFront + depth;
    addBox(b, {-half, y_out - 0.05f, rail}, {half, y_out, rail + 0.05f}, {12, 1, 1});  // front handrail
    for (const float x : {-half, half - 0.05f})
        addBox(b, {x, kFront, rail}, {x + 0.05f, y_out - 0.05f, rail + 0.05f}, {1, 3, 1});  // side handrails
    // Balusters reach 1 cm into the slab and the handrail: overlapping, never face on face.
    const float bar = 0.02f;
    for (int k = 0; k <= 28; ++k) {  // front balusters
        const float x = -half + 0.025f + (2.0f * half - 0.05f) * float(k) / 28.0f;
        addBox(b, {x - 0.5f * bar, y_out - 0.035f, top - 0.01f},
               {x + 0.5f * bar, y_out - 0.015f, rail + 0.01f});
    }
    for (const float x : {-half + 0.025f, half - 0.025f})
        for (int k = 0; k < 5; ++k) {  // side balusters
            const float y = kFront + 0.1f + 0.11f * float(k);
            addBox(b, {x - 0.5f * bar, y - 0.5f * bar, top - 0.01f},
                   {x + 0.5f * bar, y + 0.5f * bar, rail + 0.01f});
        }
}

// A window in the opening x in [x0, x1], z in [bottom, bottom + kWindowHeight]: a frame with a mullion
// and a transom standing in the recess (sunk 1 cm into the reveals, so no face lies on another), the
// sill, and a pair of open shutters on the wall face beside it.
void addWindow(MeshBuilder* b, float x0, float x1, float bottom) {
    const float inner = kFront - kRecess, top = bottom + kWindowHeight, w = 0.06f, d = 0.06f, sink = 0.01f;
    const float xm = 0.5f * (x0 + x1), zt = bottom + 0.7f * kWindowHeight;
    addBox(b, {x0 - sink, inner, bottom - sink}, {x0 + w, inner + d, top + sink});  // jambs
    addBox(b, {x1 - w, inner, bottom - sink}, {x1 + sink, inner + d, top + sink});
    addBox(b, {x0 + w, inner, bottom - sink}, {x1 - w, inner + d, bottom + w}, {2, 1, 1});  // bottom rail
    addBox(b, {x0 + w, inner, top - w}, {x1 - w, inner + d, top + sink}, {2, 1, 1});        // head
    addBox(b, {xm - 0.025f, inner, bottom + w - sink}, {xm + 0.025f, inner + d, top - w + sink});  // mullion
    for (const float xa : {x0 + w, xm + 0.025f})                                                   // transom
        addBox(b, {xa, inner, zt - 0.025f}, {xa + (xm - 0.025f - x0 - w), inner + d, zt + 0.025f});
    // The sill: a slab flush with the recess floor, protruding from the wall face; its underside is
    // the drip edge.
    addBox(b, {x0 - 0.06f, kFront, bottom - 0.06f}, {x1 + 0.06f, kFront + 0.07f, bottom}, {4, 1, 1});
    const float shutter = 0.5f * (x1 - x0);
    addBox(b, {x0 - 0.02f - shutter, kFront, bottom + 0.02f}, {x0 - 0.02f, kFront + 0.03f, top}, {1, 1, 3});
    addBox(b, {x1 + 0.02f, kFront, bottom + 0.02f}, {x1 + 0.02f + shutter, kFront + 0.03f, top}, {1, 1, 3});
}

}  // namespace

TriangleMesh makeFacade(uint64_t) {
    MeshBuilder b;
    // Back layer: the solid wall behind the window recesses (its face shows through the openings).
    addBox(&b, {-kHalfWidth, kBack, 0.0f}, {kHalfWidth, kFront - kRecess, kHeight}, {8, 1, 12});
    // Front layer: full-height piers between and beside the openings, and between the piers, spandrels
    // below, between and above the windows. The pieces abut at vertical faces only, so every up-facing
    // face (recess floors, the wall top) is exposed.
    const float inner = kFront - kRecess;
    const float gap_x[2][2] = {{kWindowX[0] - kWindowHalfWidth, kWindowX[0] + kWindowHalfWidth},
                               {kWindowX[1] - kWindowHalfWidth, kWindowX[1] + kWindowHalfWidth}};
    addBox(&b, {-kHalfWidth, inner, 0.0f}, {gap_x[0][0], kFront, kHeight}, {1, 1, 12});
    addBox(&b, {gap_x[0][1], inner, 0.0f}, {gap_x[1][0], kFront, kHeight}, {2, 1, 12});
    addBox(&b, {gap_x[1][1], inner, 0.0f}, {kHalfWidth, kFront, kHeight}, {1, 1, 12});
    for (const auto& gap : gap_x) {
        float z0 = 0.0f;
        for (const float bottom : kWindowBottom) {
            addBox(&b, {gap[0], inner, z0}, {gap[1], kFront, bottom}, {2, 1, 2});
            z0 = bottom + kWindowHeight;
            addWindow(&b, gap[0], gap[1], bottom);
        }
        addBox(&b, {gap[0], inner, z0}, {gap[1], kFront, kHeight}, {2, 1, 1});
    }
    // Cornice along the top, another drip edge.
    addBox(&b, {-kHalfWidth, kFront, kHeight - 0.18f}, {kHalfWidth, kFront + 0.14f, kHeight}, {16, 1, 1});
    addBalcony(&b);
    return b.finish({0.80f, 0.74f, 0.62f});
}

TriangleMesh makeFountain(uint64_t) {
    MeshBuilder b;
    const int sides = 48;
    // Basin: floor at z = 0.15, ring wall from r = 0.85 to 1.0, 0.5 m high, a rim overhanging both
    // sides of the wall (its undersides are drip edges).
    addLathe(&b, {0, 0, 0},
             {{0.0f, 0.0f},
              {1.0f, 0.0f},
              {1.0f, 0.42f},
              {1.05f, 0.42f},
              {1.05f, 0.5f},
              {0.81f, 0.5f},
              {0.81f, 0.42f},
              {0.85f, 0.42f},
              {0.85f, 0.15f},
              {0.0f, 0.15f}},
             sides);
    // Column on a plinth.
    addLathe(&b, {0, 0, 0},
             {{0.0f, 0.1f}, {0.22f, 0.1f}, {0.22f, 0.28f}, {0.13f, 0.36f}, {0.11f, 1.1f}, {0.0f, 1.1f}}, 32);
    // Bowl: a cup flaring from the column to a rim of radius 0.5 m, hollow on top.
    addLathe(&b, {0, 0, 0},
             {{0.0f, 1.0f},
              {0.12f, 1.0f},
              {0.42f, 1.22f},
              {0.5f, 1.3f},
              {0.5f, 1.35f},
              {0.45f, 1.35f},
              {0.0f, 1.24f}},
             sides);
    // Spout.
    addCylinder(&b, {0, 0, 1.2f}, {0, 0, 1.46f}, 0.035f, 16);  // into the knob
    addLathe(&b, {0, 0, 1.45f}, {{0.0f, 0.0f}, {0.06f, 0.0f}, {0.06f, 0.03f}, {0.0f, 0.06f}}, 16);
    return b.finish({0.62f, 0.60f, 0.56f});
}

TriangleMesh makeFountainWater(uint64_t) {
    // The basin's water: a disc whose top, 0.38 m up, lies 4 cm under the wall's inner lip, reaching 1 cm
    // into the wall (parts may overlap). It stands on the ground like every model (z = 0 is the ground),
    // the part below the basin floor hidden in the fountain. A separate object, so that the water has a
    // material of its own and a fountain can stand dry.
    MeshBuilder b;
    addLathe(&b, {0, 0, 0}, {{0.0f, 0.0f}, {0.86f, 0.0f}, {0.86f, 0.38f}, {0.0f, 0.38f}}, 48);
    return b.finish({0.05f, 0.11f, 0.12f});
}

}  // namespace ug::envmodels
