// The viewport renderer (docs/architecture.md "Rendering"): sky, terrain or a ground grid, and the details by
// instancing. The Ghost Tile's candidate frames are uploaded once (an SSBO, 32 bytes a candidate); each
// detail type has one vertex/index buffer holding its mesh LODs and one resident instance buffer of 8-byte
// packed (tile, candidate) instances (render_data.h) in which every tile owns a slot. A live result
// re-uploads only the slots of the tiles it changed (glBufferSubData per slot; the whole buffer only when
// the type's array had to grow). When the view moves, the CPU culls tiles, picks a LOD per tile and type
// and writes one indirect command per visible tile and type (baseInstance = the tile's slot; the packed
// instance is an instanced vertex attribute, which honours baseInstance on GL 4.3 where the shader has no
// gl_BaseInstance); a frame then issues one glMultiDrawElementsIndirect per type and mesh LOD and one
// glMultiDrawArraysIndirect per type for the impostor point sprites. After the scene: the primitives'
// translucent hulls (blended, depth-tested, no depth write), then the overlay lines and points.
// Static meshes (io/mesh_instances.h: environmental objects, snow, icicles): each entry one vertex buffer,
// one index buffer holding its levels of detail (static_lod.h: up to 3 meshoptimizer levels; a large entry
// drawn once, such as a terrain snow chunk, split into 2 m pieces first) and one per-instance buffer
// (render_data.h GpuStaticInstance, sorted into 8 m chunks), culled as a whole by the union of its
// instances' boxes, then per chunk or piece, each at the coarsest level whose error stays under a pixel
// (none below half a pixel), and drawn with one glDrawElementsInstancedBaseInstance per visible piece or
// run of visible chunks at one level, lit like the details (lit_surface.frag,
// box-projected texture), casting into and receiving from the shadow map, and in the occlusion target.
// The terrain keeps its own path (terrain.vert's slope tint, world-XY texture with a turned second
// lookup), so today's pictures are unchanged.
// The renderer only draws what it is given and exposes numbers; it decides nothing about instances.
//
// Light that shows contact (ViewportLook): before the scene, a depth-only pass from the sun into a shadow
// map (shadow_frame.h: fitted to what the camera sees; the casters culled for the sun's view with the
// camera's LOD choice, impostors cast none); the scene is drawn into an offscreen colour + depth target,
// then composited onto the caller's framebuffer with screen-space ambient occlusion (ambient_occlusion.frag
// at half resolution, blurred by ao_blur.frag, applied by composite.frag); the hulls go into the offscreen target before that (they
// are depth-tested against the scene), the overlays onto the caller's framebuffer after it. render() draws into whatever framebuffer is bound when it is
// called and leaves it bound.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "editor/gl/shader_program.h"
#include "editor/markers.h"
#include "editor/orbit_camera.h"
#include "editor/render_data.h"
#include "editor/shadow_frame.h"
#include "editor/static_lod.h"
#include "field/bounds.h"
#include "material/material.h"
#include "ghosttile/ghost_tile.h"
#include "mesh/triangle_mesh.h"

