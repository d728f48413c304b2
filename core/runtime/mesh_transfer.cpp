#include "runtime/mesh_transfer.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>
#include <utility>

#include "base/error.h"

namespace bounce {

namespace {

using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;

OpenMesh::Vec3f om(const glm::vec3& v) { return {v.x, v.y, v.z}; }
glm::vec3 gl(const OpenMesh::Vec3f& v) { return {v[0], v[1], v[2]}; }

// OpenMesh reports every refused face on its error stream; a soup with many
// non-manifold edges would flood stderr with lines we count and report
// ourselves. Silenced for the scope of the build, restored after.
class QuietOpenMesh {
 public:
  QuietOpenMesh() : was_enabled_(::omerr().is_enabled()) { ::omerr().disable(); }
  ~QuietOpenMesh() {
    if (was_enabled_) ::omerr().enable();
  }
  QuietOpenMesh(const QuietOpenMesh&) = delete;
  QuietOpenMesh& operator=(const QuietOpenMesh&) = delete;

 private:
  bool was_enabled_;
};

struct FaceSource {
  std::uint32_t triangle;
  bool back;  // the back copy of a two-sided face
};

// The scene's faces into `mesh`, sharing vertices where OpenMesh can.
void add_scene_faces(const Scene& scene, Mesh& mesh, OpenMesh::FPropHandleT<FaceSource> source,
                     LitMeshCounts& counts) {
  const QuietOpenMesh quiet;
  // One vertex set per side: the back copy of a two-sided face cannot share
  // the front's vertices (its half-edges would collide with the neighbours').
  std::vector<Mesh::VertexHandle> shared[2];
  shared[0].resize(scene.positions.size());
  auto vertex = [&](int side, std::uint32_t v) {
    if (shared[side].empty()) shared[side].resize(scene.positions.size());
    Mesh::VertexHandle& h = shared[side][v];
    if (!h.is_valid()) h = mesh.add_vertex(om(scene.positions[v]));
    return h;
  };
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    const glm::uvec3 tri = scene.triangles[t];
    const int sides = scene.two_sided(t) ? 2 : 1;
    for (int side = 0; side < sides; ++side) {
      // The back copy reverses the winding, so its front is the other side.
      const glm::uvec3 c = side == 0 ? tri : glm::uvec3(tri[0], tri[2], tri[1]);
      Mesh::FaceHandle f =
          mesh.add_face(vertex(side, c[0]), vertex(side, c[1]), vertex(side, c[2]));
      if (!f.is_valid()) {
        f = mesh.add_face(mesh.add_vertex(om(scene.positions[c[0]])),
                          mesh.add_vertex(om(scene.positions[c[1]])),
                          mesh.add_vertex(om(scene.positions[c[2]])));
        if (!f.is_valid())
          throw Error("mesh transfer", "OpenMesh refused triangle " + std::to_string(t) +
                                           " even with vertices of its own");
        ++counts.duplicated_faces;
      }
      mesh.property(source, f) = {static_cast<std::uint32_t>(t), side == 1};
      if (side == 1) ++counts.back_faces;
    }
  }
}

// Splits edges longer than max_len, longest first in each pass (longest-edge
// bisection keeps the triangles' shapes from degrading), until none is left.
void refine(Mesh& mesh, float max_len, std::size_t max_faces, Progress* progress,
            LitMeshCounts& counts) {
  const float max_len2 = max_len * max_len;
  std::vector<std::pair<float, Mesh::EdgeHandle>> long_edges;
  for (;;) {
    long_edges.clear();
    for (Mesh::EdgeHandle e : mesh.edges()) {
      const float l2 = mesh.calc_edge_sqr_length(e);
      if (l2 > max_len2) long_edges.emplace_back(l2, e);
    }
    if (long_edges.empty()) return;
    std::sort(long_edges.begin(), long_edges.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    for (const auto& [l2, e] : long_edges) {
      // Edge lengths change only when the edge itself is split, so the
      // recorded length is still right here.
      const Mesh::HalfedgeHandle h = mesh.halfedge_handle(e, 0);
      const OpenMesh::Vec3f mid =
          0.5f * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h)));
      mesh.split_copy(e, mesh.add_vertex(mid));
      ++counts.split_edges;
    }
    if (mesh.n_faces() > max_faces)
      throw Error("mesh transfer", "refinement passed " + std::to_string(max_faces) +
                                       " faces; use a coarser grid or a larger max edge");
    if (progress != nullptr) progress->check();
  }
}

}  // namespace

