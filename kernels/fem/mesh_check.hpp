#pragma once
// Checks that a triangle mesh bounds one solid the FEM meshers can fill (kernels/fem/object_mesh,
// kernels/fem/solid_mesh), each answering with the first reason it is not, naming the triangle or
// edge, or "" where it is. io/read_obj checks the topology of a file on its own (io/ may not use
// kernels/), with file and line in its messages; these checks take the mesh however it came.
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace clatter::kernels::fem {

// A mesh that cannot bound a solid: bad input (the caller names the file), not a failure.
class SurfaceError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Finite coordinates, indices in range, no corner repeated, at least 4 triangles, and every edge
// shared by exactly two triangles that run along it in opposite directions: closed, manifold and
// consistently oriented (the enclosed volume's sign, and so "inside", depend on it).
std::string surface_topology_problem(const std::vector<std::array<double, 3>>& vertices_m,
                                     const std::vector<std::array<int, 3>>& triangles);

// A triangle whose smallest height is below relative_height times the bounding box's diagonal:
// its normal is noise, and TetGen (coplanarity tolerance 1e-8 of the box) takes it for a line.
inline constexpr double kDegenerateRelativeHeight = 1e-8;
std::string degenerate_triangle_problem(const std::vector<std::array<double, 3>>& vertices_m,
                                        const std::vector<std::array<int, 3>>& triangles,
                                        double relative_height = kDegenerateRelativeHeight);

// TetGen's own test for facets that cross (the check solid_mesh always ran before its fill:
// TetGen 1.5 aborts on them). Chosen over CGAL's does_self_intersect because TetGen is linked
// already, with exact predicates, and CGAL would add GMP and a dependency --version must name.
// Needs a surface that passed surface_topology_problem.
std::string self_intersection_problem(const std::vector<std::array<double, 3>>& vertices_m,
                                      const std::vector<std::array<int, 3>>& triangles);

// Every check above, then the volume's sign ("the faces point inward") and one solid: the
// surface's connected parts must enclose one positive volume each at most once (a part with a
// negative volume is a cavity, allowed; two positive parts are two bodies, six rigid motions
// each). Throws SurfaceError with the reason; returns the enclosed volume, m^3.
double check_object_surface(const std::vector<std::array<double, 3>>& vertices_m,
                            const std::vector<std::array<int, 3>>& triangles);

// One triangle of each cavity: each connected part of the surface that encloses a negative volume
// (wound inward, as a hollow body's inner wall is), in order of their first triangle.
std::vector<int> cavity_triangles(const std::vector<std::array<double, 3>>& vertices_m,
                                  const std::vector<std::array<int, 3>>& triangles);

// A mesh in millimetres read as metres is 1000 times too large and 1e9 times too heavy. The
// object bank models objects one hits and hears (cups to crates), so a body over max_size_m
// across (bounding-box diagonal) or over max_mass_kg is more likely a unit slip than real: 5 m
// is five times the largest object the banks are sized for and a 5 mm part read in metres;
// 1000 kg is a cubic metre of water, and a 10 cm steel cube (7.9 kg) read in metres weighs 7.9e9.
// A warning, not a refusal: the caller decides. "" where plausible.
struct ScaleLimits {
  double max_size_m = 5;
  double max_mass_kg = 1000;
};
std::string implausible_scale(const std::vector<std::array<double, 3>>& vertices_m, double volume_m3, double rho_kg_m3,
                              const ScaleLimits& limits = {});

}  // namespace clatter::kernels::fem
