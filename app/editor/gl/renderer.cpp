#include "editor/gl/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include <epoxy/gl.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "editor/shadow_frame.h"
#include "material/uv_projection.h"

namespace ug::editor::gl {

namespace {

// UG_SHADOW_REDRAW_ALWAYS=1: every swap of static meshes and every live result redraws the sun's map, as
// before the map was kept across swaps that change no caster; the GUI tests compare the pictures.
bool shadowRedrawnOnEverySwap() {
    static const bool always = std::getenv("UG_SHADOW_REDRAW_ALWAYS") != nullptr;
    return always;
}

// UG_STATIC_REUPLOAD_ALWAYS=1: every swap uploads every static entry again (the GUI tests compare the
// pictures with and without).
bool staticsReuploadedOnEverySwap() {
    static const bool always = std::getenv("UG_STATIC_REUPLOAD_ALWAYS") != nullptr;
    return always;
}

const glm::vec3 kSunDir = glm::normalize(glm::vec3(0.45f, -0.50f, 0.74f));
// The smallest far sprite, in shadow-map texels, that is drawn into the map (Renderer::shadowPass); per
// instance, through a band up to 1.5 times that (detail_impostor.vert).
constexpr float kMinCasterTexels = 8.0f;

// What the candidate SSBO holds per candidate (std430: two vec4).
struct GpuCandidateFrame {
    float position_scale[4];
    float rotation[4];
};
static_assert(sizeof(GpuCandidateFrame) == 32);

// The shadow map's texture unit (unit 0 is left to the material textures).
constexpr GLint kShadowUnit = 1;
constexpr GLint kSilhouetteUnit = 5;
// lit_surface.frag's u_texture_mode: how a surface's texture coordinates come about (material/uv_projection.h).
constexpr int kTextureBoxModel = 1;  // box projection of the model-space position (detail types)
constexpr int kTextureWorldXY = 2;   // world X and Y (the terrain)

GLint loc(const ShaderProgram& p, const char* name) { return glGetUniformLocation(p.id, name); }

// Pixels per metre at unit depth: the impostors' point size (u_point_scale) and thinning (ViewParams).
float pointScale(const OrbitCamera& cam, int height) { return 0.5f * float(height) / std::tan(0.5f * cam.fov_y_rad); }

// The bound texture's filtering and wrapping (both axes alike).
void setSampling(GLenum target, GLint min_filter, GLint mag_filter, GLint wrap) {
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, min_filter);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, mag_filter);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, wrap);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, wrap);
}

// Interleaved position + normal, shared by the terrain, the detail meshes and the static meshes.
void uploadMesh(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                const std::vector<uint32_t>& indices, GLuint* vao, GLuint* vbo, GLuint* ebo) {
    std::vector<float> interleaved(positions.size() * 6);
    for (size_t i = 0; i < positions.size(); ++i) {
        std::memcpy(&interleaved[i * 6], &positions[i].x, 3 * sizeof(float));
        const glm::vec3 n = i < normals.size() ? normals[i] : glm::vec3(0.0f, 0.0f, 1.0f);
        std::memcpy(&interleaved[i * 6 + 3], &n.x, 3 * sizeof(float));
    }
    glGenVertexArrays(1, vao);
    glBindVertexArray(*vao);
    glGenBuffers(1, vbo);
    glBindBuffer(GL_ARRAY_BUFFER, *vbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(interleaved.size() * sizeof(float)), interleaved.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
    glGenBuffers(1, ebo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, *ebo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(uint32_t)), indices.data(), GL_STATIC_DRAW);
    glBindVertexArray(0);
}

// A full mip chain's level count for a w x h image.
int mipLevels(int w, int h) { return int(std::floor(std::log2(float(std::max({w, h, 1}))))) + 1; }


}  // namespace

void Renderer::setLighting(const ShaderProgram& p, const glm::vec3& eye, float fog_density) const {
    glUniform3fv(loc(p, "u_sun_dir"), 1, glm::value_ptr(kSunDir));
    glUniform3fv(loc(p, "u_eye"), 1, glm::value_ptr(eye));
    glUniform1f(loc(p, "u_fog_density"), fog_density);
    // Unused uniforms are optimised away (location -1), which glUniform ignores.
    glUniform1i(loc(p, "u_shadow_map"), kShadowUnit);
    glUniformMatrix4fv(loc(p, "u_shadow_texture"), 1, GL_FALSE, glm::value_ptr(shadow_texture_));
    glUniform1f(loc(p, "u_shadow_strength"), shadow_valid_ ? 1.0f : 0.0f);
    glUniform1f(loc(p, "u_shadow_offset_m"), shadow_offset_m_);
}

Renderer::~Renderer() {
    releaseScene();
    releaseStaticMeshes();
    releaseTargets();
    for (ShaderProgram* p : {&sky_, &terrain_, &detail_, &impostor_, &grid_, &marker_, &hull_, &shadow_detail_,
                             &shadow_impostor_, &ambient_occlusion_, &ao_blur_, &composite_, &static_mesh_, &shadow_static_,
                             &static_glossy_})
        destroyProgram(p);
    if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
    if (marker_vao_) glDeleteVertexArrays(1, &marker_vao_);
    if (overlay_vao_) glDeleteVertexArrays(1, &overlay_vao_);
    if (overlay_buffer_) glDeleteBuffers(1, &overlay_buffer_);
    releaseThumbnails();
    if (marker_buffer_) glDeleteBuffers(1, &marker_buffer_);
    for (IndirectBuffer* b : {&indirect_, &shadow_indirect_}) {
        if (b->id) glDeleteBuffers(1, &b->id);
        if (b->runs_id) glDeleteBuffers(1, &b->runs_id);
    }
}

bool Renderer::init(const std::string& dir, std::string* error) {
    const char* lighting[] = {"u_sun_dir", "u_eye", "u_fog_density"};
    auto with = [&](std::vector<const char*> names, bool lit) {
        if (lit) names.insert(names.end(), std::begin(lighting), std::end(lighting));
        return names;
    };
    if (!loadProgram(dir, "sky.vert", "sky.frag", {"u_view_to_world", "u_tan_half_fov", "u_sun_dir"}, &sky_, error) ||
        !loadProgram(dir, "terrain.vert", "lit_surface.frag", with({"u_view_proj", "u_color"}, true), &terrain_, error) ||
        !loadProgram(dir, "instanced_detail.vert", "lit_surface.frag",
                     with({"u_view_proj", "u_tile_size_m", "u_drop_unit_m", "u_color", "u_lod_diameter_px",
                           "u_impostor_px"},
                          true),
                     &detail_, error) ||
        !loadProgram(dir, "detail_impostor.vert", "impostor.frag",
                     with({"u_view_proj", "u_tile_size_m", "u_drop_unit_m", "u_color", "u_center", "u_coverage_m2",
                           "u_point_scale", "u_to_eye", "u_lod_diameter_px", "u_impostor_px", "u_upness",
                           "u_sprite_radius_m", "u_layer_first", "u_silhouettes", "u_sprite_extent"},
                          true),
                     &impostor_, error) ||
        // The far sprites cast as sprites (detail_impostor.vert, SHADOW_CASTER).
        !loadProgram(dir, "detail_impostor.vert", "impostor.frag",
                     {"u_view_proj", "u_tile_size_m", "u_drop_unit_m", "u_center", "u_coverage_m2", "u_point_scale",
                      "u_to_eye", "u_eye", "u_lod_diameter_px", "u_impostor_px", "u_sprite_radius_m", "u_layer_first",
                      "u_silhouettes", "u_sprite_extent", "u_min_caster_px"},
                     &shadow_impostor_, error, {"SHADOW_CASTER"}) ||
        !loadProgram(dir, "ground_grid.vert", "ground_grid.frag",
                     with({"u_view_proj", "u_grid_center", "u_grid_half_m", "u_ground_z", "u_cell_m", "u_fade_m"}, true), &grid_,
                     error) ||
        !loadProgram(dir, "skeleton_marker.vert", "flat_color.frag", {"u_view_proj", "u_point_size"}, &marker_, error) ||
        !loadProgram(dir, "skeleton_marker.vert", "primitive_hull.frag", {"u_view_proj", "u_alpha"}, &hull_, error) ||
        !loadProgram(dir, "instanced_detail.vert", "shadow_depth.frag",
                     {"u_view_proj", "u_tile_size_m", "u_drop_unit_m", "u_eye", "u_lod_diameter_px", "u_impostor_px"},
                     &shadow_detail_, error) ||
        !loadProgram(dir, "screen_pass.vert", "ambient_occlusion.frag",
                     {"u_depth", "u_near_far", "u_tan_half_fov", "u_ao_radius_m"}, &ambient_occlusion_, error) ||
        !loadProgram(dir, "screen_pass.vert", "ao_blur.frag", {"u_ao"}, &ao_blur_, error) ||
        !loadProgram(dir, "screen_pass.vert", "composite.frag", {"u_color", "u_ao"}, &composite_, error) ||
        !loadProgram(dir, "static_mesh.vert", "lit_surface.frag", with({"u_view_proj", "u_color"}, true), &static_mesh_,
                     error) ||
        !loadProgram(dir, "static_mesh.vert", "lit_surface.frag", with({"u_view_proj", "u_color", "u_gloss"}, true),
                     &static_glossy_, error, {"GLOSSY"}) ||
        !loadProgram(dir, "static_mesh.vert", "shadow_depth.frag", {"u_view_proj"}, &shadow_static_, error))
        return false;
    for (IndirectBuffer* b : {&indirect_, &shadow_indirect_}) {
        glGenBuffers(1, &b->id);
        glGenBuffers(1, &b->runs_id);
    }

    glGenVertexArrays(1, &empty_vao_);
    // Markers (every frame) and the channel overlay (kept until replaced): position, colour.
    for (auto [vao, buffer] : {std::pair{&marker_vao_, &marker_buffer_}, std::pair{&overlay_vao_, &overlay_buffer_}}) {
        glGenVertexArrays(1, vao);
        glGenBuffers(1, buffer);
        glBindVertexArray(*vao);
        glBindBuffer(GL_ARRAY_BUFFER, *buffer);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(MarkerVertex), nullptr);
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(MarkerVertex), reinterpret_cast<void*>(3 * sizeof(float)));
    }
    glBindVertexArray(0);
    return true;
}

