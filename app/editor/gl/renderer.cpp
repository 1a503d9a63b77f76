#include "editor/gl/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include <epoxy/gl.h>
#include <glm/gtc/type_ptr.hpp>

namespace ug::editor::gl {

namespace {

const glm::vec3 kSunDir = glm::normalize(glm::vec3(0.45f, -0.50f, 0.74f));

// What the candidate SSBO holds per candidate (std430: two vec4).
struct GpuCandidateFrame {
    float position_scale[4];
    float rotation[4];
};
static_assert(sizeof(GpuCandidateFrame) == 32);

GLint loc(const ShaderProgram& p, const char* name) { return glGetUniformLocation(p.id, name); }

void setLighting(const ShaderProgram& p, const glm::vec3& eye, float fog_density) {
    glUniform3fv(loc(p, "u_sun_dir"), 1, glm::value_ptr(kSunDir));
    glUniform3fv(loc(p, "u_eye"), 1, glm::value_ptr(eye));
    glUniform1f(loc(p, "u_fog_density"), fog_density);
}

}  // namespace

Renderer::~Renderer() {
    releaseScene();
    for (ShaderProgram* p : {&sky_, &terrain_, &detail_, &impostor_, &grid_, &marker_, &hull_}) destroyProgram(p);
    if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
    if (marker_vao_) glDeleteVertexArrays(1, &marker_vao_);
    if (marker_buffer_) glDeleteBuffers(1, &marker_buffer_);
    if (indirect_buffer_) glDeleteBuffers(1, &indirect_buffer_);
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
                     with({"u_view_proj", "u_tile_size_m", "u_drop_unit_m", "u_color"}, true), &detail_, error) ||
        !loadProgram(dir, "detail_impostor.vert", "flat_color.frag",
                     with({"u_view_proj", "u_tile_size_m", "u_drop_unit_m", "u_color", "u_center", "u_half_size_m",
                           "u_point_scale",
                           "u_to_eye"},
                          true),
                     &impostor_, error) ||
        !loadProgram(dir, "ground_grid.vert", "ground_grid.frag",
                     with({"u_view_proj", "u_grid_center", "u_grid_half_m", "u_ground_z", "u_cell_m", "u_fade_m"}, true), &grid_,
                     error) ||
        !loadProgram(dir, "skeleton_marker.vert", "flat_color.frag", {"u_view_proj", "u_point_size"}, &marker_, error) ||
        !loadProgram(dir, "skeleton_marker.vert", "primitive_hull.frag", {"u_view_proj", "u_alpha"}, &hull_, error))
        return false;
    glGenBuffers(1, &indirect_buffer_);
    glGenVertexArrays(1, &empty_vao_);
    glGenVertexArrays(1, &marker_vao_);
    glGenBuffers(1, &marker_buffer_);
    glBindVertexArray(marker_vao_);
    glBindBuffer(GL_ARRAY_BUFFER, marker_buffer_);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(MarkerVertex), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(MarkerVertex), reinterpret_cast<void*>(3 * sizeof(float)));
    glBindVertexArray(0);
    return true;
}

void Renderer::releaseScene() {
    for (TypeBuffers& t : types_) {
        GLuint vaos[] = {t.vao, t.impostor_vao};
        glDeleteVertexArrays(2, vaos);
        GLuint buffers[] = {t.vertex_buffer, t.index_buffer, t.instance_buffer};
        glDeleteBuffers(3, buffers);
    }
    types_.clear();
    if (terrain_vao_) glDeleteVertexArrays(1, &terrain_vao_);
    GLuint buffers[] = {terrain_vertices_, terrain_indices_, candidate_buffer_};
    glDeleteBuffers(3, buffers);
    terrain_vao_ = terrain_vertices_ = terrain_indices_ = candidate_buffer_ = 0;
    terrain_index_count_ = 0;
    has_scene_ = false;
    tiles_ = nullptr;
}

