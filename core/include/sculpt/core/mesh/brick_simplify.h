#pragma once
// Fewer triangles for the same picture. Marching cubes puts a vertex on every
// crossed cell edge, so a smooth part of a sculpture carries about two
// triangles per voxel of its area: the demo's head is 238k triangles, which
// a software renderer (Mesa's llvmpipe) spends most of a frame on. Collapsing
// edges where the surface stays within a fifth of a voxel of the march's
// removes six in seven of them with no change a viewer can see (nine in
// ten when only the border's vertices are held, BorderHold::kVertices).
//
// A brick's mesh is simplified alone, with the vertices on its open border
// (its seams with the neighbouring bricks) held exactly where they are: the
// bricks still meet without a crack, whether their neighbours were
// simplified or not, and at any mix of levels (BorderHold says whether the
// triangles around them stay too). Uses meshoptimizer's
// quadric-error simplifier (Debian's libmeshoptimizer-dev).

#include <cstdint>

#include "sculpt/core/mesh/brick_mesh.h"

namespace sculpt::core {

struct SimplifiedBrick {
  BrickMesh brick;
  /// A bound on how far the surface moved, in the positions' units: the
  /// simplifier's estimate with the margin that makes it one (tested: no
  /// marched vertex lies farther than `max_error` from the result).
  float error = 0.0f;
  /// Places where the normals turn further than the limit asked, left in
  /// `brick`: triangles the simplifier made (not kept as marched) and, with
  /// TurnLimit::kHold, marched vertices it removed (NormalTurnLimit). Those
  /// TurnLimit::kCount counts, and those kHold could not avoid within its
  /// rounds (none on the played sculptures; a box's hard edges keep some).
  int64_t turning = 0;
};

/// What stays of a brick's border as it was marched.
enum class BorderHold {
  /// Its vertices and every triangle around them: welded, simplified bricks
  /// make one closed, manifold mesh (an export, a print check). An inner
  /// vertex collapsed onto a border vertex could join it to another, and
  /// the neighbour join the same two: an edge of four triangles.
  kBand,
  /// Its vertices alone: the bricks still meet without a crack, which is
  /// all a renderer drawing them one by one needs, and about half the
  /// triangles are left (the band was two thirds of them: the 512^3 bust
  /// 75k triangles against 166k, its frames 14 ms against 22 in llvmpipe).
  /// Welded, two bricks may share an edge between two of their border
  /// vertices.
  kVertices,
};

/// What the limit on turning normals does with a triangle the simplifier
/// made that would turn further.
enum class TurnLimit {
  /// The marched triangles around its corners are kept instead.
  kHold,
  /// It stays, counted (SimplifiedBrick::turning): a quick simplification
  /// that says whether the held one is needed (for a few bricks of a
  /// sculpture, where its clay turns fast). Removed vertices are not
  /// looked at (max_removed_deg): finding the surface over each costs a
  /// quarter more simplifying, and the quick pass is on the path to a
  /// new volume's full detail; where they turn, made triangles mostly
  /// turn too.
  kCount,
};

/// How far normals may turn across a triangle the simplifier made. Where
/// the shading turns fast (an eye socket's rim, a mouth's corner), a long
/// triangle from there into the smooth part around is flat enough for any
/// error bound, but the normal swings across it: drawn, it shows a streak,
/// a fan of them a star; within the angle but long, it spreads the rim's
/// turn over its length, a wedge. meshoptimizer 0.18 (Debian's) weighs
/// positions only.
struct NormalTurnLimit {
  /// Between any two corners, degrees (180: no limit).
  float max_deg = 180.0f;
  /// Along an edge longer than this (the positions' units; 0: no such
  /// rule), only `max_deg` times this over the edge's length.
  float full_turn_length = 0.0f;
  /// Between a vertex the simplifier removed and the normal the triangle
  /// made over it interpolates at its nearest point, degrees (180: no such
  /// rule): where the clay turns one way and back between a triangle's
  /// corners (a concave fillet), the corners agree, and the turn between
  /// them, dropped, shows as a light blob.
  float max_removed_deg = 180.0f;
  TurnLimit action = TurnLimit::kHold;
};

/// `brick` with edges collapsed while the surface moves by at most
/// `max_error` (the positions' units: level-0 voxels for the station's
/// meshes); border vertices stay (and, with BorderHold::kBand, the
/// triangles around them), normals and seam keys follow their vertices,
/// vertices no triangle uses are dropped. An empty mesh, or `max_error` <=
/// 0, comes back as it was. With normals, no triangle the simplifier made
/// turns them further than `turn` allows, nor drops a turn it allows no
/// more of: the marched triangles around are kept instead (or, with
/// TurnLimit::kCount, the places are only counted).
SimplifiedBrick simplify_brick_mesh(const BrickMesh& brick, float max_error,
                                    BorderHold hold = BorderHold::kBand,
                                    const NormalTurnLimit& turn = {});

}  // namespace sculpt::core