void Renderer::releaseScene() {
    for (TypeBuffers& t : types_) {
        GLuint vaos[] = {t.vao, t.impostor_vao, t.shadow_impostor_vao};
        glDeleteVertexArrays(3, vaos);
        GLuint buffers[] = {t.vertex_buffer, t.index_buffer, t.instance_buffer};
        glDeleteBuffers(3, buffers);
    }
    types_.clear();
    if (terrain_vao_) glDeleteVertexArrays(1, &terrain_vao_);
    GLuint buffers[] = {terrain_vertices_, terrain_indices_, candidate_buffer_};
    glDeleteBuffers(3, buffers);
    terrain_vao_ = terrain_vertices_ = terrain_indices_ = candidate_buffer_ = 0;
    if (silhouette_array_) glDeleteTextures(1, &silhouette_array_);
    silhouette_array_ = 0;
    for (const auto& [img, id] : textures_) glDeleteTextures(1, &id);
    textures_.clear();
    terrain_texture_ = 0;
    terrain_index_count_ = 0;
    has_scene_ = false;
    tiles_ = nullptr;
}

void Renderer::releaseTargets() {
    GLuint fbos[] = {shadow_fbo_, scene_fbo_, ao_fbo_[0], ao_fbo_[1]};
    glDeleteFramebuffers(4, fbos);
    GLuint textures[] = {shadow_depth_, scene_color_, scene_depth_, ao_texture_[0], ao_texture_[1]};
    glDeleteTextures(5, textures);
    shadow_fbo_ = scene_fbo_ = shadow_depth_ = scene_color_ = scene_depth_ = 0;
    ao_fbo_[0] = ao_fbo_[1] = ao_texture_[0] = ao_texture_[1] = 0;
    shadow_px_ = scene_w_ = scene_h_ = 0;
}

unsigned Renderer::uploadTexture(const std::shared_ptr<const TextureImage>& image, TextureCache* cache) {
    if (!image || image->width <= 0 || image->height <= 0) return 0;
    for (const auto& [img, id] : *cache)
        if (img == image.get()) return id;
    GLuint id = 0;
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_2D, id);
    const int levels = mipLevels(image->width, image->height);
    // The image is the final colour in sRGB (material.h): sampled as linear albedo.
    glTexStorage2D(GL_TEXTURE_2D, levels, GL_SRGB8_ALPHA8, image->width, image->height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, image->width, image->height, GL_RGBA, GL_UNSIGNED_BYTE, image->rgba.data());
    glGenerateMipmap(GL_TEXTURE_2D);
    // Bilinear within the nearest mip level: trilinear filtering doubles llvmpipe's cost per lookup.
    setSampling(GL_TEXTURE_2D, GL_LINEAR_MIPMAP_NEAREST, GL_LINEAR, GL_REPEAT);
    glBindTexture(GL_TEXTURE_2D, 0);
    cache->push_back({image.get(), id});
    return id;
}

void Renderer::bindMaterial(const ShaderProgram& p, const SurfaceMaterial& m, unsigned texture, int mode) const {
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, texture);
    glUniform1i(loc(p, "u_albedo"), 0);
    glUniform1i(loc(p, "u_texture_mode"), texture ? mode : 0);
    glUniform1f(loc(p, "u_texture_scale_m"), m.texture_scale_m);
    const glm::vec2 turn = textureRotationCosSin(m.texture_rotation_deg);
    glUniform2f(loc(p, "u_texture_turn"), turn.x, turn.y);
    glUniform1f(loc(p, "u_gloss"), materialGloss(m.roughness));  // read by the GLOSSY program only
    glUniform1i(loc(p, "u_alpha_cutout"), texture && m.alpha_cutout ? 1 : 0);
    glUniform1f(loc(p, "u_tint_variation"), m.tint_variation);
}

