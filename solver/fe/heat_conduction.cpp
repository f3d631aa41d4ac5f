#include "solver/fe/heat_conduction.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "solver/common/parallel.hpp"

namespace splat {

namespace {

constexpr std::size_t heat_block = 512;
constexpr std::size_t min_parallel_elements = 4096;

// Local node indices of each face, in cyclic order: the hexahedron's six
// faces (those of the unit cube, hex8.hpp), the quadrilateral's four edges.
constexpr int hex_faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
constexpr int quad_edges[4][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};

struct FaceRecord {
  std::array<int, 4> key;    // global node ids, sorted (-1 for the unused of an edge)
  std::array<int, 4> nodes;  // cyclic order in `element`
  int element;
};

std::vector<FaceRecord> all_faces(const FeBody& body) {
  const bool hex = body.kind == ElementKind::hex8;
  std::vector<FaceRecord> faces;
  faces.reserve(body.num_elements() * (hex ? 6 : 4));
  for (std::size_t e = 0; e < body.num_elements(); ++e) {
    const std::array<int, 8>& cn = body.conn[e];
    for (int f = 0; f < (hex ? 6 : 4); ++f) {
      FaceRecord r{{-1, -1, -1, -1}, {-1, -1, -1, -1}, static_cast<int>(e)};
      for (int a = 0; a < (hex ? 4 : 2); ++a)
        r.nodes[a] = cn[hex ? hex_faces[f][a] : quad_edges[f][a]];
      r.key = r.nodes;
      std::sort(r.key.begin(), r.key.end());
      faces.push_back(r);
    }
  }
  return faces;
}

Vec3 centre(const FeBody& body, const NodeSet& nodes, std::size_t e) {
  Vec3 c = Vec3::Zero();
  const int npe = body.nodes_per_element();
  for (int a = 0; a < npe; ++a) c += nodes.x[body.conn[e][a]];
  return c / npe;
}

// Current area of a face, m^2 (axisymmetric: per radian).
double face_area(const FeBody& body, const NodeSet& nodes, const HeatFace& f) {
  if (body.kind == ElementKind::hex8) {
    const Vec3 d1 = nodes.x[f.nodes[2]] - nodes.x[f.nodes[0]];
    const Vec3 d2 = nodes.x[f.nodes[3]] - nodes.x[f.nodes[1]];
    return 0.5 * d1.cross(d2).norm();
  }
  const Vec3& a = nodes.x[f.nodes[0]];
  const Vec3& b = nodes.x[f.nodes[1]];
  return (b - a).norm() * 0.5 * (a[0] + b[0]);
}

}  // namespace

bool conducts_heat(const FeBody& body) {
  const ThermalParams& th = body.material.thermal;
  return body.switches.heat_conduction && th.conductivity > 0.0 && th.c_p > 0.0;
}

void build_heat_faces(FeBody& body) {
  body.heat_offsets.clear();
  body.heat_faces.clear();
  body.heat_in.clear();
  if (!conducts_heat(body)) return;
  std::vector<FaceRecord> faces = all_faces(body);
  std::sort(faces.begin(), faces.end(), [](const FaceRecord& a, const FaceRecord& b) {
    return a.key != b.key ? a.key < b.key : a.element < b.element;
  });
  const std::size_t ne = body.num_elements();
  std::vector<std::vector<HeatFace>> per(ne);
  for (std::size_t i = 0; i + 1 < faces.size(); ++i) {
    if (faces[i].key != faces[i + 1].key) continue;
    const FaceRecord& a = faces[i];
    const FaceRecord& b = faces[i + 1];
    per[static_cast<std::size_t>(a.element)].push_back({b.element, a.nodes});
    per[static_cast<std::size_t>(b.element)].push_back({a.element, a.nodes});
    ++i;
  }
  body.heat_offsets.assign(ne + 1, 0);
  for (std::size_t e = 0; e < ne; ++e) {
    body.heat_offsets[e + 1] = body.heat_offsets[e] + static_cast<int>(per[e].size());
    body.heat_faces.insert(body.heat_faces.end(), per[e].begin(), per[e].end());
  }
  body.heat_in.assign(ne, 0.0);
}

double fe_conduct_heat(FeBody& body, const NodeSet& nodes, double dt) {
  if (body.heat_offsets.empty()) return std::numeric_limits<double>::infinity();
  const double k = body.material.thermal.conductivity;
  const double capacity = body.constants.rho0 * body.material.thermal.c_p;  // J/(m^3 K)
  const std::size_t ne = body.num_elements();
  std::vector<double> bound(ne, std::numeric_limits<double>::infinity());
  for_each_block(ne, heat_block, min_parallel_elements, [&](std::size_t first, std::size_t last) {
    for (std::size_t e = first; e < last; ++e) {
      body.heat_in[e] = 0.0;
      if (!body.active[e]) continue;
      const Vec3 ce = centre(body, nodes, e);
      double g_sum = 0.0, heat = 0.0;
      for (int i = body.heat_offsets[e]; i < body.heat_offsets[e + 1]; ++i) {
        const HeatFace& f = body.heat_faces[static_cast<std::size_t>(i)];
        const std::size_t b = static_cast<std::size_t>(f.neighbour);
        if (!body.active[b]) continue;
        const double d = (centre(body, nodes, b) - ce).norm();
        if (!(d > 0.0)) continue;
        const double G = k * face_area(body, nodes, f) / d;
        g_sum += G;
        heat += G * (body.state[b].T - body.state[e].T) * dt;
      }
      body.heat_in[e] = heat;
      if (g_sum > 0.0) bound[e] = capacity * body.volume0[e] / g_sum;
    }
  });
  if (dt > 0.0) {
    for_each_block(ne, heat_block, min_parallel_elements, [&](std::size_t first, std::size_t last) {
      for (std::size_t e = first; e < last; ++e) {
        if (body.heat_in[e] == 0.0) continue;
        add_heat(body.material, body.constants, body.switches, body.state[e],
                 body.heat_in[e] / body.volume0[e]);
      }
    });
  }
  return *std::min_element(bound.begin(), bound.end());
}

}  // namespace splat
