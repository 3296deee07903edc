#include "kernels/fem/tetgen_fill.hpp"

#include <tetgen.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <stdexcept>

namespace clatter::kernels::fem {
namespace {

void set_facets(tetgenio& in, const std::vector<std::array<double, 3>>& points, const std::vector<std::array<int, 3>>& triangles,
                bool facet_markers) {
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(points.size());
  in.pointlist = new REAL[3 * points.size()];
  for (std::size_t v = 0; v < points.size(); ++v)
    for (int k = 0; k < 3; ++k) in.pointlist[3 * v + k] = points[v][k];
  in.numberoffacets = static_cast<int>(triangles.size());
  in.facetlist = new tetgenio::facet[triangles.size()];
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    tetgenio::facet& facet = in.facetlist[f];
    tetgenio::init(&facet);
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&facet.polygonlist[0]);
    facet.polygonlist[0].numberofvertices = 3;
    facet.polygonlist[0].vertexlist = new int[3]{triangles[f][0], triangles[f][1], triangles[f][2]};
  }
  if (facet_markers) {
    in.facetmarkerlist = new int[triangles.size()];
    for (std::size_t f = 0; f < triangles.size(); ++f) in.facetmarkerlist[f] = static_cast<int>(f) + 1;  // 0: no marker
  }
}

void read_faces(const tetgenio& out, TetgenFill& result) {
  result.faces.resize(static_cast<std::size_t>(std::max(out.numberoftrifaces, 0)));
  for (std::size_t f = 0; f < result.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) result.faces[f][static_cast<std::size_t>(k)] = out.trifacelist[3 * f + k];
  if (out.trifacemarkerlist != nullptr) {
    result.face_facet.resize(result.faces.size());
    for (std::size_t f = 0; f < result.faces.size(); ++f) result.face_facet[f] = out.trifacemarkerlist[f] - 1;
  }
}

void run(const std::string& switches, tetgenio& in, tetgenio& out) {
  std::vector<char> text(switches.begin(), switches.end());
  text.push_back('\0');
  tetgenbehavior behavior;
  if (!behavior.parse_commandline(text.data())) throw std::invalid_argument("TetGen refused the switches " + switches);
  tetrahedralize(&behavior, &in, &out);
}

}  // namespace

TetgenFill tetgen_fill(const std::vector<std::array<double, 3>>& points, const std::vector<std::array<int, 3>>& triangles,
                       const std::string& switches, bool detect_intersections, bool facet_markers,
                       const std::vector<std::array<double, 3>>& holes) {
  TetgenFill result;
  tetgenio in, out;
  set_facets(in, points, triangles, facet_markers);
  if (!holes.empty()) {
    in.numberofholes = static_cast<int>(holes.size());
    in.holelist = new REAL[3 * holes.size()];
    for (std::size_t h = 0; h < holes.size(); ++h)
      for (int k = 0; k < 3; ++k) in.holelist[3 * h + k] = holes[h][k];
  }
  try {
    if (detect_intersections) {
      tetgenio found;
      run("pdQ", in, found);
      result.intersecting_faces = found.numberoftrifaces;
      if (result.intersecting_faces > 0 || switches.empty()) {
        if (result.intersecting_faces > 0) read_faces(found, result);
        return result;
      }
    }
    run(switches, in, out);
  } catch (int code) {  // TETLIBRARY: terminatetetgen throws its exit code
    result.failure_code = code;
    return result;
  }
  if (out.numberofcorners != 4 || out.numberoftetrahedra <= 0) return result;
  if (facet_markers) read_faces(out, result);
  LinearMesh& m = result.mesh;
  m.points.resize(static_cast<std::size_t>(out.numberofpoints));
  for (std::size_t v = 0; v < m.points.size(); ++v)
    m.points[v] = {out.pointlist[3 * v], out.pointlist[3 * v + 1], out.pointlist[3 * v + 2]};
  m.tets.resize(static_cast<std::size_t>(out.numberoftetrahedra));
  for (std::size_t t = 0; t < m.tets.size(); ++t)
    for (int k = 0; k < 4; ++k) m.tets[t][static_cast<std::size_t>(k)] = out.tetrahedronlist[4 * t + k];
  return result;
}

double orientation(const LinearMesh& m, const std::array<int, 4>& t) {
  const auto &a = m.points[static_cast<std::size_t>(t[0])], &b = m.points[static_cast<std::size_t>(t[1])],
             &c = m.points[static_cast<std::size_t>(t[2])], &d = m.points[static_cast<std::size_t>(t[3])];
  const Eigen::Vector3d u(b[0] - a[0], b[1] - a[1], b[2] - a[2]), v(c[0] - a[0], c[1] - a[1], c[2] - a[2]),
      w(d[0] - a[0], d[1] - a[1], d[2] - a[2]);
  return u.cross(v).dot(w);
}

}  // namespace clatter::kernels::fem