void Renderer::setScene(const Bounds& extent, const TriangleMesh* terrain, const std::vector<DetailLodMesh>* meshes,
                        const CandidateSet& candidates, float tile_size_m, const SurfaceMaterial* terrain_material) {
    releaseScene();
    terrain_material_ = terrain_material ? *terrain_material : SurfaceMaterial{};
    if (!terrain_material) terrain_material_.base_color = glm::vec3(0.20f, 0.15f, 0.09f);  // bare earth under grass
    terrain_texture_ = uploadTexture(terrain_material_.texture, &textures_);
    extent_ = extent;
    tile_size_m_ = tile_size_m;
    meshes_ = meshes;

    if (terrain && !terrain->indices.empty()) {
        uploadMesh(terrain->positions, terrain->normals, terrain->indices, &terrain_vao_, &terrain_vertices_,
                   &terrain_indices_);
        terrain_index_count_ = uint32_t(terrain->indices.size());
    }

    // The candidate frames, once: every instance of every type refers to them by index.
    std::vector<GpuCandidateFrame> frames(candidates.size());
    for (uint32_t j = 0; j < candidates.size(); ++j) {
        const glm::vec3& p = candidates.position[j];
        const glm::quat& q = candidates.rotation[j];
        frames[j] = {{p.x, p.y, p.z, candidates.scale[j]}, {q.x, q.y, q.z, q.w}};
    }
    glGenBuffers(1, &candidate_buffer_);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, candidate_buffer_);
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(std::max<size_t>(frames.size(), 1) * sizeof(GpuCandidateFrame)),
                 frames.empty() ? nullptr : frames.data(), GL_STATIC_DRAW);

    types_.resize(meshes->size());
    for (size_t i = 0; i < meshes->size(); ++i) {
        const DetailLodMesh& m = (*meshes)[i];
        TypeBuffers& t = types_[i];
        uploadMesh(m.positions, m.normals, m.indices, &t.vao, &t.vertex_buffer, &t.index_buffer);
        t.texture = uploadTexture(m.material.texture, &textures_);
        glGenBuffers(1, &t.instance_buffer);
        // The instance attribute: two unsigned ints, advancing once per instance of the mesh, from the
        // command's baseInstance on (the tile's slot).
        glBindVertexArray(t.vao);
        glBindBuffer(GL_ARRAY_BUFFER, t.instance_buffer);
        glEnableVertexAttribArray(2);
        glVertexAttribIPointer(2, 2, GL_UNSIGNED_INT, sizeof(PackedInstance), nullptr);
        glVertexAttribDivisor(2, 1);
        // The impostors read the same buffer as storage, at the instances their command's run picks (a
        // far run draws one in its stride): the run is a per-instance attribute, its command's
        // baseInstance, from the pass's runs (a buffer that keeps its name when it grows).
        for (auto [vao, runs] : {std::pair{&t.impostor_vao, indirect_.runs_id}, std::pair{&t.shadow_impostor_vao, shadow_indirect_.runs_id}}) {
            glGenVertexArrays(1, vao);
            glBindVertexArray(*vao);
            glBindBuffer(GL_ARRAY_BUFFER, runs);
            glEnableVertexAttribArray(3);
            glVertexAttribIPointer(3, 2, GL_UNSIGNED_INT, sizeof(PointRun), nullptr);
            glVertexAttribDivisor(3, 1);
        }
        glBindVertexArray(0);
    }
    // The impostors' silhouettes: one R8 array, four layers (elevations) per type, mipmapped (the sprites
    // shrink to a few pixels; impostor.frag reads the mask as a coverage).
    const int res = meshes->empty() ? 0 : (*meshes)[0].silhouettes.resolution;
    bool same_resolution = res > 0;
    for (const DetailLodMesh& m : *meshes) same_resolution = same_resolution && m.silhouettes.resolution == res;
    if (same_resolution) {
        glGenTextures(1, &silhouette_array_);
        glBindTexture(GL_TEXTURE_2D_ARRAY, silhouette_array_);
        const GLsizei layers = GLsizei(meshes->size() * kCoverageElevations);
        const int levels = mipLevels(res, res);
        glTexStorage3D(GL_TEXTURE_2D_ARRAY, levels, GL_R8, res, res, layers);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        for (size_t i = 0; i < meshes->size(); ++i)
            for (int e = 0; e < kCoverageElevations; ++e)
                glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, GLint(i * kCoverageElevations + size_t(e)), res, res, 1, GL_RED,
                                GL_UNSIGNED_BYTE, (*meshes)[i].silhouettes.mask[size_t(e)].data());
        glGenerateMipmap(GL_TEXTURE_2D_ARRAY);
        setSampling(GL_TEXTURE_2D_ARRAY, GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
        glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    }

    // The occlusion radius: a little over the largest detail's reach, so a pile's crevices and an object's
    // foot on the ground darken, but a whole hillside does not.
    float reach = 0.0f;
    for (const DetailLodMesh& m : *meshes) reach = std::max(reach, m.radius_m * m.scale_max);
    ao_radius_m_ = std::clamp(1.2f * reach, 0.03f, 2.0f);
    has_scene_ = true;
    draws_dirty_ = shadow_draws_dirty_ = shadow_map_dirty_ = true;
}

void Renderer::releaseStaticBuffers(StaticBuffers* b) {
    glDeleteVertexArrays(1, &b->vao);
    GLuint buffers[] = {b->vertex_buffer, b->index_buffer, b->instance_buffer};
    glDeleteBuffers(3, buffers);
    *b = StaticBuffers{};
}

void Renderer::releaseStaticMeshes() {
    for (StaticBuffers& b : statics_) releaseStaticBuffers(&b);
    statics_.clear();
    for (const auto& [img, id] : static_textures_) glDeleteTextures(1, &id);
    static_textures_.clear();
}

Renderer::StaticBuffers Renderer::uploadStaticEntry(const MeshInstances& entry, StaticLodMesh lods) {
    const TriangleMesh& mesh = *entry.mesh;
    StaticBuffers b;
    if (mesh.normals.size() == mesh.positions.size()) {
        uploadMesh(mesh.positions, mesh.normals, lods.indices, &b.vao, &b.vertex_buffer, &b.index_buffer);
    } else {  // MeshInstances allows meshes without normals: computed here, as the exporter does
        TriangleMesh with_normals = mesh;
        computeNormals(&with_normals);
        uploadMesh(with_normals.positions, with_normals.normals, lods.indices, &b.vao, &b.vertex_buffer,
                   &b.index_buffer);
    }
    StaticInstanceChunks chunked = chunkStaticInstances(entry);
    const std::vector<GpuStaticInstance>& instances = chunked.instances;
    glBindVertexArray(b.vao);
    glGenBuffers(1, &b.instance_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, b.instance_buffer);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(instances.size() * sizeof(GpuStaticInstance)), instances.data(),
                 GL_STATIC_DRAW);
    for (GLuint attribute : {2u, 3u}) {
        glEnableVertexAttribArray(attribute);
        glVertexAttribPointer(attribute, 4, GL_FLOAT, GL_FALSE, sizeof(GpuStaticInstance),
                              reinterpret_cast<void*>(uintptr_t(attribute - 2) * sizeof(glm::vec4)));
        glVertexAttribDivisor(attribute, 1);
    }
    glBindVertexArray(0);
    b.bounds = chunked.bounds;
    b.lods.piece_bounds = staticPieceBounds(lods, instances.front());
    b.lods.lods = std::move(lods);
    b.lods.chunks = std::move(chunked.chunks);
    b.material = entry.material ? *entry.material : SurfaceMaterial{};
    b.color = entry.material ? entry.material->base_color : mesh.base_color;
    b.texture = uploadTexture(b.material.texture, &static_textures_);
    b.casts_shadow = castsSunShadow(entry);
    b.glossy = materialGloss(b.material.roughness) > 0.0f;
    return b;
}

void Renderer::setStaticMeshes(const std::vector<MeshInstances>* meshes) {
    const std::vector<const MeshInstances*> entries = drawnStaticEntries(meshes);
    std::vector<StaticEntryKey> keys(entries.size());
    for (size_t e = 0; e < entries.size(); ++e) keys[e] = staticEntryKey(*entries[e]);
    // The sun's map is drawn again only when what casts into it changed: a footprint replaces the terrain's
    // snow, which casts nothing (castsSunShadow), and redrawing the map is a third of a winter frame.
    std::vector<SunCaster> casters = sunCasters(keys);
    if (casters != static_casters_ || shadowRedrawnOnEverySwap()) shadow_map_dirty_ = true;
    static_casters_ = std::move(casters);
    std::vector<StaticBuffers> old = std::move(statics_);
    statics_.clear();
    stats_.static_entries_uploaded = stats_.static_entries_kept = 0;
    const auto t0 = std::chrono::steady_clock::now();
    auto t1 = t0;
    if (!entries.empty()) {
        // An entry whose key the previous set had keeps its buffers.
        std::vector<long> reuse(entries.size(), -1);
        std::vector<bool> taken(old.size(), false);  // each old one serves one new entry
        for (size_t e = 0; e < entries.size(); ++e) {
            if (staticsReuploadedOnEverySwap()) continue;
            for (size_t k = 0; k < old.size() && reuse[e] < 0; ++k)
                if (!taken[k] && old[k].key == keys[e]) {
                    reuse[e] = long(k);
                    taken[k] = true;
                }
        }
        // Levels of detail for all simplified entries at once (the pieces of every new one spread over the
        // workers); naming the kept ones too keeps their levels for a later swap that moves their instances.
        std::vector<std::shared_ptr<const TriangleMesh>> lod_meshes;
        std::vector<bool> split;
        std::vector<long> simplified(entries.size(), -1);  // index into lod_meshes
        for (size_t e = 0; e < entries.size(); ++e) {
            if (entries[e]->lod_levels) continue;
            simplified[e] = long(lod_meshes.size());
            lod_meshes.push_back(entries[e]->mesh);
            split.push_back(splitsStaticEntry(entries[e]->instances.size(), entries[e]->mesh->indices.size() / 3));
        }
        const std::vector<std::shared_ptr<const StaticLodMesh>> built = static_lod_cache_.levels(lod_meshes, split, 0);
        t1 = std::chrono::steady_clock::now();
        statics_.reserve(entries.size());
        for (size_t e = 0; e < entries.size(); ++e) {
            if (reuse[e] >= 0) {
                StaticBuffers& kept = old[size_t(reuse[e])];
                statics_.push_back(std::move(kept));
                kept = StaticBuffers{};  // its GL names now belong to the new entry
                ++stats_.static_entries_kept;
                continue;
            }
            const MeshInstances& entry = *entries[e];
            StaticLodMesh lods = simplified[e] >= 0 ? *built[size_t(simplified[e])]
                                                    : authoredStaticLod(*entry.mesh, *entry.lod_levels);
            statics_.push_back(uploadStaticEntry(entry, std::move(lods)));
            statics_.back().key = std::move(keys[e]);
            ++stats_.static_entries_uploaded;
        }
    }
    for (StaticBuffers& b : old)
        if (b.vao) releaseStaticBuffers(&b);
    // Textures no entry uses any more go (every one left is named by an image an entry holds).
    std::erase_if(static_textures_, [&](const std::pair<const TextureImage*, unsigned>& t) {
        for (const StaticBuffers& b : statics_)
            if (b.texture == t.second) return false;
        glDeleteTextures(1, &t.second);
        return true;
    });
    const auto t2 = std::chrono::steady_clock::now();
    static_lod_ms_ = stats_.static_lod_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    static_upload_ms_ = stats_.static_upload_ms = std::chrono::duration<double, std::milli>(t2 - t0).count();
}

