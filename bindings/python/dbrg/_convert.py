"""A Mesh as the mesh type of Open3D or trimesh. Each package is imported only when its conversion is
called, so neither is a dependency of dbrg."""

import importlib

import numpy as np


def _import(package, caller, install):
    try:
        return importlib.import_module(package)
    except ImportError as error:
        raise ImportError("%s needs the %s package, which cannot be imported (%s): %s"
                          % (caller, package, install, error), name=package) from error


def to_open3d(mesh):
    """An open3d.geometry.TriangleMesh with the mesh's vertices (unused points among them), triangles and
    vertex normals."""
    open3d = _import("open3d", "Mesh.to_open3d()", "pip install open3d; Debian: apt-get install python3-open3d")
    # Vector3dVector and Vector3iVector copy from float64 and int32 arrays; indices stay below 2**31
    # because the library takes at most DBRG_MAX_POINTS points.
    vertices = np.ascontiguousarray(mesh.vertices, dtype=np.float64)
    triangles = np.ascontiguousarray(mesh.triangles, dtype=np.int32).reshape(-1, 3)
    result = open3d.geometry.TriangleMesh(open3d.utility.Vector3dVector(vertices),
                                          open3d.utility.Vector3iVector(triangles))
    result.vertex_normals = open3d.utility.Vector3dVector(np.ascontiguousarray(mesh.vertex_normals, dtype=np.float64))
    return result


def to_trimesh(mesh):
    """A trimesh.Trimesh with the mesh's vertices (unused points among them, in order), triangles and vertex
    normals, made with process=False so that trimesh merges and removes nothing."""
    trimesh = _import("trimesh", "Mesh.to_trimesh()", "pip install trimesh")
    return trimesh.Trimesh(vertices=np.array(mesh.vertices, dtype=np.float64),
                           faces=np.array(mesh.triangles, dtype=np.int64).reshape(-1, 3),
                           vertex_normals=np.array(mesh.vertex_normals, dtype=np.float64),
                           process=False)
