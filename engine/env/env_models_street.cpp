// Street furniture: bench, lamppost, trash can, bus shelter, fence segment.
#include <cmath>

#include "env/env_model_makers.h"

namespace ug::envmodels {
using envparts::addBox;
using envparts::addCylinder;
using envparts::addLathe;
using envparts::addPrism;
using envparts::Box;
using envparts::MeshBuilder;

namespace {

// Bench dimensions, footprint-centred (the tilted back legs reach y = -0.315).
constexpr float kSeatTop = 0.45f, kSeatFront = 0.32f, kSlatDepth = 0.095f, kSlatGap = 0.015f,
                kSlatThickness = 0.035f, kBenchHalfLength = 0.8f, kFrameX = 0.62f;
constexpr int kSeatSlats = 4;

// A leg frame at x: a front leg, a rail under the slats and a back leg tilted back to carry the
// backrest. Returns the back leg as a box so the backrest can follow it.
Box addLegFrame(MeshBuilder* b, const glm::vec3& at, float x) {
    const float seat_back = kSeatFront - kSeatSlats * kSlatDepth - (kSeatSlats - 1) * kSlatGap;
    // Each piece reaches 5 mm into the one it carries: overlapping, never touching face to face (a face
    // lying on another would be an up-facing face with no sky above it, and flickers in a viewer).
    const float rail_top = kSeatTop - kSlatThickness + 0.005f;
    addBox(b, at + glm::vec3(x - 0.03f, seat_back - 0.01f, rail_top - 0.05f),
           at + glm::vec3(x + 0.03f, kSeatFront - 0.02f, rail_top));
    addBox(b, at + glm::vec3(x - 0.03f, kSeatFront - 0.1f, 0.0f),
           at + glm::vec3(x + 0.03f, kSeatFront - 0.04f, rail_top - 0.01f));
    // Back leg: from the ground under the seat's back edge, tilted back about 12 degrees, to z = 0.9.
    const glm::vec3 foot = at + glm::vec3(x, seat_back + 0.03f, 0.0f),
                    top = at + glm::vec3(x, seat_back - 0.16f, 0.88f);
    const glm::vec3 w = glm::normalize(top - foot), u(1, 0, 0), v = glm::cross(w, u);
    Box leg;
    leg.axes[0] = u;
    leg.axes[1] = v;  // points forward (+Y) and up a little
    leg.axes[2] = w;
    leg.half = {0.03f, 0.03f, 0.5f * glm::length(top - foot)};
    leg.centre = 0.5f * (foot + top);
    // The foot's lower back corner would dip below the ground: lift the box by that much.
    leg.centre.z += leg.half.y * std::abs(v.z) + 1e-4f;
    addBox(b, leg);
    return leg;
}

}  // namespace

void addBench(MeshBuilder* b, const glm::vec3& at) {
    for (int k = 0; k < kSeatSlats; ++k) {
        const float y1 = kSeatFront - float(k) * (kSlatDepth + kSlatGap);
        addBox(b, at + glm::vec3(-kBenchHalfLength, y1 - kSlatDepth, kSeatTop - kSlatThickness),
               at + glm::vec3(kBenchHalfLength, y1, kSeatTop), {8, 1, 1});
    }
    Box leg;
    for (const float x : {-kFrameX, kFrameX}) leg = addLegFrame(b, at, x);
    // Backrest slats on the front of the back legs, over the upper part of their length.
    for (int k = 0; k < 3; ++k) {
        const float s = 0.58f + 0.14f * float(k);  // fraction of the leg's length
        Box slat = leg;
        slat.centre = leg.centre + leg.axes[2] * (leg.half.z * (2.0f * s - 1.0f)) +
                      leg.axes[1] * (leg.half.y + 0.0175f);
        slat.centre.x = at.x;
        slat.half = {kBenchHalfLength, 0.0175f, 0.045f};
        slat.cells = {8, 1, 1};
        addBox(b, slat);
    }
}

TriangleMesh makeBench(uint64_t) {
    MeshBuilder b;
    addBench(&b, {0, 0, 0});
    return b.finish({0.45f, 0.30f, 0.18f});
}

TriangleMesh makeLamppost(uint64_t) {
    MeshBuilder b;
    const int sides = 32;
    // Turned base: a plinth narrowing to a collar around the pole.
    addLathe(&b, {0, 0, 0},
             {{0.0f, 0.0f},
              {0.18f, 0.0f},
              {0.18f, 0.22f},
              {0.11f, 0.34f},
              {0.11f, 0.52f},
              {0.085f, 0.56f},
              {0.0f, 0.56f}},
             sides);
    addCylinder(&b, {0, 0, 0.5f}, {0, 0, 4.0f}, 0.06f, sides);
    // Finial on the pole top.
    addLathe(&b, {0, 0, 3.98f}, {{0.0f, 0.0f}, {0.075f, 0.0f}, {0.075f, 0.03f}, {0.0f, 0.07f}}, sides);
    // Arm to the front, the lamp head hanging from its end.
    const float arm_z = 3.85f, reach = 0.72f;
    addCylinder(&b, {0, 0, arm_z}, {0, reach, arm_z}, 0.035f, 24);
    addCylinder(&b, {0, reach, arm_z + 0.03f}, {0, reach, 3.78f}, 0.03f, 24);
    // Head: glass housing widening upwards, a rim (its underside the drip edge at z = 3.74) and a low
    // conical roof.
    addLathe(&b, {0, reach, 3.74f},
             {{0.0f, -0.34f},
              {0.10f, -0.34f},
              {0.17f, 0.0f},
              {0.28f, 0.0f},
              {0.28f, 0.04f},
              {0.24f, 0.05f},
              {0.0f, 0.10f}},
             48);
    return b.finish({0.12f, 0.16f, 0.14f});
}

TriangleMesh makeTrashCan(uint64_t) {
    MeshBuilder b;
    // One closed profile: a foot, the body, the lid rim overhanging it, a domed lid and a knob.
    addLathe(&b, {0, 0, 0},
             {{0.0f, 0.0f},
              {0.27f, 0.0f},
              {0.27f, 0.03f},
              {0.30f, 0.03f},
              {0.30f, 0.83f},
              {0.33f, 0.83f},
              {0.33f, 0.865f},
              {0.29f, 0.88f},
              {0.16f, 0.895f},
              {0.04f, 0.895f},
              {0.04f, 0.9f},
              {0.0f, 0.9f}},
             40);
    return b.finish({0.20f, 0.28f, 0.22f});
}

TriangleMesh makeBusShelter(uint64_t) {
    MeshBuilder b;
    // Roof: 3.2 x 1.6 m, overhanging the posts by 0.15 m at the sides and 0.25 m at the back.
    addBox(&b, {-1.6f, -0.8f, 2.4f}, {1.6f, 0.8f, 2.5f}, {16, 8, 1});
    // Posts, beam and glass reach into what they carry (no face lying on another).
    for (const float x : {-1.45f, 1.45f}) addBox(&b, {x - 0.05f, -0.6f, 0.0f}, {x + 0.05f, -0.5f, 2.45f});
    addBox(&b, {-1.4f, -0.58f, 2.3f}, {1.4f, -0.52f, 2.45f}, {8, 1, 1});   // header beam under the roof
    addBox(&b, {-1.4f, -0.56f, 0.12f}, {1.4f, -0.54f, 2.32f}, {8, 1, 4});  // glass back wall
    addBench(&b, {0.0f, -0.15f, 0.0f});
    return b.finish({0.35f, 0.38f, 0.40f});
}

TriangleMesh makeFenceSegment(uint64_t) {
    MeshBuilder b;
    for (const float x : {-0.94f, 0.94f}) {
        addBox(&b, {x - 0.045f, -0.045f, 0.0f}, {x + 0.045f, 0.045f, 1.16f});  // into its cap
        addBox(&b, {x - 0.06f, -0.06f, 1.15f}, {x + 0.06f, 0.06f, 1.18f});     // cap: a drip edge all round
    }
    for (const float z : {0.25f, 0.80f})
        addBox(&b, {-0.94f, -0.02f, z}, {0.94f, 0.02f, z + 0.08f}, {8, 1, 1});
    // Pickets in front of the rails: 7 cm wide, 2 cm thick, pointed.
    const std::vector<glm::vec2> picket = {
        {-0.035f, 0.06f}, {0.035f, 0.06f}, {0.035f, 1.0f}, {0.0f, 1.08f}, {-0.035f, 1.0f}};
    for (int k = 0; k < 14; ++k) {
        const float x = -0.8125f + 0.125f * float(k);
        addPrism(&b, picket, {x, 0.04f, 0.0f}, {1, 0, 0}, {0, 0, 1}, 0.02f);  // extruded along -Y to y = 0.02
    }
    return b.finish({0.46f, 0.36f, 0.25f});
}

}  // namespace ug::envmodels