void Renderer::drawStaticMeshes(const ShaderProgram& program, const glm::mat4& view_proj, const glm::vec3& eye,
                                float pixels_per_radian, bool shadow, StaticSubset subset) {
    for (const StaticBuffers& b : statics_) {
        if (shadow && !b.casts_shadow) continue;
        if (subset != StaticSubset::All && b.glossy != (subset == StaticSubset::Glossy)) continue;
        if (!boxInFrustum(view_proj, b.bounds)) {
            if (!shadow) ++stats_.static_meshes_culled;
            continue;
        }
        if (!shadow) {
            glUniform3fv(loc(program, "u_color"), 1, glm::value_ptr(b.color));
            bindMaterial(program, b.material, b.texture, kTextureBoxModel);
            if (b.texture && b.material.alpha_cutout) glDisable(GL_CULL_FACE);
            else glEnable(GL_CULL_FACE);
        }
        glBindVertexArray(b.vao);
        // One instanced draw per visible piece, or per run of consecutive visible chunks at one level
        // (baseInstance = the run's first instance; the per-instance attributes honour it). The shadow
        // pass makes the camera's choice (culled by the sun's frustum): one level coarser lightened the
        // shadows of thin branches visibly, for a few percent of frame time.
        const uint64_t triangles =
            buildStaticDraws(b.lods, view_proj, eye, pixels_per_radian, 0, &static_draws_);
        for (const StaticDrawRange& d : static_draws_)
            glDrawElementsInstancedBaseInstance(GL_TRIANGLES, GLsizei(d.index_count), GL_UNSIGNED_INT,
                                                reinterpret_cast<const void*>(uintptr_t(d.first_index) * 4u),
                                                GLsizei(d.instance_count), d.first_instance);
        if (shadow) {
            stats_.shadow_triangles += triangles;
            continue;
        }
        stats_.draw_calls += static_draws_.size();
        ++stats_.static_meshes_drawn;
        stats_.triangles += triangles;
        stats_.static_triangles += triangles;
    }
    glEnable(GL_CULL_FACE);
}

void Renderer::uploadTiles(const ResidentTiles* tiles, const TileUploads& uploads) {
    // A result that changed no tile (an environment edit away from every scattered detail) keeps the draws
    // and the sun's map.
    if (tiles != tiles_ || uploads.full || !uploads.tiles.empty() || shadowRedrawnOnEverySwap())
        draws_dirty_ = shadow_draws_dirty_ = shadow_map_dirty_ = true;
    tiles_ = tiles;
    upload_tiles_ = uploads.tiles_uploaded;
    upload_bytes_ = uploads.bytes_uploaded;
    if (!tiles) return;
    for (size_t i = 0; i < types_.size() && i < tiles->types.size() && i < uploads.types.size(); ++i) {
        const std::vector<PackedInstance>& mirror = tiles->types[i].mirror;
        const TileUploads::Type& u = uploads.types[i];
        glBindBuffer(GL_ARRAY_BUFFER, types_[i].instance_buffer);
        if (u.whole || mirror.size() > types_[i].instance_capacity) {
            // The array grew (its allocator doubles, so this is rare) or was rebuilt: all of it, once.
            glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(std::max<size_t>(mirror.size(), 1) * sizeof(PackedInstance)),
                         mirror.empty() ? nullptr : mirror.data(), GL_DYNAMIC_DRAW);
            types_[i].instance_capacity = uint32_t(mirror.size());
            continue;
        }
        for (const TileUploads::Range& r : u.ranges)
            glBufferSubData(GL_ARRAY_BUFFER, GLintptr(uint64_t(r.offset) * sizeof(PackedInstance)),
                            GLsizeiptr(uint64_t(r.count) * sizeof(PackedInstance)), mirror.data() + r.offset);
    }
}

void Renderer::setTypeVisible(size_t type, bool visible) {
    if (type < types_.size() && types_[type].visible != visible) {
        types_[type].visible = visible;
        shadow_map_dirty_ = true;
    }
}

void Renderer::setMarkers(const MarkerGeometry& m) {
    // One buffer: hull triangles, lines, points, dots, one after the other.
    marker_hull_vertices_ = uint32_t(m.hull.size());
    marker_line_vertices_ = uint32_t(m.lines.size());
    marker_points_ = uint32_t(m.points.size());
    marker_dots_ = uint32_t(m.dots.size());
    glBindBuffer(GL_ARRAY_BUFFER, marker_buffer_);
    const size_t n = m.hull.size() + m.lines.size() + m.points.size() + m.dots.size();
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(std::max<size_t>(n, 1) * sizeof(MarkerVertex)), nullptr, GL_STREAM_DRAW);
    size_t at = 0;
    for (const std::vector<MarkerVertex>* list : {&m.hull, &m.lines, &m.points, &m.dots}) {
        if (!list->empty())
            glBufferSubData(GL_ARRAY_BUFFER, GLintptr(at * sizeof(MarkerVertex)),
                            GLsizeiptr(list->size() * sizeof(MarkerVertex)), list->data());
        at += list->size();
    }
}

