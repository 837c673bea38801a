#!/usr/bin/python3
"""Writes the .vdb files the bad-input tests read (tests/core/files/vdb_file_test.cpp),
with OpenVDB's own Python bindings (Debian python3-openvdb), so the files are
what another program would hand us. Run from this folder; the outputs are
checked in, so the tests do not need the bindings."""
import pyopenvdb as vdb


def float_grid(name, cls=vdb.GridClass.FOG_VOLUME):
    g = vdb.FloatGrid()
    g.name = name
    g.gridClass = cls
    acc = g.getAccessor()
    for ijk in [(0, 0, 0), (3, 2, 1)]:
        acc.setValueOn(ijk, 0.5)
    return g


# A density grid of 3-vectors, and one of booleans: not float.
v = vdb.Vec3SGrid()
v.name = "density"
v.getAccessor().setValueOn((1, 1, 1), (1.0, 0.0, 0.0))
vdb.write("vec3_density.vdb", grids=[v])
b = vdb.BoolGrid()
b.name = "density"
b.getAccessor().setValueOn((1, 1, 1), True)
vdb.write("bool_density.vdb", grids=[b])

# No grid we can use: a float fog volume under another name.
vdb.write("no_usable_grid.vdb", grids=[float_grid("temperature")])

# Active voxels 100001 apart along x: more than the 65536 edge limit.
g = float_grid("density")
g.getAccessor().setValueOn((100000, 0, 0), 1.0)
vdb.write("too_long.vdb", grids=[g])
# 40000^3 voxels: within the edge limit, over the 2^32 voxel limit.
g = float_grid("density")
g.getAccessor().setValueOn((39999, 39999, 39999), 1.0)
vdb.write("too_many_voxels.vdb", grids=[g])

# Transforms: non-uniform scale, a rotation.
g = float_grid("density")
g.transform = vdb.createLinearTransform([[1, 0, 0, 0], [0, 2, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
vdb.write("non_uniform.vdb", grids=[g])
g = float_grid("density")
g.transform = vdb.createLinearTransform([[0, 1, 0, 0], [-1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
vdb.write("rotated.vdb", grids=[g])

# A level set only (not ours): a sphere of radius 5 voxels, voxel size 0.5,
# so the reader must divide by the voxel size.
s = vdb.createLevelSetSphere(radius=2.5, center=(4.0, 4.0, 4.0), voxelSize=0.5, halfWidth=3.0)
s.name = "ball"
vdb.write("level_set_only.vdb", grids=[s])