namespace ug::editor::gl {

struct RenderStats {
    uint64_t triangles = 0;   // terrain + static meshes + detail meshes (LOD 0-2) drawn this frame; not sky, grid, UI
    uint64_t shadow_triangles = 0;  // drawn again into the shadow map (static meshes + detail meshes)
    uint64_t shadow_points = 0;     // impostor sprites drawn into the shadow map (the far instances' casters)
    uint64_t shadow_map_draws = 0;  // 1 when this frame drew the sun's map (0: kept from an earlier frame)
    uint64_t static_meshes_drawn = 0;   // static-mesh entries that passed the frustum test this frame
    uint64_t static_meshes_culled = 0;
    uint64_t points = 0;      // impostor point sprites drawn this frame (one per far instance)
    uint64_t draw_calls = 0;  // scene draw calls: sky, ground, one per visible piece or run of visible chunks at one level of a static mesh, one multi-draw per non-empty type x LOD; not UI
    uint64_t indirect_commands = 0;  // commands the multi-draws ran (one per visible tile run x type)
    uint64_t instances_drawn = 0;
    std::array<uint64_t, kLodCount> lod_instances{};  // instances drawn per LOD (3 = impostors)
    uint64_t tiles_visible = 0;
    uint64_t tiles_culled = 0;
    double command_ms = 0.0;  // CPU culling + LOD + command building + upload, when the view changed (else 0)
    // The latest uploadTiles() (a live result): tiles re-packed and bytes sent to the GPU.
    uint64_t tiles_uploaded = 0;
    uint64_t bytes_uploaded = 0;
    uint64_t tiles_resident = 0;
    // The latest setStaticMeshes(): its levels of detail built (static_lod.h) and everything uploaded; the
    // entries it uploaded and those whose buffers it kept from the previous set (staticEntryKey).
    double static_lod_ms = 0.0;
    double static_upload_ms = 0.0;
    uint64_t static_entries_uploaded = 0;
    uint64_t static_entries_kept = 0;
    uint64_t static_triangles = 0;  // static-mesh triangles drawn this frame (part of `triangles`)
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
    // `terrain_material` (may be null: the default ground) is copied; the meshes' materials are read from
    // the meshes (render_data.h DetailLodMesh::material). Textures are uploaded once per image.
    void setScene(const Bounds& extent, const TriangleMesh* terrain, const std::vector<DetailLodMesh>* meshes,
                  const CandidateSet& candidates, float tile_size_m, const SurfaceMaterial* terrain_material = nullptr);
    // The resident tiles (kept by pointer: the owner keeps them alive; null: none) and what the latest
    // update changed in them: only those slot ranges are uploaded (the whole type buffer when `uploads`
    // says so). The indirect commands are rebuilt on the next frame.
    void uploadTiles(const ResidentTiles* tiles, const TileUploads& uploads);
    // The outliner's eye toggle: hidden types are not drawn (their commands are skipped; their tiles stay
    // resident, so showing them again costs nothing). View state only: not an edit, never saved. All types
    // are visible after setScene().
    void setTypeVisible(size_t type, bool visible);
    // The static meshes, their levels of detail built (in parallel, static_lod.h) and copied into GPU
    // buffers now (the list need not outlive the call; null or empty:
    // none). Independent of setScene(); drawn only while a scene is set. Replaces the previous list.
    void setStaticMeshes(const std::vector<MeshInstances>* meshes);
    // Forgets the scene and the instances (before the document they point into goes away).
    void clearScene() { releaseScene(); }
    // Hull triangles (translucent) and overlay lines and points (skeletons, brush, tile grid, anchors,
    // sphere sets), drawn after the scene; uploaded now (small, capped by markers.h).
    void setMarkers(const MarkerGeometry& markers);
    // The channel view's translucent triangles (channel_map.h), uploaded now and drawn every frame until
    // replaced (empty: none); `showChannelOverlay` hides them without uploading again.
    void setChannelOverlay(const std::vector<MarkerVertex>& triangles);
    void showChannelOverlay(bool visible) { overlay_visible_ = visible; }

    void setLook(const ViewportLook& look) { look_ = look; }
    const ViewportLook& look() const { return look_; }

    void render(const OrbitCamera& camera, int width_px, int height_px, const LodSettings& lod);
    const RenderStats& stats() const { return stats_; }

    // The default framebuffer's back buffer as RGBA8, rows top-down (read before the UI is drawn on it).
    void readPixels(int width_px, int height_px, std::vector<uint8_t>* rgba) const;

