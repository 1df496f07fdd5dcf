#include "pushpull/renderer/geometry.hpp"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace pushpull::renderer {

void compute_vertex_normals(std::span<const float> positions, std::span<const uint32_t> indices,
                            std::span<float> normals_out) {
  std::fill(normals_out.begin(), normals_out.end(), 0.0f);
  auto p = [&](uint32_t i) {
    return glm::vec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
  };
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
    const glm::vec3 n = glm::cross(p(b) - p(a), p(c) - p(a));  // length = 2 * area: area weighting
    for (uint32_t v : {a, b, c}) {
      normals_out[3 * v] += n.x;
      normals_out[3 * v + 1] += n.y;
      normals_out[3 * v + 2] += n.z;
    }
  }
  for (size_t v = 0; v + 2 < normals_out.size(); v += 3) {
    // In double: a huge model's summed normals square beyond a float's range (black pictures).
    glm::dvec3 n(normals_out[v], normals_out[v + 1], normals_out[v + 2]);
    const double len = glm::length(n);
    n = len > 0.0 && std::isfinite(len) ? n / len : glm::dvec3(0.0, 0.0, 1.0);
    normals_out[v] = n.x;
    normals_out[v + 1] = n.y;
    normals_out[v + 2] = n.z;
  }
}

std::vector<float> compute_vertex_normals(std::span<const float> positions,
                                          std::span<const uint32_t> indices) {
  std::vector<float> normals(positions.size());
  compute_vertex_normals(positions, indices, normals);
  return normals;
}

namespace {

// Two unit vectors orthogonal to axis (unit) and to each other.
void basis(const glm::vec3& axis, glm::vec3& u, glm::vec3& w) {
  const glm::vec3 helper = std::abs(axis.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  u = glm::normalize(glm::cross(axis, helper));
  w = glm::cross(axis, u);
}

void push(RenderMesh& m, const glm::vec3& p, const glm::vec3& n) {
  m.positions.insert(m.positions.end(), {p.x, p.y, p.z});
  m.normals.insert(m.normals.end(), {n.x, n.y, n.z});
}

// A ring of `sides` vertices around centre; returns the index of its first vertex.
uint32_t ring(RenderMesh& m, const glm::vec3& centre, const glm::vec3& u, const glm::vec3& w, float radius,
              int sides, const glm::vec3& normal_tilt, float tilt) {
  const uint32_t first = m.vertex_count();
  for (int i = 0; i < sides; ++i) {
    const float a = glm::two_pi<float>() * float(i) / float(sides);
    const glm::vec3 radial = std::cos(a) * u + std::sin(a) * w;
    push(m, centre + radius * radial, glm::normalize(radial + tilt * normal_tilt));
  }
  return first;
}

void connect(RenderMesh& m, uint32_t a, uint32_t b, int sides) {
  for (int i = 0; i < sides; ++i) {
    const uint32_t i0 = uint32_t(i), i1 = uint32_t((i + 1) % sides);
    m.indices.insert(m.indices.end(), {a + i0, a + i1, b + i1, a + i0, b + i1, b + i0});
  }
}

void cap(RenderMesh& m, const glm::vec3& centre, const glm::vec3& normal, uint32_t ring_first, int sides) {
  const uint32_t c = m.vertex_count();
  push(m, centre, normal);
  for (int i = 0; i < sides; ++i)
    m.indices.insert(m.indices.end(), {c, ring_first + uint32_t((i + 1) % sides), ring_first + uint32_t(i)});
}

}  // namespace

double winding_number(std::span<const float> positions, std::span<const uint32_t> indices,
                      const glm::vec3& point) {
  const glm::dvec3 p(point);
  double total = 0.0;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    glm::dvec3 v[3];
    for (int k = 0; k < 3; ++k) {
      const size_t i = size_t(indices[t + size_t(k)]) * 3;
      if (i + 2 >= positions.size()) return 0.0;  // malformed: no meaningful answer
      v[k] = glm::dvec3(positions[i], positions[i + 1], positions[i + 2]) - p;
    }
    // Van Oosterom and Strackee: tan(omega / 2) = a . (b x c) / (|a||b||c| + (a.b)|c| + (b.c)|a| + (c.a)|b|).
    const double la = glm::length(v[0]), lb = glm::length(v[1]), lc = glm::length(v[2]);
    const double numerator = glm::dot(v[0], glm::cross(v[1], v[2]));
    const double denominator =
        la * lb * lc + glm::dot(v[0], v[1]) * lc + glm::dot(v[1], v[2]) * la + glm::dot(v[2], v[0]) * lb;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * glm::pi<double>());
}

RenderMesh make_arrow(const glm::vec3& p0, const glm::vec3& p1, float radius, int material) {
  RenderMesh m;
  const int sides = 24;
  glm::vec3 axis = p1 - p0;
  const float length = glm::length(axis);
  if (length <= 0.0f || radius <= 0.0f) return m;
  axis /= length;
  glm::vec3 u, w;
  basis(axis, u, w);
  const float head = std::min(4.0f * radius, 0.5f * length);
  const glm::vec3 neck = p1 - head * axis;
  const uint32_t s0 = ring(m, p0, u, w, radius, sides, axis, 0.0f);
  const uint32_t s1 = ring(m, neck, u, w, radius, sides, axis, 0.0f);
  connect(m, s0, s1, sides);
  // Caps have their own vertices with axial normals (tilt 1e3 makes the radial part vanish).
  cap(m, p0, -axis, ring(m, p0, u, w, radius, sides, -axis, 1e3f), sides);
  const uint32_t h0 = ring(m, neck, u, w, 2.0f * radius, sides, axis, 0.5f);
  const uint32_t tip = ring(m, p1, u, w, 0.0f, sides, axis, 0.5f);
  connect(m, h0, tip, sides);
  cap(m, neck, -axis, ring(m, neck, u, w, 2.0f * radius, sides, -axis, 1e3f), sides);
  m.submeshes.push_back({0, static_cast<uint32_t>(m.indices.size()), material});
  return m;
}

RenderMesh make_tubes(const std::vector<std::vector<glm::vec3>>& polylines, float radius, int material) {
  RenderMesh m;
  const int sides = 8;
  for (const auto& line : polylines) {
    if (line.size() < 2) continue;
    uint32_t previous = 0;
    for (size_t i = 0; i < line.size(); ++i) {
      const glm::vec3 a = line[i == 0 ? 0 : i - 1];
      const glm::vec3 b = line[i + 1 < line.size() ? i + 1 : i];
      glm::vec3 tangent = b - a;
      if (glm::length(tangent) <= 0.0f) tangent = glm::vec3(1, 0, 0);
      tangent = glm::normalize(tangent);
      glm::vec3 u, w;
      basis(tangent, u, w);
      const uint32_t current = ring(m, line[i], u, w, radius, sides, tangent, 0.0f);
      // Rings built from independent bases may be rotated relative to each other; short segments
      // keep the twist invisible at tube radii of a few pixels.
      if (i > 0) connect(m, previous, current, sides);
      previous = current;
    }
  }
  m.submeshes.push_back({0, static_cast<uint32_t>(m.indices.size()), material});
  return m;
}

}  // namespace pushpull::renderer
