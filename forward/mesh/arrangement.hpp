// The exact 2D arrangement a region is cut in (CGAL), shared by the cut (cut_region.cpp)
// and the sliver merging (merge_slivers.cpp). Private to the ddafit_mesh target: nothing
// outside forward/mesh sees CGAL.
#pragma once

#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <vector>

#include "forward/scene.hpp"

namespace ddafit::cut {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Traits = CGAL::Arr_segment_traits_2<Kernel>;
using Point = Kernel::Point_2;
using Segment = Traits::Curve_2;
// Face data: 1 for a face inside the region (a block), 0 outside.
using Dcel = CGAL::Arr_face_extended_dcel<Traits, int>;
using Arrangement = CGAL::Arrangement_2<Traits, Dcel>;

inline Vec2 to_vec(const Point& p) { return Vec2(CGAL::to_double(p.x()), CGAL::to_double(p.y())); }

// The outer boundary of a bounded face, counter-clockwise.
std::vector<Vec2> face_polygon(Arrangement::Face_const_handle f);

// The smallest corner angle (deg), region corners excepted (merging cannot change those).
double smallest_angle(const std::vector<Vec2>& poly, const std::vector<Vec2>& region_corners);

// The shortest edge a face shares with another face of the region.
double shortest_inside_edge(Arrangement::Face_const_handle f);

// Merges the slivers among the inside faces (data 1) into neighbours, round by round, by
// removing shared edges (docs/theory.md, "Slivers"). Returns the number of merges.
int merge_slivers(Arrangement& arr, const std::vector<Vec2>& outline, double block_size, const MeshSettings& settings);

}  // namespace ddafit::cut