    // A picture of `mesh` (object space, Z up) seen from the front, to the left and above, lit by the
    // sun, framed to fill a px x px RGBA8 texture on a clear background (the Environment window's
    // palette). The texture is the renderer's (freed with it); 0 on failure. *coverage: the fraction of
    // the pixels the mesh covers (a test that something was drawn, and framed).
    unsigned meshThumbnail(const TriangleMesh& mesh, const SurfaceMaterial& material, int px, float* coverage);
    void releaseThumbnails();  // every meshThumbnail texture (a new document's palette replaces them)

private:
    struct TypeBuffers {
        // The impostors' runs come from the camera's commands or the shadow pass's: one VAO for each.
        unsigned vao = 0, impostor_vao = 0, shadow_impostor_vao = 0;
        unsigned vertex_buffer = 0, index_buffer = 0, instance_buffer = 0;
        uint32_t instance_capacity = 0;  // elements the GPU buffer holds
        bool visible = true;
        unsigned texture = 0;            // owned by textures_ (shared between types using one image)
    };
    // A material's GL state: its texture (0: none) and the uniforms lit_surface.frag reads.
    void bindMaterial(const ShaderProgram& program, const SurfaceMaterial& m, unsigned texture, int mode) const;
    using TextureCache = std::vector<std::pair<const TextureImage*, unsigned>>;
    unsigned uploadTexture(const std::shared_ptr<const TextureImage>& image, TextureCache* cache);
    void releaseScene();
    void releaseStaticMeshes();
    // Which static meshes a pass draws: all (the shadow pass), or the matte or the glossy ones (each lit by
    // its own program, lit_surface.frag's GLOSSY).
    enum class StaticSubset { All, Matte, Glossy };
    // The static meshes of `subset` in the frustum of `view_proj`, each piece or chunk at the level chosen
    // from `eye` (static_lod.h; the shadow pass makes the same choice): lit (shadow false) or depth only.
    void drawStaticMeshes(const ShaderProgram& program, const glm::mat4& view_proj, const glm::vec3& eye,
                          float pixels_per_radian, bool shadow, StaticSubset subset = StaticSubset::All);
    void releaseTargets();
    // (Re)builds the commands of `draws` when its view, the LOD settings or the tiles changed.
    struct IndirectBuffer {
        unsigned id = 0;
        size_t capacity_bytes = 0;
        size_t points_offset = 0;  // bytes: the impostor commands follow the element commands
        unsigned runs_id = 0;      // the point commands' PointRuns (a per-instance attribute)
        size_t runs_capacity_bytes = 0;
    };
    // Builds the commands of `draws` (cull + LOD per tile) for `params` and uploads them to `buffer`.
    void uploadDraws(const ViewParams& params, const LodSettings& lod, IndirectDraws* draws, IndirectBuffer* buffer);
    void shadowPass(const OrbitCamera& cam, const glm::vec3& eye, int height, const LodSettings& lod);
    void ensureSceneTarget(int width, int height);
    void drawDetails(const OrbitCamera& cam, const glm::mat4& view, const glm::mat4& view_proj, const glm::vec3& eye,
                     int height, const LodSettings& lod, float fog_density);
    void drawMeshLods(const ShaderProgram& program, const IndirectDraws& draws, const IndirectBuffer& buffer,
                      float pixels_per_radian, const LodSettings& lod, bool shadow);
    // The impostor groups of `draws` as point sprites: lit by `impostor_`, or (shadow) depth only by
    // `shadow_impostor_` into the sun's map, for the types whose sprites are at least `min_caster_m` across.
    void drawImpostors(const ShaderProgram& program, const IndirectDraws& draws, const IndirectBuffer& buffer,
                       float pixels_per_radian, const LodSettings& lod, bool shadow, float min_caster_m = 0.0f);
    void composite(unsigned target_fbo, int width, int height, const OrbitCamera& cam);
    void drawHulls(const glm::mat4& view_proj);
    void drawOverlays(const glm::mat4& view_proj);
    void setLighting(const ShaderProgram& program, const glm::vec3& eye, float fog_density) const;