void Renderer::setScene(const Bounds& extent, const TriangleMesh* terrain, const std::vector<DetailLodMesh>* meshes,
                        const CandidateSet& candidates, float tile_size_m) {
    releaseScene();
    extent_ = extent;
    tile_size_m_ = tile_size_m;
    meshes_ = meshes;

    // Interleaved position + normal, shared by the terrain and the detail meshes.
    auto uploadMesh = [](const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
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
    };

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
        glGenBuffers(1, &t.instance_buffer);
        // The instance attribute: two unsigned ints, advancing once per instance of the mesh, from the
        // command's baseInstance on (the tile's slot). The impostor VAO reads the same buffer one instance
        // per vertex (points, no mesh), from the command's `first` on.
        glGenVertexArrays(1, &t.impostor_vao);
        for (GLuint vao : {t.vao, t.impostor_vao}) {
            glBindVertexArray(vao);
            glBindBuffer(GL_ARRAY_BUFFER, t.instance_buffer);
            glEnableVertexAttribArray(2);
            glVertexAttribIPointer(2, 2, GL_UNSIGNED_INT, sizeof(PackedInstance), nullptr);
            glVertexAttribDivisor(2, vao == t.vao ? 1 : 0);
        }
        glBindVertexArray(0);
    }
    has_scene_ = true;
    draws_dirty_ = true;
}