LitMesh build_transfer_mesh(const Scene& scene, const TransferGrid& grid,
                            const TransferSettings& settings, Progress* progress) {
  if (!(settings.max_edge_cells > 0.0f) || !std::isfinite(settings.max_edge_cells))
    throw Error("mesh transfer", "max edge must be a positive number of voxels");
  if (!(settings.crease_angle_deg >= 0.0f && settings.crease_angle_deg <= 180.0f))
    throw Error("mesh transfer", "crease angle must be in [0, 180] degrees");
  LitMesh out;
  out.counts.scene_triangles = scene.triangle_count();
  if (progress != nullptr) progress->begin_stage("mesh for light transfer", 3);

  Mesh mesh;
  OpenMesh::FPropHandleT<FaceSource> source;
  mesh.add_property(source);
  add_scene_faces(scene, mesh, source, out.counts);
  if (progress != nullptr) progress->advance();
  refine(mesh, settings.max_edge_cells * grid.cell_size, settings.max_faces, progress, out.counts);
  if (progress != nullptr) progress->advance();

  // Face normals from the scene triangle each face came from: refinement
  // keeps faces in their triangle's plane, and the source's normal is exact
  // even for slivers whose own cross product is mostly rounding.
  std::vector<glm::vec3> face_normal(mesh.n_faces());
  for (Mesh::FaceHandle f : mesh.faces()) {
    const FaceSource& s = mesh.property(source, f);
    const glm::vec3 n = glm::normalize(scene.triangle_cross(s.triangle));
    face_normal[static_cast<std::size_t>(f.idx())] = s.back ? -n : n;
  }

  // Vertex normals per corner: the angle-weighted mean of the normals of the
  // faces around the vertex within the crease angle of the corner's own
  // face; corners whose normals agree share one output vertex.
  const float cos_crease = std::cos(glm::radians(settings.crease_angle_deg));
  std::vector<std::uint32_t> corner_vertex(mesh.n_halfedges(), 0);
  struct Corner {
    Mesh::HalfedgeHandle in;  // halfedge into the vertex, in the corner's face
    glm::vec3 normal;
    float angle;
  };
  std::vector<Corner> corners;
  std::size_t used_vertices = 0;
  for (Mesh::VertexHandle v : mesh.vertices()) {
    corners.clear();
    const glm::vec3 p = gl(mesh.point(v));
    for (Mesh::HalfedgeHandle in : mesh.vih_range(v)) {
      if (mesh.is_boundary(in)) continue;
      const glm::vec3 a = gl(mesh.point(mesh.from_vertex_handle(in))) - p;
      const glm::vec3 b = gl(mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(in)))) - p;
      const float la = glm::length(a), lb = glm::length(b);
      const float angle = la > 0.0f && lb > 0.0f
                              ? std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0f, 1.0f))
                              : 0.0f;
      corners.push_back(
          {in, face_normal[static_cast<std::size_t>(mesh.face_handle(in).idx())], angle});
    }
    if (corners.empty()) continue;  // isolated: left over from a refused face
    ++used_vertices;
    const std::size_t first_out = out.positions.size();
    for (const Corner& c : corners) {
      glm::vec3 sum(0.0f);
      for (const Corner& o : corners)
        if (glm::dot(o.normal, c.normal) >= cos_crease) sum += o.angle * o.normal;
      // All angles zero (a vertex of degenerate slivers only): its own face.
      const float len = glm::length(sum);
      const glm::vec3 n = len > 0.0f ? sum / len : c.normal;
      std::size_t k = first_out;
      while (k < out.positions.size() && glm::dot(out.normals[k], n) < 1.0f - 1e-5f) ++k;
      if (k == out.positions.size()) {
        out.positions.push_back(p);
        out.normals.push_back(n);
      }
      corner_vertex[static_cast<std::size_t>(c.in.idx())] = static_cast<std::uint32_t>(k);
    }
  }
  out.counts.crease_vertices = out.positions.size() - used_vertices;

  out.triangles.reserve(mesh.n_faces());
  out.source_triangle.reserve(mesh.n_faces());
  for (Mesh::FaceHandle f : mesh.faces()) {
    glm::uvec3 t;
    int k = 0;
    for (Mesh::HalfedgeHandle h : mesh.fh_range(f))
      t[k++] = corner_vertex[static_cast<std::size_t>(h.idx())];
    out.triangles.push_back(t);
    out.source_triangle.push_back(mesh.property(source, f).triangle);
  }
  out.radiosity.assign(out.positions.size(), glm::vec3(0.0f));
  out.counts.vertices = out.positions.size();
  out.counts.faces = out.triangles.size();
  if (progress != nullptr) progress->end_stage();
  return out;
}

void relight(LitMesh& mesh, const PatchGather& gather, Progress* progress) {
  const auto n = static_cast<std::int64_t>(mesh.positions.size());
  mesh.radiosity.assign(mesh.positions.size(), glm::vec3(0.0f));
  std::atomic<std::size_t> dark{0}, widened{0}, rays{0};
  if (progress != nullptr) progress->begin_stage("light onto the mesh", mesh.positions.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    if (progress != nullptr && progress->should_stop()) continue;
    const auto v = static_cast<std::size_t>(i);
    const GatherResult g = gather.gather(mesh.positions[v], mesh.normals[v]);
    mesh.radiosity[v] = g.light;
    if (g.weight <= 0.0f) dark.fetch_add(1, std::memory_order_relaxed);
    if (g.widened) widened.fetch_add(1, std::memory_order_relaxed);
    rays.fetch_add(g.rays, std::memory_order_relaxed);
    // In blocks: advance() takes a lock to report.
    if (progress != nullptr && (v & 255u) == 255u) progress->advance(256);
  }
  if (progress != nullptr) {
    progress->check();
    progress->end_stage();
  }
  mesh.counts.dark_vertices = dark.load();
  mesh.counts.widened_vertices = widened.load();
  mesh.counts.occlusion_rays = rays.load();
}

LitMesh transfer_to_mesh(const RayTracer& tracer, const std::vector<Patch>& patches,
                         const TransferGrid& grid, const std::vector<glm::vec3>& light,
                         const TransferSettings& settings, Progress* progress) {
  const PatchGather gather(patches, light, grid, &tracer, settings.gather);
  LitMesh mesh = build_transfer_mesh(tracer.scene(), grid, settings, progress);
  relight(mesh, gather, progress);
  return mesh;
}

std::vector<std::uint32_t> vertex_source_triangles(const LitMesh& mesh) {
  std::vector<std::uint32_t> triangle(mesh.positions.size(), 0);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) triangle[mesh.triangles[f][c]] = mesh.source_triangle[f];
  return triangle;
}

}  // namespace bounce
