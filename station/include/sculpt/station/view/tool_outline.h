#pragma once
// The surface the window draws for the tool: its density's iso-surface,
// from voxels averaged 2^k to one when the tool is big, so that choosing a
// big tool never stalls a frame (a 223-voxel ball meshed whole took 44 ms
// of the render thread) and drawing it costs a few thousand triangles.

#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/tool/tool.h"

namespace sculpt::station {

/// Cells a side the outline is meshed from, at most (a power-of-two
/// averaging brings a bigger tool below it).
constexpr int kToolOutlineCells = 64;
/// The same for a dab's stand-in (app/dab_stand_ins.h), drawn as clay beside
/// the clay's own meshes: a 4:1 averaging (the demo's 135^3 head ball at 64
/// cells) shades in rings there, 2:1 does not show. Made on the sculpting
/// thread when the tool changes: the bust's 223^3 ball at 2:1 (112 cells a
/// side) would hold it tens of milliseconds more, so that one stays at 4:1.
constexpr int kStandInCells = 96;

/// The tool's iso-surface in the tool's voxel coordinates (as its density
/// grid), from its voxels averaged over blocks of 2^k, k the smallest with
/// every side at most `max_cells` blocks: a coarse voxel's outline moves by
/// at most about one block, 2% of a tool that needs k = 2.
core::Mesh tool_outline(const core::Tool& tool, int max_cells = kToolOutlineCells);

/// A ball tool's (sphere_radius_vox > 0) iso-surface as a sphere about its
/// pivot, of the radius where its density crosses the surface level (the
/// hardness moves it inwards), with exact normals: microseconds, where
/// marching the demo's 135^3 head ball takes 5-10 ms. Its edges are as long
/// as keep every edge's middle within kWindowBallErrorVox of the sphere
/// (`coarse`: about kCoarseBallErrorVox, edges twice as long): the demo's
/// 66-voxel ball is 4.2k triangles. Fixed three-voxel edges made it 19k,
/// drawn for every dab that waited for its mesh, and those frames made the
/// frame time's p99.
core::Mesh ball_outline(const core::Tool& ball, bool coarse = false);
constexpr float kWindowBallErrorVox = 0.15f;
constexpr float kCoarseBallErrorVox = 4.0f * kWindowBallErrorVox;

/// tool_outline() simplified within kDrawnOutlineErrorVox, as the clay's
/// drawn meshes are (a closed mesh stays closed): a tool's flat faces and
/// gentle curves keep few of the march's triangles (the bust's 20-voxel
/// cube 10,088 -> 44 triangles; drawn twice a frame, ghost and tool, it
/// was 2.7 ms of a 16.7 ms llvmpipe frame).
core::Mesh drawn_outline(const core::Tool& tool, int max_cells = kToolOutlineCells);
constexpr float kDrawnOutlineErrorVox = 0.2f;

/// What the window draws for the tool: for a ball, ball_outline() (marched
/// at 2:1 the demo's ball was 29k triangles, drawn twice a frame, its ghost
/// and itself); any other tool, drawn_outline().
core::Mesh window_tool_outline(const core::Tool& tool);

/// What a dab's stand-in is drawn with: ball_outline() for a ball, else
/// drawn_outline() at kStandInCells (`coarse`: kToolOutlineCells).
core::Mesh stand_in_outline(const core::Tool& tool, bool coarse = false);

}  // namespace sculpt::station
