#!/usr/bin/python3
"""Re-reads a mesh file with VTK (Debian python3-vtk9), a parser independent
of ours, and prints what it found, for tests/core/mesh/mesh_io_test.cpp:

    points P polys F area A volume V boundary_edges B nonmanifold_edges N

Exit code 1 with a message when VTK cannot read the file."""
import sys

import vtk


def main():
    path = sys.argv[1]
    lower = path.lower()
    if lower.endswith(".ply"):
        reader = vtk.vtkPLYReader()
    elif lower.endswith(".obj"):
        reader = vtk.vtkOBJReader()
    elif lower.endswith(".stl"):
        reader = vtk.vtkSTLReader()  # merges the per-triangle vertices again
    elif lower.endswith(".glb"):
        reader = vtk.vtkGLTFReader()  # a scene: its one mesh is taken out below
    else:
        print(f"{path}: unknown extension", file=sys.stderr)
        return 1
    reader.SetFileName(path)
    reader.Update()
    if lower.endswith(".glb"):
        merged = vtk.vtkCompositeDataGeometryFilter()
        merged.SetInputConnection(reader.GetOutputPort())
        merged.Update()
        mesh = merged.GetOutput()
        if mesh.GetPointData().GetNormals() is None:
            print(f"{path}: VTK found no normals", file=sys.stderr)
            return 1
    else:
        mesh = reader.GetOutput()
    if mesh is None or mesh.GetNumberOfPolys() == 0:
        print(f"{path}: VTK read no polygons", file=sys.stderr)
        return 1
    props = vtk.vtkMassProperties()
    props.SetInputData(mesh)
    props.Update()
    edges = vtk.vtkFeatureEdges()
    edges.SetInputData(mesh)
    edges.BoundaryEdgesOn()
    edges.NonManifoldEdgesOff()
    edges.FeatureEdgesOff()
    edges.ManifoldEdgesOff()
    edges.Update()
    boundary = edges.GetOutput().GetNumberOfCells()
    edges.BoundaryEdgesOff()
    edges.NonManifoldEdgesOn()
    edges.Update()
    nonmanifold = edges.GetOutput().GetNumberOfCells()
    print(f"points {mesh.GetNumberOfPoints()} polys {mesh.GetNumberOfPolys()} "
          f"area {props.GetSurfaceArea():.6f} volume {props.GetVolume():.6f} "
          f"boundary_edges {boundary} nonmanifold_edges {nonmanifold}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
