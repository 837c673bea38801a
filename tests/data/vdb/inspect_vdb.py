#!/usr/bin/python3
"""Prints what OpenVDB's own Python bindings (Debian python3-openvdb) see in a
.vdb file: per grid a line
  grid NAME CLASS TYPE VOXEL_SIZE BACKGROUND ACTIVE_VOXELS MIN_ACTIVE MAX_ACTIVE
and per probe X,Y,Z given after the file, for every float grid,
  at NAME X Y Z VALUE
Exit 3 when the bindings are missing (the test then skips)."""
import sys

try:
    import pyopenvdb as vdb
except ImportError:
    sys.exit(3)

path = sys.argv[1]
probes = [tuple(int(c) for c in p.split(",")) for p in sys.argv[2:]]
for grid in vdb.readAll(path)[0]:
    lo, hi = grid.evalMinMax() if grid.activeVoxelCount() else (0, 0)
    vs = grid.transform.voxelSize()
    if vs[0] != vs[1] or vs[1] != vs[2]:
        vs = (float("nan"),)
    print("grid", grid.name, str(grid.gridClass).replace(" ", "_"), grid.valueTypeName,
          repr(vs[0]), repr(grid.background), grid.activeVoxelCount(), repr(lo), repr(hi))
    if grid.valueTypeName != "float":
        continue
    acc = grid.getConstAccessor()
    for p in probes:
        print("at", grid.name, *p, repr(acc.getValue(p)))