void Renderer::render(const OrbitCamera& camera, int width, int height, const LodSettings& lod) {
    stats_ = RenderStats{};
    stats_.tiles_uploaded = upload_tiles_;
    stats_.bytes_uploaded = upload_bytes_;
    stats_.tiles_resident = tiles_ ? tiles_->tileCount() : 0;
    stats_.static_lod_ms = static_lod_ms_;
    stats_.static_upload_ms = static_upload_ms_;
    GLint target_fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target_fbo);
    OrbitCamera cam = camera;
    cam.aspect = float(std::max(width, 1)) / float(std::max(height, 1));
    const glm::mat4 view = cam.view();
    const glm::mat4 view_proj = cam.projection() * view;
    const glm::vec3 eye = cam.eye();
    const float radius = std::max(0.5f * glm::length(extent_.hi - extent_.lo), 0.05f);
    const float fog_density = has_scene_ ? 0.06f / radius : 0.0f;

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);

    shadow_valid_ = false;
    if (has_scene_ && look_.shadows) shadowPass(cam, eye, height, lod);
    glActiveTexture(GL_TEXTURE0 + kShadowUnit);
    glBindTexture(GL_TEXTURE_2D, shadow_valid_ ? shadow_depth_ : 0);
    glActiveTexture(GL_TEXTURE0);

    // With ambient occlusion, the scene goes into the offscreen target (the occlusion reads its depth) and
    // is composited onto the caller's framebuffer; without, straight onto it (no extra full-screen pass).
    const bool occlusion = has_scene_ && look_.ambient_occlusion;
    if (occlusion) ensureSceneTarget(width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, occlusion ? scene_fbo_ : unsigned(target_fbo));
    glViewport(0, 0, width, height);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    if (!has_scene_) {
        // Nothing loaded yet: the sky alone.
    } else if (terrain_index_count_ > 0) {
        glUseProgram(terrain_.id);
        glUniformMatrix4fv(loc(terrain_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
        glUniform3fv(loc(terrain_, "u_color"), 1, glm::value_ptr(terrain_material_.base_color));
        bindMaterial(terrain_, terrain_material_, terrain_texture_, kTextureWorldXY);
        setLighting(terrain_, eye, fog_density);
        glBindVertexArray(terrain_vao_);
        glDrawElements(GL_TRIANGLES, GLsizei(terrain_index_count_), GL_UNSIGNED_INT, nullptr);
        ++stats_.draw_calls;
        stats_.triangles += terrain_index_count_ / 3;
    } else {
        // No terrain: a ground grid at z = 0 when the extent holds it, else at the extent's floor.
        const float ground_z = (extent_.lo.z <= 0.0f && extent_.hi.z >= 0.0f) ? 0.0f : extent_.lo.z;
        const float cell = std::pow(10.0f, std::floor(std::log10(radius / 5.0f)));
        glUseProgram(grid_.id);
        glUniformMatrix4fv(loc(grid_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
        const glm::vec2 c = 0.5f * glm::vec2(extent_.lo + extent_.hi);
        glUniform2fv(loc(grid_, "u_grid_center"), 1, glm::value_ptr(c));
        glUniform1f(loc(grid_, "u_grid_half_m"), 10.0f * radius);
        glUniform1f(loc(grid_, "u_ground_z"), ground_z);
        glUniform1f(loc(grid_, "u_cell_m"), cell);
        glUniform2f(loc(grid_, "u_fade_m"), 2.5f * radius, 8.0f * radius);
        setLighting(grid_, eye, fog_density);
        glDisable(GL_CULL_FACE);
        glBindVertexArray(empty_vao_);
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
        glEnable(GL_CULL_FACE);
        ++stats_.draw_calls;
    }

    if (has_scene_ && !statics_.empty()) {
        const bool any_glossy =
            std::any_of(statics_.begin(), statics_.end(), [](const StaticBuffers& b) { return b.glossy; });
        for (const ShaderProgram* p : {&static_mesh_, &static_glossy_}) {
            if (p == &static_glossy_ && !any_glossy) break;  // most scenes: no second program's setup
            glUseProgram(p->id);
            glUniformMatrix4fv(loc(*p, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
            setLighting(*p, eye, fog_density);
            drawStaticMeshes(*p, view_proj, eye, float(height) / cam.fov_y_rad, false,
                             p == &static_glossy_ ? StaticSubset::Glossy : StaticSubset::Matte);
        }
    }
    if (tiles_ && meshes_) drawDetails(cam, view, view_proj, eye, height, lod, fog_density);

    // The sky last, at the far plane: depth test LEQUAL keeps it to the pixels nothing covered.
    glDisable(GL_CULL_FACE);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glUseProgram(sky_.id);
    const glm::mat3 view_to_world = glm::transpose(glm::mat3(view));
    glUniformMatrix3fv(loc(sky_, "u_view_to_world"), 1, GL_FALSE, glm::value_ptr(view_to_world));
    const float tan_half = std::tan(0.5f * cam.fov_y_rad);
    glUniform2f(loc(sky_, "u_tan_half_fov"), tan_half * cam.aspect, tan_half);
    glUniform3fv(loc(sky_, "u_sun_dir"), 1, glm::value_ptr(kSunDir));
    glBindVertexArray(empty_vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    ++stats_.draw_calls;
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);

    drawHulls(view_proj);
    if (occlusion) composite(unsigned(target_fbo), width, height, cam);
    drawOverlays(view_proj);
    glBindVertexArray(0);
}

void Renderer::shadowPass(const OrbitCamera& cam, const glm::vec3& eye, int height, const LodSettings& lod) {
    const int px = std::clamp(look_.shadow_map_px, 256, 8192);
    const ShadowFrame tight = fitShadowFrame(cam, extent_, kSunDir, px);
    const bool moving = has_previous_eye_ && eye != previous_eye_;
    previous_eye_ = eye;
    has_previous_eye_ = true;
    if (!tight.valid) return;
    if (shadow_px_ != px) {
        if (!shadow_fbo_) glGenFramebuffers(1, &shadow_fbo_);
        if (shadow_depth_) glDeleteTextures(1, &shadow_depth_);
        glGenTextures(1, &shadow_depth_);
        glBindTexture(GL_TEXTURE_2D, shadow_depth_);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT24, px, px);
        // Hardware comparison with bilinear filtering: each lookup is a 2x2 percentage-closer filter.
        setSampling(GL_TEXTURE_2D, GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
        glBindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadow_depth_, 0);
        glDrawBuffer(GL_NONE);
        glReadBuffer(GL_NONE);
        shadow_px_ = px;
        shadow_map_dirty_ = true;
    }
    const bool same_lod = lod.lod1_px == last_lod_.lod1_px && lod.lod2_px == last_lod_.lod2_px &&
                          lod.impostor_px == last_lod_.impostor_px;
    // While the camera moves (an orbit drag, a pan), the map drawn for an earlier frame serves as long as
    // it covers this frame's view: redrawing it every frame cost an orbiting meadow a third of its frame
    // time. Its casters keep the mesh or sprite the eye of that frame gave them until the next redraw.
    const bool held =
        moving && held_shadow_complete_ && !shadow_map_dirty_ && same_lod && shadowFrameHolds(held_shadow_, tight);
    // Moving, a new map gets a margin so that the next frames fit in it; a still view gets its own,
    // tight frame back (the first still frame after a drag redraws once).
    const ShadowFrame frame =
        held ? held_shadow_ : (moving ? fitShadowFrame(cam, extent_, kSunDir, px, kMovingShadowMargin) : tight);
    shadow_texture_ = frame.texture;
    shadow_offset_m_ = 1.5f * frame.texel_m;
    shadow_valid_ = true;
    if (held) return;
    // A still view draws only the casters whose shadow can fall in it (the map is drawn for this view
    // alone); a moving one draws the whole square, so that the next frames can use the map.
    const bool complete = moving;
    const glm::mat4 receiver = cam.viewProjection();
    // A still view of an unchanged scene keeps last frame's map: the sun does not move. (The eye and the
    // LOD settings choose which instances are meshes, hence casters.)
    if (!shadow_map_dirty_ && same_lod && eye == last_shadow_eye_ && frame.view_proj == held_shadow_.view_proj &&
        (held_shadow_complete_ || receiver == shadow_receiver_))
        return;
    glBindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_);
    glViewport(0, 0, px, px);
    glClear(GL_DEPTH_BUFFER_BIT);
    // Slope-scaled offset in the map plus a normal offset at lookup (lighting.glsl) keep lit faces free of
    // acne without detaching the shadow from the object's foot.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glEnable(GL_POLYGON_OFFSET_LINE);  // the nearest casters' edges (drawMeshLods)
    glPolygonOffset(1.5f, 2.0f);
    // The terrain receives shadows but casts none: on llvmpipe its triangles would fill every texel of
    // the map each time it is drawn, and the sun term already darkens slopes turned away from it. The
    // static meshes (benches, their snow, icicles) cast: their shadows are what places them on the ground;
    // the terrain's snow does not (castsSunShadow).
    if (!statics_.empty()) {
        glUseProgram(shadow_static_.id);
        glUniformMatrix4fv(loc(shadow_static_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(frame.view_proj));
        drawStaticMeshes(shadow_static_, frame.view_proj, eye, float(height) / cam.fov_y_rad, true);
    }
    if (tiles_ && meshes_) {
        // The casters: the tiles the sun's box holds, as meshes where the camera draws meshes (the same
        // impostor switch, so a shadow belongs to what is drawn) but one mesh level coarser sooner: a
        // shadow a few texels across does not show the difference, and llvmpipe pays per vertex. Only
        // when the box or the tiles moved.
        LodSettings caster_lod = lod;
        caster_lod.lod1_px *= 2.0f;
        caster_lod.lod2_px *= 2.0f;
        // The impostors' point scale in the map: orthographic, so texels per metre at any depth.
        const float texels_per_m = 1.0f / frame.texel_m;
        if (shadow_draws_dirty_ || frame.view_proj != held_shadow_.view_proj || lod.lod1_px != last_lod_.lod1_px ||
            lod.lod2_px != last_lod_.lod2_px || lod.impostor_px != last_lod_.impostor_px ||
            complete != held_shadow_complete_ || (!complete && receiver != shadow_receiver_)) {
            ViewParams params;
            params.view_proj = frame.view_proj;
            params.eye = eye;
            params.pixels_per_radian = float(height) / cam.fov_y_rad;
            params.point_scale = texels_per_m;
            params.cull_by_receiver = !complete;
            params.receiver_view_proj = receiver;
            // Down the sun's rays from the top of the scene to its bottom (kSunDir points at the sun).
            params.shadow_sweep = -kSunDir * ((extent_.hi.z - extent_.lo.z) / kSunDir.z);
            uploadDraws(params, caster_lod, &shadow_draws_, &shadow_indirect_);
            shadow_draws_dirty_ = false;
        }
        glUseProgram(shadow_detail_.id);
        glUniformMatrix4fv(loc(shadow_detail_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(frame.view_proj));
        glUniform1f(loc(shadow_detail_, "u_tile_size_m"), tile_size_m_);
        glUniform1f(loc(shadow_detail_, "u_drop_unit_m"), tiles_->drop_unit_m);
        glUniform3fv(loc(shadow_detail_, "u_eye"), 1, glm::value_ptr(eye));
        drawMeshLods(shadow_detail_, shadow_draws_, shadow_indirect_, float(height) / cam.fov_y_rad, caster_lod, true);
        // What the camera draws as sprites casts as sprites facing the sun: without them a hut seen from
        // afar cast no shadow, and one seen from above only where its nearer tiles were meshes. Only types
        // whose sprites are kMinCasterTexels across or more (a type wholly below is skipped here, the rest
        // instance by instance in the shader): the meadow's 35,000 far grass tufts (7 texels) cost llvmpipe
        // 55 ms per redraw of the map for shadows the one-tap filter blurs away.
        glUseProgram(shadow_impostor_.id);
        glUniformMatrix4fv(loc(shadow_impostor_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(frame.view_proj));
        glUniform1f(loc(shadow_impostor_, "u_tile_size_m"), tile_size_m_);
        glUniform1f(loc(shadow_impostor_, "u_drop_unit_m"), tiles_->drop_unit_m);
        glUniform1f(loc(shadow_impostor_, "u_point_scale"), texels_per_m);
        glUniform3fv(loc(shadow_impostor_, "u_to_eye"), 1, glm::value_ptr(kSunDir));
        glUniform3fv(loc(shadow_impostor_, "u_eye"), 1, glm::value_ptr(eye));
        glUniform1f(loc(shadow_impostor_, "u_min_caster_px"), kMinCasterTexels);
        drawImpostors(shadow_impostor_, shadow_draws_, shadow_indirect_, float(height) / cam.fov_y_rad, caster_lod, true,
                      kMinCasterTexels * frame.texel_m);
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_POLYGON_OFFSET_LINE);
    last_shadow_eye_ = eye;
    held_shadow_ = frame;
    held_shadow_complete_ = complete;
    shadow_receiver_ = receiver;
    stats_.shadow_map_draws = 1;
    shadow_map_dirty_ = false;
}

void Renderer::ensureSceneTarget(int width, int height) {
    width = std::max(width, 1);
    height = std::max(height, 1);
    if (scene_fbo_ && width == scene_w_ && height == scene_h_) return;
    if (!scene_fbo_) glGenFramebuffers(1, &scene_fbo_);
    if (!ao_fbo_[0]) glGenFramebuffers(2, ao_fbo_);
    GLuint textures[] = {scene_color_, scene_depth_, ao_texture_[0], ao_texture_[1]};
    glDeleteTextures(4, textures);
    glGenTextures(1, &scene_color_);
    glBindTexture(GL_TEXTURE_2D, scene_color_);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, width, height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glGenTextures(1, &scene_depth_);
    glBindTexture(GL_TEXTURE_2D, scene_depth_);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT24, width, height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, scene_fbo_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, scene_color_, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, scene_depth_, 0);
    // The occlusion at half resolution, raw and blurred, filtered (both are read bilinearly).
    glGenTextures(2, ao_texture_);
    for (int k = 0; k < 2; ++k) {
        glBindTexture(GL_TEXTURE_2D, ao_texture_[k]);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_R8, (width + 1) / 2, (height + 1) / 2);
        setSampling(GL_TEXTURE_2D, GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
        glBindFramebuffer(GL_FRAMEBUFFER, ao_fbo_[k]);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, ao_texture_[k], 0);
    }
    glBindTexture(GL_TEXTURE_2D, 0);
    scene_w_ = width;
    scene_h_ = height;
}

void Renderer::composite(unsigned target_fbo, int width, int height, const OrbitCamera& cam) {
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glBindVertexArray(empty_vao_);
    // The occlusion (half resolution) from the scene's depth, then blurred at half resolution.
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, scene_depth_);
    glActiveTexture(GL_TEXTURE4);
    glBindTexture(GL_TEXTURE_2D, ao_texture_[0]);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, scene_color_);
    glActiveTexture(GL_TEXTURE5);
    glBindTexture(GL_TEXTURE_2D, ao_texture_[1]);
    glActiveTexture(GL_TEXTURE0);
    glBindFramebuffer(GL_FRAMEBUFFER, ao_fbo_[0]);
    glViewport(0, 0, (width + 1) / 2, (height + 1) / 2);
    glUseProgram(ambient_occlusion_.id);
    glUniform1i(loc(ambient_occlusion_, "u_depth"), 3);
    glUniform2f(loc(ambient_occlusion_, "u_near_far"), cam.nearPlane(), cam.farPlane());
    const float tan_half = std::tan(0.5f * cam.fov_y_rad);
    glUniform2f(loc(ambient_occlusion_, "u_tan_half_fov"), tan_half * cam.aspect, tan_half);
    glUniform1f(loc(ambient_occlusion_, "u_ao_radius_m"), ao_radius_m_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_FRAMEBUFFER, ao_fbo_[1]);
    glUseProgram(ao_blur_.id);
    glUniform1i(loc(ao_blur_, "u_ao"), 4);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    // The colour, darkened, onto the caller's framebuffer.
    glBindFramebuffer(GL_FRAMEBUFFER, target_fbo);
    glViewport(0, 0, width, height);
    glUseProgram(composite_.id);
    glUniform1i(loc(composite_, "u_color"), 2);
    glUniform1i(loc(composite_, "u_ao"), 5);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    stats_.draw_calls += 3;
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
}

void Renderer::setChannelOverlay(const std::vector<MarkerVertex>& triangles) {
    overlay_vertices_ = uint32_t(triangles.size());
    glBindBuffer(GL_ARRAY_BUFFER, overlay_buffer_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(std::max<size_t>(triangles.size(), 1) * sizeof(MarkerVertex)),
                 triangles.empty() ? nullptr : triangles.data(), GL_STATIC_DRAW);
}

void Renderer::drawHulls(const glm::mat4& view_proj) {
    // Hulls: translucent over the scene, depth-tested so the ground and details in front hide them, no
    // depth write so hulls behind hulls and the skeletons inside still show. Both faces: the inside of a
    // hull the camera is in still tints the view. Drawn where the scene's depth is (the offscreen target
    // when there is one), so the composite needs to carry no depth. The channel overlay is drawn the same
    // way, more opaque: its colours are the information.
    const struct {
        unsigned vao;
        uint32_t vertices;
        float alpha;
    } layers[] = {{overlay_vao_, overlay_visible_ ? overlay_vertices_ : 0u, 0.5f},
                  {marker_vao_, marker_hull_vertices_, 0.22f}};
    for (const auto& layer : layers) {
        if (layer.vertices == 0) continue;
        glDisable(GL_CULL_FACE);
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        glDepthMask(GL_FALSE);
        glUseProgram(hull_.id);
        glUniformMatrix4fv(loc(hull_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
        glUniform1f(loc(hull_, "u_alpha"), layer.alpha);
        glBindVertexArray(layer.vao);
        glDrawArrays(GL_TRIANGLES, 0, GLsizei(layer.vertices));
        ++stats_.draw_calls;
        glDisable(GL_BLEND);
        glDepthMask(GL_TRUE);
    }
}

void Renderer::drawOverlays(const glm::mat4& view_proj) {
    // Overlays last, without depth: a skeleton inside the pile it makes must stay visible.
    if (marker_line_vertices_ + marker_points_ + marker_dots_ > 0) {
        glDisable(GL_DEPTH_TEST);
        glUseProgram(marker_.id);
        glUniformMatrix4fv(loc(marker_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
        glUniform1f(loc(marker_, "u_point_size"), 6.0f);
        glEnable(GL_PROGRAM_POINT_SIZE);
        glBindVertexArray(marker_vao_);
        const GLint lines_first = GLint(marker_hull_vertices_);
        const GLint points_first = lines_first + GLint(marker_line_vertices_);
        if (marker_line_vertices_) glDrawArrays(GL_LINES, lines_first, GLsizei(marker_line_vertices_));
        if (marker_points_) glDrawArrays(GL_POINTS, points_first, GLsizei(marker_points_));
        if (marker_dots_) {
            glUniform1f(loc(marker_, "u_point_size"), 2.0f);
            glDrawArrays(GL_POINTS, points_first + GLint(marker_points_), GLsizei(marker_dots_));
        }
        glDisable(GL_PROGRAM_POINT_SIZE);
        glEnable(GL_DEPTH_TEST);
    }
}

void Renderer::uploadDraws(const ViewParams& params, const LodSettings& lod, IndirectDraws* draws,
                           IndirectBuffer* buffer) {
    buildIndirectDraws(*tiles_, *meshes_, params, lod, draws);
    const size_t element_bytes = draws->elements.size() * sizeof(DrawElementsIndirectCommand);
    const size_t point_bytes = draws->points.size() * sizeof(DrawArraysIndirectCommand);
    buffer->points_offset = element_bytes;
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, buffer->id);
    if (element_bytes + point_bytes > buffer->capacity_bytes) {
        buffer->capacity_bytes = std::max<size_t>(2 * (element_bytes + point_bytes), 4096);
        glBufferData(GL_DRAW_INDIRECT_BUFFER, GLsizeiptr(buffer->capacity_bytes), nullptr, GL_DYNAMIC_DRAW);
    }
    if (element_bytes) glBufferSubData(GL_DRAW_INDIRECT_BUFFER, 0, GLsizeiptr(element_bytes), draws->elements.data());
    if (point_bytes)
        glBufferSubData(GL_DRAW_INDIRECT_BUFFER, GLintptr(element_bytes), GLsizeiptr(point_bytes), draws->points.data());
    const size_t run_bytes = draws->point_runs.size() * sizeof(PointRun);
    glBindBuffer(GL_ARRAY_BUFFER, buffer->runs_id);
    if (run_bytes > buffer->runs_capacity_bytes) {
        buffer->runs_capacity_bytes = std::max<size_t>(2 * run_bytes, 4096);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(buffer->runs_capacity_bytes), nullptr, GL_DYNAMIC_DRAW);
    }
    if (run_bytes) glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(run_bytes), draws->point_runs.data());
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void Renderer::drawMeshLods(const ShaderProgram& program, const IndirectDraws& draws, const IndirectBuffer& buffer,
                            float pixels_per_radian, const LodSettings& lod, bool shadow) {
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, buffer.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, candidate_buffer_);
    // One multi-draw per type and LOD; each command draws the LOD's index range for one run of tiles, its
    // instances from the command's baseInstance (the tile's slot) on.
    for (size_t i = 0; i < types_.size() && i < draws.groups.size(); ++i) {
        if (!types_[i].visible) continue;
        const DetailLodMesh& m = (*meshes_)[i];
        if (!shadow) {
            glUniform3fv(loc(program, "u_color"), 1, glm::value_ptr(m.color));
            bindMaterial(program, m.material, types_[i].texture, kTextureBoxModel);
            // A cut-out sheet is seen from both sides through its holes.
            if (types_[i].texture && m.material.alpha_cutout) glDisable(GL_CULL_FACE);
            else glEnable(GL_CULL_FACE);
        }
        glUniform1f(loc(program, "u_lod_diameter_px"), m.lodDiameterPx(pixels_per_radian));
        glUniform1f(loc(program, "u_impostor_px"), m.impostorPx(lod));
        glBindVertexArray(types_[i].vao);
        for (int level = 0; level < kMeshLodCount; ++level) {
            const IndirectDraws::Group& g = draws.groups[i][size_t(level)];
            if (g.count == 0) continue;
            const auto draw = [&g] {
                glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                                            reinterpret_cast<void*>(uintptr_t(g.first) * sizeof(DrawElementsIndirectCommand)),
                                            GLsizei(g.count), 0);
            };
            draw();
            if (shadow) {
                stats_.shadow_triangles += g.instances * m.triangles(level);
                // The nearest level's blades and leaf edges are often narrower than a texel of the map, and
                // a filled triangle that covers no texel centre writes nothing: their shadows fell apart
                // into dotted runs. Its edges drawn again as lines write every texel they cross (the
                // diamond rule), so a thin caster's shadow stays connected, at most a texel wider.
                if (level == 0) {
                    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
                    draw();
                    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
                }
                continue;
            }
            ++stats_.draw_calls;
            stats_.indirect_commands += g.count;
            stats_.triangles += g.instances * m.triangles(level);
            stats_.lod_instances[size_t(level)] += g.instances;
            stats_.instances_drawn += g.instances;
        }
    }
}

void Renderer::drawDetails(const OrbitCamera& cam, const glm::mat4& view, const glm::mat4& view_proj, const glm::vec3& eye,
                           int height, const LodSettings& lod, float fog_density) {
    // Rebuild the commands (cull + LOD per tile) and upload them only when the view, the LOD settings or
    // the tiles moved; a still frame replays the same indirect buffer.
    if (draws_dirty_ || view_proj != last_view_proj_ || lod.lod1_px != last_lod_.lod1_px ||
        lod.lod2_px != last_lod_.lod2_px || lod.impostor_px != last_lod_.impostor_px) {
        const auto t0 = std::chrono::steady_clock::now();
        ViewParams params;
        params.view_proj = view_proj;
        params.eye = eye;
        params.pixels_per_radian = float(height) / cam.fov_y_rad;
        params.point_scale = pointScale(cam, height);
        uploadDraws(params, lod, &draws_, &indirect_);
        last_view_proj_ = view_proj;
        last_lod_ = lod;
        draws_dirty_ = false;
        stats_.command_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }
    stats_.tiles_visible = draws_.tiles_visible;
    stats_.tiles_culled = draws_.tiles_culled;

    glUseProgram(detail_.id);
    glUniformMatrix4fv(loc(detail_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
    glUniform1f(loc(detail_, "u_tile_size_m"), tile_size_m_);
    glUniform1f(loc(detail_, "u_drop_unit_m"), tiles_ ? tiles_->drop_unit_m : 0.0f);
    setLighting(detail_, eye, fog_density);
    // Thin sheets (leaves, blades) are closed but ~1 mm thick: back faces are never the visible side.
    const float pixels_per_radian = float(height) / cam.fov_y_rad;
    drawMeshLods(detail_, draws_, indirect_, pixels_per_radian, lod, false);

    // Impostors: one point sprite per instance, straight from the instance buffer (no instancing: on
    // llvmpipe an instanced draw pays a fixed cost per instance, which tiny far objects cannot afford);
    // one multi-draw per type, a command per run of tiles.
    glUseProgram(impostor_.id);
    glUniformMatrix4fv(loc(impostor_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
    glUniform1f(loc(impostor_, "u_tile_size_m"), tile_size_m_);
    glUniform1f(loc(impostor_, "u_drop_unit_m"), tiles_ ? tiles_->drop_unit_m : 0.0f);
    glUniform1f(loc(impostor_, "u_point_scale"), pointScale(cam, height));
    const glm::vec3 to_eye(view[0][2], view[1][2], view[2][2]);
    glUniform3fv(loc(impostor_, "u_to_eye"), 1, glm::value_ptr(to_eye));
    setLighting(impostor_, eye, fog_density);
    drawImpostors(impostor_, draws_, indirect_, pixels_per_radian, lod, false);
}

void Renderer::drawImpostors(const ShaderProgram& program, const IndirectDraws& draws, const IndirectBuffer& buffer,
                             float pixels_per_radian, const LodSettings& lod, bool shadow, float min_caster_m) {
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, buffer.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, candidate_buffer_);
    glActiveTexture(GL_TEXTURE0 + kSilhouetteUnit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, silhouette_array_);
    glActiveTexture(GL_TEXTURE0);
    glUniform1i(loc(program, "u_silhouettes"), kSilhouetteUnit);
    glEnable(GL_PROGRAM_POINT_SIZE);
    for (size_t i = 0; i < types_.size() && i < draws.groups.size(); ++i) {
        if (!types_[i].visible) continue;
        const DetailLodMesh& m = (*meshes_)[i];
        const IndirectDraws::Group& g = draws.groups[i][kImpostorLod];
        if (g.count == 0) continue;
        const float sprite_radius_m = m.silhouettes.radius * m.silhouettes.extent;
        if (shadow && 2.0f * sprite_radius_m * m.scale_max < min_caster_m) continue;
        if (!shadow) {
            glUniform3fv(loc(program, "u_color"), 1, glm::value_ptr(m.color));
            glUniform1f(loc(program, "u_tint_variation"), m.material.tint_variation);
            glUniform1f(loc(program, "u_upness"), m.upness);
        }
        glUniform3fv(loc(program, "u_center"), 1, glm::value_ptr(m.center));
        glUniform4fv(loc(program, "u_coverage_m2"), 1, m.coverage_m2.data());
        glUniform1f(loc(program, "u_impostor_px"), m.impostorPx(lod));
        // The sprite covers the masks' occupied square only (coverage.h extent).
        glUniform1f(loc(program, "u_sprite_radius_m"), sprite_radius_m);
        glUniform1f(loc(program, "u_sprite_extent"), m.silhouettes.extent);
        glUniform1i(loc(program, "u_layer_first"), silhouette_array_ ? GLint(i * kCoverageElevations) : -1000000);
        glUniform1f(loc(program, "u_lod_diameter_px"), m.lodDiameterPx(pixels_per_radian));
        glBindVertexArray(shadow ? types_[i].shadow_impostor_vao : types_[i].impostor_vao);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, types_[i].instance_buffer);
        glMultiDrawArraysIndirect(
            GL_POINTS,
            reinterpret_cast<void*>(buffer.points_offset + uintptr_t(g.first) * sizeof(DrawArraysIndirectCommand)),
            GLsizei(g.count), 0);
        if (shadow) {
            stats_.shadow_points += g.instances;
            continue;
        }
        ++stats_.draw_calls;
        stats_.indirect_commands += g.count;
        stats_.points += g.instances;
        stats_.lod_instances[kImpostorLod] += g.instances;
        stats_.instances_drawn += g.instances;
    }
    glDisable(GL_PROGRAM_POINT_SIZE);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

unsigned Renderer::meshThumbnail(const TriangleMesh& mesh, const SurfaceMaterial& material, int px, float* coverage) {
    *coverage = 0.0f;
    if (mesh.indices.empty() || mesh.positions.empty() || px < 8 || px > 1024) return 0;
    TriangleMesh lit = mesh;
    if (lit.normals.size() != lit.positions.size()) computeNormals(&lit);
    // The camera: 30 degrees across, from the front-left and above, far enough for the bounding sphere.
    const Bounds3 b = meshBounds(mesh);
    const glm::vec3 centre = 0.5f * (b.min + b.max);
    const float radius = std::max(0.5f * glm::length(b.max - b.min), 1e-3f);
    const float fov = glm::radians(30.0f);
    const glm::vec3 eye = centre + radius / std::sin(0.5f * fov) * glm::normalize(glm::vec3(-0.55f, -1.0f, 0.6f));
    const glm::mat4 view_proj = glm::perspective(fov, 1.0f, 0.05f * radius, 8.0f * radius / std::sin(0.5f * fov)) *
                                glm::lookAt(eye, centre, glm::vec3(0.0f, 0.0f, 1.0f));

    GLuint texture = 0, depth = 0, fbo = 0, vao = 0, vbo = 0, ebo = 0, instance = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, px, px, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    setSampling(GL_TEXTURE_2D, GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, px, px);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    if (complete) {
        uploadMesh(lit.positions, lit.normals, lit.indices, &vao, &vbo, &ebo);
        glBindVertexArray(vao);
        const GpuStaticInstance identity;
        glGenBuffers(1, &instance);
        glBindBuffer(GL_ARRAY_BUFFER, instance);
        glBufferData(GL_ARRAY_BUFFER, sizeof identity, &identity, GL_STATIC_DRAW);
        for (GLuint attribute : {2u, 3u}) {
            glEnableVertexAttribArray(attribute);
            glVertexAttribPointer(attribute, 4, GL_FLOAT, GL_FALSE, sizeof(GpuStaticInstance),
                                  reinterpret_cast<void*>(uintptr_t(attribute - 2) * sizeof(glm::vec4)));
            glVertexAttribDivisor(attribute, 1);
        }
        glViewport(0, 0, px, px);
        glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_CULL_FACE);  // library meshes need not be closed
        glUseProgram(static_mesh_.id);
        glUniformMatrix4fv(loc(static_mesh_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
        glUniform3fv(loc(static_mesh_, "u_color"), 1, glm::value_ptr(material.base_color));
        bindMaterial(static_mesh_, material, 0, kTextureBoxModel);
        const bool shadow_was_valid = shadow_valid_;
        shadow_valid_ = false;  // no shadow map here
        setLighting(static_mesh_, eye, 0.0f);
        shadow_valid_ = shadow_was_valid;
        glDrawElementsInstanced(GL_TRIANGLES, GLsizei(lit.indices.size()), GL_UNSIGNED_INT, nullptr, 1);
        // The shader's alpha is its ambient share (for the occlusion pass): made opaque where the mesh is
        // (its depth is nearer than the far plane) and clear elsewhere, for the window to draw it over.
        const size_t pixels = size_t(px) * size_t(px);
        std::vector<uint8_t> rgba(pixels * 4);
        std::vector<float> z(pixels);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, px, px, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
        glReadPixels(0, 0, px, px, GL_DEPTH_COMPONENT, GL_FLOAT, z.data());
        size_t covered = 0;
        for (size_t i = 0; i < pixels; ++i) {
            const bool drawn = z[i] < 1.0f;
            rgba[4 * i + 3] = drawn ? 255 : 0;
            covered += drawn ? 1 : 0;
        }
        *coverage = float(covered) / float(pixels);
        glBindTexture(GL_TEXTURE_2D, texture);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, px, px, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
        glBindVertexArray(0);
        glDeleteVertexArrays(1, &vao);
        glDeleteBuffers(1, &vbo);
        glDeleteBuffers(1, &ebo);
        glDeleteBuffers(1, &instance);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &depth);
    if (!complete) {
        glDeleteTextures(1, &texture);
        return 0;
    }
    thumbnails_.push_back(texture);
    return texture;
}

void Renderer::releaseThumbnails() {
    if (!thumbnails_.empty()) glDeleteTextures(GLsizei(thumbnails_.size()), thumbnails_.data());
    thumbnails_.clear();
}

void Renderer::readPixels(int width, int height, std::vector<uint8_t>* rgba) const {
    std::vector<uint8_t> bottom_up(size_t(width) * size_t(height) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
    rgba->resize(bottom_up.size());
    const size_t row = size_t(width) * 4;
    for (int y = 0; y < height; ++y)
        std::memcpy(rgba->data() + size_t(y) * row, bottom_up.data() + size_t(height - 1 - y) * row, row);
}

}  // namespace ug::editor::gl
