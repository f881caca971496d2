// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The benchmark yardstick: CGAL's own Delaunay triangulation of the points,
// timed (the pair style's 'reference' keyword, bench/).

#include "mesh_detail.h"

namespace tessera {

double time_plain_delaunay(const Points &pts, int n, long *faces)
{
  using PlainDelaunay = CGAL::Delaunay_triangulation_2<Kernel>;
  std::vector<PlainDelaunay::Point> cp;
  cp.reserve(static_cast<size_t>(n > 0 ? n : 0));
  for (int i = 0; i < n; i++) cp.emplace_back(pts.x(i), pts.y(i));
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  PlainDelaunay dt;
  dt.insert(cp.begin(), cp.end());
  const double seconds = std::chrono::duration<double>(clock::now() - t0).count();
  if (faces) *faces = static_cast<long>(dt.number_of_faces());
  return seconds;
}

}  // namespace tessera