    ShaderProgram sky_, terrain_, detail_, impostor_, grid_, marker_, hull_;
    ShaderProgram shadow_detail_, shadow_impostor_, ambient_occlusion_, ao_blur_, composite_, static_mesh_, shadow_static_;
    ShaderProgram static_glossy_;  // static_mesh_ with lit_surface.frag's GLOSSY: smooth materials only
    ViewportLook look_;
    // The shadow map (a depth texture with compare mode) and its framebuffer; the offscreen scene target.
    unsigned shadow_fbo_ = 0, shadow_depth_ = 0;
    int shadow_px_ = 0;
    glm::mat4 shadow_texture_{1.0f};
    float shadow_offset_m_ = 0.0f;
    bool shadow_valid_ = false;
    unsigned scene_fbo_ = 0, scene_color_ = 0, scene_depth_ = 0;
    unsigned ao_fbo_[2] = {0, 0}, ao_texture_[2] = {0, 0};  // half resolution: raw, blurred
    int scene_w_ = 0, scene_h_ = 0;
    float ao_radius_m_ = 0.1f;
    IndirectDraws shadow_draws_;
    IndirectBuffer indirect_, shadow_indirect_;
    glm::vec3 last_shadow_eye_{NAN};
    ShadowFrame held_shadow_;          // the frame the map was last drawn for (its view_proj: the casters' view)
    // Whether that map holds every caster of its square (drawn while moving), or only those whose shadow
    // reaches the view it was drawn for, `shadow_receiver_` (a still view): only the former is held.
    bool held_shadow_complete_ = false;
    glm::mat4 shadow_receiver_{0.0f};
    glm::vec3 previous_eye_{0.0f};     // the eye of the previous frame: whether the camera is moving
    bool has_previous_eye_ = false;
    bool shadow_draws_dirty_ = true;
    bool shadow_map_dirty_ = true;  // the casters changed since the map was drawn
    unsigned marker_vao_ = 0, marker_buffer_ = 0;
    uint32_t marker_hull_vertices_ = 0, marker_line_vertices_ = 0, marker_points_ = 0, marker_dots_ = 0;
    unsigned overlay_vao_ = 0, overlay_buffer_ = 0;
    uint32_t overlay_vertices_ = 0;
    bool overlay_visible_ = true;
    unsigned empty_vao_ = 0;
    unsigned terrain_vao_ = 0, terrain_vertices_ = 0, terrain_indices_ = 0;
    uint32_t terrain_index_count_ = 0;
    unsigned candidate_buffer_ = 0;
    unsigned silhouette_array_ = 0;
    TextureCache textures_;  // material images -> GL textures (the scene's)
    std::vector<unsigned> thumbnails_;  // meshThumbnail's textures
    struct StaticBuffers {
        unsigned vao = 0, vertex_buffer = 0, index_buffer = 0, instance_buffer = 0;  // indices: every level
        Bounds bounds;  // engine space, all instances
        StaticEntryLods lods;  // levels, pieces and the instance buffer's 8 m chunks, culled and chosen each frame
        SurfaceMaterial material;
        glm::vec3 color{0.6f};
        unsigned texture = 0;  // owned by static_textures_
        bool casts_shadow = true;  // castsSunShadow
        bool glossy = false;       // materialGloss > 0: drawn by static_glossy_
        StaticEntryKey key;        // what they were made of: a later set's equal entry keeps them
    };
    StaticBuffers uploadStaticEntry(const MeshInstances& entry, StaticLodMesh lods);
    void releaseStaticBuffers(StaticBuffers* b);
    std::vector<StaticBuffers> statics_;
    std::vector<SunCaster> static_casters_;  // what of statics_ casts into the sun's map
    std::vector<StaticDrawRange> static_draws_;  // scratch, per entry per pass
    double static_lod_ms_ = 0.0, static_upload_ms_ = 0.0;  // the latest setStaticMeshes()
    StaticLodCache static_lod_cache_;
    TextureCache static_textures_;
    SurfaceMaterial terrain_material_;
    unsigned terrain_texture_ = 0;  // impostor silhouettes, kCoverageElevations layers per type
    std::vector<TypeBuffers> types_;
    const std::vector<DetailLodMesh>* meshes_ = nullptr;
    const ResidentTiles* tiles_ = nullptr;
    Bounds extent_{};
    float tile_size_m_ = 0.5f;
    bool has_scene_ = false;

    IndirectDraws draws_;
    glm::mat4 last_view_proj_{0.0f};
    LodSettings last_lod_{};
    bool draws_dirty_ = true;
    uint64_t upload_tiles_ = 0, upload_bytes_ = 0;  // the latest uploadTiles()
    RenderStats stats_;
};

}  // namespace ug::editor::gl
