// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Shared by the 3D mesh's sources (mesh3d, mesh3d_update): the slots of a
// tetrahedron's triangles.  Internal to the core (not installed).
#pragma once

namespace tessera {
namespace {

// Slots of the triangle opposite slot k, ordered so that (f0 f1 f2 k) is an
// even permutation: the apex k sees it positively.
constexpr int kFace[4][3] = {{1, 3, 2}, {0, 2, 3}, {1, 0, 3}, {0, 1, 2}};

}  // namespace
}  // namespace tessera