void Renderer::uploadTiles(const ResidentTiles* tiles, const TileUploads& uploads) {
    tiles_ = tiles;
    draws_dirty_ = true;
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
    if (type < types_.size()) types_[type].visible = visible;
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
    glViewport(0, 0, width, height);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
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

    if (!has_scene_) {
        // Nothing loaded yet: the sky alone.
    } else if (terrain_index_count_ > 0) {
        glUseProgram(terrain_.id);
        glUniformMatrix4fv(loc(terrain_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
        const glm::vec3 ground(0.20f, 0.15f, 0.09f);  // darker than kTerrainColor: bare earth under the grass
        glUniform3fv(loc(terrain_, "u_color"), 1, glm::value_ptr(ground));
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

    // Hulls: translucent over the scene, depth-tested so the ground and details in front hide them, no
    // depth write (still off from the sky) so hulls behind hulls and the skeletons inside still show.
    // Both faces: the inside of a hull the camera is in still tints the view.
    if (marker_hull_vertices_ > 0) {
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        glUseProgram(hull_.id);
        glUniformMatrix4fv(loc(hull_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
        glUniform1f(loc(hull_, "u_alpha"), 0.22f);
        glBindVertexArray(marker_vao_);
        glDrawArrays(GL_TRIANGLES, 0, GLsizei(marker_hull_vertices_));
        ++stats_.draw_calls;
        glDisable(GL_BLEND);
    }
    glDepthMask(GL_TRUE);

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
    glBindVertexArray(0);
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
        buildIndirectDraws(*tiles_, *meshes_, params, lod, &draws_);
        const size_t element_bytes = draws_.elements.size() * sizeof(DrawElementsIndirectCommand);
        const size_t point_bytes = draws_.points.size() * sizeof(DrawArraysIndirectCommand);
        indirect_points_offset_ = element_bytes;
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, indirect_buffer_);
        if (element_bytes + point_bytes > indirect_capacity_bytes_) {
            indirect_capacity_bytes_ = std::max<size_t>(2 * (element_bytes + point_bytes), 4096);
            glBufferData(GL_DRAW_INDIRECT_BUFFER, GLsizeiptr(indirect_capacity_bytes_), nullptr, GL_DYNAMIC_DRAW);
        }
        if (element_bytes) glBufferSubData(GL_DRAW_INDIRECT_BUFFER, 0, GLsizeiptr(element_bytes), draws_.elements.data());
        if (point_bytes)
            glBufferSubData(GL_DRAW_INDIRECT_BUFFER, GLintptr(element_bytes), GLsizeiptr(point_bytes), draws_.points.data());
        last_view_proj_ = view_proj;
        last_lod_ = lod;
        draws_dirty_ = false;
        stats_.command_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }
    stats_.tiles_visible = draws_.tiles_visible;
    stats_.tiles_culled = draws_.tiles_culled;

    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, indirect_buffer_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, candidate_buffer_);
    // Mesh LODs 0..2: one multi-draw per type and LOD; each command draws the LOD's index range for one
    // run of tiles, its instances from the command's baseInstance (the tile's slot) on.
    glUseProgram(detail_.id);
    glUniformMatrix4fv(loc(detail_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
    glUniform1f(loc(detail_, "u_tile_size_m"), tile_size_m_);
    glUniform1f(loc(detail_, "u_drop_unit_m"), tiles_ ? tiles_->drop_unit_m : 0.0f);
    setLighting(detail_, eye, fog_density);
    // Thin sheets (leaves, blades) are closed but ~1 mm thick: back faces are never the visible side.
    for (size_t i = 0; i < types_.size() && i < draws_.groups.size(); ++i) {
        if (!types_[i].visible) continue;
        const DetailLodMesh& m = (*meshes_)[i];
        glUniform3fv(loc(detail_, "u_color"), 1, glm::value_ptr(m.color));
        glBindVertexArray(types_[i].vao);
        for (int level = 0; level < kMeshLodCount; ++level) {
            const IndirectDraws::Group& g = draws_.groups[i][size_t(level)];
            if (g.count == 0) continue;
            glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                                        reinterpret_cast<void*>(uintptr_t(g.first) * sizeof(DrawElementsIndirectCommand)),
                                        GLsizei(g.count), 0);
            ++stats_.draw_calls;
            stats_.indirect_commands += g.count;
            stats_.triangles += g.instances * m.triangles(level);
            stats_.lod_instances[size_t(level)] += g.instances;
            stats_.instances_drawn += g.instances;
        }
    }
    // Impostors: one point sprite per instance, straight from the instance buffer (no instancing: on
    // llvmpipe an instanced draw pays a fixed cost per instance, which tiny far objects cannot afford);
    // one multi-draw per type, a command per run of tiles.
    glUseProgram(impostor_.id);
    glUniformMatrix4fv(loc(impostor_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
    glUniform1f(loc(impostor_, "u_tile_size_m"), tile_size_m_);
    glUniform1f(loc(impostor_, "u_drop_unit_m"), tiles_ ? tiles_->drop_unit_m : 0.0f);
    glUniform1f(loc(impostor_, "u_point_scale"), 0.5f * float(height) / std::tan(0.5f * cam.fov_y_rad));
    const glm::vec3 to_eye(view[0][2], view[1][2], view[2][2]);
    glUniform3fv(loc(impostor_, "u_to_eye"), 1, glm::value_ptr(to_eye));
    setLighting(impostor_, eye, fog_density);
    glEnable(GL_PROGRAM_POINT_SIZE);
    for (size_t i = 0; i < types_.size() && i < draws_.groups.size(); ++i) {
        if (!types_[i].visible) continue;
        const DetailLodMesh& m = (*meshes_)[i];
        const IndirectDraws::Group& g = draws_.groups[i][kImpostorLod];
        if (g.count == 0) continue;
        glUniform3fv(loc(impostor_, "u_color"), 1, glm::value_ptr(m.color));
        glUniform3fv(loc(impostor_, "u_center"), 1, glm::value_ptr(m.center));
        glUniform1f(loc(impostor_, "u_half_size_m"), m.impostor_half_size_m);
        glBindVertexArray(types_[i].impostor_vao);
        glMultiDrawArraysIndirect(
            GL_POINTS,
            reinterpret_cast<void*>(indirect_points_offset_ + uintptr_t(g.first) * sizeof(DrawArraysIndirectCommand)),
            GLsizei(g.count), 0);
        ++stats_.draw_calls;
        stats_.indirect_commands += g.count;
        stats_.points += g.instances;
        stats_.lod_instances[kImpostorLod] += g.instances;
        stats_.instances_drawn += g.instances;
    }
    glDisable(GL_PROGRAM_POINT_SIZE);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
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
