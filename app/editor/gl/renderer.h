// The viewport renderer (DESIGN.md "Rendering"): sky, terrain or a ground grid, and the details by
// instancing. The Ghost Tile's candidate frames are uploaded once (an SSBO, 32 bytes a candidate); each
// detail type has one vertex/index buffer holding its mesh LODs and one instance buffer of 8-byte packed
// (tile, candidate) instances (render_data.h), refilled from the CPU culling and LOD buckets whenever the
// view changes; a frame issues one draw per detail type and LOD (LOD 3: impostor point sprites).
// The renderer only draws what it is given and exposes numbers; it decides nothing about instances.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "editor/gl/shader_program.h"
#include "editor/markers.h"
#include "editor/orbit_camera.h"
#include "editor/render_data.h"
#include "field/bounds.h"
#include "ghosttile/ghost_tile.h"
#include "mesh/triangle_mesh.h"

namespace ug::editor::gl {

struct RenderStats {
    uint64_t triangles = 0;   // terrain + detail meshes (LOD 0-2) drawn this frame; not sky, grid, UI
    uint64_t points = 0;      // impostor point sprites drawn this frame (one per far instance)
    uint64_t draw_calls = 0;  // scene draws this frame (sky, ground, one per non-empty type x LOD); not UI
    uint64_t instances_drawn = 0;
    std::array<uint64_t, kLodCount> lod_instances{};  // instances drawn per LOD (3 = impostors)
    uint64_t tiles_visible = 0;
    uint64_t tiles_culled = 0;
    double bucket_ms = 0.0;  // CPU culling + LOD bucketing + upload, when the view changed (else 0)
};

class Renderer {
public:
    Renderer() = default;
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    bool init(const std::string& shaders_dir, std::string* error);

    // The static scene: terrain (may be empty: a ground grid at the extent's floor is drawn instead),
    // detail meshes and the candidate frames. The pointed-to meshes must outlive the renderer's use.
    void setScene(const Bounds& extent, const TriangleMesh* terrain, const std::vector<DetailLodMesh>* meshes,
                  const CandidateSet& candidates, float tile_size_m);
    // The instances (kept by pointer: the owner keeps them alive; null: none). Call again whenever their
    // content changed (a live update): the view-dependent buckets are rebuilt on the next frame. A type's
    // instance buffer only grows (by half again when it must), so a stroke does not reallocate per stamp.
    void setInstances(const RenderInstances* instances);
    // Forgets the scene and the instances (before the document they point into goes away).
    void clearScene() { releaseScene(); }
    // Overlay lines and points (skeletons, brush), drawn over everything; uploaded now (small).
    void setMarkers(const MarkerGeometry& markers);
    // The outliner's eye toggle: a hidden type is skipped when drawing (its instances stay bucketed, so
    // showing it again costs nothing). View state only: not an edit, never saved. Types default to visible.
    void setTypeVisible(size_t type, bool visible);

    void render(const OrbitCamera& camera, int width_px, int height_px, const LodSettings& lod);
    const RenderStats& stats() const { return stats_; }

    // The default framebuffer's back buffer as RGBA8, rows top-down (read before the UI is drawn on it).
    void readPixels(int width_px, int height_px, std::vector<uint8_t>* rgba) const;

private:
    struct TypeBuffers {
        unsigned vao = 0, impostor_vao = 0;
        unsigned vertex_buffer = 0, index_buffer = 0, instance_buffer = 0;
        uint32_t instance_capacity = 0;
    };
    void releaseScene();
    void drawDetails(const OrbitCamera& cam, const glm::mat4& view, const glm::mat4& view_proj, const glm::vec3& eye,
                     int height, const LodSettings& lod, float fog_density);

    ShaderProgram sky_, terrain_, detail_, impostor_, grid_, marker_;
    unsigned marker_vao_ = 0, marker_buffer_ = 0;
    uint32_t marker_line_vertices_ = 0, marker_points_ = 0;
    unsigned empty_vao_ = 0;
    unsigned terrain_vao_ = 0, terrain_vertices_ = 0, terrain_indices_ = 0;
    uint32_t terrain_index_count_ = 0;
    unsigned candidate_buffer_ = 0;
    std::vector<TypeBuffers> types_;
    std::vector<uint8_t> type_visible_;  // per type, 1 = drawn; missing entries are visible
    const std::vector<DetailLodMesh>* meshes_ = nullptr;
    const RenderInstances* instances_ = nullptr;
    Bounds extent_{};
    float tile_size_m_ = 0.5f;
    bool has_scene_ = false;

    DrawBuckets buckets_;
    glm::mat4 last_view_proj_{0.0f};
    LodSettings last_lod_{};
    bool buckets_dirty_ = true;
    RenderStats stats_;
};

}  // namespace ug::editor::gl
